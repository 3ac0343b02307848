"""Curvature transfer (docs/theory/generation.md, Eqs. (G13)-(G15) (#curvature-transfer)) against numerical differential
geometry of the generated map (u, psi_c) -> r."""

import math

import numpy as np
import pytest
from _numgeom import derivatives, principal_curvatures
from conftest import CASES, basic_flank


@pytest.mark.parametrize("member,side", CASES)
@pytest.mark.parametrize("rp,extra", [(math.inf, {}), (300.0, {}), (math.inf, {"modified_roll": (0.05, -0.3, 0.2)}),
                                      (300.0, {"blank_offset_poly": (0.5, 2.0, -1.0), "blank_offset": 0.8})])
def test_transfer_matches_numerical_curvatures(member, side, rp, extra):
    fl = basic_flank(member, side, rp=rp, **extra)
    g = fl.grid(5, 6)
    u0, uj = fl.cutter.fillet_range
    # blade points off the junction, plus points in the middle of the fillet (the surface is only C1 at u_j)
    u = np.concatenate([g.u[:, 1:].ravel(), np.full(5, 0.5 * (u0 + uj))])
    p = np.concatenate([g.psi_c[:, 1:].ravel(), g.psi_c[:, 0]])
    G = fl.evaluate(u, p)
    hu = np.where(u < uj, 0.01, 0.04)
    k_num, n_num = principal_curvatures(fl.generator.points, u, p, G.normals, hu, 4e-4)
    np.testing.assert_allclose(n_num, G.normals, atol=1e-12)
    k = np.sort(np.stack([G.k1, G.k2], -1), axis=-1)[:, ::-1]
    rel = np.abs(k_num - k).max(axis=-1) / np.abs(k).max(axis=-1)
    assert rel.max() <= 1e-6            # measured <= 1.2e-7 (8th-order differences, float64)
    # principal directions: normal curvature along e1 of the numerical second fundamental form equals k1
    ru, rv, ruu, ruv, rvv = derivatives(fl.generator.points, u, p, hu, 4e-4)
    J = np.stack([ru, rv], -1)                                      # (..., 3, 2)
    c = np.linalg.lstsq(J[0], G.e1[0], rcond=None)[0]
    assert np.allclose(J[0] @ c, G.e1[0], atol=1e-9)
    II = -(c[0] ** 2 * ruu[0] + 2 * c[0] * c[1] * ruv[0] + c[1] ** 2 * rvv[0]) @ G.normals[0]
    assert II == pytest.approx(G.k1[0], rel=1e-6, abs=1e-9)
    np.testing.assert_allclose(np.cross(G.e1, G.e2), G.normals, atol=1e-12)


def test_convex_and_concave_signs(blank):
    from spiralbevel.conventions import Member, Side
    cv = basic_flank(Member.GEAR, Side.CONVEX, blank).mean_point()
    cc = basic_flank(Member.GEAR, Side.CONCAVE, blank).mean_point()
    assert cv.k2 > 0 > cc.k2          # lengthwise: convex flank positive, concave negative
    # lengthwise curvature of the order of cos(beta)/r_c... within the generated-surface deviation
    assert 0.5 / 114.3 < cv.k2 < 1.5 / 114.3
