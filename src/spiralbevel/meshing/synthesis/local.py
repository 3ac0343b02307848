"""Local synthesis of the pinion machine settings (seed 001 §4.3 step 1; Litvin & Fuentes, *Gear Geometry and
Applied Theory*, 2nd ed., §9.4 and Ch. 21 "Spiral bevel gears"; Litvin & Zhang, NASA CR-4342, 1991).

Given the gear (cutter and machine settings, e.g. seed 001 Table 4) and three design parameters at the mean contact
point M — the direction eta of the contact path on the gear, the semi-major axis a of the contact ellipse for the
elastic approach delta, and the second derivative m21' of the transmission error (a parabolic TE) — find the pinion
head cutter and machine settings:

1. M: the gear's reference point in the pair frame, where the common normal meets the pitch line (``mean_contact``);
2. the pinion's principal curvatures and directions at M from the gear's and the three design parameters (Litvin's
   three relations, ``_relations``);
3. pinion cutter and settings by Newton: the generated pinion flank passes through M with the normal -n_gear and has
   exactly the synthesized curvature tensor there (``machine_fit``).

Signs: TE as in :class:`~spiralbevel.meshing.tca_result.TCAResult` (positive = gear ahead of the nominal motion in its
driven direction), so a crowned pair has m21' < 0; a TE magnitude d (rad, > 0) over one mesh cycle 2 pi/z1 centred on
M means TE = -d (x / (pi/z1))^2, m21' = -2 d (z1/pi)^2. eta: see :func:`~.mean_contact.path_reference` (angle from the
gear's profile direction, root -> top, positive toward the heel).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ...conventions import Member, Side
from ...errors import DesignError, GeometryError, Problem
from ...generation import generate_flank
from ...machine import Blade, HeadCutter, MachineSettings
from ..ellipse import GLEASON_APPROACH
from ._relations import path_speed_terms, relative_curvature_from_path, tangent_components
from .machine_fit import FREE_DEFAULT, blade_point, fit_settings
from .mean_contact import MeanContact, mean_contact, path_reference

__all__ = ["SynthesisResult", "synthesize_pinion", "te_parabola_coefficient"]

_ARCSEC = math.pi / (180.0 * 3600.0)


def te_parabola_coefficient(te_magnitude: float, z1: int) -> float:
    """m21' = d^2 TE / d phi1^2 (1/rad) of a parabolic TE that drops by ``te_magnitude`` (rad) over half a mesh
    cycle (pi/z1) on each side of the mean point: -2 te_magnitude (z1/pi)^2 (seed 001 Eq. (2), a2 = m21'/2)."""
    return -2.0 * float(te_magnitude) * (z1 / math.pi) ** 2


def _principal(K, n):
    """Principal curvatures (descending) and unit directions (2, 3) of a tangent-plane tensor K at normal n."""
    a = np.cross(n, [1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.cross(n, [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(n, a)
    B = np.stack([a, b])
    lam, v = np.linalg.eigh(B @ K @ B.T)
    d = (v.T @ B)[::-1]
    d[1] = np.cross(n, d[0])
    return lam[::-1], d


@dataclass(frozen=True, eq=False)
class SynthesisResult:
    """Outcome of :func:`synthesize_pinion`. Vectors are in the fixed pair frame unless named ``_member``.

    Attributes
    ----------
    pinion_cutter : HeadCutter
    pinion_settings : MachineSettings
    pinion_flank, gear_flank : ToothFlank
    mean : MeanContact
        M, the common normal (pinion outward), phi20, the gear's principal data.
    phi1_mean, phi2_mean : float, rad
        phi10, phi20 of seed 001 Eq. (1).
    pinion_params : (2,) float
        (u mm, psi_c rad) of M on the generated pinion flank (psi_c = 0 by construction).
    pinion_k : (2,) float, 1/mm
        Synthesized pinion principal curvatures (descending, convex = positive); ``pinion_dirs`` (2, 3) directions.
    gear_k : (2,) float, 1/mm
        Gear principal curvatures (descending); ``gear_dirs`` (2, 3).
    relative_tensor : (3, 3) float, 1/mm
        K1 + K2, the relative curvature tensor at M.
    semi_axes : (2,) float, mm
        Predicted contact-ellipse semi-axes (a, b) for ``approach``; ``ellipse_dirs`` (2, 3) major, minor axis.
    eta : float, rad
        Design path direction on the gear; ``path_gear`` (3,) its unit tangent, ``path_pinion`` (3,) the path tangent
        on the pinion; ``path_speed`` (mm/rad) the speed of the contact point over the gear per unit pinion rotation.
    m21_prime : float, 1/rad
        Design d^2 TE / d phi1^2.
    approach : float, mm
    free : tuple of str
        The six solved machine quantities (plus the blade parameter u).
    iterations : int; residual : float
        Newton iterations and final scaled residual of the settings fit.
    """

    pinion_cutter: HeadCutter
    pinion_settings: MachineSettings
    pinion_flank: object
    gear_flank: object
    mean: MeanContact
    phi1_mean: float
    phi2_mean: float
    pinion_params: np.ndarray
    pinion_k: np.ndarray
    pinion_dirs: np.ndarray
    gear_k: np.ndarray
    gear_dirs: np.ndarray
    relative_tensor: np.ndarray
    semi_axes: np.ndarray
    ellipse_dirs: np.ndarray
    eta: float
    path_gear: np.ndarray
    path_pinion: np.ndarray
    path_speed: float
    m21_prime: float
    approach: float
    free: tuple
    iterations: int
    residual: float

    @property
    def ellipse_angle(self) -> float:
        """Angle of the major axis from the gear's profile direction (same reference and sign as eta), rad, in
        (-pi/2, pi/2]."""
        t_p, t_l = self._gear_reference()
        d = self.ellipse_dirs[0]
        ang = math.atan2(float(d @ t_l), float(d @ t_p))
        return float((ang + 0.5 * math.pi) % math.pi - 0.5 * math.pi)

    @property
    def eta_from_principal(self) -> float:
        """Angle of the path tangent from the gear's first principal direction (Litvin's eta_2 from e_s), rad."""
        d = self.gear_dirs[0]
        ang = math.atan2(float(np.cross(d, self.path_gear) @ (-self.mean.normal)), float(d @ self.path_gear))
        return float((ang + 0.5 * math.pi) % math.pi - 0.5 * math.pi)

    def _gear_reference(self):
        kin = self.mean.kinematics
        return path_reference(self.mean.point, -self.mean.normal, kin.gear_axis, kin.pitch_angle_gear)

    def summary(self) -> dict:
        """Plain dict for reports: lengths mm, angles deg, curvatures 1/mm, TE second derivative 1/rad."""
        s = self.pinion_settings.to_dict(degrees=True)
        c = self.pinion_cutter
        return {
            "pinion_cutter": {"point_radius": c.point_radius, "blade_angle": math.degrees(c.blade_angle),
                              "point_width": c.point_width, "edge_radius": c.edge_radius, "blade": c.blade.value},
            "pinion_settings": s,
            "free": list(self.free),
            "mean_point": self.mean.point.tolist(),
            "phi1_mean": math.degrees(self.phi1_mean), "phi2_mean": math.degrees(self.phi2_mean),
            "pinion_k": self.pinion_k.tolist(), "gear_k": self.gear_k.tolist(),
            "semi_axes": self.semi_axes.tolist(), "ellipse_angle": math.degrees(self.ellipse_angle),
            "eta": math.degrees(self.eta), "eta_from_principal": math.degrees(self.eta_from_principal),
            "path_speed": self.path_speed, "m21_prime": self.m21_prime,
            "te_magnitude_arcsec": -self.m21_prime / 2 * (math.pi / self.mean.kinematics.z1) ** 2 / _ARCSEC,
            "approach": self.approach, "iterations": self.iterations, "residual": self.residual,
        }


def _validate(eta, semi_major_axis, m21_prime, te_magnitude, approach, depth):
    p = []

    def real(v):
        return isinstance(v, numbers.Real) and not isinstance(v, bool) and math.isfinite(v)

    if not (real(eta) and abs(eta) < 0.5 * math.pi):
        p.append(Problem("eta", eta, "-pi/2 < value < pi/2", "rad"))
    if not (real(semi_major_axis) and semi_major_axis > 0):
        p.append(Problem("semi_major_axis", semi_major_axis, "> 0", "mm"))
    if (m21_prime is None) == (te_magnitude is None):
        p.append(Problem("m21_prime/te_magnitude", (m21_prime, te_magnitude), "exactly one of the two", "1/rad or rad"))
    elif m21_prime is not None and not real(m21_prime):
        p.append(Problem("m21_prime", m21_prime, "finite", "1/rad"))
    elif te_magnitude is not None and not (real(te_magnitude) and te_magnitude >= 0):
        p.append(Problem("te_magnitude", te_magnitude, ">= 0", "rad"))
    if not (real(approach) and approach > 0):
        p.append(Problem("approach", approach, "> 0", "mm"))
    if not real(depth):
        p.append(Problem("depth", depth, "finite", "mm"))
    if p:
        raise DesignError(p)


def synthesize_pinion(gear_cutter, gear_settings, blank, *, side=Side.CONCAVE, eta, semi_major_axis,
                      m21_prime=None, te_magnitude=None, approach=GLEASON_APPROACH, pinion_cutter_hint=None,
                      free=FREE_DEFAULT, depth=0.0, pinion_settings_hint=None) -> SynthesisResult:
    """Pinion head cutter and machine settings by local synthesis at the mean contact point.

    Parameters
    ----------
    gear_cutter : HeadCutter
        Gear cutter; its blade cuts the gear side that meshes with ``side`` (``side.mate``).
    gear_settings : MachineSettings
        Gear machine settings.
    blank : ISO 23509 blank (``z1, z2, Sigma``, ``hand1/2`` and the cone data of both members).
    side : Side
        Pinion side to synthesize (CONCAVE: drive side of seed 001, meshing with the gear convex side).
    eta : float, rad
        Direction of the contact path on the gear at M, from the gear's profile direction (root -> top), positive
        toward the heel.
    semi_major_axis : float, mm
        Semi-major axis a of the contact ellipse at M for the elastic approach ``approach``.
    m21_prime : float, 1/rad, optional
        d^2 TE / d phi1^2 at M (TE sign of ``TCAResult``; < 0 for a crowned pair). Give this or ``te_magnitude``.
    te_magnitude : float, rad, optional
        Depth of a parabolic TE over one mesh cycle centred on M (seed 001 Table 2: 3 arcsec).
    approach : float, mm
        Elastic approach delta (Gleason 0.00635 mm, seed 001 §4.3.2).
    pinion_cutter_hint : HeadCutter, optional
        Starting cutter (its point width and edge radius are kept; and its blade angle when it is not free). Default:
        the gear cutter's nominal radius, blade angle, point width and edge radius on the blade for ``side``.
    free : tuple of str
        Six solved quantities (``FREE_OFFSET`` = default, ``FREE_MODIFIED_ROLL``, ``FREE_FIXED_BLADE`` or any six names,
        see ``machine_fit.fit_settings``).
        Everything else starts from ``MachineSettings.from_blank`` (gamma_m1 = pinion root angle, apexes at the
        machine centre: E_m1 = X_B1 = X_D1 = 0) and stays fixed.
    depth : float, mm
        Depth of M below the gear's pitch line at the mean cone distance.
    pinion_settings_hint : MachineSettings, optional
        Starting settings in place of ``MachineSettings.from_blank`` (e.g. the pinion's solved basic settings, whose
        root cone lies on the cradle plane: the quantities not in ``free`` keep it there).

    Returns
    -------
    SynthesisResult
    """
    _validate(eta, semi_major_axis, m21_prime, te_magnitude, approach, depth)
    try:
        side = Side(side)
    except ValueError as err:
        raise DesignError.single("side", side, "'convex' or 'concave'", "-") from err
    gear_flank = generate_flank(gear_cutter, gear_settings, blank, Member.GEAR, side.mate)
    mc = mean_contact(gear_flank, blank, depth)
    kin = mc.kinematics
    if m21_prime is None:
        m21_prime = te_parabola_coefficient(te_magnitude, kin.z1)
    # relations 1-3 (see _relations): TE = D [-(phi2 - phi20) - (z1/z2) x]  =>  d^2 phi2 / d phi1^2 = -D m21'
    eps2 = -mc.drive_sign * float(m21_prime)
    v12, b, c = path_speed_terms(mc.point, mc.normal, mc.gear_tensor, kin.angular_velocity_pinion(),
                                 kin.angular_velocity_gear(), kin.gear_axis, eps2)
    t_p, t_l = path_reference(mc.point, -mc.normal, kin.gear_axis, kin.pitch_angle_gear)
    t_path = math.cos(eta) * t_p + math.sin(eta) * t_l
    lam_min = 2.0 * approach / semi_major_axis**2
    K, v_r2, v_r1, why = relative_curvature_from_path(mc.normal, t_path, v12, b, c, lam_min)
    if why:
        raise GeometryError.single("eta/semi_major_axis", (eta, semi_major_axis), "a realisable contact path", "rad/mm",
                                   why)
    K1 = K - mc.gear_tensor
    target, target_nt = tangent_components(mc.point, mc.normal, K1)
    # start: the hint or a cutter like the gear's, basic settings from the blank
    blade = Blade.for_side(side)
    if pinion_cutter_hint is None:
        pinion_cutter_hint = HeadCutter(gear_cutter.nominal_radius + blade.sign * 0.5 * gear_cutter.point_width,
                                        gear_cutter.blade_angle, gear_cutter.point_width, gear_cutter.edge_radius,
                                        blade)
    elif pinion_cutter_hint.blade is not blade:
        raise DesignError.single("pinion_cutter_hint.blade", pinion_cutter_hint.blade.value, blade.value, "-",
                                 f"the pinion {side.value} side is cut by the {blade.value} blade")
    settings0 = (MachineSettings.from_blank(blank, Member.PINION, side, pinion_cutter_hint)
                 if pinion_settings_hint is None else pinion_settings_hint)
    cutter, settings, u, info = fit_settings(pinion_cutter_hint, settings0, blank, side, target, target_nt, free)
    pinion_flank = generate_flank(cutter, settings, blank, Member.PINION, side)
    p1 = blade_point(pinion_flank.generator, info["theta"]).points
    phi1 = math.atan2(mc.point[1], mc.point[0]) - math.atan2(p1[1], p1[0])
    phi1 = float(np.angle(np.exp(1j * phi1)))
    pk, pd = _principal(K1, mc.normal)
    gk, gd = _principal(mc.gear_tensor, -mc.normal)
    lam, ed = _principal(K, mc.normal)
    axes = np.sqrt(2.0 * approach / lam[::-1])
    return SynthesisResult(
        pinion_cutter=cutter, pinion_settings=settings, pinion_flank=pinion_flank, gear_flank=gear_flank, mean=mc,
        phi1_mean=phi1, phi2_mean=mc.phi2, pinion_params=np.array([u, 0.0]), pinion_k=pk, pinion_dirs=pd,
        gear_k=gk, gear_dirs=gd, relative_tensor=K, semi_axes=axes, ellipse_dirs=ed[::-1], eta=float(eta),
        path_gear=t_path, path_pinion=v_r1 / np.linalg.norm(v_r1), path_speed=float(np.linalg.norm(v_r2)),
        m21_prime=float(m21_prime), approach=float(approach), free=tuple(free), iterations=info["iterations"],
        residual=info["residual"])
