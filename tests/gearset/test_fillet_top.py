"""The design check "fillet above the mate's tip" (gearset/fillet_top.py).

Fires: an 11/17 design of the robustness bench (shaft angle 66.8 deg, spiral angle 21.5 deg, module 2.01 mm), whose
TCA shows edge contacts at the pinion's fillet. Checked two ways other than the check's own comparison: (1) the mate's
reach brute force in 3-D: each junction point turned about its own axis through a full turn, its depth inside the
mate's face-cone solid (built from the ISO outer tip point and face angle, not from the mean addendum and the
dedendum angles the check uses); (2) the tooth contact analysis of the pair finds the edge contact there.
On two bundled examples: fires where, and only where, their TCA shows the pinion's fillet edge contact.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import spiralbevel as sb
from spiralbevel.conventions import Member, Side
from spiralbevel.gearset.fillet_top import (CAUSE, FILLET_TOP_TOL_MM, fillet_top_checks, fillet_top_messages,
                                            mate_top_height)
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design

DESIGN_11x17 = """
title = "11/17 of the robustness bench (bench_robustness.py 40 1, design 33)"
[gear_set]
pinion_teeth = 11
gear_teeth = 17
shaft_angle = 66.790
module = 2.013
face_width = 6.328
normal_pressure_angle = 20
mean_spiral_angle = 21.501
pinion_hand = "LH"
cutter_radius = 18.37
[flank]
kind = "face-milled"
"""

ALL = [(m, s) for m in (Member.PINION, Member.GEAR) for s in (Side.CONVEX, Side.CONCAVE)]


#: (member, side) -> (HeadCutter fields, MachineSettings fields, source) of the four flanks of the 11/17 design as
#: the default job developed it before TCA stopped counting touches of cut-away material past a limit line of
#: generation (docs/conventions.md): the default search now settles on another coast candidate, with no edge contact;
#: this pair's pinion fillet edge contact is real (TCA against the gap oracle of tests/meshing to 3e-6 arcsec)
SETUPS_11x17 = {('pinion', 'convex'): ({'point_radius': 18.07264390038148,
                         'blade_angle': 0.5682692271824084,
                         'point_width': 0.3224241404496507,
                         'edge_radius': 0.2795019010139679,
                         'blade': 'inner',
                         'profile_radius': 'inf',
                         'profile_ref': 0.0},
                        {'radial_setting': 22.75774303737177,
                         'cradle_angle': 0.8788363328997945,
                         'machine_root_angle': 0.3770114534793346,
                         'machine_centre_to_back': -0.03257084622416073,
                         'sliding_base': 0.0,
                         'blank_offset': 0.0,
                         'ratio_of_roll': 2.0819439643990165,
                         'modified_roll': (-0.004646277389980819,),
                         'blank_offset_poly': (),
                         'blank_offset_table': ()},
                        'local synthesis (coast side, free = modified-roll); point width 0.322 mm fitted to the '
                        'tooth space (derived 1.086 mm)'),
 ('pinion', 'concave'): ({'point_radius': 17.23648924354354,
                          'blade_angle': 0.27148011581520687,
                          'point_width': 0.7702810113342353,
                          'edge_radius': 0.4816378947987851,
                          'blade': 'outer',
                          'profile_radius': 'inf',
                          'profile_ref': 0.0},
                         {'radial_setting': 23.683762771899257,
                          'cradle_angle': 0.8555183100670555,
                          'machine_root_angle': 0.3770114534793346,
                          'machine_centre_to_back': -0.03257084622416073,
                          'sliding_base': 0.0,
                          'blank_offset': -1.1087999003063158,
                          'ratio_of_roll': 2.426328664494284,
                          'modified_roll': (),
                          'blank_offset_poly': (),
                          'blank_offset_table': ()},
                         'local synthesis (drive side, free = offset); point width 0.770 mm fitted to the tooth '
                         'space (derived 1.086 mm)'),
 ('gear', 'convex'): ({'point_radius': 17.826856227689625,
                       'blade_angle': 0.3945755321169123,
                       'point_width': 1.0692442928087118,
                       'edge_radius': 0.5933067521175278,
                       'blade': 'inner',
                       'profile_radius': 'inf',
                       'profile_ref': 0.0},
                      {'radial_setting': 23.781648053425695,
                       'cradle_angle': 0.7302366868381314,
                       'machine_root_angle': 0.5910546875382607,
                       'machine_centre_to_back': 0.7241810193192606,
                       'sliding_base': 0.0,
                       'blank_offset': 0.0,
                       'ratio_of_roll': 1.5379439278475806,
                       'modified_roll': (),
                       'blank_offset_poly': (),
                       'blank_offset_table': ()},
                      'basic settings solved for the design pressure and spiral angles, root on the root cone; '
                      'point width 1.069 mm fitted to the tooth space (derived 1.086 mm)'),
 ('gear', 'concave'): ({'point_radius': 18.913143772310377,
                        'blade_angle': 0.29805422689415884,
                        'point_width': 1.0601385597180206,
                        'edge_radius': 0.5933067521175278,
                        'blade': 'outer',
                        'profile_radius': 'inf',
                        'profile_ref': 0.0},
                       {'radial_setting': 23.531448231221834,
                        'cradle_angle': 0.8725966691359452,
                        'machine_root_angle': 0.5910546875382607,
                        'machine_centre_to_back': 0.7241810193192606,
                        'sliding_base': 0.0,
                        'blank_offset': 0.0,
                        'ratio_of_roll': 1.5379439278475806,
                        'modified_roll': (),
                        'blank_offset_poly': (),
                        'blank_offset_table': ()},
                       'basic settings solved for the design pressure and spiral angles, root on the root cone; '
                       'point width 1.060 mm fitted to the tooth space (derived 1.086 mm)')}


@pytest.fixture(scope="module")
def small():
    """The 11/17 design with the four flanks of ``SETUPS_11x17`` (a developed pair: default synthesis of the
    pinion)."""
    import warnings

    from spiralbevel.gearset.facemilled import FlankSetup
    from spiralbevel.generation.flank import generate_flank
    from spiralbevel.machine.cutter import Blade, HeadCutter
    from spiralbevel.machine.settings import MachineSettings

    spec = parse_design(DESIGN_11x17)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        blank = blank_from_design(spec)
        setups = {}
        for (m, s), (c, st, source) in SETUPS_11x17.items():
            cutter = HeadCutter(**dict(c, blade=Blade(c["blade"]), profile_radius=float(c["profile_radius"])))
            settings = MachineSettings(**st)
            flank = generate_flank(cutter, settings, blank, Member(m), Side(s))
            setups[(Member(m), Side(s))] = FlankSetup(Member(m), Side(s), cutter, settings, flank, source)
    return spec, blank, setups


def _junction_points(flank, n=7):
    """(n, 3) points (mm, member frame) of the generated junction line at the check's face stations."""
    ol, gen = flank.outline, flank.generator
    R = np.linspace(ol.Ri, ol.Re, n)
    mp = flank.mean_point()
    xj = flank._locator.junction(R, (mp.theta + np.pi - gen.mp["q"] + mp.psi_c, mp.psi_c))
    return gen.evaluate_at(np.full(n, gen.cp["u_j"]), xj[:, 1], xj[:, 2], curvature=False).points


def _reach(blank, member, p):
    """Brute force: the largest depth (mm, > 0 inside) of point ``p`` (member frame: axis z from the pitch apex) in
    the mate's face-cone solid over a full turn of the member about its own axis, the mate turned about its axis
    in the working position (axes intersecting at the pitch apex, at the shaft angle). The mate's face cone: the
    line through its ISO outer tip point (outer cone distance Re, outer addendum h_ae) at its face angle delta_a;
    depth measured normal to that line in the mate's axial section."""
    if member is Member.PINION:
        dm, hae, da, Re = float(blank.delta2), float(blank.hae2), float(blank.delta_a2), float(blank.Re2)
    else:
        dm, hae, da, Re = float(blank.delta1), float(blank.hae1), float(blank.delta_a1), float(blank.Re1)
    S = float(blank.Sigma)
    a = np.array([math.sin(S), 0.0, math.cos(S)])           # the mate's axis: in the x-z plane, Sigma from z
    tip = np.array([Re * math.cos(dm) - hae * math.sin(dm), Re * math.sin(dm) + hae * math.cos(dm)])
    d = np.array([math.cos(da), math.sin(da)])
    r, z = math.hypot(p[0], p[1]), p[2]

    def depth(phi):
        q = np.array([r * math.cos(phi), r * math.sin(phi), z])
        za = q @ a
        ra = np.linalg.norm(q - za * a)
        v = np.array([za, ra]) - tip
        return v[0] * d[1] - v[1] * d[0]                       # > 0: below the tip line, inside the mate's blank

    phis = np.linspace(-math.pi, math.pi, 721)
    k = int(np.argmax([depth(f) for f in phis]))
    best = minimize_scalar(lambda f: -depth(f), bounds=(phis[k] - 0.01, phis[k] + 0.01), method="bounded",
                           options={"xatol": 1e-10})
    return -best.fun


@pytest.mark.parametrize("m,s", ALL)
def test_check_equals_the_mates_reach_by_brute_force(small, m, s):
    """The check's comparison (junction height minus the mate's top c(R), normal to the pitch generatrix) against the
    mate's reach found by turning each junction point through a full turn in 3-D: the same point of deepest reach
    (the plane of the axes), measured normal to the mate's face cone, so the two differ by exactly the factor
    cos(theta_a) of the face cone's slope against the pitch generatrix. 1e-6 mm: the bounded scalar search's
    tolerance on the turn angle (1e-10 rad), squared, times radii of some mm, is far below; what is left is the
    round-off of the ISO dimensions (solved to 1e-9)."""
    spec, blank, setups = small
    res = fillet_top_checks(blank, {(m, s): setups[(m, s)]})[(m, s)]
    p = _junction_points(setups[(m, s)].flank)
    theta_a = float(blank.delta_a2 - blank.delta2) if m is Member.PINION else float(blank.delta_a1 - blank.delta1)
    brute = np.array([_reach(blank, m, q) for q in p])
    np.testing.assert_allclose(brute, (res.junction - res.top) * math.cos(theta_a), atol=1e-6)


def test_mate_top_is_the_clearance_at_the_mean_point(small):
    """c(R_m) is the ISO clearance c for both members (h_fm1 - h_am2 = h_fm2 - h_am1 = c)."""
    _, blank, _ = small
    for m in (Member.PINION, Member.GEAR):
        assert mate_top_height(blank, m, [float(blank.Rm)])[0] == pytest.approx(float(blank.c), abs=1e-9)


def _tca(blank, setups):
    from spiralbevel.gearset.tca import side_tca

    return {name: side_tca(blank, setups, name, n_positions=21)[1] for name in ("drive", "coast")}


@pytest.fixture(scope="module")
def small_tca(small):
    """The 21-position TCA report sections of both sides of the 11/17 pair."""
    return _tca(small[1], small[2])


def _pinion_fillet_contact(tca):
    """{side: whether the 21-position TCA of that side has an edge contact at the pinion's fillet}."""
    return {name: any(e["member"] == "pinion" and "fillet" in e["edge"] for e in sec["edge_contacts"])
            for name, sec in tca.items()}


def test_fires_where_the_tca_shows_the_fillet_edge_contact(small, small_tca):
    """On the 11/17 design the check fires on the pinion's convex (coast) flank and not on its concave (drive) flank
    (junction 0.83-0.90 and 0.64-0.86 mm above the root cone, the gear's tip contact 0.75-0.95 mm), and the TCA (the
    brute-force-checked edge-contact solve) finds the pinion's fillet edge contact on the coast side and not on the
    drive side; the message names the cause and the keys to change."""
    spec, blank, setups = small
    checks = fillet_top_checks(blank, setups)
    tca = small_tca
    msgs = fillet_top_messages(spec, blank, checks, tca)
    assert checks[(Member.PINION, Side.CONVEX)].fires
    assert not checks[(Member.PINION, Side.CONCAVE)].fires and (Member.PINION, Side.CONCAVE) not in msgs
    (text,) = msgs[(Member.PINION, Side.CONVEX)]
    assert text.startswith(CAUSE)
    for key in ("gear_set.depth.clearance_factor", "gear_set.depth.mean_addendum_factor",
                "gear_set.normal_pressure_angle"):
        assert key in text
    # the edge radius is named only where a sharp blade would bring the junction below the gear's tip contact
    sharp = checks[(Member.PINION, Side.CONVEX)].sharp_excess
    assert ("face_milling.edge_radius" in text) == (sharp <= FILLET_TOP_TOL_MM)
    assert ("no edge radius removes it" in text) == (sharp > FILLET_TOP_TOL_MM)
    # the plane-of-axes reach is the conservative bound: it flags every flank the start-of-active-flank one does
    for res in checks.values():
        assert res.reach_excess >= res.excess
    seen = {name: any(e["member"] == "pinion" and e["edge"] == "fillet" for e in tca[name]["edge_contacts"])
            for name in ("drive", "coast")}
    assert seen == {"coast": True, "drive": False}


PINION = {(Member.PINION, Side.CONVEX), (Member.PINION, Side.CONCAVE)}


@pytest.mark.parametrize("design,fires", [("iso23509_sample1", set()), ("aviation_23x65_synthesized", PINION)])
def test_bundled_examples_fire_where_the_tca_shows_the_fillet_edge_contact(design, fires):
    """The flanks the check fires on (and reports, the TCA showing the edge contact they explain) are the pinion's
    where the TCA of their side shows the pinion's fillet edge contact, on two bundled examples:

    - ISO 23509 sample 1: no flank's junction above the mate's tip contact (by 0.02 mm and more), no fillet edge
      contact in the TCA of either side. The default synthesis puts the drive (concave) pinion's root, which its
      settings cut 0.09 mm below the root cone, back on it (``pinion_fillet.raise_root``); that lifts its junction,
      and the edge radius is reduced (1.160 to 1.039 mm) so that the lift keeps it below the mate's tip contact
      (measured 0.025 mm below; 0.085 mm on the convex flank).
    - the synthesized seed-001 pair (23/65, 22.5 deg blades, edge radius 1.31 mm): both pinion junctions lie above
      the gear's tip contact (0.87-0.94 mm against 0.78-0.86 mm) and the TCA of both sides shows the pinion's fillet
      edge contact; the gear's junctions stay below the pinion's tip contact."""
    gs = sb.GearSet.from_design(design)
    checks = fillet_top_checks(gs.blank, gs.setups)
    assert len(checks) == 4
    for res in checks.values():
        assert not isinstance(res, Exception), res
    assert {k for k, r in checks.items() if r.fires} == fires
    tca = _tca(gs.blank, gs.setups)
    assert _pinion_fillet_contact(tca) == {"drive": bool(fires), "coast": bool(fires)}
    assert set(fillet_top_messages(gs.design, gs.blank, checks, tca)) == fires


def test_report_section_and_design_warning(small, small_tca):
    """The job's report step (``fillet_top_report``, after the TCA): each flank's ``fillet_top`` section; a
    ``DesignWarning`` naming the cause, also in the flank's ``checks``, only where the estimate fires and the TCA
    shows the edge contact it explains (11/17: the pinion's convex flank; its gear concave flank, also estimated
    above the pinion's tip contact, +0.33 mm, has no such edge contact in the TCA and is not reported)."""
    from spiralbevel.errors import DesignWarning
    from spiralbevel.gearset.fillet_top import fillet_top_report

    spec, blank, setups = small
    tca = small_tca
    flanks = {}
    with pytest.warns(DesignWarning, match="pinion convex: fillet above the mate's tip") as rec:
        fillet_top_report(spec, blank, setups, flanks, tca)
    assert sum(CAUSE in str(w.message) for w in rec) == 1
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):
            sec = flanks[m][s]["fillet_top"]
            assert len(sec["junction_mm"]) == 7
            assert sec["reported"] == ((m, s) == ("pinion", "convex"))
            assert sec["reported"] == any(t.startswith(CAUSE) for t in flanks[m][s].get("checks", []))
    assert flanks["gear"]["concave"]["fillet_top"]["fires"]


def test_a_junction_that_cannot_be_located_is_an_error_not_a_nan(small, monkeypatch):
    """A junction solve that returns NaN at a station makes the check 'not computed' (an error the report names),
    never a NaN in the report."""
    import spiralbevel.gearset.fillet_top as ft

    blank, setups = small[1], small[2]
    real = ft.junction_height
    monkeypatch.setattr(ft, "junction_height", lambda flank, n: np.where(np.arange(n) == 2, np.nan, real(flank, n)))
    checks = fillet_top_checks(blank, setups)
    assert checks and all(isinstance(v, sb.errors.GeometryError) for v in checks.values())
    assert "could not be located" in str(next(iter(checks.values())))
