"""The profile rows of a flank grid, located in one compiled call (``BladeLocator.rows``,
``_core.blade_locate.locate_rows``), against the per-row locator with its further starts (``Locator.at_R_h``), which
takes over from the first row the compiled call does not accept."""

import numpy as np
import pytest
from conftest import CASES, basic_flank


@pytest.mark.parametrize("member, side", CASES)
def test_rows_match_the_per_row_locator_and_its_fallback(member, side):
    flank = basic_flank(member, side)
    loc, ol = flank._locator, flank.outline
    g = flank.grid(9, 6, curvature=False)
    phi = g.theta + np.pi - flank.generator.mp["q"] + g.psi_c
    x = np.stack([g.u, phi, g.psi_c], -1)
    R, h = ol.Rh(g.axial, g.radius)
    R = R[:, 0]
    # row by row with the numpy-orchestrated locator, each row from the row below (the code before the compiled rows)
    ref = x.copy()
    for k in range(1, x.shape[1]):
        ref[:, k] = loc.at_R_h(R, h[:, k], ref[:, k - 1, 1:])
    # the same Newton from the same starts: the same iterates
    np.testing.assert_array_equal(loc.profile_rows(R, h, x[:, 0]), ref)
    # no start at one station (NaN, as a junction point that was not found): the compiled call stops before row 1,
    # the per-row locator's table starts take over and give the same points, to the Newton tolerance (|F| < 1e-10 mm
    # stops both; measured over the four flanks: u 9.4e-11 mm, phi and psi_c 1.9e-12 rad)
    xj = x[:, 0].copy()
    xj[4, 1:] = np.nan
    _, u_rows = loc.blade.rows(*ol.axial_radius(R[:, None], h[:, 1:]), xj[:, 1:])
    assert u_rows.shape[1] == 0
    got = loc.profile_rows(R, h, xj)
    np.testing.assert_allclose(got[:, 1:, 0], ref[:, 1:, 0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(got[:, 1:, 1:], ref[:, 1:, 1:], rtol=0, atol=2e-11)
