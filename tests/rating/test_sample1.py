"""ISO/TR 10300-30:2024 Annex A, Sample 1 (ISO 10300 Method B1 on the spiral bevel pair of ISO 23509 Annex F.2,
Sample 1), bundled as the design ``iso23509_sample1``, through ``spiralbevel rate iso23509_sample1 --json``.

Figures verified (relative 0.5 %, or the report's last printed digit where that is coarser, as noted):

- ``PUBLISHED`` (the report's tables A.1 to A.4 as transcribed for this project): virtual cylindrical gears d_v1,
  d_v2, beta_v, alpha_vet, m_vt, z_v1, z_v2, beta_vb, d_va1, d_va2, d_vb1, d_vb2, p_vet, g_valpha, eps_valpha, b_veff,
  eps_vbeta, eps_vgamma, rho_rel, z_vn1, z_vn2, l_bm; profile shift x_hm1, x_hm2; load factors F_mt1, K_v, K_Hbeta,
  K_Halpha; pitting factors Z_M-B, Z_LS, Z_E, Z_L, Z_v, Z_R; bending factors Y_eps, Y_LS, Y_BS and, for the pinion,
  the critical-section fillet radius rho_F1 and the bending arm h_Fa1.
- ``PUBLISHED_MORE`` (the same report's results as transcribed independently in the self-test of an open-source
  ISO 10300 calculator, not read from the report by us): the normal-section d_vn1, d_van1; K_F0; F_n; the stresses
  sigma_H0, sigma_H, the pitting limit sigma_HG1 (printed as sigma_HP1 with S_Hmin = 1) and S_H1; for the pinion
  theta, s_Fn, alpha_Fan, Y_Fa, q_s, Y_Sa, Y_RrelT, Y_deltarelT, and for both members sigma_F0, sigma_F, the root
  limit sigma_FG (printed as sigma_FP: ISO 10300-3 compares it with S_Fmin through S_F) and S_F; Y_Fa2, Y_Sa2, q_s2.
"""

import json
import math

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.rating.root import tooth_form

REL = 5e-3  # the acceptance tolerance: relative 0.5 %


@pytest.fixture(scope="module")
def sheet():
    res = CliRunner().invoke(app, ["rate", "iso23509_sample1", "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.output)


# (ISO symbol, published value); every figure printed with at least four significant digits or rounded to 0.001
# on a value >= 0.2, so that the rounding (<= 0.25 %) stays inside 0.5 %
PUBLISHED = [
    ("d_v1", 58.350), ("d_v2", 452.804), ("beta_v", 35.0), ("alpha_vet", 23.957), ("m_vt", 3.923),
    ("z_v1", 14.875), ("z_v2", 115.431), ("beta_vb", 32.615), ("d_va1", 68.023), ("d_va2", 455.984),
    ("d_vb1", 53.323), ("d_vb2", 413.796), ("p_vet", 11.262), ("g_valpha", 13.120), ("eps_valpha", 1.165),
    ("b_veff", 21.590), ("eps_vbeta", 1.227), ("eps_vgamma", 2.392), ("rho_rel", 12.459), ("z_vn1", 25.594),
    ("z_vn2", 198.613),
    ("x_hm1", 0.505), ("x_hm2", -0.505),
    ("F_mt1", 10925.3), ("K_v", 1.020), ("K_Hbeta", 1.650), ("K_Halpha", 1.161),
    ("Z_M-B", 0.916), ("Z_E", 191.646), ("Z_L", 0.992), ("Z_v", 0.974), ("Z_R", 0.930),
    ("Y_eps", 0.625),
    ("l_bm", 22.442), ("Z_LS", 0.935), ("Y_LS", 0.873), ("Y_BS", 1.054),
]

PUBLISHED_MORE = [
    ("d_vn1", 82.241), ("d_van1", 91.915), ("K_F0", 1.000), ("F_n", 14193.3),
    ("sigma_H0", 1168.5), ("sigma_H", 1712.8), ("sigma_HG1", 1617.8), ("S_H1", 0.944),
    ("theta1", 50.783), ("s_Fn1", 7.423), ("alpha_Fan1", 31.534), ("Y_Fa1", 2.033), ("q_s1", 3.630), ("Y_Sa1", 2.022),
    ("Y_RrelT1", 0.972), ("Y_deltarelT1", 1.010),
    ("sigma_F01", 316.5), ("sigma_F1", 680.1), ("sigma_FG1", 942.0), ("S_F1", 1.385),
    ("Y_Fa2", 2.480), ("Y_Sa2", 1.706), ("q_s2", 2.166),
    ("sigma_F02", 325.9), ("sigma_F2", 700.1), ("sigma_FG2", 929.8), ("S_F2", 1.328),
]


@pytest.mark.parametrize("symbol, value", PUBLISHED, ids=[p[0] for p in PUBLISHED])
def test_published_value(sheet, symbol, value):
    assert sheet[symbol] == pytest.approx(value, rel=REL)


@pytest.mark.parametrize("symbol, value", PUBLISHED_MORE, ids=[p[0] for p in PUBLISHED_MORE])
def test_published_result(sheet, symbol, value):
    # the stresses carry the rounding of the report's printed factors (about 0.1 %): still inside 0.5 %
    assert sheet[symbol] == pytest.approx(value, rel=REL)


@pytest.mark.parametrize("symbol, value", [("d_v1", 58.350), ("g_valpha", 13.120), ("rho_rel", 12.459),
                                           ("z_vn1", 25.594), ("K_Halpha", 1.161), ("Z_R", 0.930),
                                           ("l_bm", 22.442), ("Y_BS", 1.054)])
def test_published_value_to_its_last_digit(sheet, symbol, value):
    # tighter: agreement to the report's printed digit (half a unit of its last place, plus float noise)
    digits = len(f"{value}".split(".")[1])
    assert abs(sheet[symbol] - value) <= 0.5 * 10.0 ** -digits + 1e-9


def test_tooth_form_with_published_thickness(sheet):
    # pinion: z_vn1, mmn, alpha_n = 20 deg, rho_a01 = 0.8 mm, h_a0 = h_fm1 + x_hm1 mmn, published x_hm1/x_sm1
    mmn = 3.213
    tf = tooth_form(sheet["z_vn1"], mmn, math.radians(20.0), 0.8, 2.393 + 0.505 * mmn, 0.505, 0.036,
                    sheet["z_vn1"] * mmn + 2 * 4.837)
    assert tf["rho_F"] == pytest.approx(1.023, rel=REL)
    assert tf["h_Fa"] == pytest.approx(6.405, rel=REL)


def test_root_geometry_through_the_blank(sheet):
    # ISO/TR 10300-30 table A.1 prints x_sm to 3 decimals: 0.036 / -0.055 (ISO 23509 thickness with backlash)
    assert abs(sheet["x_sm1"] - 0.036) <= 0.0006
    assert abs(sheet["x_sm2"] + 0.055) <= 0.0006
    assert sheet["rho_F1"] == pytest.approx(1.023, rel=REL)
    assert sheet["h_Fa1"] == pytest.approx(6.405, rel=REL)


def test_json_keys(sheet):
    for key in ("sigma_H0", "sigma_H", "S_H", "sigma_F01", "sigma_F1", "S_F1", "sigma_F02", "sigma_F2", "S_F2",
                "Y_Fa1", "Y_Fa2", "Y_Sa1", "Y_Sa2", "Z_M-B", "Z_LS", "Z_E", "Z_K", "Z_L", "Z_v", "Z_R", "Z_X",
                "Z_NT1", "Z_W", "Y_eps", "Y_BS", "Y_LS", "Y_deltarelT1", "Y_RrelT2", "Y_X1", "Y_NT2", "K_A", "K_v",
                "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "sigma_HP1", "sigma_FP2", "sigma_HG1", "sigma_FG2",
                "l_bt", "l_br", "F_n"):
        assert math.isfinite(sheet[key]), key
        assert key in sheet["units"]


def test_stress_relations(sheet):
    # the stresses follow from their factors as ISO 10300-2/-3 write them (checks the assembly, not the factors)
    s = sheet
    assert s["sigma_H"] == pytest.approx(s["sigma_H0"] * math.sqrt(s["K_A"] * s["K_v"] * s["K_Hbeta"] * s["K_Halpha"]),
                                         rel=1e-12)
    assert s["S_H"] == pytest.approx(min(s["S_H1"], s["S_H2"]), rel=1e-12)
    assert s["sigma_H0"] == pytest.approx(
        math.sqrt(s["F_n"] / (s["l_bm"] * s["rho_rel"])) * s["Z_M-B"] * s["Z_LS"] * s["Z_E"], rel=1e-12)
    assert s["S_H1"] == pytest.approx(
        1500.0 * s["Z_NT1"] * s["Z_L"] * s["Z_v"] * s["Z_R"] * s["Z_K"] / s["sigma_H"], rel=1e-12)
    assert s["Y_LS"] == pytest.approx(s["Z_LS"] ** 2, rel=1e-12)
    for k in (1, 2):
        assert s[f"sigma_F{k}"] == pytest.approx(
            s[f"sigma_F0{k}"] * s["K_A"] * s["K_v"] * s["K_Fbeta"] * s["K_Falpha"], rel=1e-12)
        assert s[f"S_F{k}"] == pytest.approx(1.3 * s[f"sigma_FP{k}"] / s[f"sigma_F{k}"], rel=1e-12)
        assert s[f"sigma_F0{k}"] == pytest.approx(
            s["F_vmt"] / (25.4 * 3.213316) * s[f"Y_Fa{k}"] * s[f"Y_Sa{k}"] * s["Y_eps"] * s["Y_BS"] * s["Y_LS"],
            rel=1e-5)
