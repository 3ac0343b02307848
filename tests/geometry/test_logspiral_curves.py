"""Curves of seed 000 Eqs. (1)-(6), (17) and seed 002 Eqs. (25)-(35), corrected per
docs/theory/logspiral.md#printed-equations and docs/theory/gearing.md#li-surface

Each curve is checked by an independent property (defining equations, numerical angles measured from finite
differences of the points) rather than by its own formula.
"""

import numpy as np
import pytest

from spiralbevel import LogSpiralFlank
from spiralbevel._core.rotations import rot_axis, rot_y, rot_z
from spiralbevel.geometry import curves


def _tangent(fun, t, h=1e-5):
    """Central-difference tangent of a curve (4th order)."""
    return (-fun(t + 2 * h) + 8 * fun(t + h) - 8 * fun(t - h) + fun(t - 2 * h)) / (12 * h)


def _angle(a, b):
    c = np.einsum("...i,...i", a, b) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1))
    return np.arccos(np.clip(c, -1, 1))


@pytest.mark.parametrize("delta_deg", [15.0, 35.0, 70.0])
def test_spherical_involute_defining_equations(delta_deg):
    rho0, d = 80.0, np.radians(delta_deg)
    vp = np.linspace(0.0, 2.5, 31)
    p = curves.spherical_involute(vp, rho0, d)
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    psi = vp * np.sin(d)
    # Eq. (4) sphere, Eq. (2) rolling plane, Eq. (3) chord to T = rho0 t(varphi)
    # (docs/theory/logspiral.md#printed-equations, item 1: z_T = rho0 cos d)
    assert np.allclose(x**2 + y**2 + z**2, rho0**2, rtol=1e-14)
    assert np.allclose(x * np.cos(d) * np.cos(vp) + y * np.cos(d) * np.sin(vp) - z * np.sin(d), 0, atol=1e-12)
    chord = ((x - rho0 * np.sin(d) * np.cos(vp)) ** 2 + (y - rho0 * np.sin(d) * np.sin(vp)) ** 2
             + (z - rho0 * np.cos(d)) ** 2)
    assert np.allclose(chord, 4 * rho0**2 * np.sin(psi / 2) ** 2, rtol=1e-11, atol=1e-11)
    # Eq. (6) corrected (docs/theory/logspiral.md#printed-equations, item 3) equals Eq. (5)
    assert np.allclose(curves.spherical_involute_matrix_form(vp, rho0, d), p, rtol=1e-14, atol=1e-12)


def test_involute_is_the_surface_varphi_curve():
    """At fixed phi the flank is R_z(phi) applied to the involute of radius rho(phi), parameter varphi - phi."""
    flank = LogSpiralFlank(100.0, np.radians(22.0), np.radians(-31.0))
    for phi in (-0.4, 0.0, 0.7):
        vp = phi + np.linspace(-1.0, 1.5, 17)
        on_surface = flank.point(vp, phi)
        inv = curves.spherical_involute(vp - phi, float(flank.rho(phi)), flank.base_cone_angle) @ rot_z(phi).T
        assert np.allclose(on_surface, inv, rtol=1e-14, atol=1e-12)


@pytest.mark.parametrize("beta_deg", [20.0, -45.0])
def test_c_curve_angle_to_generatrix_is_beta(beta_deg):
    rho0, d, b = 100.0, np.radians(25.0), np.radians(beta_deg)
    phi = np.linspace(-0.5, 0.5, 11)
    c = curves.c_curve(phi, rho0, d, b)
    assert np.allclose(c, LogSpiralFlank(rho0, d, b).c_curve(phi), rtol=1e-15)
    # on the base cone: x^2 + y^2 = z^2 tan^2 d (seed 000 Eq. (1))
    assert np.allclose(c[:, 0] ** 2 + c[:, 1] ** 2, (c[:, 2] * np.tan(d)) ** 2, rtol=1e-13)
    tan = _tangent(lambda t: curves.c_curve(t, rho0, d, b), phi)
    ang = _angle(tan, c)  # angle between the curve and the generatrix (toward the heel for beta > 0)
    expected = abs(b) if b > 0 else np.pi - abs(b)
    assert np.allclose(ang, expected, atol=1e-9)


@pytest.mark.parametrize("beta_deg", [35.0, -25.0])
@pytest.mark.parametrize("psi", [0.1, -0.3, 0.6])
def test_conical_log_spiral_measured_angle(beta_deg, psi):
    """docs/theory/logspiral.md, Eq. (S11): the psi = const curve lies on cos g = cos psi cos d with tan b_g = tan b sin
    g/sin d."""
    rho0, d, b = 100.0, np.radians(20.0), np.radians(beta_deg)
    phi = np.linspace(-0.4, 0.4, 9)
    p = curves.conical_log_spiral(phi, psi, rho0, d, b)
    flank = LogSpiralFlank(rho0, d, b)
    assert np.allclose(p, flank.point(flank.varphi_of(psi, phi), phi), rtol=1e-14)
    gamma = curves.cone_angle_of_psi(psi, d)
    assert np.allclose(np.arccos(p[:, 2] / np.linalg.norm(p, axis=-1)), gamma, atol=1e-12)
    assert np.isclose(curves.psi_of_cone_angle(gamma, d), abs(psi), atol=1e-12)
    tan = _tangent(lambda t: curves.conical_log_spiral(t, psi, rho0, d, b), phi)
    tan *= np.sign(np.einsum("...i,...i", tan, p))[:, None]  # toe -> heel
    measured = _angle(tan, p)
    assert np.allclose(measured, abs(curves.cone_spiral_angle(b, d, gamma)), atol=1e-9)
    assert np.isclose(curves.cone_spiral_angle(b, d, d), b)  # equals beta on the base cone


@pytest.mark.parametrize("beta_deg", [35.0, -35.0])
def test_taper_curve_angle_and_cone(beta_deg):
    """Seed 002 Eq. (33) with r = r0 exp(phi sin a cot b) (docs/theory/gearing.md#conjugacy)."""
    r0, a, b = 30.0, np.radians(19.0), np.radians(beta_deg)
    phi = np.linspace(-0.6, 0.6, 13)
    p = curves.taper_curve(phi, r0, a, b)
    assert np.allclose(np.hypot(p[:, 0], p[:, 1]), p[:, 2] * np.tan(a), rtol=1e-14)
    tan = _tangent(lambda t: curves.taper_curve(t, r0, a, b), phi)
    tan *= np.sign(np.einsum("...i,...i", tan, p))[:, None]
    assert np.allclose(_angle(tan, p), abs(b), atol=1e-9)
    # right hand (b > 0): turns positively about +z from toe to heel
    assert np.sign(np.diff(np.arctan2(p[:, 1], p[:, 0]))[0] * np.diff(np.linalg.norm(p, axis=-1))[0]) == np.sign(b)


@pytest.mark.parametrize("shaft_deg, z1, z2, beta_deg", [(90.0, 23, 65, 35.0), (75.0, 17, 41, -30.0)])
def test_mating_taper_curves_touch_on_the_pitch_line_while_rolling(shaft_deg, z1, z2, beta_deg):
    """docs/theory/gearing.md#li-surface (mating pitch curve) and Eq. (M9): curve 2 on pitch cone 2, same spiral angle,
    opposite hand, touching on the pitch line."""
    S, b = np.radians(shaft_deg), np.radians(beta_deg)
    g1 = np.arctan2(np.sin(S), z2 / z1 + np.cos(S))
    g2 = S - g1
    r0 = 35.0
    a2 = np.array([np.sin(S), 0.0, np.cos(S)])
    pitch_line = np.array([np.sin(g1), 0.0, np.cos(g1)])
    c2_own = curves.mating_taper_curve(np.linspace(-0.5, 0.5, 11), r0, g1, S, b)
    assert np.allclose(np.hypot(c2_own[:, 0], c2_own[:, 1]), c2_own[:, 2] * np.tan(g2), rtol=1e-14)
    for phi1 in np.linspace(-0.4, 0.4, 5):
        phi2 = -(z1 / z2) * phi1  # docs/conventions.md rolling
        R1 = rot_z(phi1)
        R2 = rot_axis(a2, phi2) @ rot_y(S)
        t1 = -phi1  # curve-1 parameter on the pitch line
        t2 = float(curves.mating_parameter(t1, g1, S))
        p1 = R1 @ curves.taper_curve(t1, r0, g1, b)
        p2 = R2 @ curves.mating_taper_curve(t2, r0, g1, S, b)
        assert np.allclose(p1, p2, atol=1e-11)
        assert np.allclose(np.cross(p1, pitch_line), 0.0, atol=1e-11)  # on the common pitch generatrix
        d1 = R1 @ _tangent(lambda t: curves.taper_curve(t, r0, g1, b), t1)
        d2 = R2 @ _tangent(lambda t: curves.mating_taper_curve(t, r0, g1, S, b), t2)
        assert np.linalg.norm(np.cross(d1, d2)) < 1e-8 * np.linalg.norm(d1) * np.linalg.norm(d2)
    # same spiral angle, opposite hand: curve 2 in its own frame turns the other way about its axis
    q = curves.mating_taper_curve(np.linspace(0.0, 0.3, 5), r0, g1, S, b)
    turn = np.diff(np.unwrap(np.arctan2(q[:, 1], q[:, 0]))) * np.diff(np.linalg.norm(q, axis=-1))
    assert np.all(np.sign(turn) == -np.sign(b))
    t = np.array([0.1])
    tan = _tangent(lambda t: curves.mating_taper_curve(t, r0, g1, S, b), t)
    ang = _angle(tan, curves.mating_taper_curve(t, r0, g1, S, b))[0]
    assert np.isclose(min(ang, np.pi - ang), abs(b), atol=1e-9)
