"""Local synthesis of a hypoid pinion (Litvin's approach; Litvin and Fuentes, *Gear Geometry and Applied Theory*,
2nd ed., §9.4 and ch. 20 "Hypoid gear drives"; Litvin, Chaing, Kuan, Lundy and Tsung, "Generation and geometry of
hypoid gear-member with face-hobbed teeth of uniform depth", and NASA CR-4259 for the face-milled hypoid pinion).

The pair frame is that of ``HypoidPairKinematics`` (crossed axes, docs/conventions.md "Hypoid pair frame"). Given the
generated wheel flank, the mean contact point M is the pitch point P of the Method 1 blank: the wheel's mean point is
turned about its axis into P, where its normal is perpendicular to the relative velocity (the pitch-point relations
of the blank, tests/meshing/test_hypoid_pair.py). At M the three design parameters — the direction eta of the
contact path on the wheel, the semi-major axis a of the contact ellipse for the elastic approach delta and the
second derivative m21' of the transmission error — fix the pinion's curvature tensor by Litvin's three relations,
written here for crossed axes (the derivation of ``_relations`` with the pinion axis through c1 = (0, E, 0) instead
of the origin):

* v12 = w1 x (r - c1) - w2 x r (``HypoidPairKinematics.relative_velocity``), b = -K2 v12 - w12 x n,
* c = (w2 x n).v12 + n.(w12 x (w2 x r)) - eps2 n.(a2 x r)   (the wheel axis passes through the origin),

from d/dt (n.v12) = 0 along the motion with dv12/dt = w12 x dr/dt - (dw2/dt) x r and dn/dt = w2 x n - K2 v_r2. Then
v_r2 = -c/(t.b) t and (K1 + K2) v_r1 = b, v_r1 = v_r2 - v12 (``relative_curvature_from_path``). The pinion's cutter
and machine settings (default: point radius, blade angle, radial setting, cradle angle, ratio of roll and blank offset
E_m1) are solved so that the generated pinion flank passes through M with the normal -n_wheel and the synthesized
curvature tensor (``machine_fit.fit_settings`` in the pinion member frame, whose origin is the pinion pitch apex o1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...conventions import Member, Side
from ...design.hypoid_member import member_blank
from ...errors import DesignError, GeometryError
from ...generation import generate_flank
from ...machine.cutter import HeadCutter
from ...machine.settings import MachineSettings
from ..ellipse import GLEASON_APPROACH
from ..hypoid_kinematics import HypoidPairKinematics
from ..hypoid_pair import pitch_point
from ._relations import curvature_tensor, relative_curvature_from_path, tangent_components
from .local import te_parabola_coefficient
from .machine_fit import FREE_DEFAULT, blade_point, fit_settings
from .mean_contact import path_reference

__all__ = ["HypoidSynthesis", "hypoid_path_terms", "synthesize_hypoid_pinion", "tca_surfaces"]


def hypoid_path_terms(r, n, K2, kinematics, eps2):
    """Vectors v12, b and scalar c of Litvin's relations for crossed axes (module docstring), per unit pinion rotation.

    Parameters
    ----------
    r, n : (3,) float, mm and -
        Contact point (pair frame) and pinion outward unit normal.
    K2 : (3, 3) float, 1/mm
        Wheel curvature tensor w.r.t. the wheel's outward normal (-n).
    kinematics : HypoidPairKinematics
    eps2 : float, rad/rad^2
        d^2 phi2 / d phi1^2.

    Returns
    -------
    v12 : (3,) float, mm/rad; b : (3,) float, 1/rad; c : float, mm/rad^2
    """
    r, n = np.asarray(r, float), np.asarray(n, float)
    w1, w2 = kinematics.angular_velocity_pinion(), kinematics.angular_velocity_gear()
    w12 = w1 - w2
    a2 = kinematics.gear_axis
    v12 = kinematics.relative_velocity(r)
    b = -K2 @ v12 - np.cross(w12, n)
    c = np.cross(w2, n) @ v12 + n @ np.cross(w12, np.cross(w2, r)) - eps2 * (n @ np.cross(a2, r))
    return v12, b, float(c)


@dataclass(frozen=True, eq=False)
class HypoidSynthesis:
    """Outcome of :func:`synthesize_hypoid_pinion`; vectors in the hypoid pair frame.

    Attributes
    ----------
    pinion_cutter : HeadCutter
    pinion_settings : MachineSettings
    pinion_flank, gear_flank : ToothFlank
    kinematics : HypoidPairKinematics
    point, normal : (3,) float
        M (mm) and the pinion's outward unit normal there.
    phi1_mean, phi2_mean : float, rad
        Rotations of the pinion and wheel flanks (member frames) that bring their points of M to M.
    pinion_params : (2,) float
        (u mm, psi_c rad) of M on the pinion flank (psi_c = 0).
    relative_tensor : (3, 3) float, 1/mm
        K1 + K2 at M.
    semi_axes : (2,) float, mm
        Predicted contact-ellipse semi-axes for ``approach``.
    eta : float, rad; path_gear : (3,) float; path_speed : float, mm/rad
    m21_prime : float, 1/rad; approach : float, mm; drive_sign : int
    iterations : int; residual : float
    """

    pinion_cutter: HeadCutter
    pinion_settings: MachineSettings
    pinion_flank: object
    gear_flank: object
    kinematics: HypoidPairKinematics
    point: np.ndarray
    normal: np.ndarray
    phi1_mean: float
    phi2_mean: float
    pinion_params: np.ndarray
    relative_tensor: np.ndarray
    semi_axes: np.ndarray
    eta: float
    path_gear: np.ndarray
    path_speed: float
    m21_prime: float
    approach: float
    drive_sign: int
    iterations: int
    residual: float

    def summary(self) -> dict:
        """Plain dict for reports (the keys of the spiral bevel local synthesis' summary where they apply): lengths
        mm, angles deg, TE second derivative 1/rad, TE magnitude arcsec over half a mesh cycle each side of M."""
        c = self.pinion_cutter
        z1 = self.kinematics.z1
        return {
            "pinion_cutter": {"point_radius": c.point_radius, "blade_angle": math.degrees(c.blade_angle),
                              "point_width": c.point_width, "edge_radius": c.edge_radius, "blade": c.blade.value},
            "pinion_settings": self.pinion_settings.to_dict(degrees=True),
            "mean_point": self.point.tolist(), "mean_normal": self.normal.tolist(),
            "phi1_mean": math.degrees(self.phi1_mean), "phi2_mean": math.degrees(self.phi2_mean),
            "semi_axes": self.semi_axes.tolist(), "eta": math.degrees(self.eta), "path_speed": self.path_speed,
            "m21_prime": self.m21_prime,
            # inverse of te_parabola_coefficient: the TE drop over pi/z1 each side of M, arcsec
            "te_magnitude_arcsec": -self.m21_prime / 2 * (math.pi / z1) ** 2 / math.radians(1.0 / 3600.0),
            "approach": self.approach, "iterations": self.iterations, "residual": self.residual,
        }


def _rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def synthesize_hypoid_pinion(gear_flank, pinion_cutter, pinion_settings, blank, *, side=Side.CONCAVE, eta,
                             semi_major_axis, m21_prime=None, te_magnitude=None, approach=GLEASON_APPROACH,
                             free=FREE_DEFAULT) -> HypoidSynthesis:
    """Pinion head cutter and machine settings of a hypoid pair by local synthesis at the pitch point.

    Parameters
    ----------
    gear_flank : ToothFlank
        Generated wheel flank of the side that meshes with ``side`` (``side.mate``), e.g. from
        ``spiralbevel.meshing.hypoid_pair.hypoid_basic_flanks``.
    pinion_cutter, pinion_settings : HeadCutter, MachineSettings
        Start of the fit (e.g. the pinion's basic settings); quantities not in ``free`` keep their values.
    blank : BevelBlank
        ISO 23509 Method 1 blank (or Method 0: then the pitch point is on the pitch line).
    side : Side
        Pinion side.
    eta : float, rad
        Contact-path direction on the wheel from its profile direction (root -> top), positive toward the heel.
    semi_major_axis : float, mm
        Semi-major axis of the contact ellipse at M for ``approach``.
    m21_prime : float, 1/rad, optional
        d^2 TE / d phi1^2 at M (< 0 for a crowned pair); or ``te_magnitude`` (rad) over one mesh cycle.
    approach : float, mm
    free : tuple of str
        Six solved quantities (``machine_fit``).

    Returns
    -------
    HypoidSynthesis
    """
    side = Side(side)
    if gear_flank.member is not Member.GEAR or gear_flank.side is not side.mate:
        raise DesignError.single("gear_flank", repr(gear_flank), f"a gear {side.mate.value} flank", "-")
    if (m21_prime is None) == (te_magnitude is None):
        raise DesignError.single("m21_prime/te_magnitude", (m21_prime, te_magnitude), "exactly one of the two",
                                 "1/rad or rad")
    if not (math.isfinite(eta) and abs(eta) < 0.5 * math.pi):
        raise DesignError.single("eta", eta, "-pi/2 < value < pi/2", "rad")
    if not (math.isfinite(semi_major_axis) and semi_major_axis > 0):
        raise DesignError.single("semi_major_axis", semi_major_axis, "> 0", "mm")
    kin = HypoidPairKinematics.from_blank(blank)
    if m21_prime is None:
        m21_prime = te_parabola_coefficient(te_magnitude, kin.z1)
    _, o1, a2, o2, B2 = kin.axes()
    P = pitch_point(kin, blank)
    mp = gear_flank.mean_point()
    q2 = B2.T @ (P - o2)
    phi2 = math.atan2(q2[1], q2[0]) - math.atan2(mp.point[1], mp.point[0])
    R2 = B2 @ _rz(phi2)
    n = -(R2 @ mp.normal)
    K2 = curvature_tensor(np.array([mp.k1, mp.k2]), np.stack([R2 @ mp.e1, R2 @ mp.e2]))
    drive = 1 if n @ np.cross(kin.pinion_axis, P - kin.pinion_centre) > 0 else -1
    eps2 = -drive * float(m21_prime)
    v12, b, c = hypoid_path_terms(P, n, K2, kin, eps2)
    t_p, t_l = path_reference(P - o2, -n, a2, float(blank.delta2))
    t_path = math.cos(eta) * t_p + math.sin(eta) * t_l
    lam_min = 2.0 * approach / semi_major_axis**2
    K, v_r2, _, why = relative_curvature_from_path(n, t_path, v12, b, c, lam_min)
    if why:
        raise GeometryError.single("eta/semi_major_axis", (eta, semi_major_axis), "a realisable contact path",
                                   "rad/mm", why)
    target, target_nt = tangent_components(P - o1, n, K - K2)
    view = member_blank(blank, Member.PINION)
    cutter, settings, u, info = fit_settings(pinion_cutter, pinion_settings, view, side, target, target_nt, free)
    flank = generate_flank(cutter, settings, view, Member.PINION, side)
    p1 = blade_point(flank.generator, info["theta"]).points
    q1 = P - o1
    phi1 = math.atan2(q1[1], q1[0]) - math.atan2(p1[1], p1[0])
    lam = np.linalg.eigvalsh(K + np.outer(n, n))[:2]           # tangent-plane eigenvalues (the normal gets 1)
    lam = np.sort(lam)
    return HypoidSynthesis(
        pinion_cutter=cutter, pinion_settings=settings, pinion_flank=flank, gear_flank=gear_flank, kinematics=kin,
        point=P, normal=n, phi1_mean=float(np.angle(np.exp(1j * phi1))), phi2_mean=float(np.angle(np.exp(1j * phi2))),
        pinion_params=np.array([u, 0.0]), relative_tensor=K, semi_axes=np.sqrt(2.0 * approach / lam),
        eta=float(eta), path_gear=t_path, path_speed=float(np.linalg.norm(v_r2)), m21_prime=float(m21_prime),
        approach=float(approach), drive_sign=drive, iterations=info["iterations"], residual=info["residual"])


def tca_surfaces(synthesis: HypoidSynthesis):
    """Contact surfaces of the synthesized pair for ``solve_tca`` with ``synthesis.kinematics``: both flanks turned so
    that their points of M meet at M at zero roll; returns ``(pinion, gear, start)`` with ``start`` (5,) the TCA's
    starting guess at the mean contact."""
    from ..formate import FormateFlank
    from ..formate_surface import FormateSurface
    from ..generated_surface import GeneratedSurface

    c1 = GeneratedSurface(synthesis.pinion_flank, synthesis.phi1_mean)
    gear = FormateSurface if isinstance(synthesis.gear_flank, FormateFlank) else GeneratedSurface
    c2 = gear(synthesis.gear_flank, synthesis.phi2_mean)
    return c1, c2, np.r_[c1.reference_params, c2.reference_params, 0.0]
