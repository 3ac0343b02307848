"""Checks on a developed pair: pinion undercut at the achieved pressure angles, design-vs-achieved per flank."""

import math
import warnings

import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank_checks import achieved_undercut, section_limit_depth
from spiralbevel.generation.basic_settings_solve import FlankFit
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.facemilled import flank_checks
from _design_12x41 import design_12x41

@pytest.mark.parametrize("z1", [9, 12])
def test_undercut_threshold_at_the_achieved_angle(z1):
    """The root-undercut warning switches on exactly where (dvn1/2) sin^2(alpha) = hfm1: the threshold angle by the
    closed-form inversion of the nominal limit depth, L(alpha) = L(alpha_n) sin^2(alpha) / sin^2(alpha_n)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bl = blank_from_design(parse_design(design_12x41(z1)))
    a0 = min(bl.alpha_nD, bl.alpha_nC)
    L0 = section_limit_depth(bl, 1, "m")
    a_root = math.asin(math.sqrt(bl.hfm1 / L0) * math.sin(a0))     # hfm1 = L(a_root)
    a_active = math.asin(math.sqrt(bl.ham2 / L0) * math.sin(a0))   # ham2 = L(a_active) < a_root
    d = math.radians(0.01)
    assert achieved_undercut(bl, a_root + d, math.radians(25.0)) == []
    below = achieved_undercut(bl, math.radians(25.0), a_root - d)   # the smaller of the two angles counts
    assert len(below) == 1 and "root undercut" in below[0] and "gear_set.normal_pressure_angle" in below[0]
    active = achieved_undercut(bl, a_active - d, a_active - d)
    assert len(active) == 1 and "gear_set.pinion_teeth" in active[0]


def test_flank_checks_name_the_key():
    a, b = math.radians(20.0), math.radians(35.0)
    ok = FlankFit(a, a + math.radians(0.04), b, b - math.radians(0.04), (0.0, -0.009, 0.002), 3)
    assert flank_checks(ok, Member.GEAR, Side.CONVEX) == []
    bad = FlankFit(a, a - math.radians(0.3), b, b + math.radians(0.1), (-0.02, None, 0.0), 3)
    msgs = flank_checks(bad, Member.PINION, Side.CONCAVE)
    assert len(msgs) == 3
    assert "face_milling.pinion_concave.cutter.blade_angle" in msgs[0] and "-0.300 deg" in msgs[0]
    assert "face_milling.pinion_concave.machine" in msgs[1]
    assert "below the blank's root cone by 0.020 / 0.000 mm at the toe / heel" in msgs[2]


def test_flank_checks_of_a_synthesized_flank_name_the_synthesis():
    """A synthesized flank has no face_milling.<m>_<s>.machine to change: the root check names the [synthesis] keys
    (the fixed-blade set, the one that solves the machine centre to back, first), says when the default synthesis
    produced the flank, and gives toe/mean/heel in one line."""
    a = math.radians(20.0)
    fit = FlankFit(a, a, a, a, (-0.019, -0.0189, -0.0188), 3)
    source = "local synthesis (coast side, free = fixed-blade)"
    default = parse_design(design_12x41())
    given = parse_design(design_12x41() + "\n[synthesis]\nfree = \"fixed-blade\"\n")
    (msg,) = flank_checks(fit, Member.PINION, Side.CONVEX, source, default)
    assert "face_milling" not in msg
    assert "0.019 / 0.019 / 0.019 mm at the toe / mean / heel" in msg
    assert "default synthesis (no [synthesis] section)" in msg and 'synthesis.free = "offset"' in msg
    assert "gear_set.cutter_radius (now 114.3 mm)" in msg
    (msg,) = flank_checks(fit, Member.PINION, Side.CONVEX, source, given)
    assert "default synthesis" not in msg and 'set synthesis.free = "offset" or "modified-roll"' in msg
    (msg,) = flank_checks(fit, Member.PINION, Side.CONVEX, "local synthesis (drive side, free = offset)", given)
    assert "synthesis.path_direction" in msg and "face_milling" not in msg


def _involute_top_land(d, s, ha, alpha_d, alpha_c):
    """Top land of a spur tooth by the involute construction: each flank is the curve a taut string unwinds from its
    own base circle (radius d/2 cos(alpha)); its polar angle at radius r is measured on the constructed point."""
    import numpy as np

    r, ra = 0.5 * d, 0.5 * d + ha

    def polar(rb, rad):
        t = math.sqrt((rad / rb) ** 2 - 1.0)
        x, y = rb * (math.cos(t) + t * math.sin(t)), rb * (math.sin(t) - t * math.cos(t))
        return float(np.arctan2(y, x))

    width = s / r
    for a in (alpha_d, alpha_c):
        rb = r * math.cos(a)
        width -= polar(rb, ra) - polar(rb, r)
    return ra * width


@pytest.mark.parametrize("z1", [12, 20])
def test_pointed_teeth_at_the_achieved_angles(z1):
    """The pointed-teeth check on the achieved angles switches on exactly where the involute construction of the
    virtual normal spur tooth gives a top land of 0.2 m_n; below it nothing is flagged."""
    from scipy.optimize import brentq

    from spiralbevel.design.blank_checks import _MIN_TOPLAND, achieved_top_land
    from spiralbevel.design.blank_thickness import virtual_normal_diameter

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bl = blank_from_design(parse_design(design_12x41(z1)))
    ac = bl.alpha_nC
    for k in (1, 2):
        dvn = virtual_normal_diameter(bl.Rm, getattr(bl, f"delta{k}"), bl.beta_m1,
                                      math.cos(0.5 * (bl.alpha_nD + bl.alpha_nC)) ** 2)
        s, ha = getattr(bl, f"smn{k}"), getattr(bl, f"ham{k}")
        limit = _MIN_TOPLAND * bl.mmn
        assert _involute_top_land(dvn, s, ha, bl.alpha_nD, ac) > limit   # the nominal design is fine
        assert achieved_top_land(bl, k, bl.alpha_nD, ac) == []
        # the drive angle at which the top land reaches the limit, by the construction
        a_lim = brentq(lambda a, dvn=dvn, s=s, ha=ha, lim=limit: _involute_top_land(dvn, s, ha, a, ac) - lim,
                       bl.alpha_nD, math.radians(60.0))
        d = math.radians(0.01)
        assert achieved_top_land(bl, k, a_lim - d, ac) == []
        msgs = achieved_top_land(bl, k, a_lim + d, ac)
        assert len(msgs) == 1 and "gear_set.depth.thickness_factor" in msgs[0]
        assert ("pinion" if k == 1 else "wheel") in msgs[0]
