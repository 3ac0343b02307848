"""Scallop height and stepover of a ball-end tool on a curved surface (exact circle model).

Derivation (the cross-section normal to two neighbouring parallel passes)
-------------------------------------------------------------------------
Model the surface in the cross-section as a circle of signed curvature kappa (convex = positive, radius
rho_s = 1/|kappa|) with centre O. A ball of radius R touching it from outside has its centre C on the offset circle of
radius |1/kappa + R| about O (convex: rho_s + R, O inside the material; concave: rho_s - R, O on the tool side, which
needs R < rho_s). Two neighbouring passes are a surface arc w apart, i.e. the centres subtend theta = |kappa| w at O.
The scallop cusp P is where the two ball circles meet; by symmetry it lies on the bisector at |OP| = |1/kappa + h|,
h being the scallop height measured along the surface normal. The law of cosines in the triangle O C P (angle theta/2
at O, |CP| = R) gives

    R^2 = a^2 + b^2 - 2 a b cos(theta/2),    a = 1/kappa + R,  b = 1/kappa + h

(the concave case has a, b both negated, which changes nothing). Multiplying by kappa^2 and using
1 - cos x = 2 sin^2(x/2):

    sin(|kappa| w / 4) = (|kappa| / 2) * q,    q = sqrt( h (2R - h) / ((1 + kappa R)(1 + kappa h)) ).

Hence the stepover for a requested scallop height

    w = (4/|kappa|) asin(|kappa| q / 2)                        (-> 2 q as kappa -> 0)

and, inverted (a quadratic in h, smaller root), the scallop height for a given stepover

    h = (B - sqrt(B^2 - 4C)) / 2,   S = 4 sin^2(|kappa| w / 4) / kappa^2,  B = 2R - S kappa (1 + kappa R),
    C = S (1 + kappa R).

Largest scallop: the cusp is the *lower* intersection of the two ball circles only while they still meet below the
ball centres; at the tangency limit sin(theta/2) = R/|a| the scallop reaches

    h_max = 2R / (1 + sqrt(1 + 2 R kappa))                     (= R flat, < R convex, > R concave)

and beyond it the two balls no longer cut a common cusp (the quadratic's other root is spurious). A concave section
with R > rho_s/2 has no limit: the two balls always overlap.

Flat limit (kappa = 0): w = 2 sqrt(2 R h - h^2) and h = R - sqrt(R^2 - w^2/4), the textbook formulas. For small h
the stepover is w ~ sqrt(8 h R rho_s / (rho_s ± R)) (+ convex, - concave), the classical approximation. A convex
surface needs a smaller stepover than a flat one, a concave surface allows a larger one.
"""

from __future__ import annotations

import numpy as np

__all__ = ["stepover_for_scallop", "scallop_for_stepover", "flat_stepover", "max_scallop"]


def _asin_over_x(x):
    """asin(x)/x, continuous at 0 (series 1 + x^2/6 + 3x^4/40 below 1e-3)."""
    x = np.asarray(x, float)
    small = np.abs(x) < 1e-3
    if not small.any():  # the tool-path march's case: the same quotient, without the series and the selections
        return np.arcsin(np.clip(x, -1.0, 1.0)) / x
    xs = np.where(small, 1.0, x)
    return np.where(small, 1.0 + x**2 / 6.0 + 3.0 * x**4 / 40.0, np.arcsin(np.clip(xs, -1.0, 1.0)) / xs)


def _sin_over_x(x):
    """sin(x)/x, continuous at 0."""
    return np.sinc(np.asarray(x, float) / np.pi)


def flat_stepover(tool_radius, scallop_height):
    """Stepover w = 2 sqrt(2 R h - h^2) on a flat surface, mm (a check of the curved formula at kappa = 0)."""
    R, h = np.asarray(tool_radius, float), np.asarray(scallop_height, float)
    return 2.0 * np.sqrt(2.0 * R * h - h * h)


def max_scallop(tool_radius, curvature):
    """Largest scallop height two neighbouring ball passes can leave, 2R / (1 + sqrt(1 + 2 R kappa)), mm.

    Parameters
    ----------
    tool_radius : float or (...) float, mm
    curvature : float or (...) float, 1/mm
        Convex = positive.

    Returns
    -------
    (...) float, mm
        ``inf`` for a concave section with 1 + 2 R kappa <= 0 (the balls always overlap).
    """
    R = np.asarray(tool_radius, float)
    k = np.asarray(curvature, float)
    arg = 1.0 + 2.0 * R * k
    with np.errstate(invalid="ignore"):
        return np.where(arg > 0, 2.0 * R / (1.0 + np.sqrt(np.maximum(arg, 0.0))), np.inf)


def stepover_for_scallop(tool_radius, scallop_height, curvature):
    """Surface arc between two passes that leaves exactly the scallop height ``scallop_height``.

    Parameters
    ----------
    tool_radius : float or (...) float, mm
        Ball radius R > 0.
    scallop_height : float or (...) float, mm
        Scallop height h, 0 < h < min(R, :func:`max_scallop`); NaN above the limit.
    curvature : float or (...) float, 1/mm
        Normal curvature of the surface across the passes, convex = positive; concave needs 1 + kappa R > 0.

    Returns
    -------
    (...) float, mm
        Stepover w measured along the surface (arc length). Where the concave case allows any stepover
        (|kappa| q / 2 >= 1) the result is the full circle 2 pi / |kappa|.

    Notes
    -----
    Exact for a surface section of constant curvature; see the module docstring for the derivation. Kernels trust
    their input: the public tool-path planner validates R, h and kappa.
    """
    R = np.asarray(tool_radius, float)
    h = np.asarray(scallop_height, float)
    k = np.asarray(curvature, float)
    q = np.sqrt(h * (2.0 * R - h) / ((1.0 + k * R) * (1.0 + k * h)))
    x = 0.5 * np.abs(k) * q
    full = x >= 1.0
    if full.any():
        with np.errstate(divide="ignore", over="ignore"):
            w_full = np.where(full, 2.0 * np.pi / np.where(k == 0, 1.0, np.abs(k)), 0.0)
        w = np.where(full, w_full, 2.0 * q * _asin_over_x(np.minimum(x, 1.0)))
    else:  # no full circle (the tool-path march's case, about 2,000 calls per plan): the same numbers, fewer calls
        w = 2.0 * q * _asin_over_x(x)
    return np.where(h < max_scallop(R, k), w, np.nan)


def scallop_for_stepover(tool_radius, stepover, curvature):
    """Scallop height left by two passes a surface arc ``stepover`` apart (inverse of :func:`stepover_for_scallop`).

    Parameters
    ----------
    tool_radius : float or (...) float, mm
    stepover : float or (...) float, mm
        Surface arc between the passes, 0 <= w.
    curvature : float or (...) float, 1/mm
        Convex = positive.

    Returns
    -------
    (...) float, mm
        Scallop height h (NaN where the passes are too far apart for the two balls to meet).
    """
    R = np.asarray(tool_radius, float)
    w = np.asarray(stepover, float)
    k = np.asarray(curvature, float)
    S = (0.25 * w * w) * _sin_over_x(0.25 * np.abs(k) * w) ** 2
    B = 2.0 * R - S * k * (1.0 + k * R)
    C = S * (1.0 + k * R)
    disc = B * B - 4.0 * C
    with np.errstate(invalid="ignore"):
        root = np.sqrt(disc)
    # stable smaller root: 2C / (B + sqrt(disc))
    return np.where(disc >= 0, 2.0 * C / (B + root), np.nan)
