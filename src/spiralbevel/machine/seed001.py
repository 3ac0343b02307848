"""Seed 001 (Liu, Chen, Li, Machines 2024, 12, 34) blank and machine settings, as decoded in docs/theory/example.md
(Tables 1, 4, 5)

Table 1 (blank), Table 4 (gear, inner blade -> gear convex side) and Table 5 (pinion, outer blade -> pinion concave
side). Pitch angles are the exact atan(23/65) (the table's 19 deg 29' / 70 deg 31' are these values rounded); mean
addenda/dedenda are the table's (outer) values reduced to the mean cone distance along the face/root angles.
Assumptions (not printed in seed 001): the pinion point width is taken equal to the gear's 2.29 mm; the machine root
angles are the blank root angles.

Two readings of Tables 4 and 5 (docs/conventions.md, "Seed 001 Tables 4 and 5"; tests/machine/test_seed001_reading.py):

* **Sliding base.** Seed 001 counts X_B positive *away* from the cutter (withdrawing the work); spiralbevel counts it
  toward the cutter (deeper). The printed X_B2 = 0.051 mm and X_B1 = -0.059 mm are therefore stored as -0.051 and
  +0.059 mm. With them both generated roots lie on Table 1's root cone (gear 0.007 mm, pinion 0.005 mm from it);
  read with the printed signs the gear root would be 0.095 mm too deep and the pinion root 0.113 mm too shallow.
* **Pinion blade angle.** The pinion cutter has the blade angle 22 deg 30' of Table 5, not its "modified blade angle"
  21 deg 10' (which is 22 deg 30' - 1 deg 20', the gear's correction mirrored). Table 5 is the output of a local
  synthesis against the gear of Table 4 (modified blade angle 23 deg 50'), so its pinion is tangent to that gear at the
  mean point: with 22 deg 30' the mean-point normal pressure angles differ by 0.12 deg (pinion 22.75, gear 22.63 deg);
  with 21 deg 10' by 1.25 deg (21.38 deg), which no synthesis output can have.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.machine.cutter import Blade, HeadCutter
from spiralbevel.machine.settings import MachineSettings

__all__ = ["seed001_blank", "seed001_settings"]


def _dms(d, m=0, s=0.0):
    return math.radians(d + m / 60 + s / 3600)


def seed001_blank() -> SimpleNamespace:
    """Seed 001 Table 1 with the ISO 23509 attribute names used by ``BevelBlank`` (mm, rad)."""
    d1 = math.atan2(23, 65)
    d2 = 0.5 * math.pi - d1
    da1, da2 = _dms(21, 58, 30), _dms(71, 36, 40)
    df1, df2 = _dms(18, 23, 20), _dms(68, 1, 30)
    Rm, b = 115.9511, 37.0
    half = 0.5 * b
    return SimpleNamespace(
        z1=23, z2=65, Sigma=0.5 * math.pi, hand1=Hand.RIGHT, hand2=Hand.LEFT,
        delta1=d1, delta2=d2, delta_a1=da1, delta_a2=da2, delta_f1=df1, delta_f2=df2,
        theta_f1=d1 - df1, theta_f2=d2 - df2, Rm=Rm, Re2=Rm + half, Ri2=Rm - half, b2=b,
        beta_m1=math.radians(30.0), beta_m2=math.radians(30.0),
        hfm1=2.24 - half * math.tan(d1 - df1), hfm2=5.80 - half * math.tan(d2 - df2),
        ham1=5.10 - half * math.tan(da1 - d1), ham2=1.54 - half * math.tan(da2 - d2), rc0=114.3,
    )


def seed001_settings() -> dict:
    """Seed 001 Tables 4 and 5: ``{(Member, Side): (HeadCutter, MachineSettings)}`` (docs/theory/example.md#table-4 and
    #table-5), read as the module docstring says: sliding bases with spiralbevel's sign, pinion blade 22 deg 30'."""
    blank = seed001_blank()
    gear_cutter = HeadCutter(point_radius=113.155, blade_angle=_dms(23, 50), point_width=2.29, edge_radius=1.31,
                             blade=Blade.INNER)
    gear = MachineSettings(radial_setting=115.078, cradle_angle=_dms(59, 20, 7), machine_root_angle=blank.delta_f2,
                           machine_centre_to_back=0.0, sliding_base=-0.051, blank_offset=0.0, ratio_of_roll=1.06)
    pinion_cutter = HeadCutter(point_radius=124.879, blade_angle=_dms(22, 30), point_width=2.29, edge_radius=1.31,
                               blade=Blade.OUTER)
    pinion = MachineSettings(radial_setting=91.116, cradle_angle=_dms(56, 58, 56), machine_root_angle=blank.delta_f1,
                             machine_centre_to_back=1.231, sliding_base=0.059, blank_offset=34.197,
                             ratio_of_roll=2.499)
    return {(Member.GEAR, Side.CONVEX): (gear_cutter, gear), (Member.PINION, Side.CONCAVE): (pinion_cutter, pinion)}
