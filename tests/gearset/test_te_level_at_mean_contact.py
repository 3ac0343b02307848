"""The TE-level check of a developed pair whose mean contact M lies below the pitch line: 10/19 at beta 44.9 deg
(bench/bench_robustness.py 100 2, design 56). The default synthesis develops its coast side with M at half the
middle of the working depth (0.19 mm below the gear's pitch line); the TE's stationary point, where the synthesis
prescribes the design level, then lies about a quarter of half a mesh cycle off the TCA's mean position. The level
fitted around it (``tca_checks.parabolic_level``) is the design's; a parabola centred on the mean position read
9.3 arcsec.
"""

import math
import warnings

import numpy as np
import pytest

from spiralbevel.gearset import facemilled as gfm
from spiralbevel.gearset.tca import run_pair_tca
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.meshing.tca_checks import TE_LEVEL_TOL, parabolic_level, te_level_warnings

DESIGN_10X19 = """
title = "sample"
[gear_set]
pinion_teeth = 10
gear_teeth = 19
shaft_angle = 107.889
module = 1.410
face_width = 2.935
normal_pressure_angle = 20
mean_spiral_angle = 44.893
pinion_hand = "LH"
cutter_radius = 12.52
[flank]
kind = "face-milled"
"""


def test_te_level_fitted_around_the_mean_contact_is_the_design_level():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(DESIGN_10X19)
        blank = blank_from_design(spec)
        setups, synth = gfm.setup_flanks(spec, blank, with_synthesis=True)
    grids = {k: st.flank.grid(9, 5, curvature=False) for k, st in setups.items()}
    results, section, _ = run_pair_tca(blank, setups, grids, n_positions=21)
    z1 = spec.gear_set.pinion_teeth
    half = math.pi / z1
    design = gfm.DEFAULT_SYNTHESIS["te_magnitude"]
    for name in ("drive", "coast"):
        sec = section[name]
        assert sec["edge_contact_positions_deg"] == [] and sec["no_contact_positions_deg"] == [], name
        phi, te = np.radians(sec["pinion_rotation_deg"]), np.asarray(sec["transmission_error_arcsec"])
        assert parabolic_level(phi, te, z1) == pytest.approx(design, rel=TE_LEVEL_TOL), name
        assert te_level_warnings(results[name], name, design, z1) == [], name
    # the coast TE's stationary point: the vertex of the parabola through the three positions around the largest TE
    sec = section["coast"]
    phi, te = np.radians(sec["pinion_rotation_deg"]), np.asarray(sec["transmission_error_arcsec"])
    k = int(np.argmax(te))
    a2, a1, _ = np.polyfit(phi[k - 1:k + 2], te[k - 1:k + 2], 2)
    assert -a1 / (2 * a2) > 0.15 * half
