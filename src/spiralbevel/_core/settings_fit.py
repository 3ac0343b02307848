"""Compiled residual and Newton of the pinion settings fit (``meshing.synthesis.machine_fit``).

The residual maps seven unknowns -- six machine/cutter quantities and the cutter angle theta of the point at the
cradle angle psi_c = 0 -- to the seven rotation-invariant quantities of the generated point (axial position, radius,
axial and radial normal components, curvature tensor components K_aa, K_ab, K_bb in the tangent basis of
``meshing.synthesis._relations.tangent_components``), minus the goal, times the weights.

The point, its outward normal and their first derivatives in the (phi, psi_c) chart come from the compiled jet
:func:`~spiralbevel._core.generation_blade_jet.blade_jet_u`. The curvature tensor follows from that first-order jet
alone by Weingarten's relation: the shape operator K = dn/dr (outward normal, convex = positive) maps r_phi to n_phi
and r_psi to n_psi, so for a tangent vector t = a r_phi + b r_psi, (a, b) = G^-1 (r_phi . t, r_psi . t) with the
first fundamental form G, and K t = a n_phi + b n_psi. This is the same tensor as the curvature-transfer relations of
the enveloping process (docs/theory/generation.md, Eqs. (G13)-(G15)) give; the tests compare both.

Unknown codes (``codes (6,) int64``): 0 cutter point radius R_h (mm), 1 blade angle alpha (rad), 2 radial setting S
(mm), 3 cradle angle q (rad), 4 machine root angle gamma (rad), 5 machine centre to back X_D (mm), 6 sliding base X_B
(mm), 7 blank offset E_m (mm; the kernel's E is -E_m), 8 ratio of roll m (-), 9 modified roll 2C (-, the first roll
coefficient of ``prm``, which must hold at least one). ``cut (5,) float`` = (s, rho_f, profile radius, profile ref,
point width W): the blade constants that, with R_h and alpha, give the derived blade constants of
``_core.generation.cutter_params``. Below the fillet junction the blade is continued (as in the jet's chart).
Where the cutter or the settings would be invalid (``HeadCutter`` and ``MachineSettings`` ranges) or the chart is
singular, every residual is ``BAD`` (large and finite: a Newton step into it is shortened).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .generation_blade_jet import (_CHI0, _E, _G, _HEAD, _M, _Q, _RC, _RH, _RP, _S, _UJ, _UP, _XB, _XD, _ZC,
                                   blade_jet_u)
from .jit import kernel
from .linalg import lu_solve

__all__ = ["BAD", "CODES", "invariants", "residual", "newton"]

BAD = 1e6

CODES = dict(point_radius=0, blade_angle=1, radial_setting=2, cradle_angle=3, machine_root_angle=4,
             machine_centre_to_back=5, sliding_base=6, blank_offset=7, ratio_of_roll=8, modified_roll=9)


@kernel(inline="always")
def _fill(a, v):
    """Every entry of ``a (n,)`` set to ``v`` (a loop: ``a[:] = v`` compiles numba's broadcasting set-item)."""
    for i in range(a.size):
        a[i] = v


@kernel(inline="always")
def _max_abs(f):
    """max |f_i| of ``f (n,)``, NaN if any entry is NaN (as ``np.max(np.abs(f))``)."""
    m = 0.0
    for i in range(f.size):
        a = abs(f[i])
        if math.isnan(a):
            return a
        m = max(m, a)
    return m


def _lstsq_py(J, f):
    return np.linalg.lstsq(J, -f, rcond=-1)[0]   # rcond=-1: machine precision, as numba's compiled lstsq had it


@kernel(nogil=False)   # it takes the GIL for the call-back (numba warns about nogil with object mode)
def _lstsq(J, f, dx):
    """dx = the least-squares solution of J dx = -f (``np.linalg.lstsq``) for a singular J: called back in Python
    (numba's compiled lstsq costs about 2 s of compile time for a branch that almost never runs)."""
    with numba.objmode(r="float64[:]"):
        r = _lstsq_py(J, f)
    for i in range(dx.size):
        dx[i] = r[i]


@kernel
def _set(prm0, cut, codes, x, prm):
    """Copy ``prm0`` into ``prm`` with the unknowns ``x[:6]`` set; False where the cutter or settings are invalid."""
    for i in range(prm0.size):
        prm[i] = prm0[i]
    Rh, alpha = prm0[_RH], 0.5 * math.pi - prm0[_CHI0]
    for k in range(6):
        c, v = codes[k], x[k]
        if c == 0:
            Rh = v
        elif c == 1:
            alpha = v
        elif c == 2:
            prm[_S] = v
        elif c == 3:
            prm[_Q] = v
        elif c == 4:
            prm[_G] = v
        elif c == 5:
            prm[_XD] = v
        elif c == 6:
            prm[_XB] = v
        elif c == 7:
            prm[_E] = -v
        elif c == 8:
            prm[_M] = v
        else:
            prm[_HEAD] = v
    for k in range(6):
        if not math.isfinite(x[k]):
            return False
    # MachineSettings ranges
    if not (prm[_S] > 0.0 and -math.pi <= prm[_Q] <= math.pi and 0.0 < prm[_G] < 0.5 * math.pi and prm[_M] > 0.0):
        return False
    # HeadCutter ranges: the edge radius takes at most half the point width and leaves a positive point radius
    s, rf, rp, up, width = cut[0], cut[1], cut[2], cut[3], cut[4]
    if not (Rh > 0.0 and 0.0 < alpha < 0.5 * math.pi):
        return False
    sa, ca = math.sin(alpha), math.cos(alpha)
    reach = rf * (1.0 - sa) / ca
    if reach > 0.5 * width or Rh - s * reach <= 0.0:
        return False
    chi0 = 0.5 * math.pi - alpha
    prm[_RH], prm[_CHI0] = Rh, chi0
    if math.isinf(rp):
        prm[_UJ] = rf * (1.0 - sa) / ca
    else:
        rc = Rh + s * up * sa + s * rp * ca
        zc = -up * ca + rp * sa
        chi_j = math.acos(min(max((zc + rf) / (rf + rp), -1.0), 1.0))
        u_j = up + rp * (chi0 - chi_j)
        if not 0.0 < chi_j < 0.5 * math.pi:    # the edge radius must join the arc
            return False
        prm[_RC], prm[_ZC], prm[_UP], prm[_UJ], prm[_RP] = rc, zc, up, u_j, rp
    return True


@kernel
def _point_invariants(jet, out):
    """Invariants (7,) of the jet ``(3, 6)`` into ``out``; returns the tangential normal component."""
    p0, p1, p2 = jet[0, 0], jet[1, 0], jet[2, 0]
    n0, n1, n2 = jet[0, 1], jet[1, 1], jet[2, 1]
    rad = math.sqrt(p0 * p0 + p1 * p1)
    h0, h1 = p0 / rad, p1 / rad
    # tangent basis: t_a = unit(z - (z.n) n), t_b = n x t_a
    a0, a1, a2 = -n2 * n0, -n2 * n1, 1.0 - n2 * n2
    na = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    a0, a1, a2 = a0 / na, a1 / na, a2 / na
    b0, b1, b2 = n1 * a2 - n2 * a1, n2 * a0 - n0 * a2, n0 * a1 - n1 * a0
    # first fundamental form of the (phi, psi_c) chart and its inverse
    g11 = g12 = g22 = 0.0
    for i in range(3):
        g11 += jet[i, 2] * jet[i, 2]
        g12 += jet[i, 2] * jet[i, 3]
        g22 += jet[i, 3] * jet[i, 3]
    det = g11 * g22 - g12 * g12
    i11, i12, i22 = g22 / det, -g12 / det, g11 / det
    # (r_phi . t, r_psi . t) and (n_phi . t, n_psi . t) for t = t_a, t_b
    ra0 = jet[0, 2] * a0 + jet[1, 2] * a1 + jet[2, 2] * a2
    ra1 = jet[0, 3] * a0 + jet[1, 3] * a1 + jet[2, 3] * a2
    rb0 = jet[0, 2] * b0 + jet[1, 2] * b1 + jet[2, 2] * b2
    rb1 = jet[0, 3] * b0 + jet[1, 3] * b1 + jet[2, 3] * b2
    na0 = jet[0, 4] * a0 + jet[1, 4] * a1 + jet[2, 4] * a2
    na1 = jet[0, 5] * a0 + jet[1, 5] * a1 + jet[2, 5] * a2
    nb0 = jet[0, 4] * b0 + jet[1, 4] * b1 + jet[2, 4] * b2
    nb1 = jet[0, 5] * b0 + jet[1, 5] * b1 + jet[2, 5] * b2
    # chart coordinates of t_a, t_b; then t . K t' = (coordinates of t') . (n_phi . t, n_psi . t)
    ca0, ca1 = i11 * ra0 + i12 * ra1, i12 * ra0 + i22 * ra1
    cb0, cb1 = i11 * rb0 + i12 * rb1, i12 * rb0 + i22 * rb1
    out[0] = p2
    out[1] = rad
    out[2] = n2
    out[3] = n0 * h0 + n1 * h1
    out[4] = ca0 * na0 + ca1 * na1
    out[5] = 0.5 * (cb0 * na0 + cb1 * na1 + ca0 * nb0 + ca1 * nb1)   # symmetric part (exact tensor: symmetric)
    out[6] = cb0 * nb0 + cb1 * nb1
    return -n0 * h1 + n1 * h0


@kernel(inline="always")   # one call site in kernels (residual): inlined there
def invariants(prm0, cut, codes, x, out):
    """Invariants (7,) of the generated point of the unknowns ``x (7,)`` into ``out``; returns (valid, n_t, u): the
    tangential normal component n_t and the blade parameter u (mm) of the point (NaN where not valid)."""
    prm = np.empty(prm0.size)
    jet = np.empty((3, 6))
    if not _set(prm0, cut, codes, x, prm) or not math.isfinite(x[6]):
        _fill(out, math.nan)
        return False, math.nan, math.nan
    u = blade_jet_u(prm, x[6] + math.pi - prm[_Q], 0.0, jet)[0]
    if not math.isfinite(u):
        _fill(out, math.nan)
        return False, math.nan, math.nan
    nt = _point_invariants(jet, out)
    for i in range(7):
        if not math.isfinite(out[i]):
            return False, math.nan, math.nan
    return True, nt, u


@kernel
def residual(prm0, cut, codes, x, goal, w, f):
    """(invariants(x) - goal) w into ``f (7,)``; every entry ``BAD`` where the point is not valid."""
    ok = invariants(prm0, cut, codes, x, f)
    if not ok[0]:
        _fill(f, BAD)
        return
    for i in range(7):
        f[i] = (f[i] - goal[i]) * w[i]


@kernel(inline="always")   # one call site (newton): inlined there
def jacobian(prm0, cut, codes, x, goal, w, rel_step, J):
    """Central-difference Jacobian (7, 7) of :func:`residual` at ``x`` into ``J`` (step rel_step max(1, |x_j|))."""
    fp, fm, xp = np.empty(7), np.empty(7), x.copy()
    for j in range(7):
        h = rel_step * max(1.0, abs(x[j]))
        xp[j] = x[j] + h
        residual(prm0, cut, codes, xp, goal, w, fp)
        xp[j] = x[j] - h
        residual(prm0, cut, codes, xp, goal, w, fm)
        xp[j] = x[j]
        for i in range(7):
            J[i, j] = (fp[i] - fm[i]) / (2.0 * h)


@kernel
def newton(prm0, cut, codes, x0, goal, w, max_step, tol, max_iter, rel_step):
    """Newton's method on :func:`residual` from ``x0``, the rules of ``_core.newton.solve_batched`` for one system:
    stop when max |f| < tol, a step whose largest |dx_j| / max_step_j exceeds 1 scaled down to 1, a singular or
    non-finite step replaced by least squares / zero. Returns (x, converged, iterations, residual)."""
    x = x0.copy()
    f = np.empty(7)
    J, A, b, dx = np.empty((7, 7)), np.empty((7, 7)), np.empty(7), np.empty(7)
    it = 0
    while True:   # one call site of the inlined _max_abs
        residual(prm0, cut, codes, x, goal, w, f)
        res = _max_abs(f)
        if res < tol or not it < max_iter:
            return x, res < tol, it, res
        it += 1
        jacobian(prm0, cut, codes, x, goal, w, rel_step, J)
        finite = True
        for j in range(7):
            b[j] = -f[j]
            for k in range(7):
                A[j, k] = J[j, k]
                finite = finite and math.isfinite(J[j, k])
        if not lu_solve(A, b, dx):
            if finite:
                _lstsq(J, f, dx)
            else:
                _fill(dx, 0.0)
        scale = 1.0
        for j in range(7):
            if not math.isfinite(dx[j]):
                dx[j] = 0.0
            scale = max(scale, abs(dx[j]) / max_step[j])
        for j in range(7):
            x[j] += dx[j] / scale
