"""Numpy helpers of tooth contact analysis on stacked data (the Newton iteration itself is compiled:
:mod:`spiralbevel._core.tca_newton`).

* a surface's data at m parameter points is stacked as ``S (m, 3, k)``: columns (r, n) for k = 2, or
  (r, n, r_q0, r_q1, n_q0, n_q1) for k = 6, member frame;
* the gear pose R(a2, phi2) B2 equals B2 R_z(phi2) (B2 = R_y(S) maps e_z to a2, so R(a2, phi2) = B2 R_z(phi2) B2^T),
  and one product with the stacked (6, 3) matrix [B2; [a2]x B2] gives the fixed-frame gear data and a2 x (gear data)
  together (:func:`assembly_constants`);
* :func:`is_singular` classifies converged systems as line contact (certificates first, SVD where they do not decide).

Pure functions on float64 arrays (mm, rad, xyz on axis -2 of stacked data).
"""

from __future__ import annotations

import numpy as np


__all__ = ["assembly_constants", "stack_state", "is_singular"]


def assembly_constants(axes, scale):
    """Constants of the stacked contact system from :func:`spiralbevel._core.tca.assembly_axes` output.

    Returns
    -------
    d : (3,) float, mm
        o1 - o2.
    M2 : (6, 3) float
        [B2; [a2]x B2]: gear member frame (turned by phi2 about its z axis) -> fixed frame, and a2 x that.
    scale : float, mm
    """
    a1, o1, a2, o2, B2 = axes
    if not (a1[0] == 0.0 and a1[1] == 0.0 and a1[2] == 1.0):
        raise ValueError("the pinion axis of the assembly must be +z")
    A2 = np.array([[0.0, -a2[2], a2[1]], [a2[2], 0.0, -a2[0]], [-a2[1], a2[0], 0.0]])
    return np.asarray(o1 - o2, float), np.concatenate([B2, A2 @ B2], 0), float(scale)


def stack_state(r, n, dr=None, dn=None):
    """Stack surface data ``r, n (m, 3)`` (and ``dr, dn (m, 3, 2)``) into ``S (m, 3, 2 or 6)``."""
    if dr is None:
        return np.stack([r, n], -1)
    return np.concatenate([r[..., None], n[..., None], dr, dn], -1)


def is_singular(J, tol):
    """Whether s_min / s_max of the column-equilibrated ``J (m, 5, 5)`` is below ``tol`` (line contact).

    Certificates first, an SVD only where they do not decide: with unit columns s_max >= 1 and, for the triangular
    factor R of a QR decomposition, s_min <= min_k |R_kk| (an eigenvalue of R bounds s_min from above): singular
    when min_k |R_kk| < tol; regular when |det| = prod_k |R_kk| > 5^2.5 tol
    (see :func:`spiralbevel._core.tca_step.step`). Compiled: :func:`spiralbevel._core.tca_solve.singular_batch`.
    Non-finite systems are not singular.
    """
    from . import tca_solve  # numba stays off the import path of the modules that only need the numpy helpers

    J = np.ascontiguousarray(J, float)
    return tca_solve.singular_batch(J.reshape((-1,) + J.shape[-2:]), float(tol)).reshape(J.shape[:-2])
