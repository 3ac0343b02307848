"""Multi-point control (seed 001 §4.3.1, Eqs. (16)-(17), docs/theory/tca.md, Eqs. (T5), (T8)) on the seed 001 example:
pinion concave /
gear convex (Tables 1, 2, 4), eta = 6 deg, a = 3.7 mm, CMC of 3 arcsec by Steps 1-4.

Independent checks: the TE at the control points is measured again by the TCA engine on the regenerated flank, and
one control point is recomputed by a plain scalar root-finder (brentq on the blank offset, TCA contact solver for the
contact), not by the batched 6 x 6 system."""

import math

import numpy as np
import pytest
from _synth_common import ARCSEC, TE
from scipy.optimize import brentq

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.motion_curves import seed001_cmc
from spiralbevel.meshing.synthesis.cmc_design import active_range, te_summary
from spiralbevel.meshing.synthesis.multipoint import _Surface, multipoint_control, multipoint_tca

Z1 = 23
T = 2 * math.pi / Z1
N_POS = 61                                   # TCA positions: x = -T/2 + k T/60
GRID = np.linspace(-T / 2, T / 2, N_POS)


@pytest.fixture(scope="module")
def cmc():
    return seed001_cmc(TE, Z1)


@pytest.fixture(scope="module")
def controls(synth_pos):
    lo, hi = active_range(synth_pos)
    inside = GRID[(GRID >= lo) & (GRID <= hi)]
    return inside[::5]                       # control points on the TCA grid, every 5th position


@pytest.fixture(scope="module")
def spline(synth_pos, cmc, controls):
    return multipoint_control(synth_pos, cmc, controls, interpolation="spline")


@pytest.fixture(scope="module")
def spline_tca(spline):
    return multipoint_tca(spline, n_positions=N_POS)


@pytest.mark.parametrize("kind", ["linear", "spline", "polynomial"])
def test_control_point_errors_below_tolerance(synth_pos, cmc, controls, kind, spline):
    r = spline if kind == "spline" else multipoint_control(synth_pos, cmc, controls, interpolation=kind)
    assert r.law.kind == kind
    assert np.all(r.control_point_errors <= 1e-9)  # Eq. (17) with an absolute tolerance (docs/theory/tca.md, Eq. (T8))
    i = r.mean_index
    assert r.control_points[i] == 0.0 and r.offsets[i] == r.law.base == synth_pos.pinion_settings.blank_offset
    # the law passes through its nodes
    np.testing.assert_allclose(r.law(r.psi_c1), r.offsets, atol=1e-13)


def test_tca_of_final_pair_meets_cmc_at_control_points_and_follows_it(spline, spline_tca, cmc):
    res, r = spline_tca, spline
    x = res.phi1 - res.phi1_mean
    k0 = list(res.pairs).index(0)
    idx = [int(np.argmin(np.abs(x - c))) for c in r.control_points]
    np.testing.assert_allclose(x[idx], r.control_points, atol=1e-15)
    te = res.te_pairs[idx, k0]
    np.testing.assert_allclose(te, r.target, atol=1e-9)      # TCA engine, regenerated flank, aligned pair
    # between control points: within 5 % of the CMC depth (3 arcsec) over the controlled range
    s = te_summary(res, r)
    assert s["controlled_range_deviation_arcsec"] < 0.05 * TE / ARCSEC


def test_blank_offset_varies_smoothly_along_the_path(spline):
    r = spline
    d = r.offset_increments
    # Figure 6: the offset departs from E_m10 by a small amount (measured ~0.9 um here; bound 10 um)
    assert np.max(np.abs(d)) < 1e-2 and np.max(np.abs(d)) > 0
    psi = np.linspace(r.psi_c1.min(), r.psi_c1.max(), 2001)
    e = r.law(psi)
    # continuous with a continuous rate: no jumps between neighbouring samples beyond the rate bound
    rate = r.law.rate(psi)
    assert np.max(np.abs(np.diff(e))) <= np.max(np.abs(rate)) * (psi[1] - psi[0]) * 1.01
    assert np.max(np.abs(np.diff(rate))) < 1e-2 * np.max(np.abs(rate)) + 1e-12
    # the nodes follow the path monotonically (one cradle angle per control point)
    assert np.all(np.diff(r.psi_c1) < 0) or np.all(np.diff(r.psi_c1) > 0)


def test_one_control_point_by_scalar_root_finding(spline, synth_pos):
    """E_m1 at one node by brentq: offset with the law's rate there, contact by the TCA solver, TE = target."""
    r, s = spline, synth_pos
    k = int(np.argmax(np.abs(r.offset_increments)))
    psi_k, rate = r.psi_c1[k], float(r.law.rate(r.psi_c1[k]))
    kin = s.mean.kinematics
    gear = _Surface(s.gear_flank, s.phi2_mean, r.gear_params[r.mean_index])
    i0 = r.mean_index
    x0 = np.r_[r.pinion_params[k], r.gear_params[k], r.phi2[k] - s.phi2_mean]

    def contact(e, xk, start):
        st = s.pinion_settings.replace(blank_offset=e - rate * psi_k, blank_offset_poly=(rate,))
        fl = generate_flank(s.pinion_cutter, st, _blank(), Member.PINION, Side.CONCAVE)
        sol, conv, _, _, _ = ContactProblem(_Surface(fl, s.phi1_mean, start[:2]), gear, kin).solve(
            np.array([xk]), start[None], tol=1e-12)
        assert conv[0]
        return sol[0]

    phi2_ref = r.phi2[i0] - s.phi2_mean                      # M on the final flank (rate-free there to 1e-9 rad)

    def g(e):
        sol = contact(e, r.control_points[k], x0)
        return s.mean.drive_sign * (-(sol[4] - phi2_ref) - kin.z1 / kin.z2 * r.control_points[k]) - r.target[k]

    e0 = r.law.base
    e = brentq(g, e0 - 0.01, e0 + 0.01, xtol=1e-14)
    assert e == pytest.approx(r.offsets[k], abs=1e-9)        # mm


def _blank():
    from spiralbevel.machine import seed001_blank

    return seed001_blank()


def test_three_pairs_and_transfer_points_on_straight_blades(synth_pos, cmc):
    """Seed 001 model (Eq. (16), straight blades) over the whole cycle: three pair curves are copies shifted by one
    pitch, the envelope transfers where the CMC envelope does, and its depth is the predesigned 3 arcsec within 5 %."""
    r = multipoint_control(synth_pos, cmc, np.linspace(-T / 2, T / 2, 11), interpolation="spline",
                           straight_blades=True)
    assert np.all(r.control_point_errors <= 1e-9)
    res = multipoint_tca(r, n_positions=N_POS, straight_blades=True)
    x = res.phi1 - res.phi1_mean
    c0 = float(cmc(0.0))
    ref = cmc(x) - c0
    k0 = list(res.pairs).index(0)
    assert np.nanmax(np.abs(res.te_pairs[:, k0] - ref)) < 0.05 * TE
    for kk, k in enumerate(res.pairs):
        if k != 0:
            ok = np.isfinite(res.te_pairs[:, kk]) & (np.abs(x + k * T) <= T / 2)
            np.testing.assert_allclose(res.te_pairs[ok, kk], cmc(x[ok] + k * T) - c0, atol=0.05 * TE)
    # transfer of the CMC envelope: Delta phi2(t) = Delta phi2(t - T) near t = T/2 (brentq)
    t_cmc = brentq(lambda t: float(cmc(t) - cmc(t - T)), 0.3 * T, 0.7 * T) - T   # the same crossing seen at -T/2
    assert len(res.transfer_phi1) >= 1
    assert np.min(np.abs(np.r_[res.transfer_phi1 - t_cmc, res.transfer_phi1 - t_cmc - T])) < 2 * T / (N_POS - 1)
    s = te_summary(res, r)
    assert abs(-s["max_transmission_error_arcsec"] - TE / ARCSEC) < 0.05 * TE / ARCSEC


def test_zero_motion_curve_makes_the_pair_conjugate_at_the_control_points(synth_pos, controls):
    """A CMC of zero: the TE vanishes at every control point, and stays far below the synthesis parabola between."""
    r = multipoint_control(synth_pos, lambda x: 0.0 * np.asarray(x, float), controls, interpolation="spline")
    assert np.all(r.control_point_errors <= 1e-9)
    res = multipoint_tca(r, n_positions=N_POS)
    x = res.phi1 - res.phi1_mean
    inr = (x >= controls.min()) & (x <= controls.max())
    k0 = list(res.pairs).index(0)
    parabola = TE * (x[inr] / (T / 2)) ** 2                     # what the local synthesis alone gives (magnitude)
    assert np.max(np.abs(res.te_pairs[inr, k0])) < 0.02 * np.max(parabola)


def test_synthesis_parabola_needs_only_third_order_offset_corrections(synth_pos):
    """Consistency with the local synthesis: controlling its own parabola (m21'/2 x^2) changes E_m1 only at third
    order in x (the synthesis matches the TE to second order at M)."""
    m2 = synth_pos.m21_prime
    h = 0.01
    r = multipoint_control(synth_pos, lambda x: 0.5 * m2 * np.asarray(x, float) ** 2, [-2 * h, -h, h, 2 * h],
                           interpolation="spline")
    d = r.offset_increments
    i = r.mean_index
    ratio_pos, ratio_neg = d[i + 2] / d[i + 1], d[i - 2] / d[i - 1]
    for ratio in (ratio_pos, ratio_neg):
        assert 5.0 < ratio < 11.0                                 # 2^3 = 8 for a cubic leading term


def test_linear_law_has_no_whole_cycle_tca(synth_pos, cmc, controls):
    r = multipoint_control(synth_pos, cmc, controls, interpolation="linear")
    with pytest.raises(DesignError, match="interpolation"):
        multipoint_tca(r)


@pytest.mark.parametrize("kw", [dict(interpolation="cubic"), dict(tol_abs=-1.0), dict(max_outer=0)])
def test_bad_input_raises_design_error(synth_pos, cmc, kw):
    with pytest.raises(DesignError):
        multipoint_control(synth_pos, cmc, [0.05], **kw)


@pytest.mark.parametrize("pts", [[0.0], [], [np.nan], [4.0]])
def test_bad_control_points(synth_pos, cmc, pts):
    with pytest.raises(DesignError, match="control_points"):
        multipoint_control(synth_pos, cmc, pts)
