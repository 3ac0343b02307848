"""Contact ellipses (meshing/ellipse.py): analytic sphere-on-plane, sphere-in-cup and crossed cylinders, principal
curvatures against the closed-form log-spiral curvatures, and the ellipse of a TCA contact against the separation
of the two surfaces computed directly (the locus where separation = delta)."""

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from spiralbevel._core import logspiral as ls
from spiralbevel._core.rotations import rot_axis, rot_y, rot_z
from spiralbevel.errors import DesignError
from spiralbevel.meshing.contact_surface import NormalDeviation, principal_curvatures, quadratic_crowning
from spiralbevel.meshing.ellipse import contact_ellipse, contact_ellipse_from_surfaces
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair

DELTA = 0.00635
I3 = np.eye(3)


class Graph:
    """z = sign * (R - sqrt(R^2 - u^2 - v^2)) style surfaces given by a height function; outward normal sign."""

    def __init__(self, height, up):
        self.height, self.up = height, up
        self.fd_step = (1e-4, 1e-4)

    def evaluate(self, p):
        p = np.asarray(p, float)
        u, v = p[..., 0], p[..., 1]
        z, zu, zv = self.height(u, v)
        r = np.stack([u, v, z], -1)
        n = np.stack([-zu, -zv, np.ones_like(z)], -1)
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        return r, self.up * n


def cap(R, below):
    """Spherical cap through the origin; centre at (0, 0, R) (below=False: sphere above the origin)."""
    def h(u, v):
        w = np.sqrt(R**2 - u**2 - v**2)
        return R - w, u / w, v / w
    return h


def cylinder_x(R):  # axis along x, through (0, 0, R)
    def h(u, v):
        w = np.sqrt(R**2 - v**2)
        return R - w, 0 * u, v / w
    return h


def cylinder_y_below(R):  # axis along y, through (0, 0, -R)
    def h(u, v):
        w = np.sqrt(R**2 - u**2)
        return -(R - w), -u / w, 0 * v
    return h


def plane(u, v):
    return 0 * u, 0 * u, 0 * u


O = np.zeros(2)


def test_sphere_on_plane():
    R = 20.0
    sphere = Graph(cap(R, False), up=-1.0)  # body above, outward normal -z at the origin
    flat = Graph(plane, up=1.0)
    e = contact_ellipse_from_surfaces(sphere, O, I3, flat, O, I3, DELTA)
    np.testing.assert_allclose(e.semi_axes, np.sqrt(2 * R * DELTA), rtol=1e-6)  # Hertz geometry: a^2 = 2 R delta
    np.testing.assert_allclose(e.relative_curvatures, 1 / R, rtol=1e-6)


def test_sphere_in_spherical_cup():
    R1, R2 = 20.0, 50.0
    ball = Graph(cap(R1, False), up=-1.0)
    cup = Graph(cap(R2, False), up=1.0)  # concave: outward normal toward the cup's centre
    e = contact_ellipse_from_surfaces(ball, O, I3, cup, O, I3, DELTA)
    lam = 1 / R1 - 1 / R2
    np.testing.assert_allclose(e.semi_axes, np.sqrt(2 * DELTA / lam), rtol=1e-6)


def test_crossed_cylinders_axes_and_orientation():
    R1, R2 = 10.0, 40.0
    c1 = Graph(cylinder_x(R1), up=-1.0)  # curved in y with radius R1
    c2 = Graph(cylinder_y_below(R2), up=1.0)  # curved in x with radius R2
    e = contact_ellipse_from_surfaces(c1, O, I3, c2, O, I3, DELTA)
    np.testing.assert_allclose(e.relative_curvatures, [1 / R2, 1 / R1], rtol=1e-6)
    np.testing.assert_allclose(e.semi_axes, [np.sqrt(2 * DELTA * R2), np.sqrt(2 * DELTA * R1)], rtol=1e-6)
    assert abs(e.directions[0] @ [1, 0, 0]) == pytest.approx(1.0, abs=1e-9)  # major axis along x
    # the same from principal curvatures and directions
    k1, d1 = principal_curvatures(c1, O)
    k2, d2 = principal_curvatures(c2, O)
    e2 = contact_ellipse(k1, d1, k2, d2, [0, 0, 1.0], DELTA)
    np.testing.assert_allclose(e2.semi_axes, e.semi_axes, rtol=1e-9)


def test_bad_approach():
    with pytest.raises(DesignError, match="approach"):
        contact_ellipse(np.ones(2), np.eye(3)[:2], np.ones(2), np.eye(3)[:2], [0, 0, 1.0], approach=0.0)


def test_numerical_principal_curvatures_match_closed_form_logspiral():
    pair = conjugate_logspiral_pair()
    s = pair.pinion
    q = np.array(s.reference_params)
    g = ls.geometry(q[0], q[1], s.rho0, s.delta, s.beta)
    # the convention of docs/theory/logspiral.md#flank-types (k > 0 toward n) -> ours (convex positive w.r.t. n_out =
    # sign(psi) n): k_ours = -sign(psi) k
    closed = np.sort(-np.sign(g["psi"]) * np.array([g["k1"], g["k2"]]))

    class FD:  # no analytic derivatives: central differences of evaluate
        fd_step = (1e-5, 1e-5)
        evaluate = staticmethod(s.evaluate)

    for surf in (s, FD()):
        k, _ = principal_curvatures(surf, q)
        np.testing.assert_allclose(k, closed, rtol=1e-6)


def _separation_radius(res, pinion, gear, theta, delta, hint):
    """Distance from the contact point, along the tangent direction theta, where the separation of the two surfaces
    measured along the common normal equals delta (each surface intersected with the normal line by fsolve)."""
    i, k = 20, int(res.pair[20])
    c, n = res.point_fixed[i, k], res.normal_fixed[i, k]
    d1, d2 = res.ellipse_dirs1[i]
    R1 = rot_z(res.phi1[i] + 2 * np.pi * res.pairs[k] / res.z1)
    a2 = np.array([np.sin(res.shaft_angle), 0, np.cos(res.shaft_angle)])
    R2 = rot_axis(a2, res.phi2_pairs[i, k] - 2 * np.pi * res.pairs[k] / res.z2) @ rot_y(res.shaft_angle)
    u = np.cos(theta) * (R1 @ d1) + np.sin(theta) * (R1 @ d2)

    def height(surface, R, q0, rho):
        def f(y):  # unknowns shifted by +1: MINPACK's difference step is useless for unknowns near 1e-17
            y = y - 1.0
            return R @ surface.evaluate(y[:2])[0] - (c + rho * u + y[2] * n)
        y, info, ier, msg = fsolve(f, np.r_[q0, 0.0] + 1.0, xtol=1e-13, full_output=True)
        assert np.max(np.abs(info["fvec"])) < 1e-9, msg
        return y[2] - 1.0

    def sep(rho):
        return height(gear, R2, res.params2[i, k], rho) - height(pinion, R1, res.params1[i, k], rho) - delta

    return brentq(sep, 0.5 * hint, 2.0 * hint, xtol=1e-12)


@pytest.mark.parametrize("theta", [0.0, np.pi / 4, np.pi / 2, 2.0])
def test_tca_ellipse_against_direct_separation(theta):
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    errs = []
    for delta in (DELTA, DELTA / 16):
        res = solve_tca(crowned, pair.gear, kin, n_positions=41, approach=delta)
        a, b = res.semi_axes[20]
        r_ell = 1 / np.hypot(np.cos(theta) / a, np.sin(theta) / b)
        errs.append(abs(_separation_radius(res, crowned, pair.gear, theta, delta, r_ell) / r_ell - 1))
    print(f"theta={theta:.3f}: relative radius errors {errs}")
    assert errs[0] < 2e-2  # cubic terms of the separation at the Gleason approach
    assert errs[1] < errs[0] / 3.5  # and they vanish like sqrt(delta): ratio 4 expected, 4.0-4.1 measured
