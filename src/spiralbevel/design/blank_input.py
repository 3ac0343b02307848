"""Input data of the ISO 23509 blank geometry (Method 0 without offset, Method 1 for hypoids; face milling).

:class:`BlankInput` holds the basic data of a spiral bevel gear pair in SI-internal units (mm, rad). Every field is
checked when the object is built; all problems are reported at once in one :class:`~spiralbevel.errors.DesignError`.

References
----------
ISO 23509:2016, clause 5 (initial data, Tables 2 and 3) and Annex F.2 (Sample 1). The symbols follow the standard,
written in ASCII: ``alpha_dD`` = α_dD, ``theta_f2`` = θ_f2, ``c_ham`` = c_ham, ...
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ..conventions import Hand
from ..errors import DesignError, Problem

__all__ = ["BlankInput", "TAPERS"]

#: Depthwise taper systems: ``"given"`` (dedendum angles given, ISO data type II), ``"standard"`` (root lines through
#: the pitch apex), ``"uniform"`` (constant depth), ``"duplex"`` (dedendum angle sum from the cutter radius: constant
#: slot width), ``"trl"`` (tilted root line: the duplex sum capped at 1.3 times the standard one, ISO 23509 Annex C
#: modified slot width).
TAPERS = ("given", "standard", "uniform", "duplex", "trl")

_DEG = math.pi / 180.0


def _is_real(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


@dataclass(frozen=True, kw_only=True)
class BlankInput:
    """Basic data of a spiral bevel gear pair without offset (ISO 23509 Method 0, face milling).

    Exactly one of ``de2`` and ``met`` sets the size. Angles are radians, lengths millimetres.

    Parameters
    ----------
    z1, z2 : int
        Numbers of teeth of the pinion and of the wheel, ``5 <= z1 <= z2``.
    b : float, mm
        Face width of the wheel, b2.
    beta_m : float, rad
        Mean spiral angle βm (same for both members when a = 0), ``0 <= beta_m < 75 deg``.
    rc0 : float, mm
        Nominal cutter radius of the face-milling head (used for the toe/heel spiral angles and the duplex taper).
    hand1 : Hand or {"RH", "LH"}
        Hand of spiral of the pinion; the wheel has the opposite hand.
    shaft_angle : float, rad
        Shaft angle Σ, ``0 < Σ < 180 deg`` with the wheel pitch angle δ2 <= 90 deg (external or crown wheel).
    de2 : float or None, mm
        Outer pitch diameter of the wheel.
    met : float or None, mm
        Outer transverse module, met = de2 / z2.
    b1 : float or None, mm
        Face width of the pinion; default b. A wider pinion is extended equally at toe and heel so that the design
        (mean) point stays at the wheel's mid-face.
    alpha_dD, alpha_dC : float, rad
        Design pressure angles of the drive and coast sides, ``0 < alpha < 45 deg``.
    f_alim : float
        Influence factor of the limit pressure angle, ``0 <= f_alim <= 1`` (no effect when a = 0).
    c_ham : float or None
        Mean addendum factor of the wheel, ham2 = c_ham·hmw; default ``0.210 + 0.290/u²``.
    k_d : float
        Depth factor, hmw = k_d·mmn.
    k_c : float
        Clearance factor, c = k_c·hmw.
    k_t : float
        Thickness factor (ISO data type II); the standard's thickness modification coefficient is x_smn = k_t/2.
    jen, jet : float or None, mm
        Outer normal backlash or outer transverse (circular) backlash; at most one; default no backlash.
    taper : {"duplex", "trl", "standard", "uniform", "given"}
        Depthwise taper. ``"given"`` takes the dedendum angles from ``theta_*`` (ISO data type II).
    theta_a1, theta_a2, theta_f1, theta_f2 : float or None, rad
        Addendum and dedendum angles, only with ``taper="given"``. Uniform clearance is assumed (θa1 = θf2,
        θa2 = θf1), so give θf2 or θa1, and θf1 or θa2; values given for both of a pair must agree.
    a : float, mm
        Hypoid offset, ``|a| < de2/2``; positive when the pinion offset follows the hand of spiral of the wheel
        (ISO 23509 B.3, ``docs/conventions.md``). 0 gives the spiral bevel pair of ISO 23509 Method 0; a != 0 the
        hypoid pair of Method 1 (Gleason), with ``beta_m`` the desired pinion mean spiral angle βΔ1 and the pinion
        face width computed (``b1`` not given).
    gear_generated : bool
        True (default) for a generated (rolled) gear, False for a Formate (non-generated, plunge-cut) gear, whose
        flanks are the cutter surface (ISO 23509 Method 1 distinguishes the two). A Formate gear is offered on the
        hypoid chain only (``a != 0``); the Method 1 dimension sheet is the same for both (see
        ``docs/theory/universal.md``).

    Raises
    ------
    DesignError
        Listing every bad field with its value, the allowed range and the unit.
    """

    z1: int
    z2: int
    b: float
    beta_m: float
    rc0: float
    hand1: Hand = Hand.LEFT
    shaft_angle: float = math.pi / 2
    de2: float | None = None
    met: float | None = None
    b1: float | None = None
    alpha_dD: float = 20.0 * _DEG
    alpha_dC: float = 20.0 * _DEG
    f_alim: float = 0.0
    c_ham: float | None = None
    k_d: float = 2.0
    k_c: float = 0.125
    k_t: float = 0.0
    jen: float | None = None
    jet: float | None = None
    taper: str = "duplex"
    theta_a1: float | None = None
    theta_a2: float | None = None
    theta_f1: float | None = None
    theta_f2: float | None = None
    a: float = 0.0
    gear_generated: bool = True

    def __post_init__(self) -> None:
        if isinstance(self.hand1, str) and not isinstance(self.hand1, Hand):
            try:
                object.__setattr__(self, "hand1", Hand(self.hand1.upper()))
            except ValueError:
                pass
        problems = self._check()
        if problems:
            raise DesignError(problems)

    # ------------------------------------------------------------------ derived inputs
    @property
    def u(self) -> float:
        """Gear ratio u = z2 / z1."""
        return self.z2 / self.z1

    @property
    def de2_value(self) -> float:
        """Outer pitch diameter of the wheel, from ``de2`` or ``met·z2``, mm."""
        return float(self.de2) if self.de2 is not None else float(self.met) * self.z2  # type: ignore[arg-type]  # one is set

    @property
    def c_ham_value(self) -> float:
        """Mean addendum factor used: the given one or 0.210 + 0.290/u² (Gleason/ISO recommendation)."""
        return float(self.c_ham) if self.c_ham is not None else 0.210 + 0.290 / self.u**2

    def pressure_angles(self, alpha_lim: float) -> tuple[float, float, float, float, float]:
        """ISO 23509 pressure angles for a limit pressure angle ``alpha_lim`` (rad; 0 without offset).

        Returns
        -------
        alpha_nD, alpha_nC, alpha_eD, alpha_eC, alpha_n : float, rad
            Generated (normal) drive and coast angles ``alpha_d + -f_alim*alpha_lim``, effective angles
            ``alpha_n -+ alpha_lim`` and the mean normal pressure angle (mean of drive and coast).
        """
        alpha_nD = self.alpha_dD + self.f_alim * alpha_lim
        alpha_nC = self.alpha_dC - self.f_alim * alpha_lim
        return alpha_nD, alpha_nC, alpha_nD - alpha_lim, alpha_nC + alpha_lim, 0.5 * (alpha_nD + alpha_nC)

    def mean_depths(self, mmn: float) -> tuple[float, float, float, float, float, float]:
        """ISO 23509 depths at the mean point for the mean normal module ``mmn`` (mm).

        Returns
        -------
        hmw, c, ham1, ham2, hfm1, hfm2 : float, mm
            Working depth k_d*mmn, clearance k_c*hmw, addenda (c_ham*hmw on the wheel) and dedenda (mate's addendum
            plus clearance).
        """
        hmw = self.k_d * mmn
        c = self.k_c * hmw
        ham2 = self.c_ham_value * hmw
        ham1 = hmw - ham2
        return hmw, c, ham1, ham2, ham2 + c, ham1 + c

    @property
    def b1_value(self) -> float:
        """Pinion face width used, mm."""
        return float(self.b1) if self.b1 is not None else float(self.b)

    # ------------------------------------------------------------------ validation
    def _check(self) -> list[Problem]:
        P: list[Problem] = []

        def bad(name, allowed, unit, reason=""):
            P.append(Problem(name, getattr(self, name), allowed, unit, reason))

        def real_in(name, lo, hi, unit, lo_open=True, hi_open=True, scale=1.0, optional=False):
            """Check lo (<|<=) value (<|<=) hi; angles (scale = 1 deg) are reported in degrees."""
            v = getattr(self, name)
            if v is None and optional:
                return True
            shown_unit = "deg" if scale != 1.0 else unit
            lo_s, hi_s = ("<" if lo_open else "<="), ("<" if hi_open else "<=")
            if lo is not None and hi is not None:
                allowed = f"{lo / scale:g} {lo_s} {name} {hi_s} {hi / scale:g}"
            elif lo is not None:
                allowed = f"{name} {'>' if lo_open else '>='} {lo / scale:g}"
            else:
                allowed = f"{name} {hi_s} {hi / scale:g}"
            if not _is_real(v):
                P.append(Problem(name, v, allowed, shown_unit, "a finite number is required"))
                return False
            ok = True
            if lo is not None:
                ok &= v > lo if lo_open else v >= lo
            if hi is not None:
                ok &= v < hi if hi_open else v <= hi
            if not ok:
                if scale != 1.0:
                    P.append(Problem(name, round(v / scale, 6), allowed, "deg", f"given in radians: {v!r}"))
                else:
                    bad(name, allowed, unit)
            return ok

        z_ok = True
        for name in ("z1", "z2"):
            v = getattr(self, name)
            if not (isinstance(v, int) and not isinstance(v, bool)) or v < 5:
                bad(name, "integer >= 5", "-")
                z_ok = False
        if z_ok and self.z1 > self.z2:
            bad("z1", f"z1 <= z2 = {self.z2} (the pinion is the member with fewer teeth)", "-")
            z_ok = False

        sig_ok = real_in("shaft_angle", 0.0, math.pi, "rad", scale=_DEG)
        if sig_ok and z_ok:
            sig_max = math.acos(-self.z1 / self.z2)
            if self.shaft_angle > sig_max + 1e-12:
                P.append(Problem("shaft_angle", round(self.shaft_angle / _DEG, 6),
                                 f"0 < shaft_angle <= acos(-z1/z2) = {sig_max / _DEG:.6g}", "deg",
                                 "the wheel pitch angle would exceed 90 deg: internal bevel gears are not supported"))

        if not isinstance(self.hand1, Hand):
            bad("hand1", "Hand.RIGHT/'RH' or Hand.LEFT/'LH'", "-")

        size_ok = False
        if (self.de2 is None) == (self.met is None):
            P.append(Problem("de2/met", (self.de2, self.met), "exactly one of de2, met given", "-"))
        elif self.de2 is not None:
            size_ok = real_in("de2", 0.0, None, "mm")
        else:
            size_ok = real_in("met", 0.0, None, "mm")

        b_ok = real_in("b", 0.0, None, "mm")
        b1_ok = real_in("b1", 0.0, None, "mm", optional=True)
        beta_ok = real_in("beta_m", 0.0, 75 * _DEG, "rad", lo_open=False, scale=_DEG)
        real_in("alpha_dD", 0.0, 45 * _DEG, "rad", scale=_DEG)
        real_in("alpha_dC", 0.0, 45 * _DEG, "rad", scale=_DEG)
        real_in("f_alim", 0.0, 1.0, "-", lo_open=False, hi_open=False)
        rc0_ok = real_in("rc0", 0.0, None, "mm")
        real_in("c_ham", 0.0, 1.0, "-", optional=True)
        real_in("k_d", 0.0, 4.0, "-", hi_open=False)
        real_in("k_c", 0.0, 1.0, "-", lo_open=False)
        real_in("k_t", -0.5, 0.5, "-", lo_open=False, hi_open=False)
        real_in("jen", 0.0, None, "mm", lo_open=False, optional=True)
        real_in("jet", 0.0, None, "mm", lo_open=False, optional=True)
        if self.jen is not None and self.jet is not None:
            P.append(Problem("jen/jet", (self.jen, self.jet), "at most one of jen, jet given", "-"))

        a_ok = _is_real(self.a)
        if not a_ok:
            bad("a", "a finite number", "mm")
        elif self.a != 0.0:
            if size_ok and abs(self.a) >= 0.5 * self.de2_value:
                bad("a", f"|a| < de2/2 = {0.5 * self.de2_value:.6g}", "mm", "the offset must be smaller than the "
                    "wheel's pitch radius (ISO 23509 Method 1)")
            if self.b1 is not None:
                bad("b1", "None for a hypoid (a != 0)", "mm", "ISO 23509 Method 1 computes the pinion face width")
            if not 0.0 < self.beta_m:
                bad("beta_m", "beta_m > 0 for a hypoid (a != 0)", "deg", "the desired pinion spiral angle of "
                    "ISO 23509 Method 1 must be positive")

        if not isinstance(self.gear_generated, bool):
            bad("gear_generated", "True (generated gear) or False (Formate gear)", "-")
        elif not self.gear_generated and a_ok and self.a == 0.0:
            bad("gear_generated", "True for a = 0", "-", "a Formate (non-generated) gear is offered on the hypoid "
                "chain (ISO 23509 Method 1, a != 0) only")
        self._check_taper(P, real_in)

        # cross-field: face width against the cone distance, cutter radius against the face
        if z_ok and sig_ok and size_ok and b_ok:
            delta1 = math.atan2(math.sin(self.shaft_angle), math.cos(self.shaft_angle) + self.u)
            delta2 = self.shaft_angle - delta1
            re2 = self.de2_value / (2.0 * math.sin(delta2))
            if self.b >= re2:
                bad("b", f"0 < b < Re2 = {re2:.6g}", "mm", "the face would reach past the pitch apex")
            elif b1_ok and self.b1 is not None and self.b1 >= 2.0 * re2 - self.b:
                bad("b1", f"0 < b1 < 2*Rm = {2.0 * re2 - self.b:.6g}", "mm", "the pinion face would reach the apex")
            elif beta_ok and rc0_ok:
                rm = re2 - self.b / 2.0
                if self.rc0 <= rm * math.sin(self.beta_m) and self.taper in ("duplex", "trl"):
                    bad("rc0", f"rc0 > Rm*sin(beta_m) = {rm * math.sin(self.beta_m):.6g}", "mm",
                        f"{self.taper} taper: the dedendum angle sum would not be positive")
        return P

    def _check_taper(self, P: list[Problem], real_in) -> None:
        thetas = ("theta_a1", "theta_a2", "theta_f1", "theta_f2")
        if self.taper not in TAPERS:
            P.append(Problem("taper", self.taper, " | ".join(TAPERS), "-"))
            return
        given = [t for t in thetas if getattr(self, t) is not None]
        if self.taper != "given":
            if given:
                P.append(Problem(given[0], getattr(self, given[0]), "None unless taper = 'given'", "-",
                                 f"inconsistent inputs: taper = {self.taper!r} computes the dedendum angles"))
            return
        ok = all(real_in(t, -10 * _DEG, 20 * _DEG, "rad", scale=_DEG, optional=True) for t in thetas)
        if not ok:
            return
        for x, y in (("theta_f1", "theta_a2"), ("theta_f2", "theta_a1")):
            vx, vy = getattr(self, x), getattr(self, y)
            if vx is None and vy is None:
                P.append(Problem(f"{x}/{y}", (None, None), f"one of {x}, {y} given with taper='given'", "-"))
            elif vx is not None and vy is not None and abs(vx - vy) > 1e-9:
                P.append(Problem(y, round(vy / _DEG, 6), f"{y} = {x} = {vx / _DEG:.6g}", "deg",
                                 "inconsistent inputs: uniform clearance requires theta_a1 = theta_f2 and "
                                 "theta_a2 = theta_f1"))
