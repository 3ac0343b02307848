"""Envelope solver on log-spiral flanks (the closed form is used only as the oracle, never by the solver)."""

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from _meshing_helpers import PAIRS, flank_points_only, gear_candidate, make_case, wrap
from spiralbevel.errors import ConvergenceError, DesignError, NoContactError
from spiralbevel.meshing.conjugate import compare_conjugate, logspiral_invariant, nearest_points
from spiralbevel.meshing.envelope import solve_contact_line, solve_envelope
from spiralbevel.meshing.kinematics import BevelPairKinematics


def _c(case):
    """arccos(tan d1 / tan g1): half the angle between the two planes of action (docs/theory/gearing.md, Eq. (M7))."""
    return np.arccos(np.tan(case.delta1) / np.tan(case.kin.pitch_angle_pinion))


@pytest.mark.parametrize("pair", PAIRS)
@pytest.mark.parametrize("branch", [1, -1])
def test_meshing_roots_match_closed_form(pair, branch):
    # docs/theory/gearing.md, Eqs. (M1)-(M8): phi1* = +-arccos(tan d1 / tan g1) - varphi for a seed-000 flank; +1 <->
    # "+" with outward n, psi>0
    case = make_case(*pair)
    env = solve_envelope(case.surface, case.kin, case.u, case.v, branch=branch)
    varphi = case.u + case.v / np.sin(case.delta1)
    assert env.converged.all()
    assert np.max(np.abs(wrap(env.phi1 - (branch * _c(case) - varphi)))) < 1e-12
    assert np.max(np.abs(env.phi1)) <= np.pi  # within pi of the default guess 0
    assert env.residual.max() < 1e-12


def test_nearest_root_and_guess_window():
    case = make_case(*PAIRS[0])
    varphi = case.u + case.v / np.sin(case.delta1)
    guess = -_c(case) - varphi + 0.1 + 2 * np.pi  # near the "-" root, one turn away
    env = solve_envelope(case.surface, case.kin, case.u, case.v, branch=None, phi1_guess=guess)
    assert np.max(np.abs(env.phi1 - (-_c(case) - varphi + 2 * np.pi))) < 1e-12


def test_vectorized_roots_equal_per_point_scipy():
    case = make_case(*PAIRS[2])
    env = solve_envelope(case.surface, case.kin, case.u, case.v)
    r1, n1 = case.surface(case.u, case.v)
    for i, j in [(0, 0), (5, 3), (12, 14), (30, 7), (17, 11)]:
        def f(a, i=i, j=j):
            return float(case.kin.meshing_function(r1[i, j], n1[i, j], a))
        x0 = env.phi1[i, j]
        root = brentq(f, x0 - 0.2, x0 + 0.2, xtol=1e-15, rtol=1e-15)
        assert abs(env.phi1[i, j] - root) < 1e-12
        root_fs = fsolve(lambda a: f(a[0]), x0 + 0.05, xtol=1e-14)[0]
        assert abs(env.phi1[i, j] - root_fs) < 1e-12


def test_envelope_condition_by_differentiating_the_family():
    # independent second method (docs/theory/gearing.md#conjugacy): det[r2_u, r2_v, r2_phi1] = 0 at the solved phi1,
    # where
    # r2(u, v, phi1) = M(phi1) r1(u, v) is the family of member-1 surfaces in the gear frame (central differences)
    case = make_case(*PAIRS[4])
    u, v = case.u[::6], case.v[:, ::4]
    env = solve_envelope(case.surface, case.kin, u, v)
    h = 1e-5

    def fam(du, dv, dp):
        r = case.surface(u + du, v + dv)[0]
        return case.kin.to_gear(r, env.phi1 + dp)

    ru = (fam(h, 0, 0) - fam(-h, 0, 0)) / (2 * h)
    rv = (fam(0, h, 0) - fam(0, -h, 0)) / (2 * h)
    rp = (fam(0, 0, h) - fam(0, 0, -h)) / (2 * h)
    det = np.einsum("...i,...i->...", np.cross(ru, rv), rp)
    scale = np.linalg.norm(np.cross(ru, rv), axis=-1) * np.linalg.norm(rp, axis=-1)
    assert np.max(np.abs(det) / scale) < 1e-8
    # and it is not identically zero off the solution
    rp_off = (case.kin.to_gear(case.surface(u, v)[0], env.phi1 + 0.1 + h)
              - case.kin.to_gear(case.surface(u, v)[0], env.phi1 + 0.1 - h)) / (2 * h)
    ru_off = (case.kin.to_gear(case.surface(u + h, v)[0], env.phi1 + 0.1)
              - case.kin.to_gear(case.surface(u - h, v)[0], env.phi1 + 0.1)) / (2 * h)
    rv_off = (case.kin.to_gear(case.surface(u, v + h)[0], env.phi1 + 0.1)
              - case.kin.to_gear(case.surface(u, v - h)[0], env.phi1 + 0.1)) / (2 * h)
    det_off = np.einsum("...i,...i->...", np.cross(ru_off, rv_off), rp_off)
    assert np.min(np.abs(det_off) / scale) > 1e-3


@pytest.mark.parametrize("pair", PAIRS)
def test_conjugate_of_logspiral_is_mating_logspiral(pair):
    # docs/theory/gearing.md, Eqs. (M1)-(M8): base cones sin d1/sin g1 = sin d2/sin g2 -> envelope is the seed-000 flank
    # (d2, beta2 = -beta, psi2 > 0) on the plane +arccos; distance <= 1e-9 mm, 1 - |n.n| <= 1e-12
    case = make_case(*pair)
    env = solve_envelope(case.surface, case.kin, case.u, case.v, branch=1)
    assert np.all(env.points[..., 2] > 0)  # gear body toward +z (docs/conventions.md)
    inv = logspiral_invariant(env.points, case.delta2, -case.beta)
    assert np.ptp(inv) < 1e-12
    cand, bounds = gear_candidate(env.points, case.delta2, -case.beta)
    rep = compare_conjugate(env.points, env.normals, cand, bounds, tol=1e-12,
                            invariant=lambda x: logspiral_invariant(x, case.delta2, -case.beta))
    assert rep.max_distance <= 1e-9  # measured <= 1e-12 with tol=1e-12 (docs/theory/gearing.md#conjugacy: 2.9e-13)
    assert rep.max_distance <= 1e-12
    assert rep.max_normal_mismatch <= 1e-12
    assert rep.n_outside == 0 and rep.is_conjugate
    # outward normals: the envelope normal is the outward normal of the psi2 > 0 gear flank (n,
    # docs/theory/logspiral.md, Eq. (S2) (#surface))
    foot = nearest_points(env.points, cand, bounds)
    assert np.min(np.einsum("ij,ij->i", foot.normals, env.normals.reshape(-1, 3))) > 1 - 1e-12


@pytest.mark.parametrize("pair", PAIRS[::2])
def test_other_plane_of_action_gives_the_psi_negative_branch(pair):
    case = make_case(*pair)
    env = solve_envelope(case.surface, case.kin, case.u, case.v, branch=-1)
    inv = logspiral_invariant(env.points, case.delta2, -case.beta, psi_sign=-1.0)
    assert np.ptp(inv) < 1e-12


def test_wrong_base_cone_is_reported():
    # docs/theory/gearing.md, Eqs. (M1)-(M8): d2 + 0.5 deg -> invariant spread ~1.3e-3, distance ~0.14 mm, mismatch
    # ~6e-5 (their grid);
    # here the spread, distance and mismatch must be far above the conjugate-case values and the report must flag it
    case = make_case(*PAIRS[0])
    env = solve_envelope(case.surface, case.kin, case.u, case.v)
    d2 = case.delta2 + np.radians(0.5)
    cand, bounds = gear_candidate(env.points, d2, -case.beta)
    rep = compare_conjugate(env.points, env.normals, cand, bounds,
                            invariant=lambda x: logspiral_invariant(x, d2, -case.beta))
    assert not rep.is_conjugate
    assert rep.max_distance > 1e-2
    assert rep.invariant_spread > 1e-4
    assert rep.max_normal_mismatch > 1e-6
    assert "NOT CONJUGATE" in rep.summary()


@pytest.mark.parametrize("pair", PAIRS)
def test_contact_line_is_planar_log_spiral_in_plane_of_action(pair):
    case = make_case(*pair)
    kin, phi1 = case.kin, 0.05
    u = np.linspace(-0.3, 0.0, 13)
    c = _c(case)
    cl = solve_contact_line(case.surface, kin, phi1, u, (1e-3, 1.0))
    assert cl.converged.all()
    # closed form: varphi = +arccos(...) - phi1 (the first sign change from psi = 0+ is the "+" plane here)
    assert np.max(np.abs(cl.u + cl.v / np.sin(case.delta1) - (c - phi1))) < 1e-12
    x = cl.contact_points
    # plane through the apex: smallest singular vector of the point matrix
    nu = np.linalg.svd(x)[2][-1]
    assert np.max(np.abs(x @ nu)) < 1e-12 * np.max(np.linalg.norm(x, axis=1)) + 1e-12
    assert abs(np.dot(nu, kin.pitch_line)) < 1e-13
    assert abs(abs(np.dot(nu, kin.pinion_axis)) - np.sin(case.delta1)) < 1e-13
    assert abs(abs(np.dot(nu, kin.gear_axis)) - np.sin(case.delta2)) < 1e-13
    # planar log spiral with pole O and angle beta: d ln rho / d theta = +-cot(beta) (polar angle in the plane)
    e1 = kin.pitch_line
    e2 = np.cross(nu, e1)
    theta = np.unwrap(np.arctan2(x @ e2, x @ e1))
    lnrho = np.log(np.linalg.norm(x, axis=1))
    slope = np.diff(lnrho) / np.diff(theta)
    assert np.max(np.abs(np.abs(slope) - abs(1 / np.tan(case.beta)))) < 1e-10
    # the same points, seen from the gear, lie on the conjugate gear flank
    inv = logspiral_invariant(cl.points, case.delta2, -case.beta)
    env = solve_envelope(case.surface, kin, case.u, case.v)
    ref = logspiral_invariant(env.points[:1, :1], case.delta2, -case.beta)
    period = 2 * np.pi * np.sin(case.delta2) / abs(np.tan(case.beta))
    assert np.max(np.abs(wrap((inv - ref) * 2 * np.pi / period))) * period / (2 * np.pi) < 1e-12


def test_contact_line_equals_per_point_brentq():
    case = make_case(*PAIRS[3])
    phi1, u = -0.1, np.linspace(-0.3, 0.1, 9)
    # the window excludes the other plane of action (at psi ~ 0.01 for u = -0.3)
    cl = solve_contact_line(case.surface, case.kin, phi1, u, (0.05, 1.0))
    for k in range(u.size):
        def f(vv, k=k):
            r, n = case.surface(u[k], vv)
            return float(case.kin.meshing_function(r, n, phi1))

        root = brentq(f, cl.v[k] - 0.01, cl.v[k] + 0.01, xtol=1e-15, rtol=1e-15)
        assert abs(cl.v[k] - root) < 1e-12


def test_contact_line_solve_for_u_and_v0():
    case = make_case(*PAIRS[0])
    cl_v = solve_contact_line(case.surface, case.kin, 0.0, [-0.2, -0.1], (1e-3, 1.0))
    # given psi (v), solve phi (u): the same contact points
    cl_u = solve_contact_line(case.surface, case.kin, 0.0, cl_v.v, (-0.5, 0.5), solve_for="u")
    assert np.allclose(cl_u.u, [-0.2, -0.1], atol=1e-12)
    assert np.allclose(cl_u.v, cl_v.v, atol=0)
    # u = 0.5: both planes of action cross the psi < 0 window, at psi = (+-c - 0.5) sin d1; without v0 the first
    # sign change from the low end (the "-" plane) is taken, with v0 the one nearest to it
    sd, c = np.sin(case.delta1), _c(case)
    first = solve_contact_line(case.surface, case.kin, 0.0, [0.5], (-1.0, -1e-3))
    near = solve_contact_line(case.surface, case.kin, 0.0, [0.5], (-1.0, -1e-3), v0=[-0.05])
    assert abs(first.v[0] - (-c - 0.5) * sd) < 1e-12
    assert abs(near.v[0] - (c - 0.5) * sd) < 1e-12


def test_finite_difference_normals():
    # surface given as points only: normals from 4th-order central differences (error ~ step^4)
    case = make_case(*PAIRS[2], n_u=7, n_v=5)
    ref = solve_envelope(case.surface, case.kin, case.u, case.v)
    r, n = case.surface(case.u, case.v)
    h = 1e-6
    cross = np.cross(case.surface(case.u + h, case.v)[0] - r, case.surface(case.u, case.v + h)[0] - r)
    sign = np.sign(np.einsum("...i,...i->...", cross, n))
    assert np.all(sign == sign.flat[0])
    fd = solve_envelope(flank_points_only(100.0, case.delta1, case.beta), case.kin, case.u, case.v,
                        orientation=sign.flat[0])
    assert np.max(np.abs(fd.phi1 - ref.phi1)) < 1e-9
    assert np.max(np.abs(fd.points - ref.points)) < 1e-7
    assert np.min(np.einsum("...i,...i->...", fd.normals, ref.normals)) > 1 - 1e-12


def test_no_contact_raises_with_position():
    # axial plane y = 0 (n = e_y): f = -v sin g1 cos phi1 + u cos g1 has no root when u / v > tan g1
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    def plane(u, v):
        return (np.stack([u, 0 * u, v], -1), np.stack([0 * u, 1 + 0 * u, 0 * u], -1))
    with pytest.raises(NoContactError, match="index"):
        solve_envelope(plane, kin, np.array([10.0, 80.0]), np.array([100.0, 100.0]))
    res = solve_envelope(plane, kin, np.array([10.0, 80.0]), np.array([100.0, 100.0]), strict=False)
    assert res.converged.tolist() == [True, False]
    assert np.isnan(res.points[1]).all() and np.isfinite(res.points[0]).all()
    case = make_case(*PAIRS[0])
    with pytest.raises(NoContactError, match="phi1"):
        solve_contact_line(case.surface, kin, 0.0, [0.5], (1e-3, 0.01))


def test_bad_arguments():
    case = make_case(*PAIRS[0])
    with pytest.raises(DesignError, match="branch"):
        solve_envelope(case.surface, case.kin, 0.0, 0.1, branch=2)
    with pytest.raises(DesignError, match="v_bounds"):
        solve_contact_line(case.surface, case.kin, 0.0, [0.0], (1.0, 0.0))
    with pytest.raises(DesignError, match="solve_for"):
        solve_contact_line(case.surface, case.kin, 0.0, [0.0], (0.0, 1.0), solve_for="w")


def _reparametrized(case):
    """The same flank with v -> v + v^2 / 2: the contact-rotation angle is no longer linear in v, so the
    closed-form secant start is not the root and the safeguarded Newton has to work."""
    return lambda u, v: case.surface(u, v + 0.5 * v ** 2)


def test_convergence_error_reports_iterations():
    case = make_case(*PAIRS[0])
    with pytest.raises(ConvergenceError) as err:
        solve_contact_line(_reparametrized(case), case.kin, 0.0, [-0.2, -0.1], (1e-3, 0.8), max_iter=1)
    assert err.value.iterations == 1 and err.value.residual > 0


def test_contact_line_start_is_exact_on_logspiral_and_newton_finishes_elsewhere():
    # log-spiral: the contact rotation phi1*(v) = +-c - u - v / sin d1 is linear in v (Eq. (M7)), so the secant of the
    # angle between the bracket ends is the root (0 Newton iterations); on the reparametrized flank it is not, and the
    # result must still equal a per-point brentq on the rotation-matrix form of f (same round-off bound as above)
    case = make_case(*PAIRS[1])
    u = np.linspace(-0.3, 0.0, 11)
    cl = solve_contact_line(case.surface, case.kin, 0.05, u, (1e-3, 1.0))
    assert cl.iterations == 0 and cl.converged.all()
    surf = _reparametrized(case)
    cl2 = solve_contact_line(surf, case.kin, 0.05, u, (1e-3, 0.8))
    assert cl2.iterations > 0 and cl2.converged.all()
    for k in range(u.size):
        def f(vv, k=k):
            r, n = surf(u[k], vv)
            return float(case.kin.meshing_function(r, n, 0.05))

        root = brentq(f, cl2.v[k] - 0.01, cl2.v[k] + 0.01, xtol=1e-15, rtol=1e-15)
        assert abs(cl2.v[k] - root) < 1e-12
    # the same contact points as on the original parametrization (points ~120 mm, roots to ~1e-15: measured 6e-14 mm)
    assert np.max(np.abs(cl2.pinion_points - cl.pinion_points)) < 1e-12


def test_rigid_rotation_of_the_flank_only_shifts_phi1():
    # invariance: turning the member-1 surface by a about a1 shifts every contact rotation by -a and turns the
    # conjugate surface by -(z1/z2) a about the gear axis
    case = make_case(*PAIRS[1], n_u=5, n_v=4)
    a = 0.37
    Rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    def turned(u, v):
        return tuple(x @ Rz.T for x in case.surface(u, v))
    e0 = solve_envelope(case.surface, case.kin, case.u, case.v)
    e1 = solve_envelope(turned, case.kin, case.u, case.v)
    assert np.max(np.abs(wrap(e1.phi1 - (e0.phi1 - a)))) < 1e-12
    b = -case.kin.ratio * a
    Rb = np.array([[np.cos(b), -np.sin(b), 0], [np.sin(b), np.cos(b), 0], [0, 0, 1]])
    assert np.max(np.abs(e1.points - e0.points @ Rb.T)) < 1e-11
