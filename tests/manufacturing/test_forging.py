"""Forging relief (spiralbevel.manufacturing.forging): draft passes, minimality of the two feature parameters,
continuity at the start line, exact normals and curvatures against the generic differential geometry.

The flank case straddles |psi| = |beta| (seed 000 Eq. (39), corrected sign rule of the outward normal), so the
theoretical convex flank fails below that line and passes above it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from spiralbevel.errors import DesignError
from spiralbevel.geometry.diffgeom import surface_geometry
from spiralbevel.manufacturing.forging import (ForgingRelief, RelievedFlank, design_forging_relief,
                                               relieved_draft_map)

from ._cases import BETA, DELTA, make

DRAFT = math.radians(1.0)
GRID = 31  # check grid of the design and of every draft map below (a 31 x 31 design takes ~1 s)


@pytest.fixture(scope="module")
def case():
    flank, domain = make(1, 1, psi=(0.3, 0.8), phi=(0.0, 0.4))
    design = design_forging_relief(flank, domain, draft_angle=DRAFT, n_phi=GRID, n_psi=GRID)
    return flank, domain, design


def _draft(flank, domain, relief):
    return relieved_draft_map(RelievedFlank(flank, domain, relief), draft_angle=DRAFT, n_phi=GRID, n_psi=GRID)


def test_relieved_flank_passes_where_the_theoretical_one_fails(case):
    flank, domain, design = case
    theo = _draft(flank, domain, None)
    assert theo.failing_area_fraction > 0.3 and not theo.passes
    res = _draft(flank, domain, design.relief)
    assert res.passes and res.failing_area_fraction == 0.0
    # the start line lies where the theoretical flank clears the draft angle: sin(psi_s - beta) cos(delta) >= sin(1 deg)
    assert math.sin(design.relief.start_psi - BETA) * math.cos(DELTA) >= math.sin(DRAFT) - 1e-12
    assert design.max_deviation > 0 and design.volume > 0


def test_perturbing_either_parameter_toward_less_relief_fails(case):
    flank, domain, design = case
    r = design.relief
    dpsi = (domain.psi_max - domain.psi_min) / (GRID - 1)
    assert not _draft(flank, domain, ForgingRelief(r.start_psi - dpsi, r.rate)).passes
    # bisection bracket 1e-7: one part in 1e4 less rate fails, the design passes
    assert not _draft(flank, domain, ForgingRelief(r.start_psi, r.rate * (1 - 1e-4))).passes


def test_chosen_start_has_the_least_volume_of_all_passing_starts(case):
    """Brute force over start lines: the smallest passing rate at each start (found here by a plain scan, not the
    module's bisection) never gives less volume than the design."""
    flank, domain, design = case
    varphi, phi = domain.grid(GRID, GRID)
    psi = (varphi - phi) * math.sin(DELTA)
    for ps in np.linspace(design.relief.start_psi, domain.psi_max - 0.02, 4)[1:]:
        rates = design.relief.rate * np.geomspace(0.2, 3.0, 60)
        ok = [k for k in rates if _draft(flank, domain, ForgingRelief(ps, k)).passes]
        if not ok:
            continue
        _, _, dA, w = RelievedFlank(flank, domain, ForgingRelief(ps, ok[0])).evaluate(varphi, phi)
        vol = np.trapezoid(np.trapezoid(w * dA / math.sin(DELTA), psi[0], axis=1), phi[:, 0])
        assert vol >= design.volume * (1 - 1e-6)


def test_position_and_normal_continuous_at_the_start_line(case):
    """Approaching the start line from the relieved side, the gap to the theoretical flank falls as eps^2 and the
    normal difference as eps (G1 contact; a jump would not fall at all)."""
    flank, domain, design = case
    rel = RelievedFlank(flank, domain, design.relief)
    theo = RelievedFlank(flank, domain, None)
    phi = np.linspace(domain.phi_min, domain.phi_max, 5)
    gaps = []
    for eps in (1e-3, 1e-4, 1e-5):
        vp = domain.to_varphi(design.relief.start_psi - eps, phi)
        p1, n1, _, _ = rel.evaluate(vp, phi)
        p0, n0, _, _ = theo.evaluate(vp, phi)
        gaps.append((np.abs(p1 - p0).max(), np.abs(n1 - n0).max()))
    (p_a, n_a), _, (p_c, n_c) = gaps
    assert 0.9e4 < p_a / p_c < 1.1e4  # quadratic: w = rho kappa eps^2 / 2
    assert 0.9e2 < n_a / n_c < 1.1e2  # linear
    vp = domain.to_varphi(design.relief.start_psi + 1e-6, phi)
    assert np.array_equal(rel.evaluate(vp, phi)[0], theo.evaluate(vp, phi)[0])  # untouched above the line


def test_exact_normals_and_curvatures_against_generic_differential_geometry(case):
    flank, domain, design = case
    rel = RelievedFlank(flank, domain, design.relief)
    ps = design.relief.start_psi
    psi = np.array([domain.psi_min + 0.01, 0.5 * (domain.psi_min + ps), ps - 5e-3])  # stencils off the line
    phi = np.array([0.05, 0.2, 0.35])
    vp = domain.to_varphi(psi, phi)
    _, n, _, _ = rel.evaluate(vp, phi)
    geo = surface_geometry(rel.point, vp, phi, reference=n, step=2e-3)
    assert np.abs(geo.normal - n).max() < 1e-9  # Richardson first derivatives: ~1e-11 measured
    # second method for the curvatures: Weingarten map from the (closed-form) normal's first derivatives
    h = 1e-6
    n_u = (rel.evaluate(vp + h, phi)[1] - rel.evaluate(vp - h, phi)[1]) / (2 * h)
    n_v = (rel.evaluate(vp, phi + h)[1] - rel.evaluate(vp, phi - h)[1]) / (2 * h)
    dot = lambda a, b: np.einsum("...i,...i->...", a, b)  # noqa: E731
    L, M1, M2, N = dot(geo.r_u, n_u), dot(geo.r_u, n_v), dot(geo.r_v, n_u), dot(geo.r_v, n_v)
    E, F, G = geo.E, geo.F, geo.G
    K = (L * N - M1 * M2) / (E * G - F**2)
    H = (E * N - F * (M1 + M2) + G * L) / (2 * (E * G - F**2))
    assert np.allclose(geo.gaussian_curvature, K, rtol=1e-5, atol=1e-9)
    assert np.allclose(geo.mean_curvature, H, rtol=1e-5, atol=1e-8)


def test_curvature_jumps_by_the_relief_hessian(case):
    """Just inside the start line w and grad w vanish, so the shape operator changes by minus the surface Hessian of
    w = rho kappa u^2 / 2, u = psi_s - psi: d2w/dpsi2 grad(psi) grad(psi)^T with |grad psi|^2 = sin^2(delta) (1/E + 1/G)
    (psi = (varphi - phi) sin(delta), F = 0). Hence the sum of the principal curvatures drops by
    rho kappa sin^2(delta) (1/E + 1/G) and the Gaussian curvature changes accordingly; both measured by the generic
    differential geometry on either side of the line."""
    flank, domain, design = case
    r = design.relief
    phi = np.array([0.1, 0.3])
    vp = domain.to_varphi(r.start_psi - 1e-4, phi)
    rel = RelievedFlank(flank, domain, r)
    n = rel.evaluate(vp, phi)[1]
    k_rel = surface_geometry(rel.point, vp, phi, reference=n, step=1e-4)
    k_theo = surface_geometry(RelievedFlank(flank, domain, None).point, vp, phi, reference=n, step=1e-4)
    rho = flank.rho0 * np.exp(phi * math.sin(DELTA) / math.tan(BETA))
    psi = r.start_psi - 1e-4
    E = (rho * math.sin(psi) * math.cos(DELTA)) ** 2
    G = (rho * math.sin(DELTA) / math.sin(BETA)) ** 2
    w2 = rho * r.rate  # d2w/dpsi2
    expected = -w2 * math.sin(DELTA) ** 2 * (1 / E + 1 / G)
    got = (k_rel.k1 + k_rel.k2) - (k_theo.k1 + k_theo.k2)
    assert np.allclose(got, expected, rtol=2e-3)  # O(u) = 1e-4 terms left out of the closed form


def test_flank_already_passing_needs_no_relief():
    flank, domain = make(1, -1, psi=(0.3, 0.8))  # concave flank: always draftable along +z
    d = design_forging_relief(flank, domain, draft_angle=DRAFT, n_phi=11, n_psi=11)
    assert d.relief is None and d.volume == 0.0


def test_top_failing_flank_is_refused_with_the_design_key():
    flank, domain = make(1, 1, psi=(0.1, 0.4))  # |psi| < |beta| everywhere (the 30 deg aviation pinion's case)
    with pytest.raises(DesignError) as info:
        design_forging_relief(flank, domain, draft_angle=DRAFT, n_phi=11, n_psi=11)
    assert "manufacturing.draft_angle" in str(info.value) and "mean_spiral_angle" in str(info.value)


@pytest.mark.parametrize("bad", [-0.1, math.pi / 2, float("nan"), "x"])
def test_bad_draft_angle(bad):
    flank, domain = make(1, 1, psi=(0.3, 0.8))
    with pytest.raises(DesignError) as info:
        relieved_draft_map(RelievedFlank(flank, domain, None), draft_angle=bad)
    assert "draft_angle" in str(info.value)


@pytest.mark.parametrize("field,value", [("start_psi", 0.0), ("rate", -1.0), ("rate", float("inf")), ("rate", True)])
def test_bad_relief_parameters(field, value):
    kw = {"start_psi": 0.5, "rate": 1.0, field: value}
    with pytest.raises(DesignError) as info:
        ForgingRelief(**kw)
    assert field in str(info.value)


def test_relieved_flank_round_trips_through_step(case, tmp_path):
    """Relieved flank written as an exact B-spline face and read back: exact points at the nodes and midway between
    them (also across the start line, where the curvature jumps) lie within 1e-3 mm of the read surface."""
    pytest.importorskip("OCP")
    from spiralbevel.io.step import read_step_surfaces, write_step

    flank, domain, design = case
    rel = RelievedFlank(flank, domain, design.relief)
    concave, cdom = make(1, -1, psi=(0.3, 0.8), phi=(0.0, 0.4))
    n, m = 25, 17
    pa = rel.point(*domain.grid(n, m))
    pb = RelievedFlank(concave, cdom, None).point(*cdom.grid(n, m))
    out = write_step(tmp_path / "relieved.step", pa, pb)
    surface = read_step_surfaces(out.path)[0]
    fine = rel.point(*domain.grid(2 * n - 1, 2 * m - 1))
    worst = float(surface.distance(fine.reshape(-1, 3)).max())
    assert worst <= 1e-3, worst
