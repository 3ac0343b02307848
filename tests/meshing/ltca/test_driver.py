"""LTCA driver over a synthetic mesh cycle on an FE-modelled log-spiral tooth segment.

The unloaded contact (the TCA protocol input) is constructed: three pairs with parabolic transmission errors
te_k(x) = a (x - k p)^2 (max 0 at the pair's own mean position, -3 arcsec at the transfer points), contact points
moving toe -> heel along the mid-profile line of tooth k's concave flank, and a constant relative curvature.
"""

import numpy as np
import pytest

from spiralbevel.errors import DesignError, NoContactError
from spiralbevel.meshing.ltca.lcp import solve_load_distribution
from spiralbevel.meshing.ltca.ltca import ContactPosition, PairContact, _assemble, run_ltca
from spiralbevel.meshing.ltca.result import ARCSEC

pytest.importorskip("skfem")

PITCH = 2 * np.pi / 23
A_TE = -3.0 * ARCSEC / (PITCH / 2) ** 2
AXIS = np.array([0.0, 0.0, 1.0])
KREL = np.diag([1 / 800.0, 1 / 30.0])


def _bilinear(grid, f, g):
    n0, n1 = grid.shape[:2]
    u, v = f * (n0 - 1), g * (n1 - 1)
    i, j = min(int(u), n0 - 2), min(int(v), n1 - 2)
    a, b = u - i, v - j
    return ((1 - a) * (1 - b) * grid[i, j] + a * (1 - b) * grid[i + 1, j] + (1 - a) * b * grid[i, j + 1]
            + a * b * grid[i + 1, j + 1])


def synthetic_positions(tc, n_pos=21):
    out = []
    for x in np.linspace(-PITCH / 2, PITCH / 2, n_pos):
        pairs = []
        for k in (-1, 0, 1):
            u = (x - k * PITCH) / (0.8 * PITCH)
            if abs(u) > 1:
                pairs.append(None)
                continue
            f = 0.5 + 0.4 * u
            P = _bilinear(tc.grids[k], f, 0.5)
            n = _bilinear(tc.normals[k], f, 0.5)
            d = _bilinear(tc.grids[k], f + 0.01, 0.5) - _bilinear(tc.grids[k], f - 0.01, 0.5)
            pairs.append(PairContact(point=P, normal=n / np.linalg.norm(n), direction=d, te=A_TE * (x - k * PITCH) ** 2,
                                     curvature=KREL, tooth_pinion=k, tooth_gear=k))
        out.append(ContactPosition(float(x), pairs))
    return out


@pytest.fixture(scope="module")
def cycle(pinion_segment):
    _, tc = pinion_segment
    pos = synthetic_positions(tc)
    kw = dict(gear_axis=AXIS, grid=(15, 5), half_length=6.0, half_width=0.6)
    return tc, pos, kw, run_ltca(pos, 2e4, tc, tc, **kw), run_ltca(pos, 6e4, tc, tc, approach_target=None, **kw)


def test_unloaded_te_is_the_least_lag_pair(cycle):
    tc, pos, kw, res, _ = cycle
    expect = np.array([max(p.te for p in ps.pairs if p is not None) for ps in pos]) / ARCSEC
    assert np.allclose(res.te_unloaded, expect, atol=1e-9)
    assert res.te_unloaded.min() == pytest.approx(-3.0, abs=1e-9)


def test_loaded_te_equilibrium_and_torque_monotone(cycle):
    tc, pos, kw, lo, hi = cycle
    assert np.all(lo.te_loaded < lo.te_unloaded) and np.all(hi.te_loaded < lo.te_loaded)
    assert np.allclose(lo.load_share.sum(axis=1), 1.0, atol=1e-12)
    assert np.all(lo.load_share >= 0) and np.all(lo.load_share <= 1 + 1e-12)
    # at the mean position pair 0 is ahead of its neighbours by 3 arcsec and carries most of the load
    m = len(pos) // 2
    assert lo.load_share[m, 1] > 0.5
    # more torque: more load sharing at the transfer point and a larger peak pressure
    assert hi.load_share[0].min() > lo.load_share[0].min() - 1e-12 and hi.peak_pressure > lo.peak_pressure
    for F, p in zip(lo.force, lo.pressure):
        assert np.all(F >= 0) and np.all(p >= 0)


def test_approach_torque(cycle):
    tc, pos, kw, res, _ = cycle
    T = res.approach_torque
    assert 1e2 < T < 1e7
    m = len(pos) // 2
    from spiralbevel.meshing.ltca.ltca import _BendingOnly

    # the driver's compliances: the FE's own local response removed (the half-space term models it)
    bt = _BendingOnly(tc)
    s = _assemble(m, pos[m], bt, bt, AXIS, np.zeros(3), kw["grid"], kw["half_length"], kw["half_width"],
                  206000.0 / (2 * 0.91))
    sol = solve_load_distribution(s.C, s.w, s.h, T)
    # elastic approach at the mean contact point from the deformations, (C F)_m (= dtheta h_m - w_m since d_m = 0)
    i = int(np.argmin(np.linalg.norm(s.q - pos[m].pairs[1].point, axis=1)))
    assert sol.active[i]
    assert (s.C @ sol.force)[i] == pytest.approx(0.00635, rel=1e-8)


def test_no_contact_and_bad_torque(cycle):
    tc, pos, kw, _, _ = cycle
    with pytest.raises(NoContactError, match="position 1"):
        run_ltca([pos[0], ContactPosition(0.1, [None, None, None])], 1e4, tc, tc, approach_target=None, **kw)
    with pytest.raises(DesignError, match="torque"):
        run_ltca(pos, 0.0, tc, tc, **kw)


def test_plot(cycle):
    fig = cycle[3].plot()
    assert len(fig.axes) >= 3
