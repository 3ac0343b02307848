"""Contact ratios of the virtual cylindrical gears (ISO 10300-1) and the low-contact-ratio design check."""

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.design.contact_ratio import MIN_TOTAL, contact_ratio_warnings, contact_ratios
from spiralbevel.errors import DesignWarning

R = math.radians
# ISO 23509 Annex F Sample 1 (14/39, 35 deg): the pair of ISO/TR 10300-30 Annex A Sample 1
SAMPLE1 = dict(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3, c_ham=0.24737, k_t=0.0915)


def _blank(**kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        return compute_blank(BlankInput(**{**SAMPLE1, **kw}))


def test_sample1_published_contact_ratios():
    """ISO/TR 10300-30 Annex A Sample 1 prints eps_valpha 1.165, eps_vbeta 1.227, eps_vgamma 2.392, g_valpha 13.120 mm
    and p_vet 11.262 mm (three decimals: half a unit of the last digit)."""
    cr = contact_ratios(_blank())
    assert cr["eps_valpha"] == pytest.approx(1.165, abs=5e-4)
    assert cr["eps_vbeta"] == pytest.approx(1.227, abs=5e-4)
    assert cr["eps_vgamma"] == pytest.approx(2.392, abs=5e-4)
    assert cr["g_valpha"] == pytest.approx(13.120, abs=5e-4)
    assert cr["p_vet"] == pytest.approx(11.262, abs=5e-4)


@pytest.mark.parametrize("kw", [{}, dict(z1=12, z2=41, beta_m=R(20.0)), dict(z1=25, z2=60, beta_m=R(40.0))])
def test_path_of_contact_by_plane_geometry(kw):
    """g_valpha again by plane geometry: walk along the line of action of the virtual transverse pair (tangent to both
    base circles, through the pitch point) and find by root finding where it leaves each tip circle."""
    bl = _blank(**kw)
    cr = contact_ratios(bl)
    beta_v = 0.5 * (bl.beta_m1 + bl.beta_m2)
    a = math.atan(math.tan(bl.alpha_eD) / math.cos(beta_v))
    r1, r2 = (bl.dm1 / math.cos(bl.delta1) / 2, bl.dm2 / math.cos(bl.delta2) / 2)
    c1, c2 = np.array([0.0, -r1]), np.array([0.0, r2])       # centres; pitch point at the origin
    t = np.array([math.cos(a), math.sin(a)])                   # line of action through the pitch point
    ends = []
    for c, ra, sign in ((c1, r1 + bl.ham1, 1.0), (c2, r2 + bl.ham2, -1.0)):
        # the member's addendum limits the path on the side where the line leaves its tip circle away from its base
        # tangent point; that is the side where the distance to its centre grows
        f = lambda s, c=c, ra=ra: np.linalg.norm(s * t - c) - ra  # noqa: E731
        grow = sign if f(sign * 1e-3) > f(-sign * 1e-3) else -sign
        ends.append(brentq(f, 0.0, grow * 10 * ra))
    g = abs(ends[0] - ends[1]) if np.sign(ends[0]) != np.sign(ends[1]) else None
    assert g is not None
    assert g == pytest.approx(cr["g_valpha"], rel=1e-10)
    # the transverse base pitch is the normal pitch on the base cylinder: pi m_mn cos(alpha_n)/cos(beta_vb)
    beta_vb = math.asin(math.sin(beta_v) * math.cos(bl.alpha_eD))
    assert cr["p_vet"] * math.cos(beta_vb) == pytest.approx(math.pi * bl.mmn * math.cos(bl.alpha_eD), rel=1e-12)


def test_low_total_contact_ratio_warns_with_a_value_that_clears_it():
    """12/41 at 10 deg spiral and a narrow face: eps_vgamma below 2; the named spiral angle clears the warning."""
    kw = dict(z1=12, z2=41, de2=205.0, b=20.0, beta_m=R(10.0), rc0=114.3, c_ham=None, k_t=None)
    kw = {k: v for k, v in kw.items() if v is not None}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        bl = compute_blank(BlankInput(**kw))
    assert contact_ratios(bl)["eps_vgamma"] < MIN_TOTAL
    msgs = contact_ratio_warnings(bl)
    assert len(msgs) == 1 and "gear_set.mean_spiral_angle" in msgs[0]
    assert any("eps_vgamma" in w for w in bl.warnings)         # reported with the blank's warnings
    deg = int(msgs[0].split("mean_spiral_angle to at least ")[1].split()[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        fixed = compute_blank(BlankInput(**{**kw, "beta_m": R(deg)}))
    assert contact_ratios(fixed)["eps_vgamma"] >= MIN_TOTAL
    assert contact_ratio_warnings(fixed) == []
    # one degree less does not (the named value is the smallest whole degree)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        short = compute_blank(BlankInput(**{**kw, "beta_m": R(deg - 1)}))
    assert contact_ratios(short)["eps_vgamma"] < MIN_TOTAL


def test_common_design_has_no_contact_ratio_warning():
    bl = _blank()
    assert contact_ratio_warnings(bl) == []
    assert not any("contact ratio" in w for w in bl.warnings)
