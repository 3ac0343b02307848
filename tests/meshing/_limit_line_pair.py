"""Test helper: the coast pair of sample design 64 of ``bench/bench_robustness.py 100 2`` (13/20 teeth, shaft angle
69.1 deg, spiral angle 10.3 deg, module 7.30 mm, right hand) with the cutters and machine settings of the developed
pair (the default face-milled job: the pinion's convex flank from the default local synthesis, the gear's concave
flank from the solved basic settings), stored here so that a test rebuilds the flanks in a fraction of a second
instead of re-running the synthesis (about 30 s).

The gear's concave flank folds back over itself near its fillet junction at the end of the roll: past a limit line
of generation (``GeneratedSurface.on_sheet``) the envelope's points are cut away. Around 0.3 of a mesh cycle after
the mean contact the incoming pair's contact runs there.

``SETTINGS`` below is the output of ``python tests/meshing/_limit_line_pair.py`` (run from the repository root: it
draws the design from the bench's sampler, runs the job's flank setup with its synthesis and prints the values).
"""

from __future__ import annotations

from _interference_pair import bench_sample, build_pair, print_settings  # puts tests/ on the path
from _designs import basic_design

#: design file of the sample (``bench_robustness.sample``, seed 2, design 64)
DESIGN = basic_design(13, 20, shaft_angle="69.078", module="7.304", face_width="23.043", mean_spiral_angle="10.316",
                      hand="RH", cutter_radius="80.88", title="sample")

#: (member, side) -> (HeadCutter fields, MachineSettings fields) of the coast flanks (see the module docstring)
SETTINGS = {('pinion', 'convex'): ({'point_radius': 90.26802986784003,
                                    'blade_angle': 0.36196378019626596,
                                    'point_width': 2.308437877361893,
                                    'edge_radius': 1.5876699061679167,
                                    'blade': 'inner',
                                    'profile_radius': 'inf',
                                    'profile_ref': 0.0},
                                   {'radial_setting': 120.93106083770732,
                                    'cradle_angle': 0.6964212482941388,
                                    'machine_root_angle': 0.3797102058005068,
                                    'machine_centre_to_back': 11.260915578685939,
                                    'sliding_base': 2.5500286319328733,
                                    'blank_offset': 9.467081379948514,
                                    'ratio_of_roll': 2.4681476204974295,
                                    'modified_roll': (),
                                    'blank_offset_poly': (),
                                    'blank_offset_table': ()}),
            ('gear', 'concave'): ({'point_radius': 82.99977840556343,
                                   'blade_angle': 0.31681130648531286,
                                   'point_width': 4.1134326952906415,
                                   'edge_radius': 2.315554196016853,
                                   'blade': 'outer',
                                   'profile_radius': 'inf',
                                   'profile_ref': 0.0},
                                  {'radial_setting': 117.43934556558574,
                                   'cradle_angle': 0.7964602504398433,
                                   'machine_root_angle': 0.590957107020416,
                                   'machine_centre_to_back': 8.856039031153543,
                                   'sliding_base': 0.0,
                                   'blank_offset': 0.0,
                                   'ratio_of_roll': 1.5652730553065644,
                                   'modified_roll': (),
                                   'blank_offset_poly': (),
                                   'blank_offset_table': ()})}


def coast_pair():
    """``(pinion, gear, kinematics)`` of the coast side: the phased contact surfaces of the job's TCA."""
    return build_pair(DESIGN, SETTINGS)


def _derive():
    """The cutters and settings of the coast flanks of the developed pair (printed as ``SETTINGS``)."""
    import warnings

    from spiralbevel.conventions import Member
    from spiralbevel.gearset.facemilled import PAIR_SIDES
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job import facemilled as fm
    from spiralbevel.job.blank import blank_from_design

    text = bench_sample(64)
    assert text == DESIGN, text
    spec = parse_design(text)
    blank = blank_from_design(spec)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        setups, _ = fm.setup_flanks(spec, blank, with_synthesis=True)
    print_settings([((m.value, s.value), setups[(m, s)].cutter, setups[(m, s)].settings)
                    for m, s in zip((Member.PINION, Member.GEAR), PAIR_SIDES["coast"])])


if __name__ == "__main__":
    _derive()
