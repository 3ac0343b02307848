"""The job's conjugacy check: exact for the designed log-spiral pair, and a wrong base cone is reported."""

import dataclasses
import math

from spiralbevel.conventions import Side
from spiralbevel.io.design_file import load_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.conjugacy import conjugacy_report
from spiralbevel.job.logspiral import design_pair


def _pair():
    spec = load_design()
    return design_pair(spec, blank_from_design(spec))


def test_designed_pair_is_conjugate():
    rep = conjugacy_report(_pair())
    for side in ("convex", "concave"):
        assert rep[side]["conjugate"]
        assert rep[side]["max_distance_mm"] < 1e-9
        assert rep[side]["max_normal_mismatch"] < 1e-12


def test_wrong_base_cone_is_reported():
    pair = _pair()
    gear = pair.gear
    bad = {}
    for side in (Side.CONVEX, Side.CONCAVE):
        f = gear.flank(side)
        surf = dataclasses.replace(f.surface, base_cone_angle=f.surface.base_cone_angle + math.radians(0.5))
        dom = dataclasses.replace(f.domain, base_cone_angle=surf.base_cone_angle)
        bad[side] = dataclasses.replace(f, surface=surf, domain=dom)
    gear_bad = dataclasses.replace(gear, convex=bad[Side.CONVEX], concave=bad[Side.CONCAVE])
    rep = conjugacy_report(dataclasses.replace(pair, gear=gear_bad))
    for side in ("convex", "concave"):
        assert not rep[side]["conjugate"]
        # docs/theory/gearing.md#conjugacy (conjugacy theorem): delta2 + 0.5 deg gives a deviation of the order of 0.1
        # mm
        assert 0.01 < rep[side]["max_distance_mm"] < 1.0
