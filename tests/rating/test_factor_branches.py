"""The piecewise factors meet at their branch points (eps_vbeta = 0 and 1, eps_vgamma = 2), so a design near a
boundary gets no jump; and each branch reduces to its spur or long-helix limit."""

import math

import pytest

from spiralbevel.rating.load_factors import transverse_load_factor
from spiralbevel.rating.contact_lines import contact_line_layout, contact_line_length
from spiralbevel.rating.pitting import load_sharing_factor, mid_zone_factor


def _virtual(eps_valpha, eps_vbeta):
    # a virtual pair shaped like ISO 23509 Sample 1's (14/39, 20 deg), contact ratios set directly
    d_v1, d_v2, alpha = 58.35, 452.8, math.radians(23.957)
    return {"eps_valpha": eps_valpha, "eps_vbeta": eps_vbeta, "eps_vgamma": eps_valpha + eps_vbeta,
            "d_va1": d_v1 + 9.674, "d_va2": d_v2 + 3.18, "d_vb1": d_v1 * math.cos(alpha),
            "d_vb2": d_v2 * math.cos(alpha), "z_v1": 14.875, "z_v2": 115.431, "alpha_vet": alpha, "b_v": 25.4}


@pytest.mark.parametrize("eps_valpha", [1.1, 1.3, 1.6])
def test_mid_zone_factor_continuous_at_eps_vbeta_one(eps_valpha):
    below = mid_zone_factor(_virtual(eps_valpha, 1.0 - 1e-12))
    assert below == pytest.approx(mid_zone_factor(_virtual(eps_valpha, 1.0)), rel=1e-9)


def test_mid_zone_factor_spur_limit():
    # eps_vbeta = 0: the inner point of single contact of the pinion (F1 = 2, F2 = 2(eps_valpha - 1)), as ISO 6336's Z_B
    v = _virtual(1.3, 0.0)
    t1 = math.sqrt((v["d_va1"] / v["d_vb1"]) ** 2 - 1) - 2 * math.pi / v["z_v1"]
    t2 = math.sqrt((v["d_va2"] / v["d_vb2"]) ** 2 - 1) - 2 * 0.3 * math.pi / v["z_v2"]
    assert mid_zone_factor(v) == pytest.approx(math.tan(v["alpha_vet"]) / math.sqrt(t1 * t2), rel=1e-14)


def test_transverse_factor_continuous_at_eps_vgamma_two():
    lo, hi = _virtual(1.2, 0.8 - 1e-12), _virtual(1.2, 0.8 + 1e-12)
    a = transverse_load_factor(lo, 12000.0, 26.0, 1.95, 1.0, 0.7)
    b = transverse_load_factor(hi, 12000.0, 26.0, 1.95, 1.0, 0.7)
    assert a["K_Halpha"] == pytest.approx(b["K_Halpha"], rel=1e-9)


def _with_lines(eps_vbeta):
    v = _virtual(1.165, eps_vbeta)
    v.update(g_valpha=13.12, p_vet=11.262, b_veff=21.59, beta_vb=math.radians(32.615))
    lines = contact_line_layout(v)
    v.update(lines)
    for key in ("m", "t", "r"):
        v[f"l_b{key}"] = contact_line_length(lines[f"f_{key}"], v, lines["f_max"])
    return v


def test_load_sharing_continuous_at_eps_vbeta_one():
    # below eps_vbeta = 1 the three contact lines are shifted by X, which vanishes at eps_vbeta = 1
    lo, hi = _with_lines(1.0 - 1e-12), _with_lines(1.0)
    for key in ("f_m", "f_t", "f_r", "l_bm", "l_bt", "l_br"):
        assert lo[key] == pytest.approx(hi[key], rel=1e-9, abs=1e-9)
    assert load_sharing_factor(lo)["Z_LS"] == pytest.approx(load_sharing_factor(hi)["Z_LS"], rel=1e-9)
