"""Compiled batched Newton of the multi-point control systems (seed 001 Eqs. (16)-(17), docs/theory/tca.md, Eqs. (T5),
(T8)): one 6 x 6 system per control point, and the continuation march that traces the contact of a synthesized pair.

Unknowns z = (phi_1, psi_c1, phi_2, psi_c2, phi2, E_m1): the absolute cutter angles and cradle angles of generation of
the contact point on the pinion and on the gear (the (phi, psi_c) chart of the compiled generated-flank jet,
:mod:`spiralbevel._core.generation_blade_jet`, in which the blade parameter u is solved from the equation of meshing of
generation), the gear rotation (rad) and the pinion's instantaneous blank offset (mm, user sign of
``MachineSettings.blank_offset``). Equations, all in mm:

    o1 + R_z(phi1_mean + x) r1 - o2 - G(phi2) r2 = 0                         (3)
    L (R_z(phi1_mean + x) n1 + G(phi2) n2) . t_a = 0,   ... . t_b = 0         (2)
    L (D [-(phi2 - phi2_ref) - (z1/z2) x] - target) = 0                        (1; Eq. (17))

with G(phi2) = R(a2, phi2) R_y(S) (gear member frame -> fixed frame, docs/conventions.md), a2 = (sin S, 0, cos S),
o1, o2 the member-frame origins (pitch apexes) in the fixed frame: zero for intersecting axes; for a hypoid pair
(``HypoidPairKinematics``, crossed axes at the offset E) o1 = (0, E, 0) + t1 a1 on the pinion axis and o2 = t2 a2 on
the gear axis, so that the pinion turns about a1 = +z through o1 and the gear about a2 through o2 (the axes pass
through the origins, which is why the rotation columns of the Jacobian do not change),
t_a, t_b two fixed unit vectors across the mean normal and L = |M|. For the mean contact point the last equation is
L (E_m1 - E_m10) = 0. The pinion is generated with the local offset law E(p) = E_m1 + E' (p - psi_c1) (user sign;
the kernel sign is negated, ``MachineSettings.kernel_params``), so its point depends on E_m1 and on the rate E' (given
per system) but not on how the law continues away from psi_c1: d/dpsi_c1 of the system is the jet's psi_c column plus
E' times the derivative w.r.t. the offset's constant term.

The Jacobian is analytic in the angles (the jet columns, and a2 x (G v) for phi2); the derivative w.r.t. the offset's
constant term is a central difference of the compiled jet (step 1e-6 mm: truncation about 1e-12 relative, far below
what Newton needs: the root is set by the residual, which is exact). The step is capped per unknown (``max_step``) and
solved by Gaussian elimination with partial pivoting; a non-finite step component is set to 0. A system is converged
when max|F| < tol (mm); converged systems are frozen, exactly as the batched numpy Newton
(:func:`spiralbevel._core.newton.solve_batched`) this replaces.

The flanks are the blades, continued past the fillet junction (the jet's profile): a contact with u < u_j is not on
the real flank, and the callers treat it so (``active_range`` stops there, ``multipoint_control`` refuses it). The
(phi, psi_c) chart does not continue onto the fillet: near the junction a cutter angle meets both the blade and the
fillet, so the fillet cannot be appended as a second branch of the same chart.
"""

from __future__ import annotations

import math

import numpy as np

from .generation_blade_jet import _E, _ERATE, blade_jet_point
from .jit import kernel
from .linalg import lu_solve

__all__ = ["solve_systems", "march"]

#: central-difference step of the offset's constant term, mm
_H_OFFSET = 1e-6


@kernel(inline="always")
def _gear_matrix(phi2, S, G):
    """G = R(a2, phi2) R_y(S), a2 = (sin S, 0, cos S), into ``G (3, 3)``."""
    a0, a1, a2 = math.sin(S), 0.0, math.cos(S)
    c, s = math.cos(phi2), math.sin(phi2)
    t = 1.0 - c
    R = np.empty((3, 3))
    R[0, 0] = c + a0 * a0 * t
    R[0, 1] = a0 * a1 * t - a2 * s
    R[0, 2] = a0 * a2 * t + a1 * s
    R[1, 0] = a1 * a0 * t + a2 * s
    R[1, 1] = c + a1 * a1 * t
    R[1, 2] = a1 * a2 * t - a0 * s
    R[2, 0] = a2 * a0 * t - a1 * s
    R[2, 1] = a2 * a1 * t + a0 * s
    R[2, 2] = c + a2 * a2 * t
    cy, sy = math.cos(S), math.sin(S)   # R_y(S)
    for i in range(3):
        r0, r1, r2 = R[i, 0], R[i, 1], R[i, 2]
        G[i, 0] = r0 * cy - r2 * sy
        G[i, 1] = r1
        G[i, 2] = r0 * sy + r2 * cy


@kernel(inline="always")
def _pinion_jet(prm, phi, psi, cst, rate, out):
    """Pinion jet at (phi, psi_c) with the kernel-sign offset law E(p) = cst - rate p (``rate`` mm/rad in user sign);
    returns u (mm)."""
    prm[_E] = cst
    prm[_ERATE] = -rate
    return blade_jet_point(prm, phi, psi, out)


@kernel
def _system(prm1, prm2, z, x, target, rate, is_mean, c, F, J, uu, S1, S2, Sp, Sm, G):
    """F (6,) and J (6, 6) of one system at z (6,); u1, u2 into ``uu (2,)``. ``c`` holds the constants
    (phi1_mean, shaft angle, ratio z1/z2, drive sign, phi2_ref, L, E_m10, t_a (3), t_b (3), o1 (3), o2 (3))."""
    phi1m, S, ratio, drive, phi2_ref, L, off0 = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    cst = -z[5] + rate * z[1]   # kernel constant term of the pinion's offset law
    h = _H_OFFSET
    _pinion_jet(prm1, z[0], z[1], cst + h, rate, Sp)
    _pinion_jet(prm1, z[0], z[1], cst - h, rate, Sm)
    uu[0] = _pinion_jet(prm1, z[0], z[1], cst, rate, S1)
    uu[1] = blade_jet_point(prm2, z[2], z[3], S2)
    ca, sa = math.cos(phi1m + x), math.sin(phi1m + x)
    _gear_matrix(z[4], S, G)
    a = (math.sin(S), 0.0, math.cos(S))
    for k in range(6):
        F[k] = 0.0
        for j in range(6):
            J[k, j] = 0.0
    d_r = np.empty(3)
    d_n = np.empty(3)
    for i in range(3):
        d_r[i] = -(Sp[i, 0] - Sm[i, 0]) / (2 * h)    # d r1 / d E_m1 (user sign: the constant term is -E_m1)
        d_n[i] = -(Sp[i, 1] - Sm[i, 1]) / (2 * h)
    # member-frame columns of the pinion: phi, psi_c (total: + E' d/d(constant) = - E' d/dE_m1), E_m1
    P = np.empty((3, 8))
    for i in range(3):
        P[i, 0] = S1[i, 0]
        P[i, 1] = S1[i, 1]
        P[i, 2] = S1[i, 2]
        P[i, 3] = S1[i, 3] - rate * d_r[i]
        P[i, 4] = S1[i, 4]
        P[i, 5] = S1[i, 5] - rate * d_n[i]
        P[i, 6] = d_r[i]
        P[i, 7] = d_n[i]
    Pf = np.empty((3, 8))
    for j in range(8):
        Pf[0, j] = ca * P[0, j] - sa * P[1, j]
        Pf[1, j] = sa * P[0, j] + ca * P[1, j]
        Pf[2, j] = P[2, j]
    Gf = np.zeros((3, 6))   # gear columns in the fixed frame: r, n, r_phi, r_psi, n_phi, n_psi
    for j in range(6):
        for i in range(3):
            Gf[i, j] = G[i, 0] * S2[0, j] + G[i, 1] * S2[1, j] + G[i, 2] * S2[2, j]
    ta0, ta1, ta2, tb0, tb1, tb2 = c[7], c[8], c[9], c[10], c[11], c[12]
    sn = np.empty(3)
    for i in range(3):
        F[i] = c[13 + i] + Pf[i, 0] - c[16 + i] - Gf[i, 0]
        sn[i] = Pf[i, 1] + Gf[i, 1]
    F[3] = L * (sn[0] * ta0 + sn[1] * ta1 + sn[2] * ta2)
    F[4] = L * (sn[0] * tb0 + sn[1] * tb1 + sn[2] * tb2)
    if is_mean:
        F[5] = L * (z[5] - off0)
        J[5, 5] = L
    else:
        F[5] = L * (drive * (-(z[4] - phi2_ref) - ratio * x) - target)
        J[5, 4] = -L * drive
    # a2 x (G v) for v = r2, n2 (d/dphi2)
    gr0 = a[1] * Gf[2, 0] - a[2] * Gf[1, 0]
    gr1 = a[2] * Gf[0, 0] - a[0] * Gf[2, 0]
    gr2 = a[0] * Gf[1, 0] - a[1] * Gf[0, 0]
    gn0 = a[1] * Gf[2, 1] - a[2] * Gf[1, 1]
    gn1 = a[2] * Gf[0, 1] - a[0] * Gf[2, 1]
    gn2 = a[0] * Gf[1, 1] - a[1] * Gf[0, 1]
    gr = (gr0, gr1, gr2)
    gn = (gn0, gn1, gn2)
    for i in range(3):
        J[i, 0] = Pf[i, 2]
        J[i, 1] = Pf[i, 3]
        J[i, 2] = -Gf[i, 2]
        J[i, 3] = -Gf[i, 3]
        J[i, 4] = -gr[i]
        J[i, 5] = Pf[i, 6]
    # normal equations: columns of d(n1 + n2) projected on t_a, t_b
    for row, t0, t1, t2 in ((3, ta0, ta1, ta2), (4, tb0, tb1, tb2)):
        J[row, 0] = L * (Pf[0, 4] * t0 + Pf[1, 4] * t1 + Pf[2, 4] * t2)
        J[row, 1] = L * (Pf[0, 5] * t0 + Pf[1, 5] * t1 + Pf[2, 5] * t2)
        J[row, 2] = L * (Gf[0, 4] * t0 + Gf[1, 4] * t1 + Gf[2, 4] * t2)
        J[row, 3] = L * (Gf[0, 5] * t0 + Gf[1, 5] * t1 + Gf[2, 5] * t2)
        J[row, 4] = L * (gn[0] * t0 + gn[1] * t1 + gn[2] * t2)
        J[row, 5] = L * (Pf[0, 7] * t0 + Pf[1, 7] * t1 + Pf[2, 7] * t2)


@kernel(inline="always")
def _lu_step(J, F, dx):
    """dx = -J^-1 F (6 x 6, J and F overwritten, ``linalg.lu_solve``); NaN if singular."""
    if lu_solve(J, F, dx):
        for i in range(dx.size):
            dx[i] = -dx[i]
    else:
        for i in range(dx.size):
            dx[i] = math.nan


@kernel(inline="always")
def _max_abs(F):
    m = 0.0
    for i in range(F.shape[0]):
        a = abs(F[i])
        if not a <= m:      # NaN propagates
            m = a
    return m


@kernel
def _newton(prm1, prm2, z, x, target, rate, is_mean, c, max_step, tol, max_iter, uu):
    """Newton on one system from z (6,), in place; returns (converged, residual max-norm, iterations)."""
    F, J = np.empty(6), np.empty((6, 6))
    S1, S2, Sp, Sm = np.empty((3, 6)), np.empty((3, 6)), np.empty((3, 6)), np.empty((3, 6))
    G = np.empty((3, 3))
    dx = np.empty(6)
    it = 0
    while True:   # one call site of each inlined helper
        _system(prm1, prm2, z, x, target, rate, is_mean, c, F, J, uu, S1, S2, Sp, Sm, G)
        res = _max_abs(F)
        if res < tol or not it < max_iter:
            return res < tol, res, it
        it += 1
        _lu_step(J, F, dx)
        scale = 1.0
        for i in range(6):
            if not math.isfinite(dx[i]):
                dx[i] = 0.0
            scale = max(scale, abs(dx[i]) / max_step[i])
        for i in range(6):
            z[i] += dx[i] / scale


@kernel
def solve_systems(prm1, prm2, z0, x, target, rate, is_mean, c, max_step, tol, max_iter):
    """Newton on every system: prm1, prm2 the jet parameters of the pinion (offset entries overwritten per system)
    and of the gear; z0 (m, 6) starts, x, target, rate (m,), is_mean (m,) bool.

    Returns z (m, 6), u (m, 2) mm (blade parameters of the two contact points), converged (m,) bool,
    residual (m,) mm and the largest iteration count."""
    m = z0.shape[0]
    z = z0.copy()
    u = np.empty((m, 2))
    conv = np.zeros(m, np.bool_)
    res = np.empty(m)
    its = 0
    p1 = prm1.copy()
    for k in range(m):
        ok, r, it = _newton(p1, prm2, z[k], x[k], target[k], rate[k], is_mean[k], c, max_step, tol, max_iter, u[k])
        conv[k], res[k] = ok, r
        its = max(its, it)
    return z, u, conv, res, its


@kernel
def march(prm1, prm2, z0, xs, c, max_step, tol, max_iter):
    """Trace the contact with zero TE target and constant offset (E' = 0, mean equation on E_m1) from z0 (6,) at
    every station of ``xs (n_sides, n)`` in turn, each from a secant predictor of the two previous ones (z0 counting
    as the station before the first; the first from z0 itself). A side stops at its first station without convergence.

    Returns z (n_sides, n, 6), u (n_sides, n, 2) mm and ``count (n_sides,)``, the number of converged stations."""
    ns, n = xs.shape
    z = np.empty((ns, n, 6))
    u = np.empty((ns, n, 2))
    count = np.zeros(ns, np.int64)
    p1 = prm1.copy()
    y = np.empty(6)
    mean = np.zeros(1, np.bool_)   # the mean equation as a bool read from an array: a literal True would compile
    mean[0] = True                 # _newton and _system a second time (for Literal[bool](True))
    for s in range(ns):
        for k in range(n):
            for i in range(6):
                if k == 0:
                    y[i] = z0[i]
                elif k == 1:
                    y[i] = 2 * z[s, 0, i] - z0[i]
                else:
                    y[i] = 2 * z[s, k - 1, i] - z[s, k - 2, i]
            ok, r, it = _newton(p1, prm2, y, xs[s, k], 0.0, 0.0, mean[0], c, max_step, tol, max_iter, u[s, k])
            for i in range(6):   # a loop: an array-to-array set-item compiles numba's broadcasting checks
                z[s, k, i] = y[i]
            if not ok:
                break
            count[s] = k + 1
    return z, u, count
