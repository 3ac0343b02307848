"""The face-milled flank as a TCA contact surface."""

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings
from spiralbevel.meshing.generated_surface import GeneratedSurface, phased_for_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics


@pytest.fixture(scope="module")
def flanks():
    b = seed001_blank()
    st = seed001_settings()
    g = generate_flank(*st[(Member.GEAR, Side.CONVEX)], b, Member.GEAR, Side.CONVEX)
    p = generate_flank(*st[(Member.PINION, Side.CONCAVE)], b, Member.PINION, Side.CONCAVE)
    return p, g


def test_evaluate_matches_flank_and_rotation(flanks):
    """(phi, psi_c) chart against the flank's own evaluation and against the (u, psi_c) chart: the same points and
    normals to round-off where both are regular (the kernel's root of the equation of meshing is the chart's phi)."""
    _, g = flanks
    s = GeneratedSurface(g, rotation=0.3)
    q = s.reference_params + np.array([[0.02, 0.01], [-0.03, -0.02], [0.0, 0.0]])
    r, n = s.evaluate(q)
    fp = g.generator.evaluate_blade(q[:, 0], q[:, 1], curvature=False)
    c, sn = np.cos(0.3), np.sin(0.3)
    R = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1]])
    assert np.allclose(r, fp.points @ R.T, atol=1e-12) and np.allclose(n, fp.normals @ R.T, atol=1e-14)
    old = g.evaluate(fp.u, q[:, 1], curvature=False)           # (u, psi_c) chart, kernel's root
    assert np.allclose(old.points, fp.points, atol=1e-11) and np.allclose(old.normals, fp.normals, atol=1e-14)
    assert np.allclose(s.cutter_angle(old.theta, q[:, 1]), q[:, 0], atol=1e-13)
    assert s.contains(s.reference_params)
    # the mean point is the reference: the chart's parameters there give the located mean point
    r0, _ = GeneratedSurface(g).evaluate(s.reference_params)
    assert np.allclose(r0, g.mean_point().point, atol=1e-9)


def test_off_surface_is_nan_not_an_exception(flanks):
    _, g = flanks
    s = GeneratedSurface(g)
    # phi = 0: the blade parameter's coefficient Omega_x sin(phi) in the equation of meshing vanishes (singular chart)
    r, n = s.evaluate(np.array([[0.0, 0.1]]))
    assert np.all(np.isnan(r)) and np.all(np.isnan(n))
    assert not s.contains(np.array([0.0, 0.1]))
    assert not s.contains(s.reference_params + np.array([0.0, 0.5]))   # far past toe or heel


def test_phased_mean_points_meet_on_the_pitch_line(flanks):
    p, g = flanks
    s1, s2 = phased_for_pair(p, g)
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    r1, n1 = s1.evaluate(s1.reference_params)
    r2, n2 = s2.evaluate(s2.reference_params)
    r2f = kin.gear_to_fixed(0.0) @ r2
    assert np.allclose(r1, r2f, atol=1e-6)          # both at the mean pitch point, A_m from the apex
    assert np.linalg.norm(r1) == pytest.approx(115.9511, abs=1e-3)
    assert abs(r1[1]) < 1e-9                         # on the pitch line in the xz-plane


# ---------------------------------------------------------------------------------------------- analytic derivatives
def _central(fun, q, h):
    """Central differences (4th order) of fun(q) -> (r, n) w.r.t. both parameters, columns stacked on the last axis."""
    cols_r, cols_n = [], []
    for j in range(2):
        e = np.zeros(2)
        e[j] = h[j]
        (r1, n1), (r2, n2) = fun(q + e), fun(q - e)
        (r3, n3), (r4, n4) = fun(q + 2 * e), fun(q - 2 * e)
        cols_r.append((8 * (r1 - r2) - (r3 - r4)) / (12 * h[j]))
        cols_n.append((8 * (n1 - n2) - (n3 - n4)) / (12 * h[j]))
    return np.stack(cols_r, -1), np.stack(cols_n, -1)


def _rel(a, b):
    return np.max(np.linalg.norm(a - b, axis=-2) / np.linalg.norm(b, axis=-2))


@pytest.mark.parametrize("phase", [0.0, 0.7])
def test_derivatives_match_central_differences(flanks, phase):
    """Closed-form dr, dn (generation_blade) against 4th-order central differences of ``evaluate``, both hands."""
    for fl in flanks:
        s = GeneratedSurface(fl, rotation=phase)
        rng = np.random.default_rng(1)
        q = s.reference_params + rng.normal(size=(40, 2)) * [0.05, 0.05]
        r, n, dr, dn = s.derivatives(q)
        r0, n0 = s.evaluate(q)
        assert np.allclose(r, r0, atol=1e-12, equal_nan=True) and np.allclose(n, n0, atol=1e-14, equal_nan=True)
        on = np.isfinite(r0[:, 0])
        assert on.all()
        dr_fd, dn_fd = _central(s.evaluate, q, (1e-5, 1e-5))
        # 4th-order differences with h = 1e-5 rad: truncation ~1e-12, rounding ~1e-16 |r| / h ~ 1e-9 relative
        assert _rel(dr, dr_fd) < 1e-7 and _rel(dn, dn_fd) < 1e-7


def _kernel_cases():
    from spiralbevel._core import generation as _g

    for s_blade in (1.0, -1.0):
        for rp in (np.inf, 400.0):
            cp = _g.cutter_params(s_blade, 0.35, 60.0, 1.2, profile_radius=rp, profile_ref=3.0)
            mp = dict(S=62.0, q=1.0, gamma=0.45, XD=0.3, XB=0.2, E=1.5, m=2.1, roll=(0.05, -0.2, 0.4, 0.1),
                      E_poly=(0.3, -0.8), E_table=(np.array([-0.37, 0.13, 0.41]), np.array([0.0, 0.02, -0.01]),
                                                   np.array([0.0, 0.3, 0.0])))  # nodes off the psi grid (kinks)
            yield s_blade, cp, mp, 60.0


def test_derivatives_with_modified_roll_offset_law_and_arc_blade():
    """The kernel with every psi_c-dependent term active (modified roll, offset polynomial and cubic table) and a
    circular-arc blade with its fillet, against central differences of the generation kernels' point and normal."""
    from spiralbevel._core import generation as _g
    from spiralbevel._core.generation_jet import generated_jet

    for s_blade, cp, mp, Rc in _kernel_cases():
        def rn(q, cp=cp, mp=mp, Rc=Rc, s_blade=s_blade):
            sol = _g.solve_contact(q[..., 0], q[..., 1], cp, mp, _g.reference_angle(q[..., 1], mp, Rc))
            r, n_h, _, _ = _g.machine_state(sol, cp, mp)
            return _g.to_member(r, sol["psi"], mp), _g.to_member(-s_blade * n_h, sol["psi"], mp, point=False)

        u = np.concatenate([np.linspace(cp["u_min"] + 0.1, cp["u_j"] - 0.05, 5), np.linspace(cp["u_j"] + 0.1, 6, 8)])
        psi = np.linspace(-0.3, 0.3, 7)
        q = np.stack(np.meshgrid(u, psi, indexing="ij"), -1).reshape(-1, 2)
        S, disc = generated_jet(q[:, 0], q[:, 1], cp, mp, Rc)
        ok = np.abs(disc) < 0.99
        assert ok.sum() > 50
        r0, n0 = rn(q)
        assert np.allclose(S[ok, :, 0], r0[ok], atol=1e-11) and np.allclose(S[ok, :, 1], n0[ok], atol=1e-14)
        dr_fd, dn_fd = _central(rn, q, (1e-4, 1e-6))
        assert _rel(S[ok, :, 2:4], dr_fd[ok]) < 1e-6 and _rel(S[ok, :, 4:6], dn_fd[ok]) < 1e-6


def test_blade_chart_against_the_u_psi_chart_and_the_equation_of_meshing():
    """The (phi, psi_c) chart (generation_blade) where the (u, psi_c) chart is regular too: same points and normals to
    round-off, derivatives related by the chain rule, u on the equation of meshing (residual n.v/|v| from the
    independent velocity code of ``Generator.meshing_residual``), and derivatives against central differences; straight
    and arc blades, both blade sides, every psi_c-dependent machine term active."""
    from spiralbevel._core import generation as _g
    from spiralbevel._core.generation_blade import blade_jet, blade_points
    from spiralbevel._core.generation_jet import generated_jet
    from spiralbevel.generation.meshing import Generator

    for _s_blade, cp, mp, Rc in _kernel_cases():
        u = np.linspace(cp["u_j"] + 0.1, 6, 8)
        psi = np.linspace(-0.3, 0.3, 7)
        U, P = (a.ravel() for a in np.meshgrid(u, psi, indexing="ij"))
        S0, disc = generated_jet(U, P, cp, mp, Rc)
        ok = np.abs(disc) < 0.99
        assert ok.sum() > 30
        U, P, S0 = U[ok], P[ok], S0[ok]
        phi = _g.solve_contact(U, P, cp, mp, _g.reference_angle(P, mp, Rc))["phi"]
        S1, u1, f_u = blade_jet(phi, P, cp, mp)
        # Newton in u (arc blade) stops at 1e-14 relative; the straight blade is one exact step
        assert np.allclose(u1, U, atol=1e-10)
        assert np.allclose(S1[..., 0], S0[..., 0], atol=1e-10) and np.allclose(S1[..., 1], S0[..., 1], atol=1e-12)
        # chain rule: d/du|psi (old) = D_phi * phi_u, d/dpsi|u (old) = D_psi + D_phi * phi_psi with phi_u = 1/u_phi,
        # phi_psi = -u_psi/u_phi, and (u_phi, u_psi) read off the new chart's dr:
        # dr_new = dr_old @ d(u, psi)/d(phi, psi)
        # -> compare dr_old @ [[u_phi, u_psi], [0, 1]] with dr_new, u_phi and u_psi by the chart's own implicit rule
        e = 1e-6
        up = (blade_points(phi + e, P, cp, mp)[1] - blade_points(phi - e, P, cp, mp)[1]) / (2 * e)
        us = (blade_points(phi, P + e, cp, mp)[1] - blade_points(phi, P - e, cp, mp)[1]) / (2 * e)
        for k in (2, 4):
            d_phi = S0[..., k] * up[:, None]
            d_psi = S0[..., k + 1] + S0[..., k] * us[:, None]
            # central differences of u (h = 1e-6): error ~1e-9 relative
            assert _rel(S1[..., k:k + 1], d_phi[..., None]) < 1e-7
            assert _rel(S1[..., k + 1:k + 2], d_psi[..., None]) < 1e-7
        res = Generator.__new__(Generator)
        res.cp, res.mp = cp, mp
        theta = phi - (np.pi - mp["q"] + P)
        assert np.max(np.abs(Generator.meshing_residual(res, u1, theta, P))) < 1e-12

        def rn(q, cp=cp, mp=mp):
            Sq, _, _ = blade_jet(q[..., 0], q[..., 1], cp, mp)
            return Sq[..., 0], Sq[..., 1]

        dr_fd, dn_fd = _central(rn, np.stack([phi, P], -1), (1e-5, 1e-5))
        assert _rel(S1[..., 2:4], dr_fd) < 1e-7 and _rel(S1[..., 4:6], dn_fd) < 1e-7


def test_derivatives_nan_off_surface_and_contains_agrees_with_evaluate(flanks):
    _, g = flanks
    s = GeneratedSurface(g)
    r, n, dr, dn = s.derivatives(np.array([[0.0, 0.1], list(s.reference_params)]))
    assert np.all(np.isnan(dr[0])) and np.all(np.isnan(dn[0])) and np.all(np.isfinite(dn[1]))
    # contains (margins of the jet's point) against the outline test on evaluated points and the blade parameter
    rng = np.random.default_rng(2)
    q = s.reference_params + rng.normal(size=(400, 2)) * [0.15, 0.3]
    pts, _ = s.evaluate(q)
    fp = g.generator.evaluate_blade(q[:, 0], q[:, 1], curvature=False)
    ol = g.outline
    with np.errstate(invalid="ignore"):
        R, h = ol.Rh(pts[:, 2], np.hypot(pts[:, 0], pts[:, 1]))
        ref = np.isfinite(pts[:, 0]) & (R >= ol.Ri) & (R <= ol.Re) & (h <= ol.h_face(R)) & (
            fp.u >= g.generator.cp["u_j"])
    got = s.contains(q)
    assert 0 < got.sum() < len(q) and np.array_equal(got, ref)
