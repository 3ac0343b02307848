"""ISO/TR 10300-30:2024 Annex B, Sample 2: ISO 10300 Method B1 on the hypoid pair of ISO 23509 Annex F.3 (Sample 2,
13/42, offset 15 mm), with the blank computed by spiralbevel from the ISO 23509 inputs (``tests/_hypoid_sample2``).

The published figures below are the report's, as transcribed independently in the self-test of an open-source
ISO 10300 calculator (not read from the report by us). Verified to relative 0.5 % (most to 0.03 %): the virtual
cylindrical gears (d_vb2, p_vet, g_valpha, eps_valpha, b_veff, b_v, z_vn1, z_vn2, d_vn1, d_vn2, d_van1, d_van2,
eps_vbeta, eps_vgamma, rho_rel, l_bm), the forces and velocities (F_mt1, F_vmt, v_mt1, v_mt2, F_n), the load factors
(K_v, K_Hbeta, K_F0, K_Fbeta, a_rel, K_Halpha), the pitting factors (Z_M-B, Z_E, Z_L, Z_v, Z_R), and for bending
Y_eps, Y_BS, the pinion's critical section (theta, s_Fn, rho_F, alpha_Fan, h_Fa, Y_Fa, q_s, Y_Sa, Y_RrelT,
Y_deltarelT), the wheel's Y_Fa, Y_Sa, q_s, Y_deltarelT and both root stress limits sigma_FG (printed as sigma_FP).

Not verified: Z_LS (0.776 against the published 0.703, see the xfail below and docs/rating.md), hence neither
sigma_H0, sigma_H, Y_LS, sigma_F0, sigma_F nor the safety factors; Z_Hyp is an input (the published 0.952).
"""

import dataclasses
import math
import sys
from pathlib import Path

import pytest

from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.rating import RatingInput, rate_iso10300
from spiralbevel.rating._blank import blank_data
from spiralbevel.rating.load_factors import nominal_forces
from spiralbevel.rating.virtual import virtual_gears

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _hypoid_sample2 import SAMPLE2  # noqa: E402

REL = 5e-3  # the acceptance tolerance: relative 0.5 % (the report prints 4 to 5 significant digits)

#: the report's operating, accuracy, material and lubricant data for this pair
INPUT = dict(T1=250.0, n1=1200.0, f_pt=(11.6, 23.5), rho_a0=(0.8, 1.2), sigma_Hlim=(1500.0, 1500.0),
             sigma_Flim=(480.0, 480.0), nu40=150.0, Rz_flank=(8.0, 8.0), Rz_root=(16.0, 16.0), K_A=1.1,
             E=210000.0, nu=0.3, mounting="one-cantilever", contact_pattern="light-load", profile_crowning="low",
             Z_Hyp=0.952)

PUBLISHED = [
    ("d_vb2", 342.334), ("p_vet", 10.329), ("g_valpha", 10.435), ("eps_valpha", 1.010), ("b_veff", 24.880),
    ("b_v", 29.271), ("z_vn1", 38.131), ("z_vn2", 255.605), ("d_vn1", 100.653), ("d_vn2", 674.716),
    ("d_van1", 107.517), ("d_van2", 678.412), ("eps_vbeta", 2.096), ("eps_vgamma", 3.106), ("rho_rel", 17.926),
    ("l_bm", 13.397),
    ("F_mt1", 9366.1), ("F_vmt", 10427.4), ("v_mt", 3.354), ("v_mt2", 2.759), ("F_n", 15298.7),
    ("K_v", 1.016), ("K_Hbeta", 1.65), ("K_F0", 1.060), ("K_Fbeta", 1.556), ("a_rel", 0.211), ("K_Halpha", 1.000),
    ("Z_M-B", 0.963), ("Z_E", 191.646), ("Z_L", 0.992), ("Z_v", 0.970), ("Z_R", 0.939),
    ("Y_eps", 0.625), ("Y_BS", 1.909),
    ("theta1", 52.945), ("s_Fn1", 6.065), ("rho_F1", 1.042), ("alpha_Fan1", 27.315), ("h_Fa1", 5.098),
    ("Y_Fa1", 2.047), ("q_s1", 2.910), ("Y_Sa1", 1.903), ("Y_RrelT1", 0.972), ("Y_deltarelT1", 1.004),
    ("sigma_FG1", 936.4),
    ("Y_Fa2", 2.403), ("Y_Sa2", 1.690), ("q_s2", 2.073), ("Y_deltarelT2", 0.996), ("sigma_FG2", 929.0),
]


@pytest.fixture(scope="module")
def blank():
    return compute_blank(BlankInput(**SAMPLE2))


@pytest.fixture(scope="module")
def sheet(blank):
    return rate_iso10300(blank, RatingInput(**INPUT)).to_dict(degrees=True)


@pytest.mark.parametrize("symbol, published", PUBLISHED, ids=[p[0] for p in PUBLISHED])
def test_published_figure(sheet, symbol, published):
    assert sheet[symbol] == pytest.approx(published, rel=REL)


@pytest.mark.xfail(strict=True, reason="Z_LS of a hypoid: the contact-line length form reproduces Sample 1 but "
                   "gives 0.776 against Sample 2's 0.703 (docs/rating.md)")
def test_load_sharing_factor(sheet):
    assert sheet["Z_LS"] == pytest.approx(0.703, rel=REL)


def test_hypoid_needs_the_hypoid_factor(blank):
    from spiralbevel.errors import DesignError

    with pytest.raises(DesignError, match="hypoid_factor"):
        rate_iso10300(blank, RatingInput(**dict(INPUT, Z_Hyp=None)))


def test_general_forms_reduce_to_the_spiral_bevel_ones():
    """The hypoid branch of the virtual gears (sheared zone of action, offset face width, pitch-cone relative
    curvature rho_t cos^2(beta_B)) with zero offset angles gives the spiral bevel forms (the helical rho_rel) to
    round-off: ISO 23509 Sample 1's blank with a vanishing offset switched on."""
    from spiralbevel.design.blank import BlankInput as BI

    s1 = compute_blank(BI(z1=14, z2=39, b=25.4, beta_m=math.radians(35.0), rc0=114.3, de2=176.893))
    g0 = blank_data(s1)
    g = dataclasses.replace(g0, a=1e-6, Rm1=g0.Rm, Rm2=g0.Rm)
    assert g.hypoid and not g0.hypoid
    v0, v = virtual_gears(g0), virtual_gears(g)
    for k in v0:
        assert v[k] == pytest.approx(v0[k], rel=1e-12, abs=1e-14), k
    f0, f = nominal_forces(g0, 300.0, 1200.0), nominal_forces(g, 300.0, 1200.0)
    for k in f0:
        assert f[k] == pytest.approx(f0[k], rel=1e-12), k
    # and the normal force of the pinion's drive flank equals the virtual gear's
    assert f["F_mt1"] / (math.cos(g.alpha_nD) * math.cos(g.beta_m1)) == pytest.approx(
        f0["F_vmt"] / (math.cos(v0["alpha_vet"]) * math.cos(v0["beta_vb"])), rel=1e-12)


@pytest.mark.parametrize("value", [0.0, 1.2, float("nan")])
def test_bad_hypoid_factor_names_the_key(tmp_path, value):
    from typer.testing import CliRunner

    from spiralbevel.cli import app
    from spiralbevel.errors import DesignError

    with pytest.raises(DesignError, match="Z_Hyp"):
        RatingInput(**dict(INPUT, Z_Hyp=value))
    if math.isfinite(value):
        from _hypoid_sample2 import SAMPLE2_TOML

        f = tmp_path / "hypoid.toml"
        f.write_text(SAMPLE2_TOML + "\n[rating]\npinion_torque = 250.0\npinion_speed = 1200.0\nsigma_Hlim = 1500.0\n"
                     f"sigma_Flim = 480.0\noil_viscosity = 150.0\naccuracy_grade = 6\nhypoid_factor = {value}\n")
        res = CliRunner().invoke(app, ["rate", str(f)])
        assert res.exit_code == 2 and "rating.hypoid_factor" in " ".join(res.output.split()), res.output
        assert "Traceback" not in res.output
