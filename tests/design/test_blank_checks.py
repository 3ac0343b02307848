"""Design checks of the blank: warnings for poor practice, GeometryError for impossible teeth."""

import math
import warnings

import pytest

from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_checks import section_limit_depth, top_land
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.design.blank_thickness import spiral_angle_at
from spiralbevel.errors import DesignError, DesignWarning, GeometryError

R = math.radians
SAMPLE1 = dict(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3, c_ham=0.24737, k_t=0.0915)


def _inp(**kw):
    return BlankInput(**{**SAMPLE1, **kw})


def test_published_design_is_clean():
    with warnings.catch_warnings():
        warnings.simplefilter("error", DesignWarning)
        bl = compute_blank(_inp())
    assert bl.warnings == ()


def test_face_width_over_0p3_re_warns_and_is_recorded():
    with pytest.warns(DesignWarning, match=r"0\.3\*Re2") as rec:
        bl = compute_blank(_inp(b=32.0))  # 32 > 0.3 * 93.97 = 28.19
    assert [str(w.message) for w in rec if issubclass(w.category, DesignWarning)] == list(bl.warnings)


def test_face_width_over_10_met_warns():
    # Re = 2*80/(2 sin delta2) = 82.5 mm -> 0.3 Re = 24.7 > b = 21 > 10 met = 20
    with pytest.warns(DesignWarning, match=r"10\*met"):
        bl = compute_blank(BlankInput(z1=20, z2=80, met=2.0, b=21.0, beta_m=R(30), rc0=76.2))
    assert not any("0.3*Re2" in w for w in bl.warnings)


def test_pointed_teeth_raise_geometry_error_naming_the_top_land():
    with pytest.raises(GeometryError, match="pointed teeth") as ei:
        compute_blank(_inp(k_d=3.5))
    assert "sam1" in {p.field for p in ei.value.problems}
    assert isinstance(ei.value, DesignError)


def test_small_top_land_warns_with_toe_mean_heel_values():
    with pytest.warns(DesignWarning, match="top land") as rec:
        bl = compute_blank(_inp(k_d=2.4, c_ham=0.1))
    msgs = " ".join(str(w.message) for w in rec)
    assert "sam1" in msgs and "sae1" in msgs
    assert bl.sam1 == pytest.approx(top_land(bl, 1, "m")) and bl.sae1 < 0 < bl.sam1 < 0.2 * bl.mmn


def test_pinion_undercut_raises_with_the_stated_criterion():
    # z1 = 8 pinion, beta = 10 deg, alpha = 14.5 deg: active depth ham2 exceeds (dvn1/2) sin^2(alpha)
    with pytest.raises(GeometryError, match="pinion undercut") as ei:
        compute_blank(_inp(z1=8, z2=9, beta_m=R(10), alpha_dD=R(14.5), alpha_dC=R(14.5), c_ham=0.3, k_t=0.0))
    p = next(p for p in ei.value.problems if p.field == "hlim1")
    assert "ham2" in p.allowed


def test_root_undercut_only_warns():
    # a design between the two limits: hfm1 beyond, ham2 within the limit depth at the mean section
    kw = dict(z1=10, z2=30, met=5.0, de2=None, b=20.0, beta_m=R(20), alpha_dD=R(20), alpha_dC=R(20), c_ham=0.3,
              k_t=0.0, rc0=60.0)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        bl = compute_blank(_inp(**kw))
    hlim = section_limit_depth(bl, 1, "m")
    assert bl.ham2 <= hlim < bl.hfm1
    assert bl.hlim1 == pytest.approx(hlim, rel=1e-14)
    assert any("root undercut" in str(w.message) for w in rec)


def test_vanishing_toe_addendum_and_dedendum_raise():
    with pytest.raises(GeometryError) as ei:
        compute_blank(_inp(taper="given", theta_f1=R(8), theta_f2=R(8)))
    assert "hai2" in {p.field for p in ei.value.problems}
    with pytest.raises(GeometryError) as ei:
        compute_blank(_inp(taper="given", theta_f1=R(1), theta_f2=R(19), c_ham=0.6))
    assert {"hfi2", "hai1"} <= {p.field for p in ei.value.problems}


def test_negative_root_angle_raises():
    # a 40/40 Σ = 20 deg pair has 10 deg pitch angles; a 11 deg dedendum angle inverts the root cone
    with pytest.raises(GeometryError) as ei:
        compute_blank(BlankInput(z1=40, z2=40, met=3.0, b=6.0, beta_m=R(30), rc0=500.0, shaft_angle=R(20),
                                 taper="given", theta_f1=R(11), theta_f2=R(11)))
    assert "delta_f1" in {p.field for p in ei.value.problems}


def test_cutter_that_cannot_reach_the_heel_raises_naming_rc0():
    with pytest.raises(GeometryError, match="does not reach the heel") as ei:
        compute_blank(_inp(rc0=12.0, taper="uniform"))
    assert {p.field for p in ei.value.problems} == {"rc0"}


def test_toe_spiral_angle_bounds_are_reported():
    with pytest.raises(GeometryError, match="toe") as ei:
        compute_blank(_inp(b=60.0, beta_m=R(60), rc0=1000.0, taper="uniform"))
    p = ei.value.problems[0]
    lo, _name, hi = p.allowed.split("<=")
    lo, hi = float(lo), float(hi)
    # the reported range (6 significant digits) is sharp for the toe (the heel needs its own bound)
    with pytest.warns(DesignWarning):
        bl = compute_blank(_inp(b=60.0, beta_m=R(60), rc0=0.999 * hi, taper="uniform"))
    for rc0, reached in ((lo * (1 + 1e-5), True), (lo * (1 - 1e-5), False), (hi * (1 - 1e-5), True),
                         (hi * (1 + 1e-5), False)):
        assert (spiral_angle_at(bl.Ri1, bl.Rm, bl.beta_m1, rc0) is not None) is reached


def test_top_land_messages_name_keys_that_widen_it():
    """The top-land and undercut messages name design-file keys, and the change they name widens the top land (checked
    on the computed blank, member by member: k_t > 0 thickens the pinion and thins the wheel, a larger c_ham shortens
    the pinion's addendum and lengthens the wheel's)."""
    base = dict(k_d=2.4, c_ham=0.1)
    with pytest.warns(DesignWarning) as rec:
        bl = compute_blank(_inp(**base))
    msgs = [str(w.message) for w in rec if "top land of the pinion" in str(w.message)]
    assert msgs and all("raise gear_set.depth.thickness_factor" in m and
                        "raise gear_set.depth.mean_addendum_factor" in m for m in msgs), msgs
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        thicker = compute_blank(_inp(**{**base, "k_t": SAMPLE1["k_t"] + 0.05}))
        shorter = compute_blank(_inp(**{**base, "c_ham": base["c_ham"] + 0.05}))
    for where in "ime":
        assert top_land(thicker, 1, where) > top_land(bl, 1, where)     # raise k_t: wider pinion top land
        assert top_land(shorter, 1, where) > top_land(bl, 1, where)     # raise c_ham: wider pinion top land
        assert top_land(thicker, 2, where) < top_land(bl, 2, where)     # so the wheel's advice is to lower both
        assert top_land(shorter, 2, where) < top_land(bl, 2, where)
    with pytest.raises(GeometryError) as ei:
        compute_blank(_inp(k_d=3.5))
    assert "gear_set.depth.thickness_factor" in str(ei.value)
    with pytest.raises(GeometryError) as ei:
        compute_blank(_inp(z1=8, z2=9, beta_m=R(10), alpha_dD=R(14.5), alpha_dC=R(14.5), c_ham=0.3, k_t=0.0))
    text = str(ei.value)
    assert "gear_set.pinion_teeth" in text and "gear_set.normal_pressure_angle" in text and " z1," not in text
