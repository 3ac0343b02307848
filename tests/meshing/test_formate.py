"""Formate (non-generated) wheel flanks of a hypoid pair (spiralbevel.meshing.formate): the design mean-point angles
reached by the settings solve, the flank's curvatures against numerical differential geometry of the surface, and the
Formate flank as the cutter surface (the universal generator with the cradle locked)."""

import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.machine.default_cutter import design_pressure_angle
from spiralbevel.meshing.formate import FormateFlank, solve_formate_settings
from _hypoid_sample2 import sample2_blank

R = math.radians


@pytest.fixture(scope="module")
def formate():
    blank = sample2_blank()
    return blank, {side: solve_formate_settings(blank, Member.GEAR, side) for side in Side}


def _normal_curvature(flank, x, t):
    """t . dn/ds along the unit tangent t at parameters x, by central differences of points and normals."""
    h = np.array([1e-5, 1e-7])                   # mm, rad: truncation ~1e-10, round-off ~1e-9 relative
    d = []
    for k in range(2):
        e = np.zeros(2)
        e[k] = h[k]
        a, m = flank.evaluate(*(x + e)), flank.evaluate(*(x - e))
        d.append(((a.points - m.points) / (2 * h[k]), (a.normals - m.normals) / (2 * h[k])))
    A = np.stack([d[0][0], d[1][0]], 1)
    c = np.linalg.lstsq(A, t, rcond=None)[0]
    return float(t @ (c[0] * d[0][1] + c[1] * d[1][1]))


@pytest.mark.parametrize("side", list(Side))
def test_formate_wheel_has_the_design_angles(formate, side):
    blank, flanks = formate
    cutter, settings, flank = flanks[side]
    assert not settings.generated
    mp = flank.mean_point()
    assert mp.spiral_angle == pytest.approx(blank.beta_m2, abs=1e-8)
    assert mp.pressure_angle == pytest.approx(design_pressure_angle(blank, Member.GEAR, side), abs=1e-8)
    assert mp.hand_sign == blank.hand2.sign
    assert math.hypot(*mp.point[:2]) == pytest.approx(blank.Rm2 * math.sin(blank.delta2), abs=1e-9)
    # a straight-blade Formate flank is a cone: no curvature along the blade
    assert mp.k1 == 0.0


@pytest.mark.parametrize("side", list(Side))
def test_formate_curvature_by_numerical_geometry(formate, side):
    _, flanks = formate
    flank = flanks[side][2]
    mp = flank.mean_point()
    x = np.array([mp.u, mp.theta])
    for k, e in ((mp.k1, mp.e1), (mp.k2, mp.e2)):
        assert _normal_curvature(flank, x, e) == pytest.approx(k, abs=1e-8)
    np.testing.assert_allclose(np.cross(mp.e1, mp.e2), mp.normal, atol=1e-12)
    # e1 runs from root to top: the height above the pitch cone grows along it
    p = mp.point
    rho = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    d = flank.outline.delta
    assert mp.e1 @ (math.cos(d) * rho - math.sin(d) * np.array([0.0, 0.0, 1.0])) > 0


def test_formate_flank_needs_formate_settings(formate):
    blank, flanks = formate
    cutter, settings, _ = flanks[Side.CONVEX]
    with pytest.raises(DesignError, match="settings.generated"):
        FormateFlank(cutter, settings.replace(generated=True), blank, Member.GEAR, Side.CONVEX)


def _formate_angles_by_cradle_kernel(blank, cutter, settings, hand):
    """Mean-point spiral and pressure angles of a Formate wheel flank in an independent model: the cutter surface of
    revolution written in the cradle machine's own frame at psi_c = 0 (absolute cutter angle phi, the machine-frame
    formulas of ``spiralbevel._core.generation``: r = C + rho e(phi) + z k, cutter normal sin(chi) e + s cos(chi) k),
    carried into the wheel frame by that kernel's ``to_member`` (not the universal generator's 4x4 chain that
    ``FormateFlank`` uses), mirrored for a right-hand wheel, located at (axial, radius) = R_m2 (cos delta2,
    sin delta2) by scipy's fsolve, and the angles measured on the pitch cone there."""
    from scipy.optimize import fsolve

    from spiralbevel._core import generation as g
    from spiralbevel.machine.settings import MachineSettings

    ms = MachineSettings(radial_setting=settings.radial_setting, cradle_angle=settings.cradle_angle,
                         machine_root_angle=settings.machine_root_angle,
                         machine_centre_to_back=settings.machine_centre_to_back, sliding_base=settings.sliding_base,
                         blank_offset=settings.blank_offset, ratio_of_roll=settings.ratio_of_roll)
    mp = ms.kernel_params()
    cp = g.cutter_params(cutter.sign, cutter.blade_angle, cutter.point_radius, cutter.edge_radius)
    mirror = np.array([1.0, -1.0, 1.0]) if hand.sign > 0 else np.ones(3)
    Rm, d = blank.Rm2, blank.delta2

    def surface(x):
        rho, z, chi, _ = g.profile(np.asarray(x[0], float), cp)
        e = np.array([math.cos(x[1]), math.sin(x[1]), 0.0])
        k = np.array([0.0, 0.0, 1.0])
        C = mp["S"] * np.array([math.cos(math.pi - mp["q"]), math.sin(math.pi - mp["q"]), 0.0])
        r = C + float(rho) * e + float(z) * k
        n = -cp["s"] * (math.sin(float(chi)) * e + cp["s"] * math.cos(float(chi)) * k)     # out of the tooth
        return (mirror * g.to_member(r, np.zeros(()), mp), mirror * g.to_member(n, np.zeros(()), mp, point=False))

    def miss(x):
        p = surface(x)[0]
        return np.array([p[2] - Rm * math.cos(d), math.hypot(p[0], p[1]) - Rm * math.sin(d)])

    best = min(((np.linalg.norm(miss((u, ph))), (u, ph)) for u in np.linspace(0.5, 12.0, 12)
                for ph in np.linspace(-math.pi, math.pi, 73)), key=lambda t: t[0])
    x = fsolve(miss, best[1], xtol=1e-14)
    assert np.linalg.norm(miss(x)) < 1e-9
    p, n = surface(x)
    radial = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    gen = math.sin(d) * radial + math.cos(d) * np.array([0.0, 0.0, 1.0])      # pitch generatrix through p
    N = math.cos(d) * radial - math.sin(d) * np.array([0.0, 0.0, 1.0])       # pitch cone normal
    t = np.cross(n, N)
    return math.acos(abs(t @ gen) / np.linalg.norm(t)), math.asin(abs(n @ N)), p, n


@pytest.mark.parametrize("side", list(Side))
def test_formate_flank_by_an_independent_model_at_the_mean_point(formate, side):
    """The Formate wheel flank's mean point (spiral angle beta_m2, pressure angle of its side) by the cradle kernel's
    machine-frame cutter surface: the same point, the same normal and the design angles."""
    blank, flanks = formate
    cutter, settings, flank = flanks[side]
    beta, alpha, p, n = _formate_angles_by_cradle_kernel(blank, cutter, settings, flank.hand)
    # the settings solve stops within 1e-9 rad of the design angles; fsolve adds ~1e-12 rad
    assert beta == pytest.approx(blank.beta_m2, abs=2e-9)
    assert alpha == pytest.approx(design_pressure_angle(blank, Member.GEAR, side), abs=2e-9)
    mp = flank.mean_point()
    np.testing.assert_allclose(p, mp.point, atol=1e-8)
    np.testing.assert_allclose(n, mp.normal, atol=1e-9)
