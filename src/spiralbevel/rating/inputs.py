"""Operating, accuracy, mounting and material data of an ISO 10300 rating: :class:`RatingInput`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from ..errors import DesignError, Problem

__all__ = ["RatingInput", "pitch_deviation_from_grade", "MOUNTINGS", "CONTACT_PATTERNS", "PROFILE_CROWNINGS",
           "MATERIALS"]

MOUNTINGS = ("both-straddle", "one-cantilever", "both-cantilever")
CONTACT_PATTERNS = ("full-load", "light-load", "sample-estimated")
PROFILE_CROWNINGS = ("low", "high")
MATERIALS = ("case-hardened", "through-hardened")


@dataclass(frozen=True)
class RatingInput:
    """Inputs of an ISO 10300 Method B1 rating (subscript 1 = pinion, 2 = wheel; pairs are ``(pinion, wheel)``).

    Parameters
    ----------
    T1 : float, N m
        Nominal pinion torque, > 0.
    n1 : float, 1/min
        Pinion speed, > 0.
    K_A : float
        Application factor, >= 1.
    f_pt : (2,) float, um
        Single pitch deviation of pinion and wheel, > 0 (the larger one enters K_v and K_Halpha).
    rho_a0 : (2,) float, mm
        Cutter edge radius of the blades cutting the root of pinion and wheel, > 0.
    sigma_Hlim, sigma_Flim : (2,) float, N/mm^2
        Allowable stress numbers (contact, bending) of pinion and wheel material, > 0.
    nu40 : float, mm^2/s
        Kinematic viscosity of the lubricant at 40 degC, > 0.
    Rz_flank, Rz_root : (2,) float, um
        Mean peak-to-valley roughness of the flanks and of the root fillets, > 0.
    mounting : str
        ``"both-straddle"``, ``"one-cantilever"`` or ``"both-cantilever"`` (ISO 10300-1 mounting factor).
    contact_pattern : str
        How the contact pattern is verified: ``"full-load"`` (each set in its housing under full load),
        ``"light-load"`` (each set under light test load) or ``"sample-estimated"`` (a sample set, estimated for
        full load).
    profile_crowning : str
        ``"low"`` (default) or ``"high"`` profile crowning: the distribution of the load over the contact lines
        (load sharing factor Z_LS, Y_LS).
    E : float, N/mm^2
        Young's modulus of both members.
    nu : float
        Poisson's ratio of both members.
    density : float, kg/mm^3
        Density of both members (reduced mass of K_v).
    S_Hmin, S_Fmin : float
        Minimum safety factors (permissible stresses sigma_HP = sigma_HG / S_Hmin, sigma_FP = sigma_FG / S_Fmin).
    material : str
        ``"case-hardened"`` or ``"through-hardened"``: selects the life, size and roughness curves.
    load_cycles : float or None
        Number of load cycles of the pinion (the wheel's is this divided by u); None = long life (Z_NT = Y_NT = 1).
    Z_Hyp : float or None
        ISO 10300-2 hypoid factor of a hypoid pair (0 < Z_Hyp <= 1, required with an offset; unused without).
    """

    T1: float
    n1: float
    f_pt: tuple
    rho_a0: tuple
    sigma_Hlim: tuple
    sigma_Flim: tuple
    nu40: float
    Rz_flank: tuple = (8.0, 8.0)
    Rz_root: tuple = (16.0, 16.0)
    K_A: float = 1.0
    mounting: str = "one-cantilever"
    contact_pattern: str = "light-load"
    profile_crowning: str = "low"
    E: float = 206000.0
    nu: float = 0.3
    density: float = 7.86e-6
    S_Hmin: float = 1.0
    S_Fmin: float = 1.3
    material: str = "case-hardened"
    load_cycles: Optional[float] = None
    Z_Hyp: Optional[float] = None

    def __post_init__(self):
        problems = []

        def check(name, value, lo, hi, unit, allowed):
            vals = value if isinstance(value, tuple) else (value,)
            for v in vals:
                if not (isinstance(v, (int, float)) and math.isfinite(v) and lo < v <= hi):
                    problems.append(Problem(name, value, allowed, unit))
                    return

        check("T1", self.T1, 0.0, 1e7, "N m", "0 < T1 <= 1e7")
        check("n1", self.n1, 0.0, 1e6, "1/min", "0 < n1 <= 1e6")
        check("K_A", self.K_A, 1.0 - 1e-12, 10.0, "-", "1 <= K_A <= 10")
        for name, v, unit, hi in (("f_pt", self.f_pt, "um", 1000.0), ("rho_a0", self.rho_a0, "mm", 100.0),
                                  ("sigma_Hlim", self.sigma_Hlim, "N/mm^2", 5000.0),
                                  ("sigma_Flim", self.sigma_Flim, "N/mm^2", 2000.0),
                                  ("Rz_flank", self.Rz_flank, "um", 100.0), ("Rz_root", self.Rz_root, "um", 200.0)):
            if not (isinstance(v, tuple) and len(v) == 2):
                problems.append(Problem(name, v, "a pair (pinion, wheel)", unit))
            else:
                check(name, v, 0.0, hi, unit, f"0 < value <= {hi:g}")
        check("nu40", self.nu40, 0.0, 1e5, "mm^2/s", "0 < nu40 <= 1e5")
        check("E", self.E, 1000.0, 1e6, "N/mm^2", "1000 < E <= 1e6")
        check("nu", self.nu, 0.0, 0.5 - 1e-9, "-", "0 < nu < 0.5")
        check("density", self.density, 0.0, 1e-4, "kg/mm^3", "0 < density <= 1e-4")
        check("S_Hmin", self.S_Hmin, 0.0, 10.0, "-", "0 < S_Hmin <= 10")
        check("S_Fmin", self.S_Fmin, 0.0, 10.0, "-", "0 < S_Fmin <= 10")
        if self.Z_Hyp is not None:
            check("Z_Hyp", self.Z_Hyp, 0.0, 1.0, "-", "0 < Z_Hyp <= 1")
        if self.load_cycles is not None:
            check("load_cycles", self.load_cycles, 0.0, 1e15, "-", "0 < N_L <= 1e15")
        for name, v, allowed in (("mounting", self.mounting, MOUNTINGS),
                                 ("contact_pattern", self.contact_pattern, CONTACT_PATTERNS),
                                 ("profile_crowning", self.profile_crowning, PROFILE_CROWNINGS),
                                 ("material", self.material, MATERIALS)):
            if v not in allowed:
                problems.append(Problem(name, v, " | ".join(allowed), "-"))
        if problems:
            raise DesignError(problems)


def pitch_deviation_from_grade(grade: int, d_T: float, mmn: float) -> float:
    """Single pitch tolerance of a bevel gear of an ISO 17485 accuracy grade.

    Parameters
    ----------
    grade : int
        Accuracy grade B, 2 ... 11.
    d_T : float, mm
        Tolerance diameter (the mean pitch diameter dm is used).
    mmn : float, mm
        Mean normal module.

    Returns
    -------
    float, um
        f_ptT = (0.003 d_T + 0.3 mmn + 5) sqrt(2)^(B - 4) (ISO 17485:2006, single pitch tolerance).
    """
    if not (isinstance(grade, int) and 2 <= grade <= 11):
        raise DesignError.single("accuracy_grade", grade, "an integer 2 ... 11", "-")
    return (0.003 * d_T + 0.3 * mmn + 5.0) * math.sqrt(2.0) ** (grade - 4)
