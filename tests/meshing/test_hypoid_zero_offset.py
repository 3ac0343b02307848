"""Offset zero through the hypoid path reproduces the spiral bevel results: the bundled face-milled design's TCA in
the hypoid pair frame (HypoidPairKinematics.from_blank, phased_for_hypoid_pair) and the seed 001 local synthesis by
the crossed-axes relations (synthesize_hypoid_pinion) against the intersecting-axes code."""

import math
from pathlib import Path

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.machine import Blade, HeadCutter, MachineSettings, seed001_blank, seed001_settings
from spiralbevel.meshing.generated_surface import phased_for_pair
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks, phased_for_hypoid_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.synthesis import synthesize_pinion
from spiralbevel.meshing.synthesis.hypoid_local import synthesize_hypoid_pinion
from spiralbevel.meshing.tca import solve_tca

DATA = Path(__file__).parents[2] / "src" / "spiralbevel" / "data"


@pytest.fixture(scope="module")
def bundled():
    """The bundled face-milled design's blank and its four flanks with solved basic settings (default cutters)."""
    from spiralbevel.io.design_file import load_design
    from spiralbevel.job.blank import blank_from_design

    blank = blank_from_design(load_design(str(DATA / "aviation_23x65_facemilled.toml")))
    return blank, hypoid_basic_flanks(blank)


@pytest.mark.parametrize("pinion_side", [Side.CONCAVE, Side.CONVEX])
def test_bundled_facemilled_tca_through_the_hypoid_path(bundled, pinion_side):
    blank, setups = bundled
    f1, f2 = setups[(Member.PINION, pinion_side)][2], setups[(Member.GEAR, pinion_side.mate)][2]
    kin0 = BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
    kin = HypoidPairKinematics.from_blank(blank)
    assert (kin.offset, kin.pinion_apex, kin.gear_apex) == (0.0, 0.0, 0.0)
    results = []
    for k, phase in ((kin0, lambda: phased_for_pair(f1, f2)), (kin, lambda: phased_for_hypoid_pair(kin, blank, f1,
                                                                                                       f2))):
        c1, c2 = phase()
        results.append(solve_tca(c1, c2, k, n_positions=21, start=np.r_[c1.reference_params, c2.reference_params,
                                                                           0.0]))
    a, b = results
    np.testing.assert_array_equal(a.status, b.status)
    # round-off: the two phasings turn the flanks by angles equal to ~1e-16 rad (arctan of the same numbers)
    np.testing.assert_allclose(b.te_arcsec, a.te_arcsec, rtol=0, atol=1e-7, equal_nan=True)


def test_seed001_synthesis_through_the_crossed_axes_relations():
    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    kw = dict(side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7, te_magnitude=3.0 * math.pi / 648000.0)
    ref = synthesize_pinion(gc, gs, blank, **kw)
    start = HeadCutter(gc.nominal_radius + 0.5 * gc.point_width, gc.blade_angle, gc.point_width, gc.edge_radius,
                       Blade.OUTER)
    got = synthesize_hypoid_pinion(generate_flank(gc, gs, blank, Member.GEAR, Side.CONVEX), start,
                                   MachineSettings.from_blank(blank, Member.PINION, Side.CONCAVE, start), blank, **kw)
    np.testing.assert_allclose(got.point, ref.mean.point, atol=1e-9)
    np.testing.assert_allclose(got.normal, ref.mean.normal, atol=1e-12)
    np.testing.assert_allclose(got.relative_tensor, ref.relative_tensor, atol=1e-12)
    # the settings fit converges to 1e-9 on its scaled residual: settings agree to ~1e-8 relative
    for key in ("radial_setting", "cradle_angle", "ratio_of_roll", "blank_offset"):
        assert getattr(got.pinion_settings, key) == pytest.approx(getattr(ref.pinion_settings, key), rel=1e-7, abs=1e-7)
    assert got.pinion_cutter.blade_angle == pytest.approx(ref.pinion_cutter.blade_angle, rel=1e-8)
    assert got.phi1_mean == pytest.approx(ref.phi1_mean, abs=1e-9)
