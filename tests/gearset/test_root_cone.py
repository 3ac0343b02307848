"""The design check "root below the root cone" and the placement of a synthesized root on it (gearset/root_cone.py).

The check's root heights (the cutter's tip line located on the equation of meshing, then Newton's method at each face
station) against a brute force that uses no equation of meshing: the cutter's tip circle swept over a dense grid of
cutter angles and cradle angles, each point mapped into the member's axial section by the machine kinematics alone,
and at each station the lowest of these points above the root cone (the tip plane lies outside the surface of
revolution it generates, so the lowest swept point at a cone distance is the root there, approached from above by the
grid's spacing squared). Cases: the 12/41 pinion's concave flank (where the 3-station ``root_deviation`` of the
design-vs-achieved table finds no enveloped point) with its root sunk 0.4 mm (sliding base) and tilted (machine root
angle), and a developed 11/25 pair whose synthesized drive pinion's root lay 1.75 mm below the root cone before
:func:`raise_root`.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation.basic_settings_solve import root_deviation
from spiralbevel.generation.flank import generate_flank
from spiralbevel.gearset.pinion_fillet import raise_root
from spiralbevel.gearset.root_cone import (CAUSE, CAUSE_ABOVE, ROOT_STATIONS, root_cone, root_cone_checks,
                                           root_cone_messages, root_heights)
from spiralbevel.io.design_file import parse_design
from _design_12x41 import design_12x41
from _designs import basic_design, basic_setups, developed
from _synthesis_stand_in import Result

#: design 10 of ``bench_robustness.py 40 1``: the default synthesis' drive pinion cut 1.754 mm below the root cone
DESIGN_11x25 = basic_design(11, 25, shaft_angle="106.111", module="10.144", face_width="20.500",
                            mean_spiral_angle="10.314", hand="LH", cutter_radius="100.52",
                            title="11/25 of the robustness bench (bench_robustness.py 40 1, design 10)")


@pytest.fixture(scope="module")
def case():
    return basic_setups(design_12x41())


def brute_root(flank, R):
    """Lowest height (mm) above the root cone of the swept tip circle at cone distances ``R`` (module docstring):
    a grid of cutter angle x cradle angle over the whole cutter circle and +-0.6 rad of roll (points 0.26 mm apart
    on a 60 mm cutter), the lowest point of each station's bin (|R' - R| < 0.5 mm), then three times a grid ten
    times finer around it (+-3 steps of the last grid) with a bin ten times narrower."""
    gen, ol = flank.generator, flank.outline
    u0 = gen.cp["u_min"]

    def heights(phi, psi):
        ax, rad, _ = gen.point_at(u0, phi, psi)
        Rx, h = ol.Rh(ax, rad)
        return Rx, h - ol.h_root(Rx)

    phi, psi = np.meshgrid(np.linspace(-math.pi, math.pi, 1441), np.linspace(-0.6, 0.6, 401), indexing="ij")
    Rx, d = heights(phi, psi)
    out = []
    for Rk in R:
        dphi, dpsi, w = 2.0 * math.pi / 1440, 1.2 / 400, 0.5
        i = np.argmin(np.where(np.abs(Rx - Rk) < w, d, np.inf))
        p0, s0, best = phi.flat[i], psi.flat[i], d.flat[i]
        for _ in range(3):
            P, S = np.meshgrid(p0 + np.linspace(-3, 3, 61) * dphi, s0 + np.linspace(-3, 3, 61) * dpsi, indexing="ij")
            Rl, dl = heights(P, S)
            w *= 0.1
            j = np.argmin(np.where(np.abs(Rl - Rk) < w, dl, np.inf))
            p0, s0, best = P.flat[j], S.flat[j], dl.flat[j]
            dphi, dpsi = dphi / 10.0, dpsi / 10.0
        out.append(best)
    return np.array(out)


@pytest.mark.parametrize("change", [("sliding_base", 0.4), ("machine_root_angle", math.radians(0.3))],
                         ids=["sunk", "tilted"])
def test_root_heights_against_the_swept_tip_circle(case, change):
    spec, blank, setups = case
    st = setups[(Member.PINION, Side.CONCAVE)]
    name, d = change
    settings = dataclasses.replace(st.settings, **{name: getattr(st.settings, name) + d})
    flank = generate_flank(st.cutter, settings, blank, Member.PINION, Side.CONCAVE)
    R, h = root_heights(flank)
    assert len(R) == ROOT_STATIONS
    ref = brute_root(flank, R)
    # the brute force approaches the root from above by its last grid's spacing squared over the curvature radius
    # (3e-4 mm steps: below 1e-8 mm) and from below by the root's slope along the face times its last bin's
    # half-width (tilted: 0.0052 x 5e-4 mm = 3e-6 mm)
    assert np.max(np.abs(ref - h)) < 1e-5
    if name == "sliding_base":   # the sunk root: 0.4 mm deeper all along the face (0 before, to 1e-5 mm)
        assert h == pytest.approx(-0.4, abs=0.02)
    else:                        # tilted: deeper toward one end, the check's station and the brute force agree
        assert np.ptp(h) > 0.05


def test_root_heights_agree_with_root_deviation_where_it_finds_the_root(case):
    """A second measure of the same root: ``root_deviation`` samples the fillet 0.02 rad of the edge radius above
    the tip (rho (1 - cos 0.02) = 2e-4 rho higher) by the locator's Newton solve, at toe, mean and heel."""
    _, blank, setups = case
    st = setups[(Member.PINION, Side.CONVEX)]
    sunk = generate_flank(st.cutter, dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base + 0.4),
                          blank, Member.PINION, Side.CONVEX)
    for flank in (st.flank, sunk):
        dev = np.array(root_deviation(flank), float)
        R, h = root_heights(flank, 3)
        rho = flank.cutter.edge_radius
        assert np.all(np.abs(dev - (h + rho * (1 - math.cos(0.02)))) < 1e-3)


def test_raise_root_puts_the_root_on_the_cone_with_the_same_blade(case):
    _, blank, setups = case
    st = setups[(Member.PINION, Side.CONCAVE)]
    sunk = dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base + 0.4)
    flank = generate_flank(st.cutter, sunk, blank, Member.PINION, Side.CONCAVE)
    assert root_cone(flank).below
    new = raise_root(blank, Result(st.cutter, sunk, flank))
    after = root_cone(new.pinion_flank)
    assert not after.below and after.lowest == pytest.approx(0.0, abs=1e-3)
    assert np.max(np.abs(brute_root(new.pinion_flank, after.R[[0, 5, 10]]) - after.height[[0, 5, 10]])) < 1e-5
    delta = new.pinion_settings.sliding_base - sunk.sliding_base
    assert delta == pytest.approx(-0.4, abs=0.02)
    # the same blade surface: the old blade parameter u is u + Delta / cos(alpha) of the shortened blade
    c = st.cutter
    u_j = c.fillet_range[1]
    u, psi = np.meshgrid(np.linspace(u_j + 0.5, u_j + 6.0, 12), np.linspace(-0.15, 0.15, 7))
    old = flank.generator.points(u, psi)
    shifted = new.pinion_flank.generator.points(u + delta / math.cos(c.blade_angle), psi)
    assert np.max(np.abs(shifted - old)) < 1e-11            # round-off of the generation kernel at ~100 mm
    assert new.pinion_cutter.point_width == c.point_width     # kept: the cutter-fit refit narrows it from the derived
    assert new.pinion_cutter.edge_radius <= c.edge_radius     # reduced only where the junction would rise too high
    # a root on the cone is left alone
    assert raise_root(blank, Result(st.cutter, st.settings, st.flank)).pinion_flank is st.flank


def test_messages_name_the_key(case):
    spec, blank, setups = case
    st = setups[(Member.PINION, Side.CONCAVE)]
    sunk = dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base + 0.4)
    flank = generate_flank(st.cutter, sunk, blank, Member.PINION, Side.CONCAVE)
    basic = {(Member.PINION, Side.CONCAVE): dataclasses.replace(st, settings=sunk, flank=flank)}
    msg = root_cone_messages(spec, basic, root_cone_checks(basic))[(Member.PINION, Side.CONCAVE)][0]
    assert msg.startswith(CAUSE) and "face_milling.pinion_concave.machine.machine_root_angle" in msg
    assert f"{-root_cone(flank).lowest:.3f} mm below" in msg
    # a synthesized pinion with the point width given in the design file: that key, and the width that places it
    given = parse_design(design_12x41().replace("[flank]", "[face_milling]\npoint_width = 2.0\n[flank]"))
    synth = {(Member.PINION, Side.CONCAVE): dataclasses.replace(basic[(Member.PINION, Side.CONCAVE)],
                                                                 source="local synthesis (drive side)")}
    msg = root_cone_messages(given, synth, root_cone_checks(synth))[(Member.PINION, Side.CONCAVE)][0]
    w = st.cutter.point_width - 2.0 * root_cone(flank).lowest * math.tan(st.cutter.blade_angle)
    assert "face_milling.point_width" in msg and f"at least {w:.3f} mm" in msg
    assert root_cone_messages(spec, setups, root_cone_checks(setups)) == {}    # the basic roots lie on the cone


def test_root_above_the_cone_warns_with_reason_and_key(case):
    """A root lifted 0.3 mm above the root cone (sliding base, basic settings otherwise) was never checked: it is now,
    with the same 11-station measure (its heights against the brute force at toe, mean and heel), the reason (a
    shallower tooth space: less clearance to the mate's tip) and the key; a synthesized flank's warning names the
    [synthesis] keys, the fixed-blade set (which moves the tip plane) first."""
    spec, blank, setups = case
    st = setups[(Member.PINION, Side.CONVEX)]
    lifted = dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base - 0.3)
    flank = generate_flank(st.cutter, lifted, blank, Member.PINION, Side.CONVEX)
    res = root_cone(flank)
    assert res.above and not res.below
    # the brute force approaches the root from above by its grid spacing squared (< 1e-5 mm, see brute_root)
    assert np.max(np.abs(brute_root(flank, res.R[[0, 5, 10]]) - res.height[[0, 5, 10]])) < 1e-5
    assert res.to_dict()["highest_mm"] == pytest.approx(res.highest) and res.to_dict()["above"]
    up = {(Member.PINION, Side.CONVEX): dataclasses.replace(st, settings=lifted, flank=flank)}
    (msg,) = root_cone_messages(spec, up, root_cone_checks(up))[(Member.PINION, Side.CONVEX)]
    assert msg.startswith(CAUSE_ABOVE) and f"{res.highest:.3f} mm above" in msg and "clearance" in msg
    assert "face_milling.pinion_convex.machine.machine_root_angle" in msg
    source = "local synthesis (coast side, free = fixed-blade)"
    syn = {(Member.PINION, Side.CONVEX): dataclasses.replace(up[(Member.PINION, Side.CONVEX)], source=source)}
    (msg,) = root_cone_messages(spec, syn, root_cone_checks(syn))[(Member.PINION, Side.CONVEX)]
    assert "face_milling" not in msg and "default synthesis (no [synthesis] section)" in msg
    assert 'synthesis.free = "offset" or "modified-roll"' in msg and "gear_set.cutter_radius" in msg


def test_developed_pair_roots_on_the_cone():
    """The default synthesis of the 11/25 design puts every root on the root cone (the drive pinion's lay 1.754 mm
    below it before the placement), and the report section says so."""
    _, blank, setups, _ = developed(DESIGN_11x25)
    checks = root_cone_checks(setups)
    assert all(not r.below and r.lowest > -1e-3 for r in checks.values())
    st = setups[(Member.PINION, Side.CONCAVE)]
    assert "synthesis" in st.source
    got = checks[(Member.PINION, Side.CONCAVE)]
    assert np.max(np.abs(brute_root(st.flank, got.R[[0, 10]]) - got.height[[0, 10]])) < 1e-5   # as above


#: a miter set whose default drive synthesis (free = fixed-blade) cuts the pinion's root 1.576 mm below the root cone
#: with a machine root angle tilted 8.15 deg (the dedendum angle) from the root cone's: a move of the sliding base by
#: the depth would lift the root 1.592 mm, 0.016 mm above the cone (found by a newcomer's walk with own designs)
DESIGN_MITER = basic_design(20, 20, module=4, face_width=25, mean_spiral_angle=30, hand="LH",
                            title="20/20 miter, the sliding base tilted against the root cone")


def test_raise_root_lands_on_the_cone_where_the_slide_is_tilted():
    _, _, setups, _ = developed(DESIGN_MITER)
    flank = setups[(Member.PINION, Side.CONCAVE)].flank
    assert "root raised" in setups[(Member.PINION, Side.CONCAVE)].source
    rc = root_cone(flank)
    # the highest of the 11 stations on the cone (the secant step is exact for a parallel shift of the tip plane),
    # checked by the swept tip circle at every station (the oracle's own 1e-5 mm)
    assert abs(rc.highest) < 1e-6 and not rc.below and not rc.above
    assert abs(np.max(brute_root(flank, rc.R))) < 1e-5


#: design 58 of ``bench_robustness.py 100 2``: the default coast synthesis (free = fixed-blade) put the pinion's
#: cutter tip plane 1.85 mm above the root cone at every station (a shallower tooth space, less than the clearance to
#: the gear's tip left); the default synthesis lowers it onto the cone (blade extended, point width narrower)
DESIGN_17x24 = basic_design(17, 24, shaft_angle="94.491", module="8.755", face_width="19.483",
                            mean_spiral_angle="16.142", hand="LH", cutter_radius="118.84",
                            title="17/24 of the robustness bench (bench_robustness.py 100 2, design 58)")


def test_default_synthesis_lowers_a_root_above_the_cone():
    _, _, setups, _ = developed(DESIGN_17x24)
    st = setups[(Member.PINION, Side.CONVEX)]
    assert "root lowered onto the root cone" in st.source
    rc = root_cone(st.flank)
    assert abs(rc.lowest) < 1e-6 and not rc.below and not rc.above     # the lowest station on the cone (secant step)
    assert abs(np.min(brute_root(st.flank, rc.R))) < 1e-5              # the swept tip circle's own 1e-5 mm
