"""Compiled location of blade points of a generated flank in the (phi, psi_c) chart.

* :func:`locate_axial_radius`: for every target (axial z, radius) mm, Newton on (phi, psi_c) rad for
  F = (radius(phi, psi_c) - radius, z(phi, psi_c) - axial) with the analytic Jacobian of the compiled jet
  (:mod:`spiralbevel._core.generation_blade_jet`: d radius / dq = (x x_q + y y_q) / radius, dz / dq = z_q).
* :func:`locate_R_u`: for every target (R, u) mm (R the cone-distance coordinate R = radius sin(delta) + z cos(delta)
  of the blank outline, u the blade parameter), F = (R(phi, psi_c) - R, u(phi, psi_c) - u); the R row analytic as
  above, the u row by central differences of the jet's u (step 1e-7 rad: truncation about 1e-13 mm, below the
  tolerance; the root is set by the residual, which is exact).
 The rules are those of the batched numpy Newton
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

__all__ = ["locate_axial_radius", "locate_R_u"]


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
def _step(J, F, p, q, max_step):
    """(p, q) + the capped Newton step -J^-1 F of a 2 x 2 system (non-finite components 0)."""
    det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
    d0 = -(J[1, 1] * F[0] - J[0, 1] * F[1]) / det
    d1 = -(J[0, 0] * F[1] - J[1, 0] * F[0]) / det
    if not math.isfinite(d0):
        d0 = 0.0
    if not math.isfinite(d1):
        d1 = 0.0
    scale = max(1.0, abs(d0) / max_step[0], abs(d1) / max_step[1])
    return p + d0 / scale, q + d1 / scale


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
            p, q = _step(J, F, p, q, max_step)
            uk = _residual(prm, p, q, axial[k], radius[k], S, F, J)
            r = _max2(F)
        x[k, 0], x[k, 1], u[k] = p, q, uk
        conv[k] = r < tol
        res[k] = r
    return x, u, conv, res


@kernel
def _residual_R_u(prm, phi, psi, R, ut, sd, cd, S, F, J):
    """F (2,), J (2, 2) of the (R, u) system at (phi, psi); returns u (mm)."""
    h = 1e-7
    up = blade_jet_point(prm, phi + h, psi, S)
    um = blade_jet_point(prm, phi - h, psi, S)
    J[1, 0] = (up - um) / (2 * h)
    up = blade_jet_point(prm, phi, psi + h, S)
    um = blade_jet_point(prm, phi, psi - h, S)
    J[1, 1] = (up - um) / (2 * h)
    u = blade_jet_point(prm, phi, psi, S)
    x, y, z = S[0, 0], S[1, 0], S[2, 0]
    rad = math.sqrt(x * x + y * y)
    F[0] = rad * sd + z * cd - R
    F[1] = u - ut
    for j in range(2):
        J[0, j] = sd * (x * S[0, 2 + j] + y * S[1, 2 + j]) / rad + cd * S[2, 2 + j]
    return u


@kernel
def locate_R_u(prm, x0, R, ut, sd, cd, tol, max_iter, max_step):
    """Newton from ``x0 (m, 2)`` (phi, psi_c) for every target ``R, ut (m,)`` mm; ``sd, cd`` = sin, cos of the
    member's pitch angle. Returns x (m, 2) rad, u (m,) mm, converged (m,) bool and the residual max-norm (m,) mm."""
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
        uk = _residual_R_u(prm, p, q, R[k], ut[k], sd, cd, S, F, J)
        r = _max2(F)
        it = 0
        while not r < tol and it < max_iter:
            it += 1
            p, q = _step(J, F, p, q, max_step)
            uk = _residual_R_u(prm, p, q, R[k], ut[k], sd, cd, S, F, J)
            r = _max2(F)
        x[k, 0], x[k, 1], u[k] = p, q, uk
        conv[k] = r < tol
        res[k] = r
    return x, u, conv, res
