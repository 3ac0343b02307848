"""Forging draft (seed 000 §5.1): corrected inequalities of docs/theory/logspiral.md, Eq. (S13), area fraction and its
convergence."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate
from scipy.optimize import brentq

from spiralbevel.conventions import Side
from spiralbevel.errors import DesignError
from spiralbevel.geometry.domain import ParallelogramDomain
from spiralbevel.manufacturing.draft import analytic_failing_fraction, draft_map

from ._cases import BETA, DELTA, Flank, make

PSI_WIDE = (0.3, 0.8)  # straddles |beta| = 0.569 rad: both pass and fail regions on the convex flank


def _raw_point(varphi, phi, rho0, delta, beta):
    """Seed 000 Eq. (16) written out independently of the kernel."""
    psi = (varphi - phi) * math.sin(delta)
    rho = rho0 * math.exp(phi * math.sin(delta) / math.tan(beta))
    t = np.array([math.sin(delta) * math.cos(varphi), math.sin(delta) * math.sin(varphi), math.cos(delta)])
    w = np.array([math.sin(varphi), -math.cos(varphi), 0.0])
    return rho * (math.cos(psi) * t + math.sin(psi) * w)


def _outward_normal_fd(varphi, phi, f, h=1e-5):
    """Outward normal from finite differences of the raw surface, oriented without the docs/theory/logspiral.md, Eqs.
    (S4), (S9) sign rule: the
    involute profile (the varphi-curve) is convex, so its second derivative points into the material."""
    args = (f.rho0, f.base_cone_angle, f.spiral_angle)
    P = lambda a, b: _raw_point(a, b, *args)  # noqa: E731
    ru = (P(varphi + h, phi) - P(varphi - h, phi)) / (2 * h)
    rv = (P(varphi, phi + h) - P(varphi, phi - h)) / (2 * h)
    ruu = (P(varphi + h, phi) - 2 * P(varphi, phi) + P(varphi - h, phi)) / h**2
    n = np.cross(ru, rv)
    n /= np.linalg.norm(n)
    return -n if n @ ruu > 0 else n


@pytest.mark.parametrize("beta_sign", [1, -1])
@pytest.mark.parametrize("psi_sign", [1, -1])
def test_corrected_inequalities_eight_sign_cases(beta_sign, psi_sign):
    # hand x branch x (|psi| below / above |beta|) = 8 cases, docs/theory/logspiral.md, Eq. (S13)
    flank, domain = make(beta_sign, psi_sign, psi=PSI_WIDE)
    res = draft_map(flank, domain, n_phi=7, n_psi=41)
    convex = psi_sign == beta_sign
    assert res.side is (Side.CONVEX if convex else Side.CONCAVE)
    gap = np.abs(res.varphi - res.phi) - abs(flank.spiral_angle) / math.sin(DELTA)
    away = np.abs(gap) > 1e-9
    assert (gap > 0).any() and (gap < 0).any()  # both sides of |beta| are on the grid
    expected = gap >= 0 if convex else np.ones_like(gap, bool)
    assert np.array_equal(res.draftable[away], expected[away])
    # independent normal (finite differences, orientation from the convex profile) gives the same n_out . z
    for i, j in [(0, 0), (3, 10), (6, 40), (2, 25)]:
        n_fd = _outward_normal_fd(res.varphi[i, j], res.phi[i, j], flank)
        assert res.normal_dot_die[i, j] == pytest.approx(n_fd[2], abs=1e-8)
    # die opening the other way (-z): the convex flank fails where it passed and the concave flank fails everywhere
    rev = draft_map(flank, domain, die_direction=(0, 0, -2.5), n_phi=7, n_psi=41)
    np.testing.assert_allclose(rev.normal_dot_die, -res.normal_dot_die, atol=1e-15)
    expected_rev = gap <= 0 if convex else np.zeros_like(gap, bool)
    assert np.array_equal(rev.draftable[away], expected_rev[away])


@settings(max_examples=40, deadline=None)
@given(beta=st.floats(0.05, 1.2), delta=st.floats(0.1, 1.4), a=st.floats(0.01, 0.5), width=st.floats(0.01, 0.5),
       beta_sign=st.sampled_from([1, -1]), psi_sign=st.sampled_from([1, -1]))
def test_inequalities_random_flanks(beta, delta, a, width, beta_sign, psi_sign):
    lo, hi = a, a + width
    if psi_sign != beta_sign and hi + beta >= math.pi / 2:
        return  # outside |psi - beta| < 90 deg n_out = sign(psi) n no longer holds (rejected with DesignError)
    flank, domain = make(beta_sign, psi_sign, psi=(lo, hi), delta=delta, beta=beta)
    res = draft_map(flank, domain, n_phi=3, n_psi=9)
    gap = np.abs(res.varphi - res.phi) - beta / math.sin(delta)
    away = np.abs(gap) > 1e-9
    expected = gap >= 0 if psi_sign == beta_sign else np.ones_like(gap, bool)
    assert np.array_equal(res.draftable[away], expected[away])


def _fraction_dblquad(flank, domain):
    """Failing area / total area for v_d = +z by scipy dblquad of |r_varphi x r_phi| over the (varphi, phi)
    parallelogram, with the failing set |varphi - phi| < |beta| / sin(delta) (convex flank) as integration limits."""
    s = math.sin(domain.base_cone_angle)
    b = abs(flank.spiral_angle)

    def dA(varphi, phi):  # |r_varphi| |r_phi| from Eqs. (19)-(20), F = 0
        psi = (varphi - phi) * s
        rho = flank.rho0 * math.exp(phi * s / math.tan(flank.spiral_angle))
        return rho * abs(math.sin(psi)) * math.cos(domain.base_cone_angle) * rho * s / abs(math.sin(flank.spiral_angle))

    def area(psi_a, psi_b):  # psi_a < psi_b
        val, _ = integrate.dblquad(dA, domain.phi_min, domain.phi_max, lambda ph: ph + psi_a / s,
                                   lambda ph: ph + psi_b / s, epsabs=0, epsrel=1e-12)
        return val

    total = area(domain.psi_min, domain.psi_max)
    if domain.psi_min > 0:
        fa, fb = domain.psi_min, min(domain.psi_max, max(domain.psi_min, b))
    else:
        fa, fb = max(domain.psi_min, min(domain.psi_max, -b)), domain.psi_max
    return area(fa, fb) / total if fb > fa else 0.0


@pytest.mark.parametrize("beta_sign,psi_sign", [(1, 1), (-1, -1), (1, -1)])
def test_area_fraction_converges_at_second_order(beta_sign, psi_sign):
    flank, domain = make(beta_sign, psi_sign, psi=PSI_WIDE)
    ref = _fraction_dblquad(flank, domain) if beta_sign == psi_sign else 0.0
    closed = analytic_failing_fraction(flank, domain)
    assert closed == pytest.approx(ref, rel=1e-10, abs=1e-14)
    errs = []
    for n in (9, 17, 33, 65):
        res = draft_map(flank, domain, n_phi=n, n_psi=n)
        assert res.analytic_fraction == closed
        errs.append(abs(res.failing_area_fraction - ref))
    if beta_sign != psi_sign:
        assert max(errs) == 0.0  # concave: nothing fails
        return
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all((rates > 1.8) & (rates < 2.3)), rates  # O(h^2): linear interpolation + exact clipping
    assert errs[-1] < 2e-5


def test_area_element_and_total_area_against_the_raw_surface():
    flank, domain = make(1, 1, psi=PSI_WIDE)
    res = draft_map(flank, domain, n_phi=65, n_psi=65)
    # total area by dblquad of |r_varphi x r_phi| from finite differences of the raw Eq. (16), rtol ~ FD error
    s = math.sin(DELTA)

    def dA(varphi, phi, h=1e-5):
        P = lambda a, b: _raw_point(a, b, flank.rho0, DELTA, flank.spiral_angle)  # noqa: E731
        ru = (P(varphi + h, phi) - P(varphi - h, phi)) / (2 * h)
        rv = (P(varphi, phi + h) - P(varphi, phi - h)) / (2 * h)
        return float(np.linalg.norm(np.cross(ru, rv)))

    total, _ = integrate.dblquad(dA, domain.phi_min, domain.phi_max, lambda ph: ph + domain.psi_min / s,
                                 lambda ph: ph + domain.psi_max / s, epsrel=1e-9)
    assert res.total_area == pytest.approx(total, rel=2e-4)  # grid O(h^2) with h = 1/64 of the domain


def _fraction_tilted_reference(flank, domain, v):
    """Reference for any die direction: for each phi, roots of n_out.v in psi (brentq), quad over the failing
    intervals; outer quad over phi. Uses only Eqs. (16), (21) written out here."""
    d, b = domain.base_cone_angle, flank.spiral_angle
    s = math.sin(d)
    sgn = 1.0 if domain.psi_min > 0 else -1.0

    def g(psi, phi):
        varphi = phi + psi / s
        t = np.array([s * math.cos(varphi), s * math.sin(varphi), math.cos(d)])
        w = np.array([math.sin(varphi), -math.cos(varphi), 0.0])
        return sgn * float((math.cos(psi - b) * w - math.sin(psi - b) * t) @ v)

    def jac(psi, phi):
        rho = flank.rho0 * math.exp(phi * s / math.tan(b))
        return rho * rho * abs(math.sin(psi)) * math.cos(d) / abs(math.sin(b))

    def inner(phi, failing):
        grid = np.linspace(domain.psi_min, domain.psi_max, 201)
        vals = [g(x, phi) for x in grid]
        pts = [domain.psi_min]
        for k in range(200):
            if vals[k] * vals[k + 1] < 0:
                pts.append(brentq(g, grid[k], grid[k + 1], args=(phi,), xtol=1e-15))
        pts.append(domain.psi_max)
        tot = 0.0
        for a, c in zip(pts[:-1], pts[1:]):
            if not failing or g(0.5 * (a + c), phi) > 0:
                tot += integrate.quad(jac, a, c, args=(phi,), epsabs=0, epsrel=1e-12)[0]
        return tot

    fail = integrate.quad(inner, domain.phi_min, domain.phi_max, args=(True,), epsabs=0, epsrel=1e-10, limit=200)[0]
    total = integrate.quad(inner, domain.phi_min, domain.phi_max, args=(False,), epsabs=0, epsrel=1e-10)[0]
    return fail / total


def test_tilted_die_direction_converges_to_independent_quadrature():
    flank, domain = make(1, 1, psi=PSI_WIDE)
    v = np.array([0.35, -0.2, 1.0])
    ref = _fraction_tilted_reference(flank, domain, v / np.linalg.norm(v))
    assert 0.05 < ref < 0.95  # a genuinely mixed case
    errs = [abs(draft_map(flank, domain, v, n_phi=n, n_psi=n).failing_area_fraction - ref) for n in (17, 33, 65)]
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(rates > 1.6), (errs, rates)  # second order (a curved boundary crossing the cells)
    res = draft_map(flank, domain, v, n_phi=9, n_psi=9)
    assert res.boundary is None and res.analytic_fraction is None


def test_left_hand_mirror_has_the_same_draft():
    # mirror in the xz-plane: v -> (vx, -vy, vz); the failing fraction is unchanged
    fr, dr = make(1, 1, psi=PSI_WIDE)
    fl, dl = make(-1, -1, psi=PSI_WIDE)
    v = np.array([0.3, 0.4, 1.0])
    a = draft_map(fr, dr, v, n_phi=33, n_psi=33)
    b = draft_map(fl, dl, v * [1, -1, 1], n_phi=33, n_psi=33)
    assert a.failing_area_fraction == pytest.approx(b.failing_area_fraction, rel=1e-12)
    assert a.total_area == pytest.approx(b.total_area, rel=1e-12)


def test_analytic_boundary_line():
    flank, domain = make(1, 1, psi=PSI_WIDE)
    res = draft_map(flank, domain, n_phi=5, n_psi=5)
    assert res.boundary_psi == flank.spiral_angle
    np.testing.assert_allclose(res.boundary[:, 0] - res.boundary[:, 1], flank.spiral_angle / math.sin(DELTA))
    np.testing.assert_allclose(res.boundary[:, 1], [domain.phi_min, domain.phi_max])
    conc, cdom = make(1, -1, psi=PSI_WIDE)
    r2 = draft_map(conc, cdom, n_phi=5, n_psi=5)
    assert r2.boundary is None and r2.passes and r2.failing_area_fraction == 0.0


def test_whole_convex_flank_below_beta_fails():
    flank, domain = make(1, 1, psi=(0.2, 0.4))  # |psi| < beta everywhere: seed 000 Fig. 8 "damaged domain"
    res = draft_map(flank, domain, n_phi=5, n_psi=5)
    assert not res.draftable.any() and res.failing_area_fraction == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("v", [(0, 0, 0), (0, 0, float("nan")), (1, 2), "up"])
def test_bad_die_direction(v):
    flank, domain = make(1, 1)
    with pytest.raises(DesignError, match="die_direction"):
        draft_map(flank, domain, v)


@pytest.mark.parametrize("kw", [dict(n_phi=1), dict(n_psi=2.5), dict(n_phi=True)])
def test_bad_grid(kw):
    flank, domain = make(1, 1)
    with pytest.raises(DesignError, match="n_p"):
        draft_map(flank, domain, **kw)


def test_analytic_fraction_needs_axial_direction_and_valid_flank():
    flank, domain = make(1, 1)
    with pytest.raises(DesignError, match="parallel to"):
        analytic_failing_fraction(flank, domain, (1, 0, 1))
    with pytest.raises(DesignError, match="spiral_angle"):
        draft_map(Flank(100.0, DELTA, 0.0), domain)
    with pytest.raises(DesignError, match="rho0"):
        draft_map(Flank(-1.0, DELTA, BETA), domain)
    with pytest.raises(DesignError, match="psi"):
        draft_map(flank, ParallelogramDomain(0.0, 0.5, -1.4, -1.2, DELTA))  # |psi - beta| >= 90 deg


@pytest.mark.parametrize("coords", ["varphi", "psi"])
def test_plot_draft_draws_regions_and_both_boundaries(coords, tmp_path):
    import matplotlib.pyplot as plt

    from spiralbevel.viz.draft_plot import plot_draft

    flank, domain = make(1, 1, psi=PSI_WIDE)
    res = draft_map(flank, domain, n_phi=21, n_psi=41)
    fig = plot_draft(res, coords=coords)
    ax = fig.axes[0]
    assert len(ax.collections) >= 2  # the draft-angle mesh and the zero-draft contour
    dashed = [ln for ln in ax.lines if ln.get_linestyle() == "--"]
    assert len(dashed) == 1
    xs = dashed[0].get_xdata()
    if coords == "psi":
        np.testing.assert_allclose(xs, np.degrees(flank.spiral_angle))
    else:
        np.testing.assert_allclose(xs, np.degrees(res.boundary[:, 0]))
    fig.savefig(tmp_path / "draft.png", dpi=60)
    plt.close(fig)
    fig2, ax2 = plt.subplots()
    assert plot_draft(draft_map(*make(1, -1), n_phi=5, n_psi=5), ax=ax2) is fig2  # concave: no boundary
    assert not [ln for ln in ax2.lines if ln.get_linestyle() == "--"]
    plt.close(fig2)
    with pytest.raises(DesignError, match="coords"):
        plot_draft(res, coords="xy")


def test_accepts_the_public_logspiral_flank():
    # the functions take any object with rho0/base_cone_angle/spiral_angle; the public class's outward normals
    # (computed by its own evaluate()) give the same n_out . v_d
    mod = pytest.importorskip("spiralbevel.geometry.logspiral")
    flank = mod.LogSpiralFlank(100.0, DELTA, -BETA)
    domain = ParallelogramDomain(-0.6, 0.0, -0.8, -0.3, DELTA)
    v = np.array([0.2, 0.1, 1.0])
    res = draft_map(flank, domain, v, n_phi=9, n_psi=9)
    normal = flank.evaluate(res.varphi, res.phi).normal
    np.testing.assert_allclose(res.normal_dot_die, normal @ (v / np.linalg.norm(v)), atol=1e-14)
