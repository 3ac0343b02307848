"""Compiled flank points of a face-milled generated member: point, outward normal, principal curvatures and
directions at given surface parameters (u, phi, psi_c) that satisfy the equation of meshing.

Per point, the mathematics of the numpy kernels of :mod:`spiralbevel._core.generation` (docs/theory/generation.md,
Eqs. (G1)-(G8), seed 001 Eqs. (7)-(15)): the blade meridian at u (edge-radius fillet for u < u_j, straight or arc
blade above), the cutter point and normal in the machine frame (``machine_state``), mapped to the member frame; the
principal curvatures and directions of the generated flank by the curvature transfer from the cutter surface
(docs/theory/generation.md, Eqs. (G13)-(G15), Litvin and Fuentes, Ch. 8: ``transfer_curvature`` with the relative
velocity of ``relative_velocity``), then ordered as ``FlankPoints`` states: k1 along the profile (the principal
direction most perpendicular to the position vector), e1 from root to top, e1 x e2 = n.

``prm`` is the parameter vector of :func:`spiralbevel._core.generation_blade_jet.parameters` (the mirror flag set for
a right-hand member, no phasing turn) and ``fil (3,)`` = (rho_f, T, chi_j) of the edge-radius fillet
(``cutter_params``).
"""

from __future__ import annotations

import math

import numpy as np

from .generation_blade_jet import (_CHI0, _G, _MIRROR, _Q, _RC, _RH, _RP, _S, _S_BLADE, _UJ, _UP, _XB, _XD, _ZC,
                                   _roll_offset)
from .jit import kernel

__all__ = ["fillet_parameters", "flank_points"]


def fillet_parameters(cp) -> np.ndarray:
    """``fil (3,) float`` = (rho_f mm, T mm, chi_j rad) of the cutter dict ``cp`` (:func:`cutter_params`)."""
    return np.array([cp["rho_f"], cp["T"], cp["chi_j"]], float)


@kernel
def _profile(prm, fil, u):
    """Blade meridian at u: rho, z (mm), chi (rad), d chi / du (1/mm); the fillet torus below u_j
    (``generation.profile``)."""
    s, uj = prm[_S_BLADE], prm[_UJ]
    if u < uj:
        rf = fil[0]
        chi = fil[2] - (uj - u) / rf
        return fil[1] + s * rf * math.sin(chi), -rf * (1.0 - math.cos(chi)), chi, 1.0 / rf
    rp = prm[_RP]
    if math.isinf(rp):
        chi0 = prm[_CHI0]
        return prm[_RH] + s * u * math.cos(chi0), -u * math.sin(chi0), chi0, 0.0
    chi = prm[_CHI0] - (u - prm[_UP]) / rp
    return prm[_RC] - rp * s * math.sin(chi), prm[_ZC] - rp * math.cos(chi), chi, -1.0 / rp


@kernel
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@kernel
def _to_member(v0, v1, v2, sg, cg, ci, si, my):
    """Machine-frame direction to the member frame: B^T, R_z(-psi_i), then the mirror y -> my y
    (``generation.to_member`` with ``point=False``)."""
    xb = v0 * sg + v2 * cg
    return ci * xb + si * v1, my * (-si * xb + ci * v1), -v0 * cg + v2 * sg


@kernel(inline="always")   # one call site (flank_points): inlined there
def flank_point(prm, fil, u, phi, psi, curvature, out):
    """Flank point at (u, phi, psi_c) (mm, rad, rad) into ``out (4, 3)``: rows point (mm), outward unit normal, e1, e2
    (NaN unless ``curvature``); returns (k1, k2) in 1/mm (NaN unless ``curvature``)."""
    s, S, g, XB, XD, my = prm[_S_BLADE], prm[_S], prm[_G], prm[_XB], prm[_XD], prm[_MIRROR]
    psi_i, w, dw, E, dE, ddE = _roll_offset(prm, psi)
    sg, cg = math.sin(g), math.cos(g)
    ci, si = math.cos(psi_i), math.sin(psi_i)
    rho, z, chi, dchi = _profile(prm, fil, u)
    b0 = math.pi - prm[_Q] + psi
    c, sn = math.cos(phi), math.sin(phi)
    sc, cc = math.sin(chi), math.cos(chi)
    # machine frame: cutter point r, cutter normal n_h into the tooth material (n_in = s n_h), meridian tangent t_h
    r0, r1, r2 = S * math.cos(b0) + rho * c, S * math.sin(b0) + rho * sn, z
    ni0, ni1, ni2 = s * (sc * c), s * (sc * sn), s * (s * cc)
    t0, t1, t2 = s * cc * c, s * cc * sn, -sc
    # member point: r - A - X_D a with A = (0, E, -X_B), a = (-cos g, 0, sin g)
    out[0, 0], out[0, 1], out[0, 2] = _to_member(r0 + XD * cg, r1 - E, r2 + XB - XD * sg, sg, cg, ci, si, my)
    out[1, 0], out[1, 1], out[1, 2] = _to_member(-ni0, -ni1, -ni2, sg, cg, ci, si, my)
    if not curvature:
        for i in range(2, 4):   # loops: a slice set-item compiles numba's broadcasting code
            for j in range(3):
                out[i, j] = math.nan
        return math.nan, math.nan
    # generating surface: principal curvatures kI (meridian, along t_h), kII (parallel circle, along eII = n x t_h)
    kI, kII = -dchi, -s * sc / rho
    e0, e1, e2 = _cross(ni0, ni1, ni2, t0, t1, t2)
    # relative velocity at unit cradle rate (generation.relative_velocity): v12 = k x r - w a x (r - A) - E' j
    a0, a2 = -cg, sg
    d0, d1, d2 = r0, r1 - E, r2 + XB
    x0, x1, x2 = _cross(a0, 0.0, a2, d0, d1, d2)                # a x (r - A)
    v10, v11, v12_ = -r1, r0, 0.0                               # k x r
    v20, v21, v22 = w * x0, w * x1 + dE, w * x2
    u0, u1, u2 = v10 - v20, v11 - v21, v12_ - v22               # v12
    aj0, aj1, aj2 = _cross(a0, 0.0, a2, 0.0, 1.0, 0.0)          # a x j
    dt0, dt1, dt2 = -dw * x0 + w * dE * aj0, -dw * x1 + w * dE * aj1 - ddE, -dw * x2 + w * dE * aj2
    w20, w21, w22 = w * a0, 0.0, w * a2                         # w1 = k, w2 = w a
    m0, m1, m2 = -w20, -w21, 1.0 - w22                          # w12
    # curvature transfer (generation.transfer_curvature)
    vI, vII = u0 * t0 + u1 * t1 + u2 * t2, u0 * e0 + u1 * e1 + u2 * e2
    a13 = -kI * vI - (m0 * e0 + m1 * e1 + m2 * e2)
    a23 = -kII * vII + (m0 * t0 + m1 * t1 + m2 * t2)
    p0, p1, p2 = _cross(0.0, 0.0, 1.0, v20, v21, v22)
    q0, q1, q2 = _cross(w20, w21, w22, v10, v11, v12_)
    b = ni0 * (p0 - q0) + ni1 * (p1 - q1) + ni2 * (p2 - q2)
    b = b + (ni0 * dt0 + ni1 * dt1 + ni2 * dt2)
    y0, y1, y2 = _cross(m0, m1, m2, u0, u1, u2)
    a33 = kI * vI ** 2 + kII * vII ** 2 - (ni0 * y0 + ni1 * y1 + ni2 * y2) + b
    W11 = kI - a13 * a13 / a33
    W22 = kII - a23 * a23 / a33
    W12 = -a13 * a23 / a33
    mean, half = 0.5 * (W11 + W22), math.hypot(0.5 * (W11 - W22), W12)
    k_a, k_b = mean + half, mean - half
    ang = 0.5 * math.atan2(2.0 * W12, W11 - W22)               # eigenvector of k_a at angle ang from t_h
    ca, sa = math.cos(ang), math.sin(ang)
    da = _to_member(ca * t0 + sa * e0, ca * t1 + sa * e1, ca * t2 + sa * e2, sg, cg, ci, si, my)
    db = _to_member(-sa * t0 + ca * e0, -sa * t1 + ca * e1, -sa * t2 + ca * e2, sg, cg, ci, si, my)
    # order: k1 along the profile (direction most perpendicular to the point's position vector), e1 root -> top
    px, py, pz = out[0, 0], out[0, 1], out[0, 2]
    pn = math.sqrt(px * px + py * py + pz * pz)
    h0, h1, h2 = px / pn, py / pn, pz / pn
    if abs(da[0] * h0 + da[1] * h1 + da[2] * h2) <= abs(db[0] * h0 + db[1] * h1 + db[2] * h2):
        k1, k2, f = k_a, k_b, da
    else:
        k1, k2, f = k_b, k_a, db
    rn = math.sqrt(px * px + py * py)
    g0, g1 = px / rn, py / rn                                  # radial unit vector
    gr = g0 * h0 + g1 * h1
    up0, up1, up2 = g0 - gr * h0, g1 - gr * h1, -gr * h2       # away from the axis in the axial plane, normal to r
    sgn = -1.0 if f[0] * up0 + f[1] * up1 + f[2] * up2 < 0.0 else 1.0
    out[2, 0], out[2, 1], out[2, 2] = sgn * f[0], sgn * f[1], sgn * f[2]
    out[3, 0], out[3, 1], out[3, 2] = _cross(out[1, 0], out[1, 1], out[1, 2], out[2, 0], out[2, 1], out[2, 2])
    return k1, k2


@kernel
def flank_points(prm, fil, u, phi, psi, curvature):
    """:func:`flank_point` at every entry of ``u, phi, psi (m,)``: returns points, normals, e1, e2 (m, 3) and k1, k2
    (m,)."""
    m = u.shape[0]
    P, N, E1, E2 = np.empty((m, 3)), np.empty((m, 3)), np.empty((m, 3)), np.empty((m, 3))
    k1, k2 = np.empty(m), np.empty(m)
    out = np.empty((4, 3))
    for i in range(m):
        k1[i], k2[i] = flank_point(prm, fil, u[i], phi[i], psi[i], curvature, out)
        for j in range(3):
            P[i, j], N[i, j], E1[i, j], E2[i, j] = out[0, j], out[1, j], out[2, j], out[3, j]
    return P, N, E1, E2, k1, k2
