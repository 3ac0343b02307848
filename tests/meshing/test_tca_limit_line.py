"""TCA where a generated flank folds back over itself past a limit line of generation (the envelope's cuspidal edge,
the onset of undercut): the points past it are cut away, and TCA must not touch them.

The pair: the coast side of the developed 13/20 sample design of the robustness bench (tests/meshing/
_limit_line_pair.py), whose gear concave flank folds near its fillet junction at the end of the roll. TCA with 81
positions reported a corner contact there (the pinion's top edge against the gear's fillet junction on the folded
sheet, 3.93 arcsec at position 48, up to 4.45 arcsec), which the 21- and 41-position TCAs, starting their Newton solves
from other predictors, stepped over: their surface contact (0.372 arcsec at the same rotation) was the real one.
Checked here: by a brute-force sweep of the blade over the roll, every point past the limit line is cut away; and the
first touch of TCA against an independent oracle (tests/meshing/_gap_oracle.py: the angular gap about the gear axis,
maximised over the overlap of the two flanks' axial projections, where a flank that covers a (z, rho) twice counts its
deepest sheet, the other being cut away), on this pair and on the 11/12 pair of tests/meshing/_interference_pair.py.
"""

import numpy as np
import pytest

from _blade_sweep import penetration
from _gap_oracle import flank_box, tca_deviation
from _interference_pair import coast_pair as interference_pair
from _limit_line_pair import coast_pair

from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC

#: arcsec: TCA and the gap oracle (a 90 x 45 grid of each flank, 10 zoom levels of factor 4 from two grid cells)
#: agree to at most 2.9e-6 arcsec at the positions below; with a 60 x 30 grid the oracle stayed up to 6e-4 arcsec
#: behind at position 49, where the contact runs past the fold
TOL_ARCSEC = 1e-5


@pytest.fixture(scope="module")
def pair():
    return coast_pair()


def _oracle_deviation(c1, c2, kin, res, idx):
    return tca_deviation(c1, c2, kin, res, idx, n=(90, 45), k=6, starts=4, levels=10)


def test_points_past_the_limit_line_are_cut_away(pair):
    c1, c2, _ = pair
    for c, folds in ((c1, False), (c2, True)):
        b = flank_box(c)
        t = [np.linspace(b[i, 0], b[i, 1], 40) for i in (0, 1)]
        q = np.stack(np.meshgrid(*t, indexing="ij"), -1).reshape(-1, 2)
        q = q[np.all(c.boundary_margins(q) >= 0, axis=-1)]   # inside toe, heel, top and fillet junction
        off = ~c.on_sheet(q)
        assert off.any() == folds, off.sum()
        if folds:
            gen = c.flank.generator
            pts = gen.evaluate_blade(q[off, 0], q[off, 1], curvature=False).points
            pen = penetration(gen, pts, np.linspace(q[:, 1].min() - 0.3, q[:, 1].max() + 0.3, 1201))
            # the blade reaches 0.2-2.5 um into every one of them (a point of the real flank: <= 0 to round-off,
            # tests/generation/test_fold.py)
            assert off.sum() > 20 and np.min(pen) > 1e-4, (off.sum(), np.min(pen))
            assert not np.any(c.contains(q[off]))


def test_tca_matches_the_gap_oracle_where_the_contact_runs_onto_the_fold(pair):
    c1, c2, kin = pair
    start = np.r_[c1.reference_params, c2.reference_params, 0.0]
    res = solve_tca(c1, c2, kin, n_positions=81, start=start)
    idx = np.array([47, 48, 49])
    d = _oracle_deviation(c1, c2, kin, res, idx)
    assert np.all(np.abs(d) <= TOL_ARCSEC), d
    # the 21- and 41-position TCAs report the same contacts at the same rotations
    for n in (21, 41):
        r = solve_tca(c1, c2, kin, n_positions=n, start=start)
        assert np.allclose(r.te, res.te[::80 // (n - 1)], rtol=0, atol=1e-9 * ARCSEC)


def test_interference_pair_touches_on_its_real_flanks():
    # the 11/12 coast pair: the gear's fillet junction on the folded part of its concave flank had been reported as an
    # edge contact ahead of the pair's surface contact over most of the mesh cycle, up to 108 arcsec (position 0); the
    # oracle finds the surface contact there
    c1, c2, kin = interference_pair()
    res = solve_tca(c1, c2, kin, n_positions=41, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    idx = np.array([0, 14, 31])
    d = _oracle_deviation(c1, c2, kin, res, idx)
    assert np.all(np.abs(d) <= TOL_ARCSEC), d
    assert not [e for e in res.edges if e[0] in idx]
