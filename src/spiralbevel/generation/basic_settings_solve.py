"""Basic machine settings that generate the design flank: Newton on the exact generation kernel.

For one member side, the settings place the blank's root cone on the cradle plane (the plane of the blade tips), so the
generated root line lies on the root cone along the whole face width, and two unknowns are solved by Newton's method
with a finite-difference Jacobian of the *generated* flank (``generate_flank`` + ``ToothFlank.mean_point``, i.e. the
equation of meshing and ``locate``): the blade angle alpha_h and the machine spiral angle beta' (direction of the cutter
centre from the mean root point) such that, at the mean pitch point, the normal pressure angle equals the design value
(alpha_nD or alpha_nC of ISO 23509) and the spiral angle equals beta_m. With a given (fixed) cutter only beta' is
solved.

Settings of the family (``spiralbevel.machine.basic_settings``; docs/conventions.md, "Basic settings that hit the
design"):

* machine root angle gamma_m = delta_f; blank offset E_m = 0; sliding base X_B = 0;
* machine centre to back X_D = -z_R, z_R the axial position of the root-cone apex in the member frame, so that the
  root-cone apex sits at the machine centre and the root cone touches the cradle plane along the root line;
* cutter centre at (A_f - r_c sin beta', r_c cos beta') in the cradle plane (along, across the root line), with
  A_f the distance from the root-cone apex to the mean root point: S_r = |.|, q its angle from the root line;
* ratio of roll m_ic = cos(eps) / sin(phi_w): the instantaneous axis of the cradle and work rotations (through the
  machine centre) passes through the mean pitch point; phi_w is that point's angle from the work axis and eps its
  elevation above the cradle plane, seen from the root-cone apex (cos theta_f / sin delta when the apexes coincide).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import ConvergenceError, GeometryError
from spiralbevel.generation.flank import generate_flank
from spiralbevel.machine.basic_settings import basic_settings
from spiralbevel.machine.cutter import HeadCutter
from spiralbevel.machine.default_cutter import design_pressure_angle

__all__ = ["FlankFit", "flank_fit", "solve_basic_settings", "root_deviation"]

#: Newton tolerance on the mean-point angles, rad (1e-7 rad = 2e-2 arcsec, far below the 0.05 deg acceptance)
ANGLE_TOL = 1e-7
_MAX_ITER = 12


@dataclass(frozen=True)
class FlankFit:
    """Design against achieved values of one generated flank (angles rad, lengths mm).

    ``root_deviation`` holds the height of the generated root line above the blank's root cone at the toe, the mean
    cone distance and the heel (negative: below the root cone, i.e. too deep; ``None`` where no root point is
    enveloped, see :func:`root_deviation`).
    """

    pressure_angle_design: float
    pressure_angle: float
    spiral_angle_design: float
    spiral_angle: float
    root_deviation: tuple
    iterations: int

    def to_dict(self) -> dict:
        """Report section (degrees, mm)."""
        return {"pressure_angle_design_deg": math.degrees(self.pressure_angle_design),
                "pressure_angle_deg": math.degrees(self.pressure_angle),
                "spiral_angle_design_deg": math.degrees(self.spiral_angle_design),
                "spiral_angle_deg": math.degrees(self.spiral_angle),
                "root_deviation_toe_mean_heel_mm": [None if v is None else float(v) for v in self.root_deviation],
                "iterations": self.iterations}


def root_deviation(flank) -> tuple:
    """Height (mm) of the generated root line above the blank's root cone at toe, mean and heel.

    A station where the blade tip generates no enveloping root point (the root there is the trace of the tip circle,
    not an envelope: the grazing contact of the tip plane with the root cone has no solution) is ``None``.
    """
    ol = flank.outline
    # the blade tip generates the root by a grazing contact (the tip plane touches the root cone), where the contact
    # solve is singular (the generated point runs off like a square root of the cradle angle); sample the fillet at
    # the arc angle 0.02 rad from the tip instead: it lies rho_h (1 - cos 0.02) = 2e-4 rho_h above the tip plane,
    # below 1e-3 mm for any edge radius up to 5 mm
    u = flank.generator.cp["u_min"] + 0.02 * flank.cutter.edge_radius
    out: list[float | None] = []
    for R in (ol.Ri, ol.Rm, ol.Re):
        try:
            x = flank._locator.at_R_u(np.array([R]), np.array([u]))
        except GeometryError:
            out.append(None)
            continue
        p = flank.generator.points(x[:, 0], x[:, 1])
        Rx, h = ol.Rh(p[:, 2], np.hypot(p[:, 0], p[:, 1]))
        out.append(float(h[0] - ol.h_root(Rx[0])))
    return tuple(out)


def solve_basic_settings(blank, member, side, cutter: HeadCutter, solve_blade_angle: bool = True,
                         roll: str = "pitch"):
    """Cutter and basic settings whose generated flank has the design pressure and spiral angles at the mean point.

    Parameters
    ----------
    blank : BevelBlank
    member : Member
    side : Side
    cutter : HeadCutter
        Start cutter; its blade angle is the first iterate (kept when ``solve_blade_angle`` is False).
    solve_blade_angle : bool
        False for a given cutter: only the machine spiral angle is solved, the pressure angle is what the blade gives.
    roll : {"pitch", "root"}
        Ratio of roll of the family (see :func:`basic_settings`).

    Returns
    -------
    cutter : HeadCutter
    settings : MachineSettings
    flank : ToothFlank
    fit : FlankFit

    Raises
    ------
    ConvergenceError
        Newton did not reach the design angles in ``_MAX_ITER`` iterations.
    GeometryError
        The cutter does not reach the blank for some iterate.
    """
    member, side = Member(member), Side(side)
    i = member.index
    alpha_d = design_pressure_angle(blank, member, side)
    beta_d = abs(float(getattr(blank, f"beta_m{i}")))

    def build(x):
        c = cutter if not solve_blade_angle else HeadCutter(
            point_radius=cutter.point_radius, blade_angle=float(x[0]), point_width=cutter.point_width,
            edge_radius=cutter.edge_radius, blade=cutter.blade, profile_radius=cutter.profile_radius,
            profile_ref=cutter.profile_ref)
        s = basic_settings(blank, member, c, float(x[-1]), roll)
        f = generate_flank(c, s, blank, member, side)
        return c, s, f

    def residual(x):
        _, _, f = build(x)
        mp = f.mean_point()
        r = [mp.spiral_angle - beta_d]
        if solve_blade_angle:
            r.insert(0, mp.pressure_angle - alpha_d)
        return np.array(r), f

    x = np.array([cutter.blade_angle, beta_d] if solve_blade_angle else [beta_d], float)
    h = 1e-6
    r, f = residual(x)
    for it in range(1, _MAX_ITER + 1):
        if np.max(np.abs(r)) < ANGLE_TOL:
            break
        J = np.empty((x.size, x.size))
        for k in range(x.size):
            xk = x.copy()
            try:
                xk[k] += h
                J[:, k] = (residual(xk)[0] - r) / h
            except GeometryError:
                xk[k] -= 2 * h
                J[:, k] = (r - residual(xk)[0]) / h
        try:
            step = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError as err:
            raise ConvergenceError(f"{member.value} {side.value}: basic settings: singular Jacobian", it,
                                   float(np.max(np.abs(r))), x) from err
        step *= min(1.0, 0.1 / max(np.max(np.abs(step)), 1e-300))  # at most 0.1 rad (5.7 deg) per iteration
        # backtracking: halve the step while the cutter misses the blank at the trial point or the residual grows
        for _ in range(8):
            trial = x + step
            if solve_blade_angle and not (0.01 < trial[0] < 0.5 * math.pi - 0.01):
                step *= 0.5
                continue
            try:
                r1, f1 = residual(trial)
            except GeometryError:
                step *= 0.5
                continue
            if np.max(np.abs(r1)) < np.max(np.abs(r)) or np.max(np.abs(step)) < 1e-9:
                break
            step *= 0.5
        else:
            raise GeometryError.single(
                f"gear_set (cutter_radius {float(blank.rc0):.1f} mm, mean_spiral_angle, normal_pressure_angle)", "-",
                "a design whose flank a face-milling cutter can generate", "-",
                f"the {member.value} {side.value} basic settings cannot reach the design pressure and spiral angles "
                f"at the mean point (residual {math.degrees(float(np.max(np.abs(r)))):.3g} deg; the cutter stops "
                f"generating the mean point): change gear_set.cutter_radius (now {float(blank.rc0):.1f} mm, mean cone "
                f"distance Rm = {float(blank.Rm):.1f} mm) or gear_set.mean_spiral_angle")
        x, r, f = trial, r1, f1
    else:
        raise ConvergenceError(
            f"{member.value} {side.value}: basic settings did not reach the design pressure and spiral angles at the "
            f"mean point in {_MAX_ITER} iterations", _MAX_ITER, float(np.max(np.abs(r))), x)
    c, s, f = build(x)
    # gauge: turn the cutter centre by the cradle angle at which the mean point is generated (the cutter centre sits
    # at angle pi - q + psi_c), so that the mean point is generated at psi_c = 0 as by ``MachineSettings.from_blank``;
    # the flank only turns about the member axis, every mean-point quantity is unchanged
    psi = f.mean_point().psi_c
    if abs(psi) > 1e-12 and not s.modified_roll and not s.blank_offset_poly:
        s1 = s.replace(cradle_angle=s.cradle_angle - psi)
        f1 = generate_flank(c, s1, blank, member, side)
        try:
            f1.mean_point()
            s, f = s1, f1
        except GeometryError:
            # near a fold of the contact line (low spiral angles: the two cutter angles that solve the equation of
            # meshing merge close to the mean point) the turned settings' branch choice can miss the mean point; the
            # gauge is cosmetic, so keep the settings that generate it
            pass
    return c, s, f, flank_fit(blank, f, it)


def flank_fit(blank, flank, iterations: int = 0) -> FlankFit:
    """Design against achieved mean-point angles and root position of any generated flank (given settings too)."""
    i = flank.member.index
    mp = flank.mean_point()
    return FlankFit(design_pressure_angle(blank, flank.member, flank.side), mp.pressure_angle,
                    abs(float(getattr(blank, f"beta_m{i}"))), mp.spiral_angle, root_deviation(flank),
                    iterations)

