"""ISO/TR 10300-30:2024 Annex C, Sample 3: the contact lines and load sharing of ISO 10300 Method B1 on a second
hypoid pair (9/34, offset 31.75 mm, an ISO 23509 Method 2 face-hobbed blank that spiralbevel does not compute).

The blank quantities are the report's own (its tables C.1 to C.4), and so are the published figures below, both as
transcribed independently in the self-test of an open-source ISO 10300 calculator (not read from the report by us).
This pair has eps_vbeta < 1, the branch of ISO 10300-1 Annex A where the three contact lines are shifted off the
centre of the zone of action, and a large offset (zeta_mp 24 deg). It checks the contact-line layout and the
load-sharing factor Z_LS of the hypoid branch (:mod:`spiralbevel.rating.contact_lines`) on a pair other than
Sample 2, where Z_LS is 10 % off (tests/rating/test_hypoid_sample2.py).

Not checked: l_bm (the report prints 21.377 mm; the general formulas give 23.228 mm, as the independent calculator
also finds and traces to one cell of the report's own table) and rho_rel (it needs the mean cone distances of both
members, which the transcribed data do not give).
"""

import math

import pytest

from spiralbevel.rating._blank import BlankData
from spiralbevel.rating.pitting import load_sharing_factor
from spiralbevel.rating.virtual import virtual_gears

REL = 5e-3  # relative 0.5 %: the report prints 4 to 5 significant digits
ABS_F = 5e-3  # mm, the contact-line distances are printed to 0.001 mm

R = math.radians


@pytest.fixture(scope="module")
def v():
    dm1, d1 = 51.258, R(24.763)
    Rm2 = 76.756 - 0.5 * 26.0  # R_e2 - b2/2
    g = BlankData(z1=9, z2=34, Sigma=R(90.0), a=31.75, b=26.0, Rm=Rm2, rc0=76.0, dm1=dm1, dm2=146.700, delta1=d1,
                  delta2=R(63.212), beta_m1=R(44.991), beta_m2=R(21.009), mmn=4.028, alpha_nD=R(15.868),
                  alpha_nC=R(24.132), alpha_eD=R(20.0), alpha_eC=R(20.0), ham1=5.840, ham2=2.215, hfm1=3.222,
                  hfm2=6.847, x_hm1=0.450, x_sm1=0.040, x_sm2=-0.060, alpha_lim=R(-4.132), zeta_m=R(21.647),
                  zeta_mp=R(23.981), Rm1=dm1 / (2.0 * math.sin(d1)), Rm2=Rm2)
    return virtual_gears(g)


PUBLISHED = [("d_v1", 56.448), ("d_v2", 325.506), ("beta_v", 33.0), ("alpha_vet", 23.460), ("z_v1", 11.754),
             ("a_v", 190.977), ("beta_vb", 30.783), ("p_vet", 13.841), ("g_valpha", 16.280), ("eps_valpha", 1.176),
             ("b_veff", 19.981), ("b_v", 23.507), ("eps_vbeta", 0.860), ("eps_vgamma", 2.036)]


@pytest.mark.parametrize("symbol, published", PUBLISHED, ids=[p[0] for p in PUBLISHED])
def test_virtual_gear(v, symbol, published):
    got = math.degrees(v[symbol]) if symbol in ("beta_v", "alpha_vet", "beta_vb") else v[symbol]
    assert got == pytest.approx(published, rel=REL)


def test_contact_lines_off_centre(v):
    """eps_vbeta < 1: the three lines shifted by X (f_m != 0), the published f_m, f_t, f_r."""
    assert v["eps_vbeta"] < 1.0
    for key, published in (("f_m", -0.686), ("f_t", 11.205), ("f_r", -12.577)):
        assert v[key] == pytest.approx(published, abs=ABS_F), key


def test_load_sharing_factor(v):
    z = load_sharing_factor(v, "low")
    assert z["Z_LS"] == pytest.approx(0.961, rel=REL)
    assert z["Z_LS"] ** 2 == pytest.approx(0.924, rel=REL)   # Y_LS of ISO 10300-3
