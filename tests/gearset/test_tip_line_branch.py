"""The cutter's tip line stays on its own branch of the envelope from station to station (gearset/slot_blade.py
``_tip_line``), which both the root-cone check and the slot check locate.

On a 15/45 gear at a 5 deg spiral angle (the toe spiral angle -1.7 deg) the gear concave flank's tip line passes the
fold of the generation chart near the toe, where the tabulated crossings belonged only to another branch of the
envelope, 76-79 mm above the root cone: the root-cone check reported the root "78.875 mm above the root cone" there,
and the slot check stopped with an internal message ("grid(fillet) = '1 of 11 points at u = 101.2 mm'"). Checked
against the brute force of tests/gearset/test_root_cone.py (no equation of meshing: the swept tip circle's lowest
point at each cone distance)."""

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.gearset.root_cone import root_cone, root_cone_checks, root_cone_messages
from spiralbevel.gearset.slot_check import SlotFit, slot_fit
from _designs import basic_design, basic_setups


def _brute_root():
    """The brute force of tests/gearset/test_root_cone.py (loaded from its file: test modules are not importable)."""
    import importlib.util
    from pathlib import Path

    spec = importlib.util.spec_from_file_location("_root_cone_oracle", Path(__file__).with_name("test_root_cone.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.brute_root


DESIGN_15x45_B5 = basic_design(15, 45, module=4, face_width=28, mean_spiral_angle=5, title="15/45 at beta 5 deg")


@pytest.fixture(scope="module")
def case():
    return basic_setups(DESIGN_15x45_B5)


def test_tip_line_near_the_toe_is_the_root(case):
    spec, blank, setups = case
    flank = setups[(Member.GEAR, Side.CONCAVE)].flank
    res = root_cone(flank)
    # the basic settings put the root on the root cone (to 1e-6 mm); the brute force approaches it from above by its
    # grid spacing squared (< 1e-5 mm)
    assert np.max(np.abs(res.height)) < 1e-5
    assert np.max(np.abs(_brute_root()(flank, res.R[[0, 1, 5]]) - res.height[[0, 1, 5]])) < 1e-5
    assert root_cone_messages(spec, setups, root_cone_checks(setups)) == {}


def test_slot_check_reaches_the_toe(case):
    _, blank, setups = case
    assert isinstance(slot_fit(blank, setups, Member.GEAR, Side.CONCAVE), SlotFit)


def test_slot_check_failure_says_what_failed_and_what_to_change(case):
    """Where the slot check still cannot be computed, its warning says what failed in the user's terms and the keys:
    the internal locator message (a grid name and a blade parameter u) is not shown."""
    from spiralbevel.errors import GeometryError
    from spiralbevel.gearset.slot_check import slot_messages

    spec, blank, setups = case
    err = GeometryError.single("grid(fillet)", "1 of 11 points at u = 101.2 mm", "points on the generated fillet",
                               "mm", "the edge radius does not generate them")
    (msg,) = slot_messages(spec, blank, setups, {(Member.GEAR, Side.CONCAVE): err})[(Member.GEAR, Side.CONCAVE)]
    assert "grid(fillet)" not in msg and "u = " not in msg
    assert "could not be followed from its junction to the root at 1 of 11 face stations" in msg
    # this blank's toe spiral angle, -1.7 deg (beta_i2 of the ISO 23509 blank, printed by the blank's own warning)
    assert "toe -1.7 deg" in msg and "gear_set.cutter_radius" in msg
    spec, blank, setups = basic_setups(basic_design(12, 41, module=5, face_width=30, mean_spiral_angle=35))
    (msg,) = slot_messages(spec, blank, setups, {(Member.GEAR, Side.CONCAVE): err})[(Member.GEAR, Side.CONCAVE)]
    assert "STEP/STL" in msg and "face_milling.point_width" in msg
