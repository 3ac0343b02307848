"""locate(axial, radius): batched Newton vs per-point scipy.optimize.fsolve; round trip on the grid."""

import numpy as np
import pytest
from conftest import CASES, basic_flank
from scipy.optimize import fsolve


@pytest.mark.parametrize("member,side", CASES[::3])
def test_locate_matches_fsolve_and_grid(member, side):
    fl = basic_flank(member, side)
    g = fl.grid(7, 6)
    res = fl.locate(g.axial, g.radius)
    np.testing.assert_allclose(res.points, g.points, atol=1e-9)
    np.testing.assert_allclose(res.normals, g.normals, atol=1e-10)
    # curvatures jump across the fillet/blade junction (row 0, a C1 seam): compare off the seam
    np.testing.assert_allclose(res.k1[:, 1:], g.k1[:, 1:], rtol=1e-8)
    np.testing.assert_allclose(res.k2[:, 1:], g.k2[:, 1:], rtol=1e-8)
    # per-point fsolve of the same equations F1 = |r x k| - R, F2 = r.k - L (docs/theory/generation.md, Eqs. (G10)-(G11)
    # (#mean-point))
    gen = fl.generator
    rng = np.random.default_rng(1)
    idx = rng.choice(g.u.size, 8, replace=False)
    for i in idx:
        ax, rad = g.axial.ravel()[i], g.radius.ravel()[i]

        def F(x, rad=rad, ax=ax):
            p = gen.points(x[0], x[1])
            return [np.hypot(p[0], p[1]) - rad, p[2] - ax]
        x0 = [g.u.ravel()[i] + 0.3, g.psi_c.ravel()[i] + 0.01]
        x = fsolve(F, x0, xtol=1e-13)
        p = gen.points(x[0], x[1])
        assert np.abs(p - res.points.reshape(-1, 3)[i]).max() < 1e-9


def test_locate_broadcasts(gear_t4):
    mp = gear_t4.mean_point()
    r = gear_t4.locate(np.array([[mp.point[2]], [mp.point[2] + 1.0]]), np.hypot(mp.point[0], mp.point[1]) + np.zeros(3))
    assert r.points.shape == (2, 3, 3) and r.k1.shape == (2, 3)
    np.testing.assert_allclose(r.points[0, 0], mp.point, atol=1e-10)
