"""Compiled location of blade points of a generated flank in the (phi, psi_c) chart.

* :func:`locate_axial_radius`: for every target (axial z, radius) mm, Newton on (phi, psi_c) rad for
  F = (radius(phi, psi_c) - radius, z(phi, psi_c) - axial) with the analytic Jacobian of the compiled jet
  (:mod:`spiralbevel._core.generation_blade_jet`: d radius / dq = (x x_q + y y_q) / radius, dz / dq = z_q).
* :func:`locate_R_u`: for every target (R, u) mm (R the cone-distance coordinate R = radius sin(delta) + z cos(delta)
  of the blank outline, u the blade parameter), F = (R(phi, psi_c) - R, u(phi, psi_c) - u); the R row analytic as
  above, the u row the jet's implicit derivatives u_phi = -f_phi / f_u, u_psi = -f_psi / f_u.
* :func:`locate_rows`: rows of targets (axial z, radius), each row's Newton started from the solutions of the row
  before, with the acceptance rule of ``BladeLocator`` (:func:`on_branch`).
 The rules are those of the batched numpy Newton
(:func:`spiralbevel._core.newton.solve_batched`) the locator used before: the step capped per unknown
(``max_step``), a non-finite step component set to 0 (a singular 2 x 2 system gives a zero step), a system frozen
once max|F| < tol (mm), at most ``max_iter`` iterations; where the chart is singular (u not finite) F is NaN and the
system does not converge.
"""

from __future__ import annotations

import math

import numpy as np

from .generation_blade_jet import _E, _Q, _S, blade_jet_point, blade_jet_u
from .jit import kernel

__all__ = ["axial_radius", "locate_axial_radius", "locate_R_u", "locate_rows", "on_branch"]


@kernel(inline="always")
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


@kernel(inline="always")
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


@kernel(inline="always")
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
        x[k, 0], x[k, 1], u[k], res[k] = _newton_axial_radius(prm, x[k, 0], x[k, 1], axial[k], radius[k], tol,
                                                              max_iter, max_step, S, F, J)
        conv[k] = res[k] < tol
    return x, u, conv, res


@kernel
def _newton_axial_radius(prm, p, q, axial, radius, tol, max_iter, max_step, S, F, J):
    """Newton of :func:`locate_axial_radius` for one target from (p, q) = (phi, psi_c): returns phi, psi_c, u and the
    residual max-norm."""
    it = 0
    while True:   # one call site of each inlined helper
        uk = _residual(prm, p, q, axial, radius, S, F, J)
        r = _max2(F)
        if r < tol or not it < max_iter:
            return p, q, uk, r
        it += 1
        p, q = _step(J, F, p, q, max_step)


@kernel(inline="always")
def _reference_angle(prm, Rc, psi):
    """Absolute cutter angle toward the contact zone at cradle angle psi_c (``generation.reference_angle``)."""
    S, q, E = prm[_S], prm[_Q], prm[_E]
    b0 = math.pi - q + psi
    d2 = Rc ** 2 - (S * math.sin(q) - E) ** 2
    if d2 > 0.0:
        xr = -S * math.cos(q) - math.sqrt(d2)
        return math.atan2(E - S * math.sin(b0), xr - S * math.cos(b0))
    return psi - 0.5 * math.pi


@kernel(inline="always")
def _in_window(prm, Rc, phi_span, p, q):
    """True where the cutter angle p lies within phi_span (rad) of the reference angle at cradle angle q."""
    d = p - _reference_angle(prm, Rc, q)
    return abs(math.atan2(math.sin(d), math.cos(d))) <= phi_span


@kernel
def on_branch(prm, Rc, phi_span, x, u):
    """``BladeLocator.on_branch`` for ``x (m, 2)`` (phi, psi_c) with blade parameters ``u (m,)`` mm: u finite and the
    cutter angle within ``phi_span`` (rad) of the reference angle (``Rc`` the cutter's nominal radius, mm)."""
    m = x.shape[0]
    ok = np.empty(m, np.bool_)
    for k in range(m):
        ok[k] = math.isfinite(u[k]) and _in_window(prm, Rc, phi_span, x[k, 0], x[k, 1])
    return ok


@kernel
def axial_radius(prm, x):
    """Axial position z and radius (m,) mm of the blade points ``x (m, 2)`` (phi, psi_c), and their u (m,) mm."""
    m = x.shape[0]
    ax, rad, u = np.empty(m), np.empty(m), np.empty(m)
    S = np.empty((3, 6))
    for k in range(m):
        u[k] = blade_jet_point(prm, x[k, 0], x[k, 1], S)
        ax[k], rad[k] = S[2, 0], math.sqrt(S[0, 0] ** 2 + S[1, 0] ** 2)
    return ax, rad, u


@kernel
def locate_rows(prm, x0, axial, radius, tol, max_iter, max_step, Rc, phi_span, u_min):
    """Rows of blade points, each located from the row before: ``axial, radius (n, m)`` mm, row 0 from ``x0 (n, 2)``
    (phi, psi_c), row k from the solutions of row k - 1 (the Newton of :func:`locate_axial_radius`).

    A solution is accepted where it converged, its u is at least ``u_min`` (mm) and its cutter angle lies within
    ``phi_span`` (rad) of the reference angle toward the contact zone (the cutter nominal radius ``Rc``, mm):
    ``BladeLocator.on_branch``. The rows stop at the first row with a point not accepted. Returns x (n, m, 2) rad,
    u (n, m) mm and the number of rows accepted in full."""
    n, m = axial.shape
    x = np.empty((n, m, 2))
    u = np.empty((n, m))
    S = np.empty((3, 6))
    F = np.empty(2)
    J = np.empty((2, 2))
    for k in range(m):
        for i in range(n):
            p, q = (x0[i, 0], x0[i, 1]) if k == 0 else (x[i, k - 1, 0], x[i, k - 1, 1])
            p, q, uk, r = _newton_axial_radius(prm, p, q, axial[i, k], radius[i, k], tol, max_iter, max_step,
                                               S, F, J)
            x[i, k, 0], x[i, k, 1], u[i, k] = p, q, uk
            if not (r < tol and uk >= u_min and _in_window(prm, Rc, phi_span, p, q)):
                return x, u, k
    return x, u, m


@kernel(inline="always")
def _residual_R_u(prm, phi, psi, R, ut, sd, cd, S, F, J):
    """F (2,), J (2, 2) of the (R, u) system at (phi, psi); returns u (mm)."""
    u, u_phi, u_psi = blade_jet_u(prm, phi, psi, S)
    x, y, z = S[0, 0], S[1, 0], S[2, 0]
    rad = math.sqrt(x * x + y * y)
    F[0] = rad * sd + z * cd - R
    F[1] = u - ut
    for j in range(2):
        J[0, j] = sd * (x * S[0, 2 + j] + y * S[1, 2 + j]) / rad + cd * S[2, 2 + j]
    J[1, 0], J[1, 1] = u_phi, u_psi
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
        it = 0
        while True:   # one call site of each inlined helper
            uk = _residual_R_u(prm, p, q, R[k], ut[k], sd, cd, S, F, J)
            r = _max2(F)
            if r < tol or not it < max_iter:
                break
            it += 1
            p, q = _step(J, F, p, q, max_step)
        x[k, 0], x[k, 1], u[k] = p, q, uk
        conv[k] = r < tol
        res[k] = r
    return x, u, conv, res
