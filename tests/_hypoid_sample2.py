"""ISO 23509 Annex F, Sample 2 (the hypoid sample): its input data as ``BlankInput`` keywords (mm, rad) and as a
design file, shared by the hypoid tests."""

import math

R = math.radians

SAMPLE2 = dict(z1=13, z2=42, b=30.0, beta_m=R(50.0), rc0=63.5, de2=170.0, a=15.0, f_alim=1.0, c_ham=0.35, k_d=2.0,
               k_c=0.125, k_t=0.1, jet=0.2, taper="given", theta_a2=R(1.0), theta_f2=R(4.0))

#: the same sample as a face-milled design file (degrees and mm, as users write it)
SAMPLE2_TOML = """title = "Sample 2 hypoid"
[gear_set]
pinion_teeth = 13
gear_teeth = 42
outer_pitch_diameter = 170.0
face_width = 30.0
mean_spiral_angle = 50
pinion_hand = "LH"
cutter_radius = 63.5
hypoid_offset = 15.0
limit_pressure_angle_factor = 1.0
[gear_set.depth]
taper = "given"
gear_addendum_dedendum_angles = [1.0, 4.0]
mean_addendum_factor = 0.35
thickness_factor = 0.1
[flank]
kind = "face-milled"
"""


def sample2_blank():
    """The hypoid blank of Sample 2 (``compute_blank``), its own face width warning silenced (b2 = 30 mm exceeds
    0.3 Re2: the standard's sample as published)."""
    import warnings

    from spiralbevel.design.blank import BlankInput, compute_blank

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return compute_blank(BlankInput(**SAMPLE2))


def sample2_concave_pinion(blank, flanks, eta, semi_major_axis, te_magnitude):
    """The pinion concave flank of Sample 2 synthesized by ``synthesize_hypoid_pinion`` against the gear convex flank
    of ``flanks`` (``hypoid_basic_flanks(blank)``), from the pinion's basic cutter and settings (eta rad,
    semi_major_axis mm, te_magnitude rad)."""
    from spiralbevel.conventions import Member, Side
    from spiralbevel.meshing.synthesis.hypoid_local import synthesize_hypoid_pinion

    c, s, _, _ = flanks[(Member.PINION, Side.CONCAVE)]
    return synthesize_hypoid_pinion(flanks[(Member.GEAR, Side.CONVEX)][2], c, s, blank, eta=eta,
                                    semi_major_axis=semi_major_axis, te_magnitude=te_magnitude)

#: ``[synthesis]`` keys with the seed 001 values (semi-major axis 3.7 mm, 3 arcsec, 0.00635 mm approach), appended to
#: a given section whose tests were written for them: the keys a section leaves out keep the developed-pair defaults
#: (0.15 b, 8 arcsec, b/5827)
SEED001_SYNTHESIS = "semi_major_axis = 3.7\nte_magnitude = 3.0\napproach = 0.00635\n"
