"""Test helper: the coast pair of sample design 51 of ``bench/bench_robustness.py 100 2`` (11/12 teeth, shaft angle
62.9 deg, spiral angle 29.9 deg, module 10.70 mm, left hand), with the cutters and machine settings that the default
face-milled job gave its coast flanks before the TCA saw the gear's fillet interference (the pinion's convex flank
from a candidate of the default local synthesis, the gear's concave flank from the basic settings), stored here so
that a test rebuilds the flanks in a fraction of a second instead of re-running the synthesis (about 30 s).

The gear's concave flank folds back over itself near its fillet junction (past a limit line of generation); TCA
had reported that folded part's fillet junction against the pinion flank ahead of the pair's surface contact, over
most of the mesh cycle, up to 108 arcsec. The folded part is cut away: the real teeth touch at the surface contact
(tests/meshing/test_tca_limit_line.py).

``SETTINGS`` below is the output of ``python tests/meshing/_interference_pair.py`` (run from the repository root: it
draws the design from the bench's sampler, solves the basic settings and that local synthesis and prints the values).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # tests/ (_designs), also when run as a script
from _designs import basic_design  # noqa: E402

#: design file of the sample (``bench_robustness.sample``, seed 2, design 51)
DESIGN = basic_design(11, 12, shaft_angle="62.918", module="10.701", face_width="25.452", mean_spiral_angle="29.908",
                      hand="LH", cutter_radius="92.29", title="sample")

#: (member, side) -> (HeadCutter fields, MachineSettings fields) of the coast flanks (see the module docstring)
SETTINGS = {('pinion', 'convex'): ({'point_radius': 98.32769953873743,
                                    'blade_angle': 0.4239579862805787,
                                    'point_width': 5.468732227050315,
                                    'edge_radius': 2.986903211676289,
                                    'blade': 'inner',
                                    'profile_radius': 'inf',
                                    'profile_ref': 0.0},
                                   {'radial_setting': 98.59830336933095,
                                    'cradle_angle': 0.9441736941166254,
                                    'machine_root_angle': 0.4340251245555359,
                                    'machine_centre_to_back': -0.585538254496015,
                                    'sliding_base': 0.0,
                                    'blank_offset': 4.018193767672348,
                                    'ratio_of_roll': 1.9120168854525748,
                                    'modified_roll': (),
                                    'blank_offset_poly': (),
                                    'blank_offset_table': ()}),
            ('gear', 'concave'): ({'point_radius': 95.02436611352516,
                                   'blade_angle': 0.29451483388806526,
                                   'point_width': 5.468732227050314,
                                   'edge_radius': 2.986903211676289,
                                   'blade': 'outer',
                                   'profile_radius': 'inf',
                                   'profile_ref': 0.0},
                                  {'radial_setting': 99.23946890475492,
                                   'cradle_angle': 1.004307097826702,
                                   'machine_root_angle': 0.469154403767531,
                                   'machine_centre_to_back': 0.30349876312855883,
                                   'sliding_base': 0.0,
                                   'blank_offset': 0.0,
                                   'ratio_of_roll': 1.8312480533211164,
                                   'modified_roll': (),
                                   'blank_offset_poly': (),
                                   'blank_offset_table': ()})}


def coast_pair():
    """``(pinion, gear, kinematics)`` of the coast side: the phased contact surfaces of the job's TCA."""
    return build_pair(DESIGN, SETTINGS)


def build_pair(design, settings):
    """``(pinion, gear, kinematics)``: the phased contact surfaces of the two flanks of ``settings`` ((member, side)
    -> (HeadCutter fields, MachineSettings fields), pinion first) on the blank of the design file text ``design``."""
    from spiralbevel.conventions import Member, Side
    from spiralbevel.generation.flank import generate_flank
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.machine.cutter import Blade, HeadCutter
    from spiralbevel.machine.settings import MachineSettings
    from spiralbevel.meshing.generated_surface import phased_for_pair
    from spiralbevel.meshing.kinematics import BevelPairKinematics

    blank = blank_from_design(parse_design(design))
    flanks = []
    for (m, s), (c, st) in settings.items():
        c = dict(c, blade=Blade(c["blade"]), profile_radius=float(c["profile_radius"]))
        cutter, ms = HeadCutter(**c), MachineSettings(**st)
        flanks.append(generate_flank(cutter, ms, blank, Member(m), Side(s)))
    c1, c2 = phased_for_pair(*flanks)
    return c1, c2, BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)


def _derive():
    """The cutters and settings of the coast flanks (printed as ``SETTINGS``): the gear's basic settings, and the
    pinion of the default synthesis' candidate that the job took before the TCA saw the interference (path direction
    -55 deg at the mean pitch point, settings ``offset``, the default TE level and ellipse; the job now moves on to
    another candidate)."""
    from spiralbevel.conventions import Member, Side
    from spiralbevel.gearset import facemilled as fm
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.meshing import synthesis as syn
    from spiralbevel.meshing.tca_result import ARCSEC

    text = bench_sample(51)
    assert text == DESIGN, text
    spec = parse_design(text)
    blank = blank_from_design(spec)
    setups = fm._basic_setups(spec, blank)
    sy = fm.effective_synthesis(spec, blank)
    assert (-55.0, 0.0) in fm.DEFAULT_CANDIDATES and sy.free == "offset"
    gear, pin = setups[(Member.GEAR, Side.CONCAVE)], setups[(Member.PINION, Side.CONVEX)]
    res = syn.synthesize_pinion(gear.cutter, gear.settings, blank, side=Side.CONVEX, eta=math.radians(-55.0),
                                semi_major_axis=sy.semi_major_axis, te_magnitude=sy.te_magnitude * ARCSEC,
                                approach=sy.approach, free=syn.FREE_OFFSET, depth=0.0,
                                pinion_cutter_hint=pin.cutter, pinion_settings_hint=pin.settings)
    print_settings([(("pinion", "convex"), res.pinion_cutter, res.pinion_settings),
                    (("gear", "concave"), gear.cutter, gear.settings)])


def bench_sample(design: int) -> str:
    """The design-file text of sample ``design`` (counted from 0) of ``bench/bench_robustness.py 100 2`` (seed 2), as
    the bench's sampler draws it."""
    import sys
    from pathlib import Path

    import numpy as np

    sys.path.insert(0, str(Path(__file__).parents[2] / "bench"))
    import bench_robustness as br

    rng = np.random.default_rng(2)
    for _ in range(design + 1):
        text, _label = br.sample(rng)
    return text


def print_settings(flanks):
    """Print ``{(member, side): (HeadCutter fields, MachineSettings fields)}`` of ``flanks`` (((member, side) names,
    cutter, settings) in turn) as a helper's ``SETTINGS`` is written."""
    import dataclasses
    import pprint

    out = {}
    for key, cutter, settings in flanks:
        c = dataclasses.asdict(cutter)
        c["blade"] = cutter.blade.value
        if math.isinf(c["profile_radius"]):
            c["profile_radius"] = "inf"
        out[key] = (c, dataclasses.asdict(settings))
    pprint.pprint(out, width=116, sort_dicts=False)


if __name__ == "__main__":
    _derive()
