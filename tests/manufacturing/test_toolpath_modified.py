"""Tool paths along the lines of curvature of a modified (crowned) log-spiral flank
(spiralbevel.manufacturing.toolpath.follow_lines_of_curvature)."""

from __future__ import annotations


import numpy as np
import pytest

from spiralbevel.manufacturing.toolpath import follow_lines_of_curvature, plan_toolpath
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.tca_surfaces import LogSpiralSurface

from ._cases import make


@pytest.fixture(scope="module")
def case():
    flank, domain = make(1, 1, psi=(0.3, 0.5), phi=(0.0, 0.3))
    base = LogSpiralSurface(flank.rho0, flank.base_cone_angle, flank.spiral_angle,
                            psi_range=(domain.psi_min, domain.psi_max), phi_range=(domain.phi_min, domain.phi_max))
    vm = domain.to_varphi(0.4, 0.15)
    crowned = NormalDeviation(base, quadratic_crowning((vm, 0.15), (0.5, 0.3, 0.8)))  # mm/rad^2, diagonal term on
    planned = plan_toolpath(flank, domain, 5.0, 0.05, max_segment=4.0)
    return base, crowned, planned


def _rodrigues_residual(surface, path):
    """|dn x dr| / (|dn| |dr|) along a path, from the surface's own (closed-form) normals: 0 on a line of curvature
    (Rodrigues: dn = -k dr), sin of the angle between dn and dr otherwise."""
    r, n = path.surface, path.normal
    dr, dn = np.diff(r, axis=0), np.diff(n, axis=0)
    return np.linalg.norm(np.cross(dn, dr), axis=-1) / (np.linalg.norm(dn, axis=-1) * np.linalg.norm(dr, axis=-1))


def test_on_the_theoretical_flank_the_passes_are_the_varphi_curves(case):
    base, _, planned = case
    traced = follow_lines_of_curvature(base, planned)
    for a, b in zip(traced.paths, planned.paths):
        assert np.abs(a.surface - b.surface).max() < 1e-8  # F = M = 0: the principal field is d/dphi exactly


def test_traced_passes_follow_the_lines_of_curvature_of_the_crowned_flank(case):
    _, crowned, planned = case
    traced = follow_lines_of_curvature(crowned, planned)
    # the same passes kept on varphi = const (projected onto the crowned flank) are not lines of curvature there
    naive = []
    for p in planned.paths:
        r, n = crowned.evaluate(np.stack([np.full_like(p.phi, p.varphi), p.phi], -1))
        naive.append(type(p)(p.varphi, p.phi, p.psi, r, n, p.feed, p.center, p.tip, p.axis, p.arc_length))
    worst_traced = max(float(_rodrigues_residual(crowned, t).max()) for t in traced.paths)
    worst_naive = max(float(_rodrigues_residual(crowned, t).max()) for t in naive)
    assert worst_naive > 1e-2  # 0.047 measured: the crowning turns the principal directions
    assert worst_traced < 1e-3  # 7e-5 measured, limited by the chord differences of the 4 mm point spacing
    for t in traced.paths:
        assert np.allclose(np.linalg.norm(t.axis, axis=-1), 1.0)
        assert np.allclose(t.center, t.surface + traced.tool_radius * t.normal)
