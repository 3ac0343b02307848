"""Shared fixtures of the LTCA tests: a coarse log-spiral tooth segment (23/65 pair of tests/design)."""

import numpy as np
import pytest

from spiralbevel import Hand, Member, Side
from spiralbevel.design.logspiral_pair import BlankBoundaries, design_logspiral_pair

D = np.radians


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: tests that take more than ~20 s")


def logspiral_pair():
    """23/65, S = 90, alpha_n = 20, beta_m = 35 deg, RH pinion; blank of tests/design/test_logspiral_pair.py."""
    z1, z2, S, an, bm = 23, 65, D(90.0), D(20.0), D(35.0)
    g1 = np.arctan2(np.sin(S), z2 / z1 + np.cos(S))
    R_i, R_e = 85.0, 115.0
    Rm = 0.5 * (R_i + R_e)
    m = 2 * Rm * np.sin(g1) / z1
    alpha_t = np.arctan(np.tan(an) / np.cos(bm))
    bounds = []
    for g in (g1, S - g1):
        delta = np.arcsin(np.sin(g) * np.cos(alpha_t))
        bounds.append(BlankBoundaries(R_i, R_e, max(g - 1.1 * m / Rm, delta + D(0.15)), g + m / Rm))
    return design_logspiral_pair(z1, z2, S, an, bm, Hand.RIGHT, tuple(bounds))


@pytest.fixture(scope="session")
def pinion_mesh():
    from spiralbevel.meshing.ltca.mesher import mesh_tooth_segment

    p = logspiral_pair()
    cv = p.flank(Member.PINION, Side.CONVEX).grid(9, 6).point
    cc = p.flank(Member.PINION, Side.CONCAVE).grid(9, 6).point
    return mesh_tooth_segment(cv, cc, 23, n_teeth=3, thickness_divisions=2, space_divisions=2, rim_layers=2)


@pytest.fixture(scope="session")
def pinion_segment(pinion_mesh, tmp_path_factory):
    pytest.importorskip("skfem")
    from spiralbevel.meshing.ltca.compliance import tooth_compliance

    return pinion_mesh, tooth_compliance(pinion_mesh, "concave", cache_dir=tmp_path_factory.mktemp("fe"))
