"""Design of an exactly conjugate pair of logarithmic-spiral bevel gears (seed 000 surface, docs/theory/logspiral.md,
Eq. (S2) and docs/theory/gearing.md, Eq. (M8)).

Recipe (docs/theory/logspiral.md, Eq. (S12), verified): from z1, z2, the shaft angle, the normal pressure angle alpha_n
and
the mean spiral angle beta_m on the pitch cones,

    tan g1 = sin S / (z2/z1 + cos S),  g2 = S - g1
    tan alpha_t = tan alpha_n / cos beta_m
    sin delta_i = sin g_i cos alpha_t               (so sin delta1 : sin delta2 = z1 : z2, docs/theory/gearing.md, Eq.
    (M8))
    sin beta_plane = cos alpha_n sin beta_m          (spiral parameter of Eq. (16); pinion beta1 = hand * beta_plane,
                                                      gear beta2 = -beta1)
    psi_pitch,i = acos(cos g_i / cos delta_i)

Each flank is a :class:`~spiralbevel.LogSpiralFlank` with rho0 = the member's mean cone distance (so phi = 0 is the
mean sphere), turned about +z by ``rotation``; its domain is the rectangle in (psi, phi) cut by the toe/heel spheres
and the root/face cones (docs/theory/logspiral.md, Eq. (S10)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spiralbevel._core.rotations import rot_axis, rot_y, rot_z
from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.design import _logspiral_checks as chk
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.geometry.curves import psi_of_cone_angle
from spiralbevel.geometry.domain import ParallelogramDomain
from spiralbevel.geometry.logspiral import FlankGeometry, LogSpiralFlank

__all__ = ["BlankBoundaries", "DesignedFlank", "LogSpiralMemberDesign", "LogSpiralPair", "design_logspiral_pair",
           "pair_recipe"]


@dataclass(frozen=True)
class BlankBoundaries:
    """Boundaries of one member's toothed region, as seen by the log-spiral flank.

    Attributes
    ----------
    inner_cone_distance, outer_cone_distance : float, mm
        Radii R_i < R_e of the toe and heel spheres about the apex (the blank is taken as bounded by spheres; a real
        blank with front and back cones gives curved domain sides, docs/theory/logspiral.md, Eq. (S10)).
    root_angle, face_angle : float, rad
        Half-angles of the root and face cones. **Approximation:** both are treated as cones coaxial with the member
        and with their apex at the pitch apex O (ISO 23509 root/face apexes are shifted; the lead's adapter decides how
        to map them). root_angle < pitch angle < face_angle < pi/2 and root_angle > base-cone angle are required.
    """

    inner_cone_distance: float
    outer_cone_distance: float
    root_angle: float
    face_angle: float

    @property
    def mean_cone_distance(self) -> float:
        """R_m = (R_i + R_e) / 2, mm."""
        return 0.5 * (self.inner_cone_distance + self.outer_cone_distance)


@dataclass(frozen=True)
class DesignedFlank:
    """One flank of one member, placed in its member frame.

    Attributes
    ----------
    member : Member
    side : Side
    surface : LogSpiralFlank
        The unrotated surface (rho0 = mean cone distance).
    domain : ParallelogramDomain
        (psi, phi) rectangle; psi signed (positive on the convex flank of a right-hand member).
    rotation : float, rad
        Angle about +z applied to ``surface`` to place it in the member frame.
    """

    member: Member
    side: Side
    surface: LogSpiralFlank
    domain: ParallelogramDomain
    rotation: float

    def point(self, varphi, phi):
        """Points in the member frame, (..., 3) mm."""
        return self.surface.point(varphi, phi) @ rot_z(self.rotation).T

    def evaluate(self, varphi, phi) -> FlankGeometry:
        """Closed-form geometry in the member frame (see :class:`~spiralbevel.geometry.logspiral.FlankGeometry`)."""
        return self.surface.evaluate(varphi, phi).rotated(self.rotation)

    def grid(self, n_phi: int = 11, n_psi: int = 7) -> FlankGeometry:
        """Geometry on an (n_phi, n_psi) grid of the domain: rows from toe to heel, columns from root to top (|psi|
        increasing), for either hand and side — the grid convention of every flank in spiralbevel."""
        varphi, phi = self.domain.grid(n_phi, n_psi)
        if self.surface.spiral_angle < 0:  # rho decreases with phi: phi_min is the heel
            varphi, phi = varphi[::-1], phi[::-1]
        if self.domain.psi_max <= 0:  # psi < 0: psi_min is the top
            varphi, phi = varphi[:, ::-1], phi[:, ::-1]
        return self.evaluate(varphi, phi)

    def pitch_parameters(self, psi_pitch: float, cone_distance: float):
        """(varphi, phi) of the flank point on the pitch cone (|psi| = psi_pitch) at ``cone_distance`` (mm)."""
        phi = float(self.surface.phi_of_rho(cone_distance))
        psi = self.surface.psi_sign(self.side) * psi_pitch
        return float(self.surface.varphi_of(psi, phi)), phi


@dataclass(frozen=True)
class LogSpiralMemberDesign:
    """Pinion or gear of a :class:`LogSpiralPair` (angles in rad, lengths in mm).

    Attributes
    ----------
    member : Member
    hand : Hand
    teeth : int
    pitch_angle : float, rad
    base_cone_angle : float, rad
        delta_i of the recipe.
    spiral_parameter : float, rad
        Signed beta of seed 000 Eq. (16) for this member (beta_plane times the hand sign).
    psi_pitch : float, rad
        |psi| of the flank trace on the pitch cone.
    mean_cone_distance : float, mm
    mean_normal_thickness : float, mm
        Mean normal circular tooth thickness on the pitch cone (transverse arc times cos beta_m).
    boundaries : BlankBoundaries
    convex, concave : DesignedFlank
    """

    member: Member
    hand: Hand
    teeth: int
    pitch_angle: float
    base_cone_angle: float
    spiral_parameter: float
    psi_pitch: float
    mean_cone_distance: float
    mean_normal_thickness: float
    boundaries: BlankBoundaries
    convex: DesignedFlank
    concave: DesignedFlank

    def flank(self, side: Side) -> DesignedFlank:
        """The convex or concave :class:`DesignedFlank` of this member."""
        return self.convex if Side(side) is Side.CONVEX else self.concave


@dataclass(frozen=True)
class LogSpiralPair:
    """A designed log-spiral bevel pair; flanks are in member frames, the pair frame is that of docs/conventions.md.

    Attributes
    ----------
    shaft_angle, normal_pressure_angle, spiral_angle : float, rad
        Inputs (spiral_angle = beta_m on the pitch cones, unsigned).
    transverse_pressure_angle : float, rad
        alpha_t = atan(tan alpha_n / cos beta_m).
    plane_spiral_angle : float, rad
        beta_plane = asin(cos alpha_n sin beta_m), unsigned.
    pinion, gear : LogSpiralMemberDesign
    """

    shaft_angle: float
    normal_pressure_angle: float
    spiral_angle: float
    transverse_pressure_angle: float
    plane_spiral_angle: float
    pinion: LogSpiralMemberDesign
    gear: LogSpiralMemberDesign

    @property
    def ratio(self) -> float:
        """z2 / z1."""
        return self.gear.teeth / self.pinion.teeth

    def member(self, member: Member) -> LogSpiralMemberDesign:
        """The pinion or gear design."""
        return self.pinion if Member(member) is Member.PINION else self.gear

    def flank(self, member: Member, side: Side) -> DesignedFlank:
        """The placed flank of ``member`` on ``side``."""
        return self.member(member).flank(side)

    def mean_parameters(self, member: Member, side: Side):
        """(varphi, phi) in rad of the mean point: pitch cone, mean cone distance (phi = 0 by construction)."""
        m = self.member(member)
        return m.flank(side).pitch_parameters(m.psi_pitch, m.mean_cone_distance)

    def mean_point(self, member: Member, side: Side) -> FlankGeometry:
        """Closed-form geometry (member frame) at the mean point of the flank."""
        return self.flank(member, side).evaluate(*self.mean_parameters(member, side))

    def to_pair_frame(self, member: Member, vectors, pinion_roll: float = 0.0):
        """Map member-frame vectors (..., 3) to the pair frame (docs/conventions.md) at pinion roll angle phi1 (rad).

        Pinion: R_z(phi1) r. Gear: R(a2, phi2) R_y(S) r with a2 = (sin S, 0, cos S), phi2 = -(z1/z2) phi1.
        Directions (normals) map with the same rotation.
        """
        if Member(member) is Member.PINION:
            R = rot_z(pinion_roll)
        else:
            S = self.shaft_angle
            phi2 = -pinion_roll / self.ratio
            R = rot_axis([np.sin(S), 0.0, np.cos(S)], phi2) @ rot_y(S)
        return np.asarray(vectors, float) @ R.T


def _azimuth(p):
    return np.arctan2(p[..., 1], p[..., 0])


def _member(member, z, gamma, delta, beta, psi_p, bounds, angular_thickness, centre, beta_m):
    """Build one member: flanks, domains and rotations such that the tooth is centred at azimuth ``centre``."""
    name = f"boundaries[{member.value}]"
    chk.check_root_outside_base(name, bounds.root_angle, delta)
    Rm = bounds.mean_cone_distance
    surface = LogSpiralFlank(Rm, delta, beta)
    psi_lo, psi_hi = psi_of_cone_angle(bounds.root_angle, delta), psi_of_cone_angle(bounds.face_angle, delta)
    phis = sorted(float(surface.phi_of_rho(R)) for R in (bounds.inner_cone_distance, bounds.outer_cone_distance))
    raw, sigma, doms = {}, {}, {}
    for side in Side:
        s = surface.psi_sign(side)
        doms[side] = ParallelogramDomain(phis[0], phis[1], float(min(s * psi_lo, s * psi_hi)),
                                         float(max(s * psi_lo, s * psi_hi)),
                                         delta)
        chk.check_outward_rule(f"{member.value} {side.value} flank", (doms[side].psi_min, doms[side].psi_max), beta)
        g = surface.evaluate(surface.varphi_of(s * psi_p, 0.0), 0.0)
        raw[side] = _azimuth(g.point)
        e_theta = np.array([-np.sin(raw[side]), np.cos(raw[side]), 0.0])
        sigma[side] = np.sign(g.normal @ e_theta)  # +1: the flank bounds the tooth on its +azimuth edge
    if sigma[Side.CONVEX] != -sigma[Side.CONCAVE]:  # pragma: no cover - guards Eq. (S9) (#flank-types)
        raise GeometryError(f"{member.value}: convex and concave flanks face the same way; cannot bound a tooth")
    rotation = {side: float(centre + sigma[side] * angular_thickness / 2 - raw[side]) for side in Side}
    flanks = {side: DesignedFlank(member, side, surface, doms[side], rotation[side]) for side in Side}
    _check_lands(member, z, surface, flanks, sigma, psi_lo, psi_hi)
    thickness = angular_thickness * Rm * np.sin(gamma) * np.cos(beta_m)
    hand = Hand.RIGHT if beta > 0 else Hand.LEFT
    return LogSpiralMemberDesign(member, hand, z, gamma, delta, beta, psi_p, Rm, float(thickness), bounds,
                                 flanks[Side.CONVEX], flanks[Side.CONCAVE])


def _check_lands(member, z, surface, flanks, sigma, psi_lo, psi_hi):
    """Top land (face cone) and bottom space (root cone) must have positive angular width (constant along the face)."""
    plus = Side.CONVEX if sigma[Side.CONVEX] > 0 else Side.CONCAVE
    minus = plus.mate

    def az(side, psi_abs):
        f = flanks[side]
        psi = f.surface.psi_sign(side) * psi_abs
        return _azimuth(f.point(f.surface.varphi_of(psi, 0.0), 0.0))

    top = np.angle(np.exp(1j * (az(plus, psi_hi) - az(minus, psi_hi))))
    space = np.angle(np.exp(1j * (az(minus, psi_lo) + 2 * np.pi / z - az(plus, psi_lo))))
    if not top > 0:
        raise GeometryError(f"{member.value}: the tooth is pointed below the face cone (top land angle "
                            f"{np.degrees(top):.4f} deg): lower the face angle or the thickness")
    if not space > 0:
        raise GeometryError(f"{member.value}: the tooth space closes above the root cone (space angle "
                            f"{np.degrees(space):.4f} deg): raise the root angle or lower the thickness")


def pair_recipe(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle):
    """The verified design recipe of docs/theory/logspiral.md, Eq. (S12) for a log-spiral pair with line contact.

    Parameters
    ----------
    z1, z2 : int
    shaft_angle, normal_pressure_angle, spiral_angle : float, rad
        Sigma, alpha_n and the mean spiral angle beta_m on the pitch cones.

    Returns
    -------
    (g1, g2, alpha_t, delta1, delta2, beta_plane) : floats, rad
        Pitch angles (tan g1 = sin S / (z2/z1 + cos S)), transverse pressure angle (tan a_t = tan a_n / cos b_m),
        base cones (sin d_i = sin g_i cos a_t, so sin d1 : sin d2 = z1 : z2) and the spiral angle in the base-cone
        tangent plane (sin beta = cos a_n sin b_m), unsigned.
    """
    S = float(shaft_angle)
    g1 = float(np.arctan2(np.sin(S), z2 / z1 + np.cos(S)))
    g2 = S - g1
    alpha_t = float(np.arctan(np.tan(normal_pressure_angle) / np.cos(spiral_angle)))
    d1 = float(np.arcsin(np.sin(g1) * np.cos(alpha_t)))
    d2 = float(np.arcsin(np.sin(g2) * np.cos(alpha_t)))
    beta_plane = float(np.arcsin(np.cos(normal_pressure_angle) * np.sin(spiral_angle)))
    return g1, g2, alpha_t, d1, d2, beta_plane


def design_logspiral_pair(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle, pinion_hand, boundaries,
                          thickness=None) -> LogSpiralPair:
    """Design a conjugate pair of log-spiral bevel gears (line contact, zero backlash).

    Parameters
    ----------
    z1, z2 : int
        Numbers of teeth of pinion and gear, >= 2.
    shaft_angle : float, rad
        Angle S between the axes, 0 < S < pi (gear pitch angle must stay below pi/2).
    normal_pressure_angle : float, rad
        alpha_n on the pitch cones, 0 < alpha_n < pi/4.
    spiral_angle : float, rad
        Mean spiral angle beta_m on the pitch cones (unsigned, 0 < beta_m < pi/2). For log-spiral flanks it is the same
        at every cone distance.
    pinion_hand : Hand or {"RH", "LH"}
        Hand of the pinion; the gear has the opposite hand.
    boundaries : mapping Member -> BlankBoundaries, or (pinion, gear) pair
        Toe/heel spheres and root/face cones of each member (see :class:`BlankBoundaries` for the approximation).
    thickness : float, mm, optional
        Mean normal circular tooth thickness of the pinion on its pitch cone at its mean cone distance; default half
        the mean normal circular pitch. The gear gets the rest of the pitch (zero backlash).

    Returns
    -------
    LogSpiralPair

    Raises
    ------
    DesignError
        Bad scalar input (teeth, angles out of range, thickness outside (0, pitch)).
    GeometryError
        Root cone inside the base cone, pointed teeth, closed tooth space, profile beyond the generatrix.

    Notes
    -----
    Placement (docs/conventions.md, pair frame at phi1 = 0): the pinion tooth is centred on azimuth 0 (the pinion pitch
    line), the gear tooth *space* is centred on azimuth pi (the gear pitch line), so the gear tooth returned is centred
    at pi + pi/z2. Thicknesses are measured as transverse arcs of the pitch circle of the mean sphere times cos beta_m.
    Because both flank traces on any coaxial cone are log spirals with the same spiral angle, the angular tooth
    thickness is the same at every cone distance.
    """
    z1, z2, S, alpha_n, beta_m, hand = chk.check_inputs(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle,
                                                        pinion_hand)
    if isinstance(boundaries, dict):
        try:
            b1, b2 = boundaries[Member.PINION], boundaries[Member.GEAR]
        except KeyError as err:
            raise DesignError.single("boundaries", sorted(map(str, boundaries)), "keys Member.PINION and Member.GEAR",
                                     "-") from err
    else:
        try:
            b1, b2 = boundaries
        except (TypeError, ValueError) as err:
            raise DesignError.single("boundaries", boundaries, "a (pinion, gear) pair of BlankBoundaries", "-") from err
    for name, b in (("boundaries[pinion]", b1), ("boundaries[gear]", b2)):
        if not isinstance(b, BlankBoundaries):
            raise DesignError.single(name, b, "a BlankBoundaries instance", "-")
    g1, g2, alpha_t, d1, d2, beta_plane = pair_recipe(z1, z2, S, alpha_n, beta_m)
    chk.check_boundaries("boundaries[pinion]", b1, g1)
    chk.check_boundaries("boundaries[gear]", b2, g2)
    psi1 = float(psi_of_cone_angle(g1, d1))
    psi2 = float(psi_of_cone_angle(g2, d2))
    pitch_angle1 = 2 * np.pi / z1
    pn = pitch_angle1 * b1.mean_cone_distance * np.sin(g1) * np.cos(beta_m)
    if thickness is None:
        s1 = pn / 2
    else:
        try:
            s1 = float(thickness)
        except (TypeError, ValueError) as err:
            raise DesignError.single("thickness", thickness, f"0 < value < {pn:.6g}", "mm", "not a number") from err
        if not (0 < s1 < pn):
            raise DesignError.single("thickness", thickness, f"0 < value < mean normal circular pitch {pn:.6g}", "mm")
    b1_sign = hand.sign
    dtheta1 = pitch_angle1 * s1 / pn
    dtheta2 = (2 * np.pi - z1 * dtheta1) / z2
    pinion = _member(Member.PINION, z1, g1, d1, b1_sign * beta_plane, psi1, b1, dtheta1, 0.0, beta_m)
    gear = _member(Member.GEAR, z2, g2, d2, -b1_sign * beta_plane, psi2, b2, dtheta2, np.pi + np.pi / z2, beta_m)
    return LogSpiralPair(S, alpha_n, beta_m, alpha_t, beta_plane, pinion, gear)
