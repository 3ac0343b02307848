"""First-touch TE (spiralbevel.meshing.synthesis.logspiral_sensitivity) against the surface TCA, and the misalignment
sensitivity of the mismatched pair beside the line-contact pair."""

from __future__ import annotations

import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.synthesis.logspiral_crowning import (crowned_contact_surface, design_logspiral_crowning,
                                                              logspiral_contact_surface)
from spiralbevel.meshing.synthesis.logspiral_sensitivity import first_touch_te, misalignment_sensitivity
from spiralbevel.meshing.tca import solve_tca

ARCSEC = math.pi / (180 * 3600)
N = 7  # positions over one cycle (the README table uses 21)


@pytest.fixture(scope="module")
def setup():
    from spiralbevel.io.design_file import load_design
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.logspiral import design_pair

    spec = load_design()
    pair = design_pair(spec, blank_from_design(spec))
    cr = design_logspiral_crowning(pair, Side.CONVEX, semi_major_axis=6.0, path_direction=math.radians(20.0),
                                   te_level=8.0 * ARCSEC)
    kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
    c1 = crowned_contact_surface(pair, cr)
    c0 = logspiral_contact_surface(pair, Member.PINION, Side.CONVEX)
    c2 = logspiral_contact_surface(pair, Member.GEAR, Side.CONCAVE)
    p1 = pair.mean_point(Member.PINION, Side.CONVEX).point
    phi1m = -math.atan2(p1[1], p1[0])
    start = np.r_[c1.reference_params, c2.reference_params, -kin.ratio * phi1m]
    return c0, c1, c2, kin, phi1m, start


def test_first_touch_reproduces_the_surface_tca(setup):
    c0, c1, c2, kin, phi1m, start = setup
    res = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=N, start=start)
    kw = dict(phi1_mean=phi1m, phi2_mean=res.phi2_mean, drive_sign=res.drive_sign)
    te = first_touch_te(c1, c2, kin, res.phi1, **kw)
    assert np.abs(te - res.te).max() < 0.05 * ARCSEC  # grid + zoom refinement: 0.01" measured (TE up to 7.7")
    # the exact conjugate pair: every point of the contact line touches at once, TE = 0
    assert np.abs(first_touch_te(c0, c2, kin, res.phi1, **kw)).max() < 0.01 * ARCSEC


def test_mismatched_pair_is_less_sensitive_to_offset_than_the_line_contact_pair(setup):
    c0, c1, c2, kin, phi1m, start = setup
    res = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=N, start=start)
    mis = Misalignment(offset=0.05)
    study = misalignment_sensitivity(c0, c1, c2, kin, phi1_mean=phi1m, phi2_mean=res.phi2_mean,
                                     drive_sign=res.drive_sign, misalignments={"offset": mis}, n_positions=N)
    row = study.rows[0]
    assert row.line_growth > 1.0 * ARCSEC  # edge contact of the misaligned conjugate pair: 2.2" measured (7 positions)
    assert row.mismatched_growth < row.line_growth  # crowned pair: the parabola moves, its level does not grow
    # cross-check of the mismatched row against the surface TCA of the same misaligned pair
    rm = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=N, start=start, misalignment=mis)
    assert abs(row.mismatched_ptp - rm.peak_to_peak) < 0.05 * ARCSEC
