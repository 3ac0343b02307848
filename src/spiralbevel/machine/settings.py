"""Basic machine settings of a cradle-type generator (seed 001 §3.1, Eq. (15); docs/theory/generation.md#cradle-machine
and docs/theory/example.md#table-4 Tables 4-5, §3.1).

The positive direction of every setting is defined in ``docs/conventions.md`` section "Machine settings".
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError, GeometryError, Problem

__all__ = ["MachineSettings"]

_LABELS = [
    ("radial_setting", "Radial setting S_r", "mm", False),
    ("cradle_angle", "Cradle (installment) angle q", "deg", True),
    ("machine_root_angle", "Machine root angle gamma_m", "deg", True),
    ("machine_centre_to_back", "Machine centre to back X_D", "mm", False),
    ("sliding_base", "Sliding base X_B", "mm", False),
    ("blank_offset", "Blank offset E_m", "mm", False),
    ("ratio_of_roll", "Ratio of roll m_ic", "-", False),
]


@dataclass(frozen=True)
class MachineSettings:
    """Machine-tool settings for one member and side on a cradle-type generator.

    Parameters
    ----------
    radial_setting : float, mm
        S_r, distance from the cradle axis to the cutter axis, > 0.
    cradle_angle : float, rad
        q, angle from the machine root line to the ray cradle axis -> cutter centre (measured, for a left-hand
        member, counterclockwise seen from the cutter side, +Z_m toward the viewer; mirrored for a right-hand member).
    machine_root_angle : float, rad
        gamma_m, inclination of the work axis to the cradle plane, 0 < gamma_m < pi/2.
    machine_centre_to_back : float, mm
        X_D; a positive value moves the work (and its apex) along its own axis away from the machine centre, i.e.
        out of the cut.
    sliding_base : float, mm
        X_B; a positive value moves the work along -Z_m, toward the cutter, i.e. deeper into the cut
        (docs/theory/generation.md, Eqs. (G5)-(G6): the work axis passes through A = (0, E_m, -X_B)).
    blank_offset : float, mm
        E_m at psi_c = 0; a positive value moves the work axis away from the side of the root line on which the
        cutter centre lies (along +Y_m on the right-hand machine, where A_i = (0, E_m, -X_B) as in
        docs/theory/generation.md, Eqs. (G5)-(G6)).
    ratio_of_roll : float
        m_ic = d psi_i / d psi_c at psi_c = 0, > 0 (1/sin gamma_m for crown-gear generation).
    modified_roll : tuple of float
        (2C, 6D, 24E, 120F): psi_i = m_ic (psi_c - 2C psi_c^2/2! - 6D psi_c^3/3! - 24E psi_c^4/4! - 120F psi_c^5/5!),
        psi_c in rad. Up to four coefficients, missing ones are 0.
    blank_offset_poly : tuple of float, mm
        (e1, e2, ...): E_m(psi_c) = E_m + e1 psi_c + e2 psi_c^2 + ... (variable blank offset; psi_c in rad).
    blank_offset_table : tuple, optional
        ``((psi_1, ..., psi_m), (dE_1, ..., dE_m))``: psi_c nodes (rad, strictly increasing, m >= 2) and blank-offset
        increments (mm) interpolated linearly between them and extrapolated linearly beyond, added to the constant and
        polynomial parts (the instantaneous blank offset of seed 001 §4.3.1 step 3). dE_m/dt = (dE_m/dpsi_c) omega_c
        enters the relative velocity (docs/theory/generation.md, Eqs. (G5)-(G6)); at a node the slope of the segment on
        the side of
        psi_c = 0 is used. A third tuple ``(M_1, ..., M_m)`` (mm/rad^2) of second derivatives at the nodes makes it a
        cubic spline (``spiralbevel._core.generation.table_offset``). Empty: no table.
    """

    radial_setting: float
    cradle_angle: float
    machine_root_angle: float
    machine_centre_to_back: float = 0.0
    sliding_base: float = 0.0
    blank_offset: float = 0.0
    ratio_of_roll: float = 1.0
    modified_roll: tuple = field(default=())
    blank_offset_poly: tuple = field(default=())
    blank_offset_table: tuple = field(default=())

    def __post_init__(self):
        object.__setattr__(self, "modified_roll", tuple(float(c) for c in self.modified_roll))
        object.__setattr__(self, "blank_offset_poly", tuple(float(c) for c in self.blank_offset_poly))
        p = []
        table = _check_table(self.blank_offset_table, p)
        object.__setattr__(self, "blank_offset_table", table)

        def fin(name, val, ok, allowed, unit):
            if not (isinstance(val, (int, float)) and math.isfinite(val) and ok(val)):
                p.append(Problem(f"settings.{name}", val, allowed, unit))

        fin("radial_setting", self.radial_setting, lambda v: v > 0, "> 0", "mm")
        fin("cradle_angle", self.cradle_angle, lambda v: -math.pi <= v <= math.pi, "-pi..pi", "rad")
        fin("machine_root_angle", self.machine_root_angle, lambda v: 0 < v < 0.5 * math.pi, "0 < value < pi/2",
            "rad")
        for name in ("machine_centre_to_back", "sliding_base", "blank_offset"):
            fin(name, getattr(self, name), lambda v: True, "finite", "mm")
        fin("ratio_of_roll", self.ratio_of_roll, lambda v: v > 0, "> 0", "-")
        if len(self.modified_roll) > 4 or not all(math.isfinite(c) for c in self.modified_roll):
            p.append(Problem("settings.modified_roll", self.modified_roll, "up to 4 finite values (2C, 6D, 24E, 120F)",
                             "-"))
        if not all(math.isfinite(c) for c in self.blank_offset_poly):
            p.append(Problem("settings.blank_offset_poly", self.blank_offset_poly, "finite", "mm"))
        if p:
            raise DesignError(p)

    # ------------------------------------------------------------------------------------------------------------
    @classmethod
    def from_blank(cls, blank, member, side, cutter, roll: str = "pitch") -> "MachineSettings":
        """Basic settings by crown-gear generation (cradle plane = root plane, apexes at the machine centre).

        A = R_m cos(theta_f) is the mean point in the root plane; with the nominal cutter radius r_c and the mean
        spiral angle beta_m, S_r = sqrt(A^2 + r_c^2 - 2 A r_c sin beta_m), q = asin(r_c cos beta_m / S_r);
        gamma_m = root angle. docs/theory/example.md#table-4 and docs/theory/generation.md, Eq. (G12) 'check' column:
        seed 001 gear, A = 115.8417 mm, S_r = 115.079 mm,
        q = 59 deg 20' 06.8".

        Ratio of roll: ``roll="pitch"`` (default) m_ic = cos(theta_f)/sin(delta), which puts the instantaneous axis of
        the relative motion on the member's pitch line (the generating crown gear, pitch angle 90 deg - theta_f about
        the cradle axis, rolls on the pitch cone); 1.0598 for the seed 001 gear, printed 1.06 in Table 4.
        ``roll="root"``: m_ic = 1/sin(gamma_m), pure rolling of the cradle plane on the root cone
        (docs/theory/generation.md, Eq. (G6) (pure rolling m_ic = 1/sin gamma_m));
        1.0783 for the seed 001 gear. With it the cutter tip line lies on the instantaneous axis, so the relative
        velocity vanishes along the generated root line.

        Parameters
        ----------
        blank : ISO 23509 blank (attributes ``Rm, theta_f1/2, delta_f1/2, beta_m1/2``).
        member : Member
        side : Side
            Must match the cutter's blade (inner -> convex, outer -> concave).
        cutter : HeadCutter
        """
        member, side = Member(member), Side(side)
        if cutter.side is not side:
            raise DesignError.single("cutter.blade", cutter.blade.value,
                                     f"{'inner' if side is Side.CONVEX else 'outer'}"
                                     f" for the {side.value} side", "-")
        i = member.index
        Rm = float(blank.Rm)
        theta_f = float(getattr(blank, f"theta_f{i}"))
        gamma = float(getattr(blank, f"delta_f{i}"))
        beta = abs(float(getattr(blank, f"beta_m{i}")))
        rc = cutter.nominal_radius
        A = Rm * math.cos(theta_f)
        # cutter centre in root-plane coordinates (along the root line, across it): (A - r_c sin b, r_c cos b)
        along, across = A - rc * math.sin(beta), rc * math.cos(beta)
        S = math.hypot(along, across)          # = sqrt(A^2 + r_c^2 - 2 A r_c sin b)
        q = math.atan2(across, along)          # = asin(r_c cos b / S) when along > 0
        if not (rc > 0 and A > 0 and S > 0):
            raise GeometryError.single("blank.Rm", Rm, "> 0 with a cutter that reaches the mean point", "mm")
        if roll == "pitch":
            m = math.cos(theta_f) / math.sin(float(getattr(blank, f"delta{i}")))
        elif roll == "root":
            m = 1.0 / math.sin(gamma)
        else:
            raise DesignError.single("roll", roll, "'pitch' or 'root'", "-")
        return cls(radial_setting=S, cradle_angle=q, machine_root_angle=gamma, ratio_of_roll=m)

    def replace(self, **changes) -> "MachineSettings":
        """A copy with some fields changed (validated again)."""
        d = asdict(self)
        d.update(changes)
        return MachineSettings(**d)

    def kernel_params(self) -> dict:
        """Plain dict of floats for ``spiralbevel._core.generation``.

        The kernel frame is the left-hand machine, where the cutter centre lies on the +Y_m side; a positive blank
        offset moves the work AWAY from the cutter-centre side, i.e. along -Y_m there (and along +Y_m on the
        right-hand machine, as A_i = (0, E_m, -X_B) in docs/theory/generation.md, Eq. (G5)). Hence E enters the kernel
        with a minus sign.
        """
        return dict(S=float(self.radial_setting), q=float(self.cradle_angle), gamma=float(self.machine_root_angle),
                    XD=float(self.machine_centre_to_back), XB=float(self.sliding_base), E=-float(self.blank_offset),
                    m=float(self.ratio_of_roll), roll=tuple(self.modified_roll),
                    E_poly=tuple(-c for c in self.blank_offset_poly),
                    E_table=(self.blank_offset_table[0],) + tuple(tuple(-v for v in q)
                                                                  for q in self.blank_offset_table[1:])
                    if self.blank_offset_table else None)

    # ------------------------------------------------------------------------------------------------------------
    def to_dict(self, degrees: bool = True) -> dict:
        """Settings as a plain dict; angles in degrees when ``degrees`` (I/O boundary), else rad."""
        d = asdict(self)
        if degrees:
            for k in ("cradle_angle", "machine_root_angle"):
                d[k] = math.degrees(d[k])
        d["modified_roll"] = list(self.modified_roll)
        d["blank_offset_poly"] = list(self.blank_offset_poly)
        d["blank_offset_table"] = [list(t) for t in self.blank_offset_table]
        return d

    def summary_rows(self, cutter=None, member=None, side=None) -> list[tuple[str, str, str]]:
        """Rows (label, value, unit) for a shop-floor machine summary sheet; angles in degrees (deg min sec)."""
        rows = []
        if member is not None or side is not None:
            rows.append(("Member / side", f"{Member(member).value if member else '-'} / "
                                          f"{Side(side).value if side else '-'}", ""))
        for key, label, unit, ang in _LABELS:
            v = getattr(self, key)
            rows.append((label, _dms(v) if ang else f"{v:.4f}", "" if ang else unit))
        names = ("2C", "6D", "24E", "120F")
        for n, c in zip(names, self.modified_roll):
            rows.append((f"Modified roll {n}", f"{c:.6g}", "-"))
        for k, c in enumerate(self.blank_offset_poly, start=1):
            rows.append((f"Blank offset coefficient e{k} (psi_c^{k})", f"{c:.6g}", "mm"))
        if self.blank_offset_table:
            for psi, dE in zip(*self.blank_offset_table[:2]):
                rows.append((f"Blank offset increment at psi_c = {math.degrees(psi):.4f} deg", f"{dE:.6g}", "mm"))
        if cutter is not None:
            rows += [("Cutter blade", cutter.blade.value, ""),
                     ("Cutter point radius R_h", f"{cutter.point_radius:.4f}", "mm"),
                     ("Blade angle alpha_h", _dms(cutter.blade_angle), ""),
                     ("Edge radius rho_h", f"{cutter.edge_radius:.4f}", "mm"),
                     ("Point width W", f"{cutter.point_width:.4f}", "mm")]
            if math.isfinite(cutter.profile_radius):
                rows.append(("Blade profile radius", f"{cutter.profile_radius:.3f}", "mm"))
        return rows


def _check_table(table, problems) -> tuple:
    """``blank_offset_table`` as ((nodes...), (values...)) of floats, or () (problems appended when invalid)."""
    if table is None or len(table) == 0:
        return ()
    allowed = "((psi_1..psi_m), (dE_1..dE_m)[, (M_1..M_m)]), m >= 2 finite values, psi strictly increasing"
    try:
        parts = tuple(tuple(float(v) for v in part) for part in table)
    except (TypeError, ValueError):
        parts = ()
    ok = len(parts) in (2, 3) and len(parts[0]) >= 2 and all(len(q) == len(parts[0]) for q in parts)
    if not (ok and all(math.isfinite(v) for q in parts for v in q)
            and all(b > a for a, b in zip(parts[0], parts[0][1:]))):
        problems.append(Problem("settings.blank_offset_table", table, allowed, "rad, mm, mm/rad^2"))
        return ()
    return parts


def _dms(rad: float) -> str:
    """Angle in rad as a signed deg-min-sec string with 0.1'' resolution."""
    tenths = round(abs(math.degrees(rad)) * 36000)
    d, rem = divmod(tenths, 36000)
    m, s = divmod(rem, 600)
    sign = "-" if rad < 0 and tenths else ""
    return f"{sign}{d}°{m:02d}′{s / 10:04.1f}″"
