"""Load distribution at one mesh position: the complementarity problem of seed 001 Eq. (18), docs/theory/ltca.md, Eqs.
(L1)-(L4).

    C F + w - d = dtheta h,   sum_i F_i h_i = T,   F >= 0,  d >= 0,  F_i d_i = 0

C (mm/N) is the flexibility matrix of the potential contact points along their normals, w (mm) the initial
separations, h (mm/rad) the lever arms h_i = (r_i x n_i) . a of the normal forces about the loaded member's axis,
T (N mm) the torque on that member and dtheta (rad) its rotation (the approach angle). The problem is the KKT system
of a strictly convex QP and is solved exactly (see :mod:`spiralbevel._core.ltca`).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError

from ..._core import ltca as _k
from ...errors import ConvergenceError, DesignError, NoContactError

__all__ = ["LoadSolution", "solve_load_distribution"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class LoadSolution:
    """Solution of the load-distribution problem at one mesh position.

    Attributes
    ----------
    force : (n,) float, N
        Normal forces F_i (>= 0).
    gap : (n,) float, mm
        Deformed separations d_i (>= 0, zero where F_i > 0).
    dtheta : float, rad
        Rotation of the loaded member that closes the gaps (loaded approach angle).
    active : (n,) bool
        Points in contact (F_i > 0).
    iterations : int
        Active-set iterations.
    method : str
        ``"zero-torque"``, ``"pdas"`` or ``"primal-active-set"``.
    """

    force: np.ndarray
    gap: np.ndarray
    dtheta: float
    active: np.ndarray
    iterations: int
    method: str

    def residuals(self, C, w, h, T):
        """Max-norm residuals (compatibility mm, equilibrium N mm, complementarity N mm) for checking."""
        comp = np.max(np.abs(C @ self.force + w - self.gap - self.dtheta * h))
        eq = abs(self.force @ h - T)
        cp = np.max(np.abs(self.force * self.gap))
        return comp, eq, cp


def _validate(C, w, h, T, position, check_spd):
    where = f" at mesh position {position}" if position is not None else ""
    C = np.asarray(C, float)
    w = np.asarray(w, float).ravel()
    h = np.asarray(h, float).ravel()
    n = len(w)
    if n == 0:
        raise NoContactError(f"no potential contact points{where}")
    if C.shape != (n, n) or h.shape != (n,):
        raise DesignError.single("C", f"shape {C.shape}, h {h.shape}", f"({n}, {n}) and ({n},)", "-",
                                 f"flexibility matrix and lever arms must match the {n} separations{where}")
    for name, arr in (("C", C), ("w", w), ("h", h)):
        if not np.all(np.isfinite(arr)):
            raise DesignError.single(name, "non-finite entries", "finite values", "-", f"load distribution{where}")
    if not np.isfinite(T) or T < 0:
        raise DesignError.single("torque", T, ">= 0", "N mm", f"load distribution{where}")
    if np.any(h <= 0):
        i = int(np.argmin(h))
        raise DesignError.single(f"h[{i}]", float(h[i]), "> 0", "mm",
                                 f"lever arms of the normal forces must all be positive{where}")
    asym = np.max(np.abs(C - C.T))
    if asym > 1e-8 * np.max(np.abs(C)):
        raise DesignError.single("C", f"asymmetry {asym:.3e}", "symmetric", "mm/N", f"flexibility matrix{where}")
    if check_spd:
        try:
            np.linalg.cholesky(C)
        except np.linalg.LinAlgError as err:
            raise DesignError.single("C", "not positive definite", "symmetric positive definite", "mm/N",
                                     f"flexibility matrix{where}") from err
    return C, w, h, float(T)


def solve_load_distribution(C, w, h, torque, active=None, position=None, check_spd=True) -> LoadSolution:
    """Solve seed 001 Eq. (18) exactly for the forces F, gaps d and the rotation dtheta.

    Parameters
    ----------
    C : (n, n) float, mm/N
        Flexibility matrix (symmetric positive definite).
    w : (n,) float, mm
        Initial separations along the normals at dtheta = 0 (may be negative).
    h : (n,) float, mm
        Lever arms of the normal forces (all > 0), so that a rotation dtheta closes point i by dtheta h_i.
    torque : float, N mm
        Torque T >= 0 transmitted by the contact.
    active : (n,) bool, optional
        Warm start for the loaded set (e.g. the previous mesh position's solution).
    position : int or str, optional
        Name of the mesh position, used in error messages.
    check_spd : bool
        Check positive definiteness of C by a Cholesky factorization.

    Returns
    -------
    LoadSolution
        At zero torque F = 0 and dtheta = min_i w_i / h_i (the unloaded first contact).

    Raises
    ------
    DesignError
        Bad shapes, non-finite data, T < 0, h_i <= 0, C not symmetric positive definite.
    NoContactError
        No potential contact points.
    """
    C, w, h, T = _validate(C, w, h, torque, position, check_spd)
    n = len(w)
    if T == 0.0:
        lam = float(np.min(w / h))
        d = w - lam * h
        return LoadSolution(np.zeros(n), np.maximum(d, 0.0), lam, np.zeros(n, bool), 0, "zero-torque")
    if active is None or not np.any(active):
        ratio = w / h
        # first guess: the points already interpenetrating at the rigid rotation of a small share of the load
        active = ratio <= ratio.min() + 1e-12 * (abs(ratio.min()) + 1e-300)
    try:
        F, d, lam, A, it, ok = _k.pdas(C, w, h, T, np.asarray(active, bool))
        method = "pdas"
        if not ok:
            log.debug("PDAS did not settle after %d iterations; primal active set", it)
            F0 = np.maximum(F, 0.0)
            F0 = F0 * (T / (F0 @ h)) if F0 @ h > 0 else None
            try:
                F, d, lam, A, it2 = _k.primal_active_set(C, w, h, T, F0)
            except RuntimeError as err:  # iteration cap: cannot happen for SPD C in exact arithmetic
                raise ConvergenceError(f"load distribution at position {position}", 20 * n + 50) from err
            it, method = it + it2, "primal-active-set"
    except LinAlgError as err:
        raise DesignError.single("C", "a principal submatrix is not positive definite", "symmetric positive "
                                 "definite", "mm/N", f"flexibility matrix at position {position}") from err
    return LoadSolution(F, d, float(lam), A & (F > 0), it, method)
