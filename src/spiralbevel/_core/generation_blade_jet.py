"""Compiled first-order jet of a face-milled generated flank in the (phi, psi_c) chart: point, outward normal and
their derivatives w.r.t. the cutter angle phi and the cradle angle psi_c.

The same mathematics as :func:`spiralbevel._core.generation_blade.blade_jet` (docs/theory/generation.md, Eqs.
(G5)-(G9); seed 001 Eqs. (11)-(15)), written per point: the blade parameter u solved from the equation of meshing of
generation ``f(u, phi, psi_c) = P cos(phi) + Q sin(phi) + R = 0`` (one exact step for a straight blade, Newton for an
arc blade), then implicit differentiation u_phi = -f_phi / f_u, u_psi = -f_psi / f_u and the chain rule through the
cradle, the blank offset and the work rotation psi_i(psi_c). The result is mapped to the member frame of the member
itself: the mirror image y -> -y of a right-hand member, then the phasing turn about +z
(``GeneratedSurface._Rm``).

The jet is written into ``out (3, 6)`` with the columns (r, n, r_phi, r_psi, n_phi, n_psi), mm and 1/rad: the layout
of :mod:`spiralbevel._core.jets` (kind :data:`~spiralbevel._core.jets.GENERATED`), which the compiled TCA Newton reads.
Where the chart is singular (f_u = 0, u not finite) every entry is NaN.

``prm`` is a flat float vector built by :func:`parameters` from the kernel dicts ``cp``, ``mp`` of
:mod:`spiralbevel._core.generation` (every machine motion of ``MachineSettings.kernel_params``: modified roll, blank
offset polynomial, piecewise-linear or cubic offset table, a scalar offset rate).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["parameters", "blade_jet_u", "blade_jet_point", "jet_batch"]

# layout of prm: fixed head, then the variable-length roll, polynomial and table coefficients
_S_BLADE, _RH, _CHI0, _RP, _RC, _ZC, _UP, _UJ = 0, 1, 2, 3, 4, 5, 6, 7
_S, _Q, _G, _XB, _XD, _M, _E, _MIRROR, _CROT, _SROT = 8, 9, 10, 11, 12, 13, 14, 15, 16, 17
_NROLL, _NPOLY, _NTAB, _TABKIND, _ERATE = 18, 19, 20, 21, 22
_HEAD = 23


def parameters(cp, mp, mirror, rotation):
    """Parameter vector ``prm (k,) float`` of :func:`blade_jet_point`, or None when the offset law is per system
    (``mp["E"]`` or ``mp["E_rate"]`` an array, as batched synthesis solvers use it), which this kernel does not take.

    Parameters
    ----------
    cp, mp : dict
        Cutter and machine parameters (:mod:`spiralbevel._core.generation`).
    mirror : bool
        Mirror image y -> -y (right-hand member).
    rotation : float, rad
        Phasing turn about +z.
    """
    rate = mp.get("E_rate")
    if np.ndim(mp["E"]) or np.ndim(rate if rate is not None else 0.0):
        return None
    roll = [float(c) for c in mp["roll"]]
    poly = [float(c) for c in mp["E_poly"]]
    table = mp.get("E_table")
    nodes, values, second, kind = [], [], [], 0
    if table is not None and len(table[0]):
        nodes, values = [float(v) for v in table[0]], [float(v) for v in table[1]]
        kind = 1
        if len(table) > 2 and table[2] is not None:
            second, kind = [float(v) for v in table[2]], 2
    if len(roll) > 4:
        raise ValueError(f"modified roll: {len(roll)} coefficients, at most 4 (2C, 6D, 24E, 120F)")
    head = [cp["s"], cp["Rh"], cp["chi0"], cp["rp"], cp["rc"], cp["zc"], cp["up"], cp["u_j"],
            mp["S"], mp["q"], mp["gamma"], mp["XB"], mp["XD"], mp["m"], float(mp["E"]),
            -1.0 if mirror else 1.0, math.cos(rotation), math.sin(rotation),
            len(roll), len(poly), len(nodes), kind, 0.0 if rate is None else float(rate)]
    return np.array(head + roll + poly + nodes + values + second, float)


@kernel(inline="always")
def _roll_offset(prm, p):
    """Work rotation psi_i, its rate w, dw/dpsi_c and the blank offset E, dE, ddE at cradle angle p
    (``generation.roll`` and ``generation.offset``)."""
    nroll, npoly, ntab, kind = int(prm[_NROLL]), int(prm[_NPOLY]), int(prm[_NTAB]), int(prm[_TABKIND])
    psi_i, w, dw = p, 1.0, 0.0
    fact = 1.0
    for k in range(nroll):  # term -c_k p^n / n!, n = k + 2
        n = k + 2
        fact *= n
        ck = prm[_HEAD + k]
        psi_i -= ck * p ** n / fact
        w -= ck * p ** (n - 1) / fact * n
        dw -= ck * p ** (n - 2) / fact * n * (n - 1)
    m = prm[_M]
    psi_i, w, dw = m * psi_i, m * w, m * dw
    E, dE, ddE = prm[_E], 0.0, 0.0
    if npoly > 0:  # Horner on (E, c_1, ..., c_n) and its first two derivatives
        o = _HEAD + nroll
        E, dE, ddE = prm[o + npoly - 1], 0.0, 0.0
        for j in range(npoly - 2, -2, -1):
            c = prm[o + j] if j >= 0 else prm[_E]
            ddE = ddE * p + 2.0 * dE
            dE = dE * p + E
            E = E * p + c
    if ntab > 0:
        o = _HEAD + nroll + npoly
        x, y = prm[o:o + ntab], prm[o + ntab:o + 2 * ntab]
        if kind == 1:
            # at a node the segment on the side of psi_c = 0 (generation.table_offset)
            hi = 0
            if p >= 0.0:
                while hi < ntab and x[hi] < p:
                    hi += 1
            else:
                while hi < ntab and x[hi] <= p:
                    hi += 1
            i = min(max(hi - 1, 0), ntab - 2)
            slope = (y[i + 1] - y[i]) / (x[i + 1] - x[i])
            E += y[i] + slope * (p - x[i])
            dE += slope
        else:
            M = prm[o + 2 * ntab:o + 3 * ntab]
            hi = 0
            while hi < ntab and x[hi] <= p:
                hi += 1
            i = min(max(hi - 1, 0), ntab - 2)
            h = x[i + 1] - x[i]
            b = (y[i + 1] - y[i]) / h - h * (2 * M[i] + M[i + 1]) / 6
            pc = min(max(p, x[0]), x[ntab - 1])
            t = pc - x[i]
            k3 = (M[i + 1] - M[i]) / h
            tE = y[i] + t * (b + t * (M[i] / 2 + t * k3 / 6))
            tdE = b + t * (M[i] + t * k3 / 2)
            tddE = M[i] + t * k3
            if p < x[0] or p > x[ntab - 1]:  # linear continuation with the end value and slope
                tE += tdE * (p - pc)
                tddE = 0.0
            E, dE, ddE = E + tE, dE + tdE, ddE + tddE
    rate = prm[_ERATE]
    if rate != 0.0:
        E, dE = E + rate * p, dE + rate
    return psi_i, w, dw, E, dE, ddE


@kernel(inline="always")
def _profile(prm, u):
    """Blade meridian (straight or arc) extended past the fillet junction: rho, z, chi, d(chi)/du."""
    s, rp = prm[_S_BLADE], prm[_RP]
    if math.isinf(rp):
        chi0 = prm[_CHI0]
        return prm[_RH] + s * u * math.cos(chi0), -u * math.sin(chi0), chi0, 0.0
    chi = prm[_CHI0] - (u - prm[_UP]) / rp
    return prm[_RC] - rp * s * math.sin(chi), prm[_ZC] - rp * math.cos(chi), chi, -1.0 / rp


@kernel   # not inlined: called twice per jet (compile-time rule of _core/jit.py)
def _meshing(prm, u, c, sn, sb, cb, S, SOz, Ox, wx, wy, wz):
    """Profile at u and the equation of meshing f = P cos(phi) + Q sin(phi) + R with f_u
    (``generation_blade._terms``)."""
    s = prm[_S_BLADE]
    rho, z, chi, dchi = _profile(prm, u)
    nr, nc = math.sin(chi), math.cos(chi)
    nz = s * nc
    h = z * nr - rho * nz
    P = nr * (wx - SOz * sb)
    Q = nr * (SOz * cb + wy) - h * Ox
    R = nz * (S * Ox * sb + wz)
    nr_u, nz_u = nc * dchi, -s * nr * dchi
    P_u = nr_u * (wx - SOz * sb)
    Q_u = nr_u * (SOz * cb + wy) - (-1.0 + z * nr_u - rho * nz_u) * Ox
    R_u = nz_u * (S * Ox * sb + wz)
    return rho, z, dchi, nr, nc, nz, h, P, Q, P * c + Q * sn + R, P_u * c + Q_u * sn + R_u


@kernel   # not inlined: the one compiled copy of the jet that every caller links (_core/jit.py)
def blade_jet_u(prm, phi, psi, out):
    """Jet at one point (phi, psi_c) rad into ``out (3, 6)`` (see module); returns the blade parameter u (mm) and its
    derivatives (u_phi, u_psi) (mm/rad; NaN where the chart is singular): the fillet junction u = u_j is a flank
    boundary of edge contact (:mod:`spiralbevel._core.tca_edge`)."""
    s, S, g, XB, XD = prm[_S_BLADE], prm[_S], prm[_G], prm[_XB], prm[_XD]
    psi_i, w, dw, E, dE, ddE = _roll_offset(prm, psi)
    sg, cg = math.sin(g), math.cos(g)
    b0 = math.pi - prm[_Q] + psi
    sb, cb = math.sin(b0), math.cos(b0)
    c, sn = math.cos(phi), math.sin(phi)
    Ox, Oz, Ox_p, Oz_p = w * cg, 1.0 - w * sg, dw * cg, -dw * sg
    wx, wy, wz = -w * sg * E, -w * cg * XB - dE, -w * cg * E
    SOz = S * Oz
    # u from the equation of meshing: one exact step (straight blade, f linear in u) or Newton (arc blade), from the
    # fillet junction as generation_blade.blade_u
    u = prm[_UJ]
    n_it = 1 if math.isinf(prm[_RP]) else 8
    tol = 1e-14 * (1.0 + abs(prm[_RH]))
    for _ in range(n_it):
        f, f_u = _meshing(prm, u, c, sn, sb, cb, S, SOz, Ox, wx, wy, wz)[9:]
        du = -f / f_u
        u = u + du
        if not abs(du) > tol:
            break
    if not math.isfinite(u):
        for i in range(3):   # loops: a slice set-item compiles numba's broadcasting code into every caller
            for j in range(6):
                out[i, j] = math.nan
        return u, math.nan, math.nan
    rho, z, dchi, nr, nc, nz, h, P, Q, _, f_u = _meshing(prm, u, c, sn, sb, cb, S, SOz, Ox, wx, wy, wz)
    tt = dw * E + w * dE
    wx_p, wy_p, wz_p = -sg * tt, -cg * XB * dw - ddE, -cg * tt
    P_p = nr * (-S * (Oz_p * sb + Oz * cb) + wx_p)
    Q_p = nr * (S * (Oz_p * cb - Oz * sb) + wy_p) - h * Ox_p
    R_p = nz * (S * (Ox_p * sb + Ox * cb) + wz_p)
    u_phi, u_psi = -(Q * c - P * sn) / f_u, -(P_p * c + Q_p * sn + R_p) / f_u
    snr, snc = s * nr, s * nc
    ru0, ru1, ru2 = snc * c, snc * sn, -nr
    nu0, nu1, nu2 = -dchi * snc * c, -dchi * snc * sn, dchi * nr
    # machine-frame columns (r - A - X_D a, n, r_phi, r_psi, n_phi, n_psi), as generation_blade.blade_jet
    out[0, 0] = S * cb + rho * c + XD * cg
    out[1, 0] = S * sb + rho * sn - E
    out[2, 0] = z + (XB - XD * sg)
    out[0, 1] = -snr * c
    out[1, 1] = -snr * sn
    out[2, 1] = -nc
    out[0, 2] = -rho * sn + u_phi * ru0
    out[1, 2] = rho * c + u_phi * ru1
    out[2, 2] = u_phi * ru2
    out[0, 3] = -S * sb + u_psi * ru0
    out[1, 3] = S * cb - dE + u_psi * ru1
    out[2, 3] = u_psi * ru2
    out[0, 4] = snr * sn + u_phi * nu0
    out[1, 4] = -snr * c + u_phi * nu1
    out[2, 4] = u_phi * nu2
    out[0, 5] = u_psi * nu0
    out[1, 5] = u_psi * nu1
    out[2, 5] = u_psi * nu2
    # to the member frame: B^T then R_z(-psi_i) on every column
    ci, si = math.cos(psi_i), math.sin(psi_i)
    for j in range(6):
        v0, v1, v2 = out[0, j], out[1, j], out[2, j]
        xb = v0 * sg + v2 * cg
        out[0, j] = ci * xb + si * v1
        out[1, j] = -si * xb + ci * v1
        out[2, j] = -cg * v0 + sg * v2
    # the work turns by psi_i(psi_c): d/dpsi_i of R_z(-psi_i) v is (v_y, -v_x, 0)
    out[0, 3] += w * out[1, 0]
    out[1, 3] -= w * out[0, 0]
    out[0, 5] += w * out[1, 1]
    out[1, 5] -= w * out[0, 1]
    # the member's own frame: mirror y -> -y (right hand), then the phasing turn R_z(rotation)
    my, cr, sr = prm[_MIRROR], prm[_CROT], prm[_SROT]
    for j in range(6):
        x, y = out[0, j], my * out[1, j]
        out[0, j] = cr * x - sr * y
        out[1, j] = sr * x + cr * y
    return u, u_phi, u_psi


@kernel(inline="always")   # one statement: inlined, no compiled function (and no second copy of the jet) of its own
def blade_jet_point(prm, phi, psi, out):
    """Jet at one point (phi, psi_c) rad into ``out (3, 6)`` (see module); returns the blade parameter u (mm)."""
    return blade_jet_u(prm, phi, psi, out)[0]


@kernel
def jet_batch(prm, q, out, u):
    """:func:`blade_jet_point` at every row of ``q (m, 2)`` into ``out (m, 3, 6)`` and ``u (m,)``."""
    for i in range(q.shape[0]):
        u[i] = blade_jet_point(prm, q[i, 0], q[i, 1], out[i])
