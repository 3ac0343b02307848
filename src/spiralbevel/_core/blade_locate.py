"""Compiled location of blade points of a generated flank on circles about the member axis, in the (phi, psi_c) chart.

For every target (axial z, radius) mm: Newton on (phi, psi_c) rad for F = (radius(phi, psi_c) - radius,
z(phi, psi_c) - axial) with the analytic Jacobian of the compiled jet (:mod:`spiralbevel._core.generation_blade_jet`:
d radius / dq = (x x_q + y y_q) / radius, dz / dq = z_q). The rules are those of the batched numpy Newton
(:func:`spiralbevel._core.newton.solve_batched`) the locator used before: the step capped per unknown
(``max_step``), a non-finite step component set to 0 (a singular 2 x 2 system gives a zero step), a system frozen
once max|F| < tol (mm), at most ``max_iter`` iterations; where the chart is singular (u not finite) F is NaN and the
system does not converge.
"""

from __future__ import annotations

import math

import numpy as np

from .generation_blade_jet import blade_jet_point
from .jit import kernel

__all__ = ["locate_axial_radius"]


@kernel
def _residual(prm, phi, psi, axial, radius, S, F, J):
    """F (2,), J (2, 2) at (phi, psi); returns u (mm)."""
    u = blade_jet_point(prm, phi, psi, S)
    x, y, z = S[0, 0], S[1, 0], S[2, 0]
    rad = math.sqrt(x * x + y * y)
    F[0] = rad - radius
    F[1] = z - axial
    for j in range(2):
        J[0, j] = (x * S[0, 2 + j] + y * S[1, 2 + j]) / rad
        J[1, j] = S[2, 2 + j]
    return u


@kernel
def _max2(F):
    """max(|F_0|, |F_1|), NaN if either is NaN (as numpy's max)."""
    a0, a1 = abs(F[0]), abs(F[1])
    if a0 != a0 or a1 != a1:
        return math.nan
    return a0 if a0 > a1 else a1


@kernel
def locate_axial_radius(prm, x0, axial, radius, tol, max_iter, max_step):
    """Newton from ``x0 (m, 2)`` (phi, psi_c) for every target ``axial, radius (m,)`` mm.

    Returns x (m, 2) rad, u (m,) mm, converged (m,) bool and the residual max-norm (m,) mm."""
    m = x0.shape[0]
    x = x0.copy()
    u = np.empty(m)
    conv = np.zeros(m, np.bool_)
    res = np.empty(m)
    S = np.empty((3, 6))
    F = np.empty(2)
    J = np.empty((2, 2))
    for k in range(m):
        p, q = x[k, 0], x[k, 1]
        uk = _residual(prm, p, q, axial[k], radius[k], S, F, J)
        r = _max2(F)
        it = 0
        while not r < tol and it < max_iter:
            it += 1
            det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
            d0 = -(J[1, 1] * F[0] - J[0, 1] * F[1]) / det
            d1 = -(J[0, 0] * F[1] - J[1, 0] * F[0]) / det
            if not math.isfinite(d0):
                d0 = 0.0
            if not math.isfinite(d1):
                d1 = 0.0
            scale = max(1.0, abs(d0) / max_step[0], abs(d1) / max_step[1])
            p += d0 / scale
            q += d1 / scale
            uk = _residual(prm, p, q, axial[k], radius[k], S, F, J)
            r = _max2(F)
        x[k, 0], x[k, 1], u[k] = p, q, uk
        conv[k] = r < tol
        res[k] = r
    return x, u, conv, res
