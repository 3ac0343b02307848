"""Basic settings of a hypoid pair from the ISO 23509 Method 1 blank (spiralbevel.meshing.hypoid_pair).

Checked three ways: (1) the achieved mean-point spiral and pressure angles of all four flanks equal the design; (2) an
independent model: the same machine in the universal generator's parametrization (4x4 chain, complex-step meshing)
located at the mean point by its own solver, angles measured there; (3) the assembled pair: both mean points brought
to the pitch point P in the hypoid pair frame have a common normal perpendicular to the relative velocity."""

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.design.hypoid_member import member_blank
from spiralbevel.errors import GeometryError
from spiralbevel.generation.basic_settings_solve import solve_basic_settings
from spiralbevel.machine.default_cutter import default_cutter, design_pressure_angle
from spiralbevel.machine.universal import UniversalGenerator, UniversalSettings
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks, pitch_point
from _hypoid_sample2 import SAMPLE2

R = math.radians
# the solver stops at 1e-7 rad on the angles; the mean point is located to ~1e-10 mm
ANGLE_TOL = 2e-7


def _blank(**changes):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        return compute_blank(BlankInput(**{**SAMPLE2, **changes}))


@pytest.fixture(scope="module")
def sample2():
    blank = _blank()
    return blank, hypoid_basic_flanks(blank)


def test_achieved_angles_equal_the_design(sample2):
    blank, flanks = sample2
    assert blank.beta_m1 - blank.beta_m2 > R(11.0)        # a real hypoid: the spiral angles differ by zeta_mp
    for (member, side), (_, _, flank, _) in flanks.items():
        mp = flank.mean_point()
        i = member.index
        assert mp.spiral_angle == pytest.approx(getattr(blank, f"beta_m{i}"), abs=ANGLE_TOL)
        assert mp.pressure_angle == pytest.approx(design_pressure_angle(blank, member, side), abs=ANGLE_TOL)
        # the mean point sits on the member's own mean cone distance
        R_mean = getattr(blank, f"Rm{i}")
        d = getattr(blank, f"delta{i}")
        assert math.hypot(*mp.point[:2]) == pytest.approx(R_mean * math.sin(d), abs=1e-8)
        assert mp.point[2] == pytest.approx(R_mean * math.cos(d), abs=1e-8)
        assert mp.hand_sign == getattr(blank, f"hand{i}").sign


def _angles_by_universal_generator(blank, member, side, cutter, settings, hand):
    """Mean-point spiral and pressure angles of the same machine in the universal generator's parametrization,
    located at (axial, radius) = R_m (cos delta, sin delta) by scipy's fsolve from a coarse grid."""
    i = member.index
    Rm, d = getattr(blank, f"Rm{i}"), getattr(blank, f"delta{i}")
    gen = UniversalGenerator(cutter, UniversalSettings.from_machine_settings(settings), hand)

    def miss(x):
        p = gen.evaluate(x[0], x[1]).points
        return np.array([p[2] - Rm * math.cos(d), math.hypot(p[0], p[1]) - Rm * math.sin(d)])

    best = None
    for u in np.linspace(0.5, 12.0, 12):
        for psi in np.linspace(-0.8, 0.8, 33):
            try:
                m = np.linalg.norm(miss((u, psi)))
            except GeometryError:
                continue
            if best is None or m < best[0]:
                best = (m, (u, psi))
    x = fsolve(miss, best[1], xtol=1e-14)
    assert np.linalg.norm(miss(x)) < 1e-9
    pt = gen.evaluate(x[0], x[1])
    p, n = pt.points, pt.normals
    radial = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    g = math.sin(d) * radial + math.cos(d) * np.array([0.0, 0.0, 1.0])       # pitch generatrix through p
    N = math.cos(d) * radial - math.sin(d) * np.array([0.0, 0.0, 1.0])       # pitch cone normal
    t = np.cross(n, N)                                                        # trace of the flank on that cone
    return math.acos(abs(t @ g) / np.linalg.norm(t)), math.asin(abs(n @ N))


@pytest.mark.parametrize("member, side", [(Member.PINION, Side.CONCAVE), (Member.GEAR, Side.CONCAVE)])
def test_independent_model_at_the_mean_point(sample2, member, side):
    blank, flanks = sample2
    cutter, settings, flank, _ = flanks[(member, side)]
    beta, alpha = _angles_by_universal_generator(blank, member, side, cutter, settings, flank.hand)
    assert beta == pytest.approx(getattr(blank, f"beta_m{member.index}"), abs=ANGLE_TOL)
    assert alpha == pytest.approx(design_pressure_angle(blank, member, side), abs=ANGLE_TOL)


def test_pitch_point_closed_form_against_least_squares():
    """The closed form of pitch_point against a bracketed root of the wheel-circle condition on the pinion circle."""
    blank = _blank()
    kin = HypoidPairKinematics.from_blank(blank)
    a1, o1, a2, o2, _ = kin.axes()
    r1, h1 = blank.Rm1 * math.sin(blank.delta1), blank.Rm1 * math.cos(blank.delta1)

    def X(t):
        return o1 + h1 * a1 + r1 * np.array([math.cos(t), math.sin(t), 0.0])

    def on_wheel(t):           # distance from the wheel apex minus R_m2 and the axial condition, combined
        v = X(t) - o2
        return (v @ a2 - blank.Rm2 * math.cos(blank.delta2)) + (np.linalg.norm(v) - blank.Rm2)

    ts = np.linspace(-math.pi, math.pi, 721)
    vals = [on_wheel(t) for t in ts]
    roots = [brentq(on_wheel, ts[k], ts[k + 1], xtol=1e-15) for k in range(720) if vals[k] * vals[k + 1] < 0]
    P = pitch_point(kin, blank)
    assert min(np.linalg.norm(X(t) - P) for t in roots) < 1e-9


@pytest.mark.parametrize("pinion_side", [Side.CONCAVE, Side.CONVEX])
def test_mating_flanks_touch_at_the_pitch_point(sample2, pinion_side):
    """Pinion and wheel mean points turned about their axes into P: opposite outward normals (tangency), and the
    common normal is perpendicular to the relative velocity (the equation of meshing holds at P)."""
    blank, flanks = sample2
    kin = HypoidPairKinematics.from_blank(blank)
    a1, o1, a2, o2, B2 = kin.axes()
    P = pitch_point(kin, blank)
    m1 = flanks[(Member.PINION, pinion_side)][2].mean_point()
    m2 = flanks[(Member.GEAR, pinion_side.mate)][2].mean_point()

    def rz(t):
        return np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0], [0.0, 0.0, 1.0]])

    q1, q2 = P - o1, B2.T @ (P - o2)
    R1 = rz(math.atan2(q1[1], q1[0]) - math.atan2(m1.point[1], m1.point[0]))
    R2 = B2 @ rz(math.atan2(q2[1], q2[0]) - math.atan2(m2.point[1], m2.point[0]))
    np.testing.assert_allclose(o1 + R1 @ m1.point, P, atol=1e-8)
    np.testing.assert_allclose(o2 + R2 @ m2.point, P, atol=1e-8)
    n1, n2 = R1 @ m1.normal, R2 @ m2.normal
    assert np.linalg.norm(n1 + n2) < 5 * ANGLE_TOL          # two angles each within ANGLE_TOL
    v = kin.relative_velocity(P)
    assert abs(n1 @ v) / np.linalg.norm(v) < 5 * ANGLE_TOL


def test_zero_offset_is_the_spiral_bevel_solve():
    """a = 0: the member views change nothing, the settings are those of the spiral bevel basic-settings solve."""
    blank = _blank(a=0.0, taper="standard", theta_a2=None, theta_f2=None, b=25.0, beta_m=R(35.0))
    assert blank.Rm1 == blank.Rm2 == blank.Rm
    flanks = hypoid_basic_flanks(blank)
    for member, side in ((Member.PINION, Side.CONVEX), (Member.GEAR, Side.CONCAVE)):
        ref = solve_basic_settings(blank, member, side, default_cutter(blank, member, side))
        assert flanks[(member, side)][1] == ref[1]
        assert member_blank(blank, member).Rm == blank.Rm
