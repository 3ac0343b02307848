"""ISO 23509:2016 Annex F.2, Sample 1 (spiral bevel 14/39, no offset, Method 0, data type II): the dimension sheet.

Which figure is checked against what (tolerances ±0.003 mm and ±0.002° unless a row says otherwise):

* **Published by the standard** (ISO 23509:2016 Annex F.2, Sample 1; same text as ANSI/AGMA ISO 23509-B17), values
  as transcribed: u, mmn, δ1, δ2, Rm, Re2, Ri2, met, dm1, dm2, di2, de1, hmw, c, ham1, hfm1, ham2, hfm2, hm, δa1,
  δf1, δa2, δf2, θa1, θf1 (``PUBLISHED_ISO23509``). ISO rounded the mean addendum factor before use, so depths differ
  from an exact computation by about 0.001 mm.
* **Published for the same gear set by ISO/TR 10300-30:2024 Annex A, Sample 1** (load capacity worked example on this
  pair, table A.1): the mean addenda and dedenda to 3 decimals, x_hm1 = 0.505, the thickness modification
  coefficients *with backlash* x_sm1 = 0.036 and x_sm2 = −0.055, and the virtual numbers of teeth in the normal
  section zvn1 = 25.594, zvn2 = 198.613 (= dvn/mmn) (``PUBLISHED_ISO10300``). x_sm1/x_sm2 pin the thickness
  factor (x_smn = k_t/2) and the backlash allocation (half the outer normal backlash from each member).
* **Printed by an independent program** for this sample (BevGear calculation report "Gleas FM ISO 23509 page 79",
  dsoftcon.be, 2023): x_smn = 0.046, mmt = 3.9227, δ, δa, δf to 4 decimals and t_zm1 = 76.494, the crossing
  point to mean point distance (``INDEPENDENT_PROGRAM``). These are not the standard's own sheet.
* **Not published in what we could find** (the standard's full sheet is not publicly available): βe, βi, the heel and
  toe depths, dae, dai, dfe, dfi, t_xo, t_xi, t_zF, t_zR, t_zm2, h_t, smn, smt, smnc, hamc, jmn. They are checked by
  an independent second computation in ``test_blank_crosscheck.py`` (axial-plane construction of every cone, point
  and apex; the backlash carried from the mean point to the heel by a separate route; chord by coordinates) and, for
  this sample, in :func:`test_sample1_unpublished_figures_by_construction` below.
"""

import math

import numpy as np
import pytest

from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput

R = math.radians
TOL_MM = 0.003  # as the transcription states: ISO rounded c_ham before use (depths ±0.001 mm) plus print rounding
TOL_DEG = 0.002

# ISO 23509:2016 Annex F.2 Sample 1, published results: quantity -> (value, unit)
PUBLISHED_ISO23509 = {
    "u": (2.786, "-"), "mmn": (3.213, "mm"), "delta1": (19.747, "deg"), "delta2": (70.253, "deg"),
    "Rm": (81.273, "mm"), "Re2": (93.973, "mm"), "Ri2": (68.573, "mm"), "met": (4.536, "mm"),
    "dm1": (54.918, "mm"), "dm2": (152.987, "mm"), "di2": (129.080, "mm"), "de1": (63.500, "mm"),
    "hmw": (6.427, "mm"), "c": (0.803, "mm"), "ham1": (4.836, "mm"), "hfm1": (2.394, "mm"),
    "ham2": (1.591, "mm"), "hfm2": (5.639, "mm"), "hm": (7.230, "mm"),
    "delta_a1": (26.240, "deg"), "delta_f1": (17.613, "deg"), "delta_a2": (72.387, "deg"),
    "delta_f2": (63.760, "deg"), "theta_a1": (6.493, "deg"), "theta_f1": (2.134, "deg"),
}

# ISO/TR 10300-30:2024 Annex A, Sample 1, table A.1 (the same gear set): quantity -> (value, tolerance)
PUBLISHED_ISO10300 = {
    "ham1": (4.837, TOL_MM), "ham2": (1.590, TOL_MM), "hfm1": (2.393, TOL_MM), "hfm2": (5.640, TOL_MM),
    "x_hm1": (0.505, 0.0005),  # printed to 3 decimals: half a unit of the last digit
    "x_sm1": (0.036, 0.0005), "x_sm2": (-0.055, 0.0005),
    "zvn1": (25.594, 0.0005), "zvn2": (198.613, 0.0005),
}

# BevGear report of the same sample (independent program, not the standard): quantity -> (value, tolerance)
INDEPENDENT_PROGRAM = {
    "x_hm1": (0.505, 0.0005), "x_smn": (0.046, 0.0005), "mmt": (3.9227, 0.00005), "mmn": (3.2133, 0.00005),
    "u": (2.7857, 0.00005), "Rm": (81.273, TOL_MM), "dm1": (54.919, TOL_MM), "dm2": (152.987, TOL_MM),
    "delta1": (19.7468, 0.0001), "delta2": (70.2532, 0.0001),  # 4 decimals: half a unit, ±0.00005° rounded up
    "delta_a1": (26.2402, 0.0001), "delta_a2": (72.3874, 0.0001),
    "delta_f1": (17.6126, 0.0001), "delta_f2": (63.7598, 0.0001),
    "hm": (7.230, TOL_MM), "c": (0.803, TOL_MM), "tzm1": (76.494, TOL_MM),
}

BASE = dict(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3, alpha_dD=R(20.0), alpha_dC=R(20.0),
            f_alim=0.0, c_ham=0.24737, k_d=2.0, k_c=0.125, k_t=0.0915, jen=0.127, shaft_angle=R(90.0), a=0.0)

CASES = {
    "given_theta": dict(taper="given", theta_a2=R(2.1342), theta_f2=R(6.4934)),
    "duplex_from_rc0": dict(taper="duplex"),
}


def _value(blank, name):
    d = blank.to_dict(degrees=True)
    if name in ("zvn1", "zvn2"):
        return d["dvn" + name[-1]] / d["mmn"]
    return d[name]


def _deviations(blank):
    out = {}
    for name, (ref, unit) in PUBLISHED_ISO23509.items():
        # u is published to 3 decimals: compare like a length (±0.003)
        out[name] = (abs(_value(blank, name) - ref), TOL_DEG if unit == "deg" else TOL_MM)
    return out


@pytest.mark.parametrize("case", sorted(CASES))
def test_sample1_every_published_result(case):
    blank = compute_blank(BlankInput(**BASE, **CASES[case]))
    bad = {k: (dev, tol) for k, (dev, tol) in _deviations(blank).items() if not dev <= tol}
    assert not bad, f"{case}: deviations beyond tolerance {bad}"
    assert blank.warnings == ()  # a published design: no warning expected


@pytest.mark.parametrize("case", sorted(CASES))
def test_sample1_iso10300_published_thickness_and_virtual_gear(case):
    blank = compute_blank(BlankInput(**BASE, **CASES[case]))
    bad = {k: (_value(blank, k), ref) for k, (ref, tol) in PUBLISHED_ISO10300.items()
           if not abs(_value(blank, k) - ref) <= tol}
    assert not bad, bad


def test_sample1_independent_program_figures():
    blank = compute_blank(BlankInput(**BASE, **CASES["given_theta"]))
    bad = {k: (_value(blank, k), ref) for k, (ref, tol) in INDEPENDENT_PROGRAM.items()
           if not abs(_value(blank, k) - ref) <= tol}
    assert not bad, bad


def test_sample1_thickness_factor_is_half_the_modification_coefficient():
    """x_smn = k_t/2 (data type II). Taking k_t itself as x_smn (the former reading) thickens the pinion by k_t*mmn =
    0.294 mm and thins the wheel by as much; it would give x_sm1 = 0.082, far from the published 0.036."""
    bl = compute_blank(BlankInput(**BASE, **CASES["given_theta"]))
    assert bl.x_smn == 0.5 * BASE["k_t"]
    backlash_term = bl.x_smn - bl.x_sm1
    former = BASE["k_t"] - backlash_term  # x_sm1 if x_smn were k_t
    assert former - PUBLISHED_ISO10300["x_sm1"][0] > 0.04  # the former reading is rejected by the published figure


def test_sample1_unpublished_figures_by_construction():
    """Heel/toe points, diameters, axial distances and h_t of Sample 1 rebuilt in the axial plane from the published
    mean-point data only (Rm, δ, θ, mean depths), with no formula of the code under test."""
    bl = compute_blank(BlankInput(**BASE, **CASES["given_theta"]))
    for k in (1, 2):
        g = lambda n, k=k: getattr(bl, f"{n}{k}")  # noqa: E731
        d, ta, tf = g("delta"), g("theta_a"), g("theta_f")
        axis_r = np.array([math.cos(d), math.sin(d)])  # pitch generator, (z toward the back, r)
        nrm = np.array([-math.sin(d), math.cos(d)])
        mean_tip, mean_root = bl.Rm * axis_r + g("ham") * nrm, bl.Rm * axis_r - g("hfm") * nrm
        face_dir = np.array([math.cos(d + ta), math.sin(d + ta)])
        root_dir = np.array([math.cos(d - tf), math.sin(d - tf)])

        def on_line(p0, u, cone_distance, axis_r=axis_r):
            """Point of the line p0 + t·u whose projection on the pitch generator is at the given cone distance."""
            t = (cone_distance - p0 @ axis_r) / (u @ axis_r)
            return p0 + t * u

        tip_e, tip_i = on_line(mean_tip, face_dir, g("Re")), on_line(mean_tip, face_dir, g("Ri"))
        root_e, root_i = on_line(mean_root, root_dir, g("Re")), on_line(mean_root, root_dir, g("Ri"))
        assert 2 * tip_e[1] == pytest.approx(g("dae"), abs=1e-9)
        assert 2 * tip_i[1] == pytest.approx(g("dai"), abs=1e-9)
        assert 2 * root_e[1] == pytest.approx(g("dfe"), abs=1e-9)
        assert 2 * root_i[1] == pytest.approx(g("dfi"), abs=1e-9)
        assert tip_e[0] == pytest.approx(g("txo"), abs=1e-9) and tip_i[0] == pytest.approx(g("txi"), abs=1e-9)
        assert (bl.Rm * axis_r)[0] == pytest.approx(g("tzm"), abs=1e-9) and g("tz") == 0.0
        if k == 2:  # whole depth perpendicular to the root cone: heel tip point to the root line
            v = tip_e - mean_root
            assert abs(root_dir[0] * v[1] - root_dir[1] * v[0]) == pytest.approx(g("ht"), abs=1e-9)
        else:  # the standard's h_t1: crown point of the pinion face cone (apex t_zF1) to its root cone (apex t_zR1)
            crown = np.array([g("txo"), (g("txo") + g("tzF")) * math.tan(d + ta)])
            v = crown - np.array([-g("tzR"), 0.0])
            assert root_dir[0] * v[1] - root_dir[1] * v[0] == pytest.approx(g("ht"), abs=1e-9)
        # outer whole depth measured perpendicular to the pitch cone, the standard's h_e
        assert (tip_e - root_e) @ nrm == pytest.approx(g("he"), abs=1e-9)
    # t_zm2 of the independent program is printed "27.4..." (cut off in the report we could read): Rm*cos(delta2)
    assert 27.4 <= bl.tzm2 < 27.5


def test_sample1_duplex_dedendum_angle_sum():
    # ISO 23509 Sample 1: sum theta_f = 8.6277 deg, theta_f2 = (1 - c_ham) * sum, theta_a2 = c_ham * sum
    blank = compute_blank(BlankInput(**BASE, taper="duplex"))
    assert math.degrees(blank.sum_theta_fC) == pytest.approx(8.6277, abs=1e-4)
    assert math.degrees(blank.theta_f2) == pytest.approx(6.4934, abs=2e-4)
    assert math.degrees(blank.theta_a2) == pytest.approx(2.1342, abs=2e-4)


def test_sample1_both_routes_agree_with_each_other():
    a = compute_blank(BlankInput(**BASE, **CASES["given_theta"]))
    b = compute_blank(BlankInput(**BASE, **CASES["duplex_from_rc0"]))
    for name in ("delta_a1", "delta_f1", "delta_a2", "delta_f2"):
        assert abs(math.degrees(getattr(a, name) - getattr(b, name))) < 2e-4  # the given angles carry 4 decimals


def test_sample1_met_instead_of_de2_gives_the_same_blank():
    kw = {k: v for k, v in BASE.items() if k != "de2"}
    a = compute_blank(BlankInput(**BASE, taper="duplex"))
    b = compute_blank(BlankInput(**kw, met=176.893 / 39, taper="duplex"))
    da, db = a.to_dict(), b.to_dict()
    for k, v in da.items():
        if isinstance(v, float):
            assert db[k] == pytest.approx(v, rel=1e-12, abs=1e-12), k


def max_deviations():
    """Largest deviations (mm, deg) from the standard's published figures per case; used by the report."""
    res = {}
    for case, extra in CASES.items():
        devs = _deviations(compute_blank(BlankInput(**BASE, **extra)))
        mm = max(d for k, (d, t) in devs.items() if PUBLISHED_ISO23509[k][1] != "deg")
        deg = max(d for k, (d, t) in devs.items() if PUBLISHED_ISO23509[k][1] == "deg")
        res[case] = (mm, deg)
    return res


if __name__ == "__main__":
    print(max_deviations())
