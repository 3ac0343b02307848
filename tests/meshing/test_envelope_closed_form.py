"""The closed form of the meshing equation in phi1 and the compiled envelope kernel, checked independently.

f(phi1) = (r1 x n1) . R_z(-phi1) p = A cos phi1 + B sin phi1 + C (docs/theory/gearing.md, Eqs. (M5a)-(M5b)); the
kernel solves it with atan2/arccos. Oracles: the rotation-matrix form of f (``BevelPairKinematics.meshing_function``)
sampled densely and solved per point with ``scipy.optimize.brentq``, and the 3 x 3 matrix map of Eq. (M6).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from spiralbevel._core import meshing as _m
from spiralbevel._core.envelope_kernel import envelope_points
from spiralbevel._core.rotations import apply
from spiralbevel.errors import NoContactError
from spiralbevel.meshing.envelope import solve_envelope
from spiralbevel.meshing.kinematics import BevelPairKinematics

EPS = np.finfo(float).eps


def _random_points(rng, n):
    r = rng.uniform(-150.0, 150.0, (n, 3))
    nrm = rng.normal(size=(n, 3))
    return r, nrm / np.linalg.norm(nrm, axis=1, keepdims=True)


@pytest.mark.parametrize("shaft_deg, z1, z2", [(90.0, 23, 65), (60.0, 11, 13), (130.0, 17, 29)])
def test_meshing_function_is_a_first_harmonic_in_phi1(shaft_deg, z1, z2):
    # the rotation-matrix form sampled at 7 angles equals A cos + B sin + C from q = r1 x n1: round-off only,
    # |f| <= |r1| |n1| = |r1|, so 8 eps |r1|
    kin = BevelPairKinematics(np.radians(shaft_deg), z1, z2)
    r, n = _random_points(np.random.default_rng(3), 500)
    A, B, C = _m.meshing_coefficients(r, n, kin.pitch_angle_pinion)
    for phi in np.linspace(-4.0, 9.0, 7):
        f = kin.meshing_function(r, n, phi)
        assert np.max(np.abs(f - (A * np.cos(phi) + B * np.sin(phi) + C)) / np.linalg.norm(r, axis=1)) < 8 * EPS


def _all_roots(fun, lo, hi, m=721):
    """Every sign change of ``fun`` on a dense grid of [lo, hi], refined by brentq (the independent oracle)."""
    x = np.linspace(lo, hi, m)
    y = fun(x)  # the rotation-matrix form, vectorized over the grid
    out = []
    for k in np.nonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0)[0]:
        out.append(brentq(lambda t: float(fun(t)), x[k], x[k + 1], xtol=1e-15, rtol=4 * EPS))
    return np.array(out), y


@pytest.mark.parametrize("branch", [1, -1, None])
def test_kernel_roots_equal_per_point_brentq_on_random_points(branch):
    # 300 random (r1, n1, guess): the kernel's root is the oracle's root with the requested slope sign (branch +1:
    # df/dphi1 < 0) or nearest to the guess, within pi of the guess; points without a sign change are "no contact"
    kin = BevelPairKinematics(np.radians(75.0), 17, 41)
    rng = np.random.default_rng(11)
    r, n = _random_points(rng, 300)
    guess = rng.uniform(-3.0, 3.0, 300)
    phi, res, exists, conv, *_ = envelope_points(r, n, guess, 0 if branch is None else branch,
                                                 kin.pitch_angle_pinion, kin.shaft_angle, kin.ratio, 1e-13)
    A, B, C = _m.meshing_coefficients(r, n, kin.pitch_angle_pinion)
    n_root = n_none = 0
    for i in range(300):
        def f(t, i=i):
            return kin.meshing_function(r[i], n[i], t)

        roots, samples = _all_roots(f, guess[i] - np.pi, guess[i] + np.pi)
        margin = np.sqrt(max(A[i] ** 2 + B[i] ** 2 - C[i] ** 2, 0.0))  # |f'| at the roots
        if roots.size == 0:
            assert not exists[i] and not conv[i]
            assert np.min(np.abs(samples)) > 0  # no root at all, not a missed one
            n_none += 1
            continue
        if margin < 1e-3 * np.linalg.norm(r[i]):  # near-tangent roots: checked by the next test
            continue
        assert exists[i] and conv[i]
        slope = np.array([B[i] * np.cos(t) - A[i] * np.sin(t) for t in roots])
        if branch is None:
            want = roots[np.argmin(np.abs(roots - guess[i]))]
        else:
            want = roots[np.sign(slope) == -branch][0]
        # round-off: the root moves by (error of f) / |f'|, error of f <= 8 eps (|A| + |B| + |C|); brentq adds
        # its xtol + rtol |x|
        tol = 8 * EPS * (abs(A[i]) + abs(B[i]) + abs(C[i])) / margin + 1e-15 + 8 * EPS * abs(want)
        assert abs(phi[i] - want) <= tol
        assert res[i] <= 1e-13
        n_root += 1
    assert n_root > 80 and n_none > 20  # both cases exercised


@pytest.mark.parametrize("closeness", [1e-6, 1e-10])
def test_near_tangent_roots_equal_brentq(closeness):
    # |C| = (1 - closeness) hypot(A, B): the two roots are 2 sqrt(2 closeness) apart and arccos alone loses digits;
    # the root moves by (error of f) / |f'| with |f'| = sqrt(R^2 - C^2), the same round-off bound as above
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    g1 = kin.pitch_angle_pinion
    rng = np.random.default_rng(5)
    m = 40
    qxy = rng.uniform(-100.0, 100.0, (m, 2))
    sign = rng.choice([-1.0, 1.0], m)
    qz = sign * (1 - closeness) * np.sin(g1) * np.hypot(qxy[:, 0], qxy[:, 1]) / np.cos(g1)
    q = np.column_stack([qxy, qz])
    # r x n = q with n a unit vector perpendicular to q and r = n x q
    t = np.cross(q, rng.normal(size=(m, 3)))
    n = t / np.linalg.norm(t, axis=1, keepdims=True)
    r = np.cross(n, q)
    assert np.max(np.abs(np.cross(r, n) - q)) < 1e-12
    A, B, C = _m.meshing_coefficients(r, n, g1)
    for branch in (1, -1):
        phi, res, exists, conv, *_ = envelope_points(r, n, 0.0, branch, g1, kin.shaft_angle, kin.ratio, 1e-13)
        assert exists.all() and conv.all()
        for i in range(m):
            def f(x, i=i):
                return float(kin.meshing_function(r[i], n[i], x))

            theta = np.arctan2(B[i], A[i])
            # f decreases on [theta, theta + pi] (branch +1) and increases on [theta - pi, theta] (branch -1)
            lo, hi = (theta, theta + np.pi) if branch == 1 else (theta - np.pi, theta)
            want = brentq(f, lo, hi, xtol=1e-15, rtol=4 * EPS)
            margin = np.sqrt(A[i] ** 2 + B[i] ** 2 - C[i] ** 2)
            tol = 8 * EPS * (abs(A[i]) + abs(B[i]) + abs(C[i])) / margin + 1e-15 + 8 * EPS * abs(want)
            assert abs(_m.wrap_near(phi[i], want) - want) <= tol


def test_kernel_equals_numpy_reference_and_matrix_map():
    # the same arithmetic as meshing_roots + polish_phi1 (numpy) and the map of Eq. (M6) built from 3 x 3 matrices:
    # phi1 to a few ulp of 2 pi, points to round-off of |r| ~ 260 mm (1e-12 mm)
    kin = BevelPairKinematics(np.radians(105.0), 12, 31)
    rng = np.random.default_rng(7)
    r, n = _random_points(rng, 4000)
    guess = rng.uniform(-1.0, 1.0, 4000)
    A, B, C = _m.meshing_coefficients(r, n, kin.pitch_angle_pinion)
    plus, minus, ex_ref = _m.meshing_roots(A, B, C)
    for branch, root in ((1, plus), (-1, minus)):
        ref = _m.wrap_near(_m.polish_phi1(A, B, C, np.where(ex_ref, root, guess)), guess)
        phi, res, exists, conv, pts, nrs, fix = envelope_points(r, n, guess, branch, kin.pitch_angle_pinion,
                                                                kin.shaft_angle, kin.ratio, 1e-13)
        assert np.array_equal(exists, ex_ref)
        assert np.max(np.abs(phi - ref)[ex_ref]) < 1e-14
        ok = conv
        M = kin.pinion_to_gear(phi[ok])
        assert np.max(np.abs(pts[ok] - apply(M, r[ok]))) < 1e-12
        assert np.max(np.abs(nrs[ok] + apply(M, n[ok]))) < 1e-14
        assert np.max(np.abs(fix[ok] - apply(kin.pinion_to_fixed(phi[ok]), r[ok]))) < 1e-12
        assert np.isnan(pts[~ok]).all() and np.isnan(nrs[~ok]).all()
        assert np.max(np.abs(kin.to_gear(r[ok], phi[ok]) - apply(M, r[ok]))) < 1e-12


def test_no_root_point_raises_no_contact():
    # q = r x n along the pinion axis: f = cos(g1) |q| never vanishes
    kin = BevelPairKinematics(np.pi / 2, 23, 65)

    def surf(u, v):
        u, v = np.broadcast_arrays(u, v)
        return (np.stack([50 + u, 0 * u, 80 + v], -1), np.stack([0 * u, 1 + 0 * u, 0 * u], -1))

    with pytest.raises(NoContactError, match="index"):
        solve_envelope(surf, kin, np.zeros(3), np.zeros(3))
