"""Basic machine settings of the family that puts the blank's root cone on the cradle plane.

For one member side: machine root angle gamma_m = delta_f, blank offset E_m = 0, sliding base X_B = 0, machine centre
to back X_D = -z_R (z_R the axial position of the root-cone apex in the member frame), so that the root-cone apex sits
at the machine centre and the root cone touches the cradle plane (the plane of the blade tips) along the root line: the
generated root line lies on the root cone along the whole face width. The cutter centre is at
(A_f - r_c sin beta', r_c cos beta') in the cradle plane (along, across the root line), A_f the distance from the
root-cone apex to the mean root point; beta' (the machine spiral angle) and the blade angle are what
``spiralbevel.generation.basic_settings_solve`` solves for. Ratio of roll m_ic = cos(eps) / sin(phi_w): the
instantaneous axis of the cradle and work rotations (through the machine centre) passes through the mean pitch point,
phi_w being that point's angle from the work axis and eps its elevation above the cradle plane seen from the root-cone
apex (cos theta_f / sin delta when the apexes coincide, as in ``MachineSettings.from_blank``).
"""

from __future__ import annotations

import math

from spiralbevel.conventions import Member
from spiralbevel.machine.cutter import HeadCutter
from spiralbevel.machine.settings import MachineSettings

__all__ = ["basic_settings"]


def _root_geometry(blank, member):
    """(z_R, A_f, phi_w, eps): root-cone apex axial position, apex-to-mean-root distance (mm), and the mean pitch
    point's angle from the work axis and elevation above the cradle plane seen from the root apex (rad)."""
    i = Member(member).index
    delta, delta_f = float(getattr(blank, f"delta{i}")), float(getattr(blank, f"delta_f{i}"))
    Rm, hfm = float(blank.Rm), float(getattr(blank, f"hfm{i}"))
    sd, cd = math.sin(delta), math.cos(delta)
    # mean root point (R = Rm, h = -hfm) in the axial section: axial = R cos d - h sin d, radius = R sin d + h cos d
    ax_f, rad_f = Rm * cd + hfm * sd, Rm * sd - hfm * cd
    z_R = ax_f - rad_f / math.tan(delta_f)
    A_f = rad_f / math.sin(delta_f)
    phi_w = math.atan2(Rm * sd, Rm * cd - z_R)
    return z_R, A_f, phi_w, phi_w - delta_f


def basic_settings(blank, member, cutter: HeadCutter, machine_spiral_angle: float, roll: str = "pitch"
                   ) -> MachineSettings:
    """Settings of the family above for a cutter and a machine spiral angle beta' (rad, >= 0 magnitude).

    ``roll="root"`` takes m_ic = 1/sin(gamma_m) instead (pure rolling of the cradle plane on the root cone).
    """
    z_R, A_f, phi_w, eps = _root_geometry(blank, member)
    i = Member(member).index
    rc = cutter.nominal_radius
    along, across = A_f - rc * math.sin(machine_spiral_angle), rc * math.cos(machine_spiral_angle)
    return MachineSettings(radial_setting=math.hypot(along, across), cradle_angle=math.atan2(across, along),
                           machine_root_angle=float(getattr(blank, f"delta_f{i}")), machine_centre_to_back=-z_R,
                           ratio_of_roll=(math.cos(eps) / math.sin(phi_w) if roll == "pitch"
                                          else 1.0 / math.sin(float(getattr(blank, f"delta_f{i}")))))
