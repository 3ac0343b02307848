"""Invariants of the blank over random designs (hypothesis): cone relations, depth sums, continuity, symmetry."""

import math
import warnings

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from spiralbevel.conventions import Hand
from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.errors import DesignWarning, GeometryError

R = math.radians


@st.composite
def designs(draw):
    z1 = draw(st.integers(9, 40))
    z2 = draw(st.integers(z1, 90))
    sig_max = min(150.0, math.degrees(math.acos(-z1 / z2)))
    sigma = R(draw(st.floats(40.0, sig_max)))
    met = draw(st.floats(1.0, 10.0))
    delta2 = sigma - math.atan2(math.sin(sigma), math.cos(sigma) + z2 / z1)
    re = met * z2 / (2 * math.sin(delta2))
    b = draw(st.floats(0.12, 0.3)) * re
    beta = R(draw(st.floats(0.0, 40.0)))
    rc0 = draw(st.floats(0.7, 2.0)) * (re - b / 2)
    taper = draw(st.sampled_from(["duplex", "trl", "standard", "uniform"]))
    alpha = R(draw(st.floats(17.0, 25.0)))
    return dict(z1=z1, z2=z2, shaft_angle=sigma, met=met, b=b, beta_m=beta, rc0=rc0, taper=taper,
                alpha_dD=alpha, alpha_dC=alpha, hand1=draw(st.sampled_from([Hand.LEFT, Hand.RIGHT])))


def _try(kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        try:
            return compute_blank(BlankInput(**kw))
        except GeometryError:
            return None


SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(designs())
def test_cone_and_depth_identities(kw):
    bl = _try(kw)
    assume(bl is not None)
    assert bl.delta1 + bl.delta2 == pytest.approx(bl.Sigma, abs=1e-14)
    assert math.sin(bl.delta1) / math.sin(bl.delta2) == pytest.approx(bl.z1 / bl.z2, rel=1e-13)  # equal pitch
    assert bl.Rm1 == bl.Rm2 == bl.Rm
    assert bl.Re1 == pytest.approx(bl.Re2, abs=1e-12) and bl.Ri1 == pytest.approx(bl.Ri2, abs=1e-12)  # b1 = b2
    assert bl.de1 / bl.de2 == pytest.approx(bl.z1 / bl.z2, rel=1e-13)
    assert bl.dm2 / bl.z2 == pytest.approx(bl.mmt, rel=1e-14)
    assert bl.hmw + bl.c == pytest.approx(bl.hm, abs=1e-13)
    assert bl.ham1 + bl.ham2 == pytest.approx(bl.hmw, abs=1e-13)
    assert bl.ham1 + bl.hfm1 == pytest.approx(bl.hm, abs=1e-13)
    assert bl.he1 == pytest.approx(bl.he2, abs=1e-12) and bl.hi1 == pytest.approx(bl.hi2, abs=1e-12)
    assert bl.Re2 - bl.Ri2 == pytest.approx(bl.b2, abs=1e-12)
    assert bl.theta_a1 == bl.theta_f2 and bl.theta_a2 == bl.theta_f1
    assert bl.hand2 is bl.hand1.opposite
    for k in (1, 2):
        g = lambda n, k=k: getattr(bl, f"{n}{k}")  # noqa: E731
        # the heel tip point sits h_e above the heel root point along the pitch-cone normal, which makes the angle
        # θf with the root-cone normal: its distance from the root cone is h_e·cos θf
        if k == 2:  # the pinion's h_t1 follows the wheel's cones and the clearance (tests/design crosscheck)
            assert g("ht") == pytest.approx(g("he") * math.cos(g("theta_f")), rel=1e-12, abs=1e-12)
        assert g("dae") - g("dfe") == pytest.approx(2 * g("he") * math.cos(g("delta")), abs=1e-10)
        assert g("dai") - g("dfi") == pytest.approx(2 * g("hi") * math.cos(g("delta")), abs=1e-10)
        assert g("be") + g("bi") == pytest.approx(g("b"), abs=1e-12)
        assert g("tz") == 0.0 and g("tzm") == pytest.approx(bl.Rm * math.cos(g("delta")), abs=1e-12)
    assert bl.smn1 + bl.smn2 <= math.pi * bl.mmn + 1e-12  # backlash only thins the teeth
    crown = abs(math.cos(bl.delta2)) < 1e-12  # delta2 = 90 deg: the virtual gear is a rack (dvn2 = hlim2 = inf)
    for key, v in bl.to_dict().items():
        if isinstance(v, float):
            assert math.isfinite(v) or (crown and key in ("dvn2", "hlim2") and v == math.inf) or (
                    key == "rho_lim" and v == math.inf), key  # rho_lim: 0/0 without offset


@SETTINGS
@given(designs(), st.sampled_from(["b", "beta_m", "met", "rc0", "shaft_angle", "alpha_dD"]))
def test_continuity_in_the_inputs(kw, name):
    """A relative input change of 1e-7 moves every output by at most 1e-4 of its scale (no jumps, no branches)."""
    a = _try(kw)
    assume(a is not None and a.delta2 < R(85.0))  # dvn2 ~ 1/cos(delta2): the crown limit has its own test
    h = 1e-7 * max(abs(kw[name]), 1e-3)
    b = _try({**kw, name: kw[name] + h})
    assume(b is not None)
    da, db = a.to_dict(degrees=False), b.to_dict(degrees=False)
    for key, va in da.items():
        if isinstance(va, float) and math.isfinite(va) and math.isfinite(db[key]):  # dvn2 = inf at delta2 = 90
            assert abs(db[key] - va) <= 1e-4 * (1.0 + abs(va)), (name, key, va, db[key])


@SETTINGS
@given(designs())
def test_hand_changes_only_the_hands(kw):
    a = _try({**kw, "hand1": Hand.LEFT})
    assume(a is not None)
    b = _try({**kw, "hand1": Hand.RIGHT})
    da, db = a.to_dict(), b.to_dict()
    assert {k for k in da if da[k] != db[k]} == {"hand1", "hand2"}


@SETTINGS
@given(designs(), st.floats(1.0, 1.3))
def test_wider_pinion_keeps_the_design_point(kw, factor):
    a = _try(kw)
    assume(a is not None)
    b = _try({**kw, "b1": kw["b"] * factor})
    assume(b is not None)
    assert b.Rm1 == b.Rm2 == a.Rm
    assert b.Re1 - b.Re2 == pytest.approx(0.5 * (b.b1 - b.b2), abs=1e-12)
    assert b.Rm - b.Ri1 == pytest.approx(0.5 * b.b1, abs=1e-12)
    assert b.delta_a2 == a.delta_a2 and b.hae2 == a.hae2  # the wheel is unchanged


@SETTINGS
@given(designs())
def test_degree_output_is_the_radian_output_converted(kw):
    bl = _try(kw)
    assume(bl is not None)
    deg, rad = bl.to_dict(degrees=True), bl.to_dict(degrees=False)
    units = {sym: unit for sym, _d, unit in bl.metadata(degrees=True)}
    for key in deg:
        if units[key] == "deg":
            assert deg[key] == pytest.approx(math.degrees(rad[key]), rel=1e-15, abs=1e-15)
        else:
            assert deg[key] == rad[key]
