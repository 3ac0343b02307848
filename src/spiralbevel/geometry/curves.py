"""Curves of log-spiral bevel gearing: spherical involutes, the c-curve, conical log spirals and pitch-cone curves.

Frame: member frame of docs/conventions.md (axis +z, apex at the origin). Sources: seed 000 Eqs. (1)-(6), (17) and
seed 002 Eqs. (25)-(35), as corrected in docs/theory/logspiral.md#printed-equations and
docs/theory/gearing.md#li-surface.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "base_cone_frame", "spherical_involute", "spherical_involute_matrix_form", "c_curve",
    "cone_angle_of_psi", "psi_of_cone_angle", "cone_spiral_angle", "conical_log_spiral",
    "taper_curve", "mating_taper_curve", "mating_parameter",
]


def base_cone_frame(varphi, delta):
    """Unit vectors t (generatrix), w, m (normal of the rolling plane), each (..., 3); docs/theory/logspiral.md, Eq.
    (S1)

    t = (sin d cos varphi, sin d sin varphi, cos d), w = (sin varphi, -cos varphi, 0),
    m = (cos d cos varphi, cos d sin varphi, -sin d); t x w = m.
    """
    varphi = np.asarray(varphi, float)
    c, s = np.cos(varphi), np.sin(varphi)
    sd, cd = np.sin(delta), np.cos(delta)
    one = np.ones_like(c)
    t = np.stack([sd * c, sd * s, cd * one], -1)
    w = np.stack([s, -c, 0.0 * c], -1)
    m = np.stack([cd * c, cd * s, -sd * one], -1)
    return t, w, m


def spherical_involute(varphi, rho0, delta):
    """Spherical involute of the base cone, seed 000 Eq. (5) (docs/theory/logspiral.md#printed-equations, item 2), (...,
    3) mm.

    Parameters
    ----------
    varphi : array_like float, rad
        Rolling angle; the involute starts at Q = rho0 t(0) (docs/theory/logspiral.md#printed-equations, item 1) for
        varphi = 0.
    rho0 : float, mm
        Sphere radius (apex distance of Q).
    delta : float, rad
        Base-cone angle.

    Notes
    -----
    psi = varphi sin(delta) (arc QT = PT); r = rho0 (cos psi t(varphi) + sin psi w(varphi)). The point lies on the
    sphere |r| = rho0 (Eq. 4) and in the rolling plane Pi(varphi) (Eq. 2), at chord 2 rho0 sin(psi/2) from
    T = rho0 t(varphi) (Eq. 3).
    """
    varphi = np.asarray(varphi, float)
    psi = varphi * np.sin(delta)
    t, w, _ = base_cone_frame(varphi, delta)
    return rho0 * (np.cos(psi)[..., None] * t + np.sin(psi)[..., None] * w)


def spherical_involute_matrix_form(varphi, rho0, delta):
    """Seed 000 Eq. (6) as corrected in docs/theory/logspiral.md#printed-equations, item 3: F(varphi) diag(cos psi, sin
    psi, cos psi) V, (..., 3) mm.

    F(a) = [[cos a, sin a, 0], [sin a, -cos a, 0], [0, 0, 1]] (a reflection-rotation, det = -1) and
    V = (rho0 sin d, rho0, rho0 cos d). Numerically identical to :func:`spherical_involute`.
    """
    varphi = np.asarray(varphi, float)
    psi = varphi * np.sin(delta)
    c, s, o, z = np.cos(varphi), np.sin(varphi), np.ones_like(varphi), np.zeros_like(varphi)
    F = np.stack([np.stack([c, s, z], -1), np.stack([s, -c, z], -1), np.stack([z, z, o], -1)], -2)
    V = np.array([rho0 * np.sin(delta), rho0, rho0 * np.cos(delta)])
    scaled = np.stack([np.cos(psi), np.sin(psi), np.cos(psi)], -1) * V
    return np.einsum("...ij,...j->...i", F, scaled)


def c_curve(phi, rho0, delta, beta):
    """The c-curve (cuspidal edge) on the base cone, seed 000 Eq. (17): c(phi) = rho(phi) t(phi), (..., 3) mm.

    It is a conical log spiral on the base cone whose angle to the generatrix is exactly beta
    (docs/theory/logspiral.md#surface (base-cone curve)).
    """
    phi = np.asarray(phi, float)
    rho = rho0 * np.exp(phi * np.sin(delta) / np.tan(beta))
    t, _, _ = base_cone_frame(phi, delta)
    return rho[..., None] * t


def cone_angle_of_psi(psi, delta):
    """Half-angle gamma of the coaxial cone holding the psi = const curves: cos gamma = cos psi cos delta, rad."""
    return np.arccos(np.cos(np.asarray(psi, float)) * np.cos(delta))


def psi_of_cone_angle(gamma, delta):
    """|psi| = acos(cos gamma / cos delta) of the flank trace on cone gamma >= delta, rad (docs/theory/logspiral.md,
    Eqs. (S10)-(S11) (#cones))."""
    return np.arccos(np.clip(np.cos(np.asarray(gamma, float)) / np.cos(delta), -1.0, 1.0))


def cone_spiral_angle(beta, delta, gamma):
    """Spiral angle of the flank trace on cone gamma: tan beta_gamma = tan beta sin gamma / sin delta, rad.

    docs/theory/logspiral.md, Eq. (S11); equals beta on the base cone (gamma = delta), signed like beta.
    """
    return np.arctan(np.tan(beta) * np.sin(np.asarray(gamma, float)) / np.sin(delta))


def conical_log_spiral(phi, psi, rho0, delta, beta):
    """The psi = const curve of the flank (tooth trace on cone gamma(psi)), (..., 3) mm.

    r(phi + psi/sin(delta), phi) of seed 000 Eq. (16); a conical log spiral with spiral angle
    :func:`cone_spiral_angle` (docs/theory/logspiral.md, Eq. (S11)).
    """
    phi = np.asarray(phi, float)
    psi = np.asarray(psi, float)
    varphi = phi + psi / np.sin(delta)
    rho = rho0 * np.exp(phi * np.sin(delta) / np.tan(beta))
    t, w, _ = base_cone_frame(varphi, delta)
    return rho[..., None] * (np.cos(psi)[..., None] * t + np.sin(psi)[..., None] * w)


def taper_curve(phi, r0, cone_angle, spiral_angle):
    """Logarithmic-spiral taper curve on a cone, seed 002 Eq. (33) corrected (docs/theory/gearing.md#li-surface (cone
    spiral)), (..., 3) mm.

    Parameters
    ----------
    phi : array_like float, rad
        Azimuth of the point about +z.
    r0 : float, mm
        Radius of the parallel circle at phi = 0 (the point (r0, 0, r0 cot alpha); slant distance r0/sin alpha).
    cone_angle : float, rad
        Cone half-angle alpha.
    spiral_angle : float, rad
        Angle beta between the curve and the generatrix (beta > 0 turns positively about +z outward: right hand).

    Notes
    -----
    r = r0 exp(phi sin(alpha) cot(beta)), point = (r cos phi, r sin phi, r cot alpha) (from tan beta = r sin alpha/r').
    """
    phi = np.asarray(phi, float)
    r = r0 * np.exp(phi * np.sin(cone_angle) / np.tan(spiral_angle))
    return np.stack([r * np.cos(phi), r * np.sin(phi), r / np.tan(cone_angle)], -1)


def mating_taper_curve(phi, r0, pitch_angle1, shaft_angle, spiral_angle):
    """Curve on pitch cone 2 mating with ``taper_curve(., r0, pitch_angle1, spiral_angle)``, in the gear member frame.

    Parameters
    ----------
    phi : array_like float, rad
        The mating curve's own azimuth parameter (measured from the gear's pitch line at azimuth pi).
    r0 : float, mm
        Parallel-circle radius of curve 1 at its phi = 0 (on the pinion pitch line, cone distance R0 = r0/sin g1).
    pitch_angle1 : float, rad
        Pitch angle gamma1 of member 1; gamma2 = shaft_angle - gamma1.
    shaft_angle : float, rad
    spiral_angle : float, rad
        Spiral angle beta of curve 1 on its pitch cone.

    Returns
    -------
    (..., 3) float, mm
        Points in the gear member frame (docs/conventions.md: axis +z, pitch line at azimuth pi at phi2 = 0).

    Notes
    -----
    docs/theory/gearing.md#li-surface (mating pitch curve) and Eq. (M9): same spiral angle, opposite hand (spiral
    parameter -beta), on pitch cone 2, phased so that its
    phi = 0 point is curve 1's phi = 0 point on the common pitch generatrix:
    point = R_z(pi) taper_curve(phi, R0 sin g2, g2, -beta). In the pair frame the gear member frame is R_y(shaft)
    (times the gear roll); rolling the pitch cones by phi1 and phi2 = -(sin g1/sin g2) phi1 keeps the two curves in
    tangent contact on the pitch line (see :func:`mating_parameter`).
    """
    g2 = shaft_angle - pitch_angle1
    R0 = r0 / np.sin(pitch_angle1)
    p = taper_curve(phi, R0 * np.sin(g2), g2, -spiral_angle)
    return p * np.array([-1.0, -1.0, 1.0])


def mating_parameter(phi1, pitch_angle1, shaft_angle):
    """Parameter of the mating curve at the cone distance of curve 1's point phi1: phi2 = -phi1 sin g1 / sin g2."""
    return -np.asarray(phi1, float) * np.sin(pitch_angle1) / np.sin(shaft_angle - pitch_angle1)
