"""TCA results independent of the number of positions (issue: 61, 241 and 961 positions on the bundled synthesized
and CMC pairs): the extremes of the TE envelope include the exact transfer points (the crossings of adjacent pairs'
TE curves, solved, not interpolated), so they no longer depend on where the positions fall."""

import math

import numpy as np
import pytest

from test_tca_oracle import _cmc, _synthesized

from spiralbevel.meshing.motion_curves import ARCSEC
from spiralbevel.meshing.synthesis.cmc_design import te_summary
from spiralbevel.meshing.synthesis.multipoint import multipoint_tca
from spiralbevel.meshing.tca import solve_tca

COUNTS = (61, 241, 961)
#: acceptance bound of the issue; what remains is the sampling of the smooth maxima of the envelope
#: (O(spacing^2): about 8e-4 arcsec between 61 and 961 positions on these pairs)
TOL = 0.05


@pytest.fixture(scope="module")
def cmc_design():
    from spiralbevel.conventions import Member, Side
    from spiralbevel.machine import seed001_blank, seed001_settings
    from spiralbevel.meshing.synthesis.cmc_design import design_seed001_style

    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    return design_seed001_style(gc, gs, blank, eta=math.radians(6.0), semi_major_axis=3.7, te_magnitude=3 * ARCSEC,
                                interpolation="spline", straight_blades=True)


def _figures(res):
    return np.array([res.te_max, res.te_min, res.peak_to_peak]) / ARCSEC


@pytest.mark.parametrize("name", ["synthesized", "cmc"])
def test_te_extremes_and_transfers_do_not_depend_on_the_position_count(name):
    c1, c2, kin, kw = (_synthesized if name == "synthesized" else _cmc)()
    runs = [solve_tca(c1, c2, kin, n_positions=n, **kw) for n in COUNTS]
    figs = np.array([_figures(r) for r in runs])
    assert np.all(np.isfinite(figs))
    assert np.max(np.ptp(figs, axis=0)) <= TOL, figs
    # the same transfer points, to the root finder's accuracy (1e-12 rad bracket or |dTE| < 5e-11 rad)
    t = [r.transfer_phi1 for r in runs]
    assert all(len(x) == len(t[0]) and len(x) > 0 for x in t)
    np.testing.assert_allclose(t[1], t[0], atol=1e-8)
    np.testing.assert_allclose(t[2], t[0], atol=1e-8)
    # each transfer is the kink of the envelope (the upper envelope of two crossing curves): its TE lies below the
    # envelope at both neighbouring positions
    r = runs[0]
    for phi_t, te_t in zip(r.transfer_phi1, r.transfer_te):
        i = np.searchsorted(r.phi1, phi_t) - 1
        assert te_t <= min(r.te[i], r.te[i + 1]) + 1e-12


def test_cmc_paper_model_depth_is_the_designed_3_arcsec_at_every_position_count(cmc_design):
    """The paper's model (straight blades down to the tip, no edges): the depth of the TE envelope (its lowest point
    with the maximum shifted to 0) is the designed 3.000 arcsec within 0.05 arcsec at 61, 241 and 961 positions."""
    depth = [te_summary(multipoint_tca(cmc_design.multipoint, n_positions=n, straight_blades=True),
                        cmc_design.multipoint)["max_transmission_error_arcsec"] for n in COUNTS]
    np.testing.assert_allclose(np.abs(depth), 3.0, atol=TOL)
    assert np.ptp(depth) <= TOL
