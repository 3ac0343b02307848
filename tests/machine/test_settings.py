"""Machine settings: seed 001 Table 4 from Table 1 (docs/theory/example.md), sign pins of docs/conventions.md,
validation."""

import math

import numpy as np
import pytest

from spiralbevel._core import generation as _g
from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import Blade, HeadCutter, MachineSettings, seed001_blank, seed001_settings


@pytest.fixture(scope="module")
def blank():
    return seed001_blank()


@pytest.fixture(scope="module")
def gear_t4():
    return seed001_settings()[(Member.GEAR, Side.CONVEX)]


def test_from_blank_reproduces_table4(blank, gear_t4):
    cutter, t4 = gear_t4
    s = MachineSettings.from_blank(blank, Member.GEAR, Side.CONVEX, cutter)
    # seed 001 Table 4: S_r2 = 115.078 mm (docs/theory/example.md#table-4 check column: 115.079 from A = 115.8417), q2 =
    # 59 deg 20' 07"
    assert blank.Rm * math.cos(blank.theta_f2) == pytest.approx(115.8417, abs=5e-5)
    assert s.radial_setting == pytest.approx(115.078, abs=1.5e-3)
    assert math.degrees(s.cradle_angle) * 3600 == pytest.approx((59 * 60 + 20) * 60 + 7, abs=0.5)
    # ratio of cutting 1.06 (printed to 2 decimals)
    assert round(s.ratio_of_roll, 2) == 1.06 == t4.ratio_of_roll
    assert s.machine_root_angle == blank.delta_f2
    assert s.ratio_of_roll == pytest.approx(math.cos(blank.theta_f2) / math.sin(blank.delta2), rel=1e-15)
    root = MachineSettings.from_blank(blank, Member.GEAR, Side.CONVEX, cutter, roll="root")
    assert root.ratio_of_roll == pytest.approx(1 / math.sin(blank.delta_f2), rel=1e-15)
    # law of sines check of the crown-gear triangle: q = asin(r_c cos b / S)
    assert math.sin(s.cradle_angle) == pytest.approx(114.3 * math.cos(math.radians(30)) / s.radial_setting,
                                                     rel=1e-13)


def test_seed001_fixtures(gear_t4):
    cutter, t4 = gear_t4
    assert cutter.blade is Blade.INNER and cutter.point_radius == 113.155 and cutter.edge_radius == 1.31
    assert t4.sliding_base == -0.051 and t4.radial_setting == 115.078
    pc, p5 = seed001_settings()[(Member.PINION, Side.CONCAVE)]
    assert pc.blade is Blade.OUTER and p5.blank_offset == 34.197 and p5.machine_centre_to_back == 1.231


def test_side_must_match_blade(blank, gear_t4):
    with pytest.raises(DesignError, match="cutter.blade"):
        MachineSettings.from_blank(blank, Member.GEAR, Side.CONCAVE, gear_t4[0])


@pytest.mark.parametrize("field,value", [("radial_setting", -1.0), ("machine_root_angle", 2.0),
                                         ("ratio_of_roll", 0.0), ("sliding_base", float("nan")),
                                         ("modified_roll", (1, 2, 3, 4, 5))])
def test_bad_settings(field, value):
    kw = dict(radial_setting=100.0, cradle_angle=1.0, machine_root_angle=1.0)
    kw[field] = value
    with pytest.raises(DesignError, match=field):
        MachineSettings(**kw)


def test_summary_and_dict(gear_t4):
    cutter, t4 = gear_t4
    d = t4.to_dict(degrees=True)
    assert d["cradle_angle"] == pytest.approx(59 + 20 / 60 + 7 / 3600, abs=1e-12)
    assert t4.to_dict(degrees=False)["cradle_angle"] == t4.cradle_angle
    rows = dict((r[0], r[1]) for r in t4.replace(modified_roll=(0.01,)).summary_rows(cutter, Member.GEAR,
                                                                                       Side.CONVEX))
    assert rows["Cradle (installment) angle q"] == "59°20′07.0″"
    assert rows["Radial setting S_r"] == "115.0780"
    assert rows["Blade angle alpha_h"] == "23°50′00.0″"
    assert rows["Modified roll 2C"] == "0.01"
    assert rows["Cutter point radius R_h"] == "113.1550"


def test_modified_roll_is_taylor_form():
    mp = MachineSettings(100.0, 1.0, 1.0, ratio_of_roll=2.0, modified_roll=(0.1, -0.2, 0.3, 0.4)).kernel_params()
    psi, w, dw = _g.roll(np.array([0.0, 0.2]), mp)
    assert psi[0] == 0 and w[0] == 2.0 and dw[0] == pytest.approx(-2.0 * 0.1)
    h = 1e-5
    p1, _, _ = _g.roll(0.2 + h, mp)
    p0, _, _ = _g.roll(0.2 - h, mp)
    assert (p1 - p0) / (2 * h) == pytest.approx(w[1], rel=1e-9)
    x = 0.2
    assert psi[1] == pytest.approx(2.0 * (x - 0.1 * x**2 / 2 + 0.2 * x**3 / 6 - 0.3 * x**4 / 24 - 0.4 * x**5 / 120),
                                   rel=1e-15)


def test_radial_setting_moves_cutter_away():
    for S in (90.0, 120.0):
        mp = MachineSettings(S, 1.0, 1.0).kernel_params()
        sol = dict(phi=np.array(0.0), psi=np.array(0.3), rho=np.array(0.0), z=np.array(0.0))
        c = _g.contact_point(sol, mp)           # rho = 0: the cutter centre
        assert np.hypot(c[0], c[1]) == pytest.approx(S, rel=1e-15)
    # at psi_c = 0 the centre is S_r(-cos q, sin q, 0) on the left-hand machine (docs/theory/generation.md, Eq. (G5))
    sol = dict(phi=np.array(0.0), psi=np.array(0.0), rho=np.array(0.0), z=np.array(0.0))
    np.testing.assert_allclose(_g.contact_point(sol, MachineSettings(100.0, 0.5, 1.0).kernel_params()),
                               [-100 * math.cos(0.5), 100 * math.sin(0.5), 0.0], atol=1e-13)


def _gear(blank, **changes):
    cutter = HeadCutter(114.3 + 1.145, math.radians(22.5), 2.29, 1.31, Blade.INNER)
    s = MachineSettings.from_blank(blank, Member.GEAR, Side.CONVEX, cutter).replace(**changes)
    return generate_flank(cutter, s, blank, Member.GEAR, Side.CONVEX)


def test_sliding_base_deepens_cut(blank):
    # positive X_B moves the work along -Z_m toward the cutter: the generated root (cutter tip line) moves toward
    # the member axis by X_B (the root-cone normal there is the cradle axis), measured normal to the root cone.
    ol = _gear(blank).outline
    R = np.array([ol.Rm])

    def root_depth(fl):
        loc = fl._locator
        x = loc.at_R_u(R, np.array([fl.cutter.fillet_range[0]]))
        p = fl.generator.points(x[:, 0], x[:, 1])[0]
        _, h = ol.Rh(p[2], np.hypot(p[0], p[1]))
        return h
    d0, d1 = root_depth(_gear(blank)), root_depth(_gear(blank, sliding_base=0.1))
    assert d1 < d0
    assert (d0 - d1) == pytest.approx(0.1 * math.cos(blank.theta_f2), rel=2e-2)


def test_machine_centre_to_back_shifts_along_axis(blank):
    a, b = _gear(blank), _gear(blank, machine_centre_to_back=1.0)
    u, p = np.array([3.0, 5.0]), np.array([0.0, 0.05])
    np.testing.assert_allclose(b.evaluate(u, p).points, a.evaluate(u, p).points - [0, 0, 1.0], atol=1e-12)


def test_blank_offset_direction_in_kernel():
    # right-hand machine: A_i = (0, E_m, -X_B) (docs/theory/generation.md, Eq. (G5)); the kernel works on the mirrored
    # left-hand machine
    mp = MachineSettings(100.0, 1.0, 1.0, sliding_base=0.2, blank_offset=3.0, blank_offset_poly=(1.0,)).kernel_params()
    E, dE, _ = _g.offset(np.array(0.5), mp)
    assert E == pytest.approx(-3.5) and dE == pytest.approx(-1.0)
