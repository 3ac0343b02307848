"""Input validation and blank checks of the log-spiral pair design (private helper of ``logspiral_pair``)."""

from __future__ import annotations

import numbers

import numpy as np

from spiralbevel.conventions import Hand
from spiralbevel.errors import DesignError, GeometryError, Problem

DEG = 180.0 / np.pi


def check_inputs(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle, pinion_hand):
    """Validate the scalar inputs; returns them normalised (ints, floats, Hand). Raises DesignError listing problems."""
    problems = []

    def teeth(name, z):
        if isinstance(z, bool) or not isinstance(z, numbers.Integral) or z < 2:
            problems.append(Problem(name, z, "integer >= 2", "-"))
            return None
        return int(z)

    def angle(name, a, lo, hi, allowed):
        try:
            x = float(a)
        except (TypeError, ValueError):
            problems.append(Problem(name, a, allowed, "rad", "not a number"))
            return None
        if not np.isfinite(x) or not (lo < x < hi):
            problems.append(Problem(name, a, allowed, "rad"))
            return None
        return x

    z1, z2 = teeth("z1", z1), teeth("z2", z2)
    sigma = angle("shaft_angle", shaft_angle, 0.0, np.pi, "0 < value < pi")
    alpha_n = angle("normal_pressure_angle", normal_pressure_angle, 0.0, np.pi / 4, "0 < value < pi/4")
    beta_m = angle("spiral_angle", spiral_angle, 0.0, np.pi / 2, "0 < value < pi/2 (the hand is pinion_hand)")
    try:
        hand = Hand(pinion_hand)
    except ValueError:
        problems.append(Problem("pinion_hand", pinion_hand, "Hand.RIGHT ('RH') or Hand.LEFT ('LH')", "-"))
        hand = None
    if problems:
        raise DesignError(problems)
    g1 = np.arctan2(np.sin(sigma), z2 / z1 + np.cos(sigma))
    if sigma - g1 >= np.pi / 2:
        raise DesignError.single("shaft_angle", shaft_angle, "a shaft angle giving a gear pitch angle < pi/2", "rad",
                                 f"gear pitch angle {(sigma - g1) * DEG:.4f} deg: crown and internal gears are not "
                                 "log-spiral flanks of this model")
    return z1, z2, sigma, alpha_n, beta_m, hand


def check_boundaries(name, b, pitch_angle):
    """Field checks of one BlankBoundaries (lengths and angle order); raises DesignError."""
    problems = []
    for field in ("inner_cone_distance", "outer_cone_distance", "root_angle", "face_angle"):
        v = getattr(b, field)
        if not isinstance(v, numbers.Real) or not np.isfinite(v):
            problems.append(Problem(f"{name}.{field}", v, "a finite number", "mm" if "distance" in field else "rad"))
    if problems:
        raise DesignError(problems)
    if not (0.0 < b.inner_cone_distance < b.outer_cone_distance):
        problems.append(Problem(f"{name}.inner_cone_distance", b.inner_cone_distance,
                                f"0 < value < outer_cone_distance = {b.outer_cone_distance}", "mm"))
    # a parallel-depth blank (gear_set.depth.taper = "uniform": root and face angles equal the pitch angle) cannot
    # carry the tapered log-spiral tooth: say which key to change
    parallel = ("parallel depth (root and face angle equal to the pitch angle, as gear_set.depth.taper = 'uniform' "
                "gives): the log-spiral tooth needs a tapered depth (its flank is similar to itself about the apex, "
                "so its depth grows with the cone distance); use gear_set.depth.taper = 'standard' or "
                "'duplex', or flank.kind = 'face-milled'")
    if not (0.0 < b.root_angle < pitch_angle):
        problems.append(Problem(f"{name}.root_angle", b.root_angle,
                                f"0 < value < pitch angle = {pitch_angle:.10g}", "rad",
                                parallel if abs(b.root_angle - pitch_angle) < 1e-12 else ""))
    if not (pitch_angle < b.face_angle < np.pi / 2):
        problems.append(Problem(f"{name}.face_angle", b.face_angle,
                                f"pitch angle = {pitch_angle:.10g} < value < pi/2", "rad",
                                parallel if abs(b.face_angle - pitch_angle) < 1e-12 else ""))
    if problems:
        raise DesignError(problems)


def check_root_outside_base(name, root_angle, delta):
    """The flank exists only outside the base cone (docs/theory/logspiral.md#singular-edge): root_angle >
    base_cone_angle."""
    if not root_angle > delta:
        raise GeometryError.single(
            f"{name}.root_angle", root_angle, f"value > base cone angle = {delta:.10g}", "rad",
            f"root angle {root_angle * DEG:.6f} deg <= base cone angle {delta * DEG:.6f} deg: the root cone lies "
            "inside the base cone, so the log-spiral flank would cross its singular edge psi = 0 (the c-curve, "
            "docs/theory/logspiral.md#singular-edge); raise the root angle or the pressure angle")


def check_outward_rule(name, psi_range, beta):
    """Keep |psi - beta| < pi/2 over the domain, the region verified in docs/theory/logspiral.md, Eq. (S9)
    (#flank-types) (n_out = sign(psi) n there).

    Beyond it the profile curvature k1 = cos(psi - beta)/(rho |sin psi|) changes sign (profile inflection).
    """
    worst = max(abs(p - beta) for p in psi_range)
    if not worst < np.pi / 2:
        raise GeometryError(f"{name}: |psi - beta| reaches {worst * DEG:.4f} deg >= 90 deg on the flank domain, so the "
                            "involute profile has an inflection (k1 = cos(psi - beta)/(rho |sin psi|) changes sign; "
                            "docs/theory/logspiral.md, Eq. (S9) (#flank-types) verifies |psi - beta| < 90 deg): "
                            "lower the face angle or the pitch angle")
