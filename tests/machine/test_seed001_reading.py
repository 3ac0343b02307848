"""Seed 001 Tables 4 and 5 read against Table 1 (docs/conventions.md, "Seed 001 Tables 4 and 5").

Two readings are pinned here: the sliding base of the paper counts positive away from the cutter (spiralbevel's
toward it), and the pinion cutter has Table 5's blade angle 22 deg 30' rather than its "modified" 21 deg 10'.
"""

import math

import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.generation.basic_settings_solve import root_deviation
from spiralbevel.machine import HeadCutter, seed001_blank, seed001_settings

GEAR, PINION = (Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)


def _table1_root_deviation(blank, member, settings) -> float:
    """Height (mm) of the generated root above Table 1's root cone, by cone geometry alone (no generation).

    The blade tips sweep the cradle plane; the work's root is the envelope of that plane, the cone about the work axis
    tangent to it, with half angle gamma_m and its apex where the work axis crosses the plane: at the axial position
    X_B / sin(gamma_m) - X_D from the member apex (the axis passes through (0, E_m, -X_B), the apex at X_D along it).
    Table 1's root cone (angle delta_f through h = -h_fm at R_m) has its apex at z_T. Two coaxial cones of equal
    angle apart by dz along the axis are -dz sin(delta_f) / cos(theta_f) apart in the height h above the pitch line.
    """
    i = member.index
    d, df, hfm = getattr(blank, f"delta{i}"), getattr(blank, f"delta_f{i}"), getattr(blank, f"hfm{i}")
    z_t = (blank.Rm * math.cos(d) + hfm * math.sin(d)) - (blank.Rm * math.sin(d) - hfm * math.cos(d)) / math.tan(df)
    gm = settings.machine_root_angle
    z_g = settings.sliding_base / math.sin(gm) - settings.machine_centre_to_back
    return -(z_g - z_t) * math.sin(df) / math.cos(d - df)


@pytest.mark.parametrize("key", [GEAR, PINION])
def test_roots_on_table1_root_cone(key):
    """Both generated roots lie within 0.01 mm of Table 1's root cone with the sliding bases read with spiralbevel's
    sign; with the printed signs they miss it by about 0.1 mm (gear too deep, pinion too shallow)."""
    blank = seed001_blank()
    cutter, settings = seed001_settings()[key]
    dev = root_deviation(generate_flank(cutter, settings, blank, *key))
    est = _table1_root_deviation(blank, key[0], settings)
    # the kernel samples the fillet 0.02 rad from the tip (1.31 mm (1 - cos 0.02) = 2.6e-4 mm above the tip plane)
    # and locates to 1e-6 mm: 5e-4 mm between the two methods
    for v in dev:
        assert v == pytest.approx(est, abs=5e-4)
        assert abs(v) < 0.01
    printed = settings.replace(sliding_base=-settings.sliding_base)
    dev_printed = root_deviation(generate_flank(cutter, printed, blank, *key))[1]
    assert dev_printed == pytest.approx(_table1_root_deviation(blank, key[0], printed), abs=5e-4)
    assert abs(dev_printed) > 0.09
    assert (dev_printed < 0) == (key == GEAR)        # printed sign: the gear too deep, the pinion too shallow


def test_pinion_blade_matches_gear_at_mean_point():
    """Table 5 is a local-synthesis result against the Table 4 gear, so pinion concave and gear convex share the
    mean-point normal: the mean-point normal pressure angles agree within 0.15 deg with the 22 deg 30' blade
    (measured 0.12 deg) and differ by 1.25 deg with the 21 deg 10' "modified" blade."""
    blank = seed001_blank()
    table = seed001_settings()
    gc, gs = table[GEAR]
    pc, ps = table[PINION]
    assert math.degrees(pc.blade_angle) == pytest.approx(22.5, abs=1e-12)
    alpha_gear = generate_flank(gc, gs, blank, *GEAR).mean_point().pressure_angle
    alpha_pin = generate_flank(pc, ps, blank, *PINION).mean_point().pressure_angle
    assert abs(math.degrees(alpha_pin - alpha_gear)) < 0.15
    modified = HeadCutter(point_radius=pc.point_radius, blade_angle=math.radians(21 + 10 / 60),
                          point_width=pc.point_width, edge_radius=pc.edge_radius, blade=pc.blade)
    alpha_mod = generate_flank(modified, ps, blank, *PINION).mean_point().pressure_angle
    assert math.degrees(alpha_gear - alpha_mod) > 1.2
    # and both readings keep the design spiral angle of Table 1 (30 deg) within 0.15 deg on the pinion
    assert math.degrees(generate_flank(pc, ps, blank, *PINION).mean_point().spiral_angle) == pytest.approx(30, abs=0.15)
