"""First derivatives of a face-milled generated flank with respect to its parameters (u, psi_c), in closed form.

The generated point is r_i(u, psi_c) = M(psi_c) (r_m(u, phi, psi_c) - A(psi_c) - X_D a) with the cutter angle
phi(u, psi_c) the root of the equation of meshing P cos phi + Q sin phi + R = 0 of
:func:`spiralbevel._core.generation.solve_contact` (seed 001 Eqs. (11)-(15), docs/theory/generation.md, Eqs. (G5)-(G8)
(and (G13)-(G15) for curvatures)). Implicit differentiation
of that equation gives phi_u and phi_psi; the chain rule through the blade meridian (u is its arc length, so
d(rho, z)/du = (s cos chi, -sin chi), the meridian tangent t_h), the cradle, the blank offset and the work rotation
psi_i(psi_c) gives dr and dn. Same frames and conventions as :mod:`spiralbevel._core.generation`; the result is in the
member frame of the canonical (left-hand) machine, outward normal n = -s n_h (as ``Generator.evaluate``).

Pure functions on float64 arrays, mm and rad.
"""

from __future__ import annotations

import numpy as np

from .generation import offset, profile, reference_angle, roll

__all__ = ["generated_jet"]


def _to_member_stack(V, psi_i, g, a):
    """B^T then R_z(-psi_i) on every column of ``V (m, 3, k)`` (machine vectors -> member frame)."""
    xb = V[:, 0, :] * np.sin(g) + V[:, 2, :] * np.cos(g)
    yb = V[:, 1, :]
    out = np.empty_like(V)
    c, s = np.cos(psi_i)[:, None], np.sin(psi_i)[:, None]
    out[:, 0, :] = c * xb + s * yb
    out[:, 1, :] = -s * xb + c * yb
    out[:, 2, :] = a[0] * V[:, 0, :] + a[2] * V[:, 2, :]
    return out


def generated_jet(u, psi, cp, mp, Rc):
    """Points, outward normals and their derivatives w.r.t. (u, psi_c) of a generated flank.

    Parameters
    ----------
    u : (...) float, mm
        Blade parameter.
    psi : (...) float, rad
        Cradle angle (broadcast with ``u``).
    cp, mp : dict
        Cutter and machine parameters (see :mod:`spiralbevel._core.generation`).
    Rc : float, mm
        Nominal cutter radius (branch choice of the cutter angle, :func:`reference_angle`).

    Returns
    -------
    S : (..., 3, 6) float
        Columns r (mm), n (-), dr/du (-), dr/dpsi_c (mm/rad), dn/du (1/mm), dn/dpsi_c (1/rad), member frame of the
        canonical machine (no mirror, no phasing turn).
    disc : (...) float
        Discriminant of the equation of meshing; |disc| <= 1 where the flank exists (elsewhere the data are
        meaningless).
    """
    with np.errstate(divide="ignore", invalid="ignore"):  # f_phi = 0 only off the flank (|disc| >= 1)
        return _jet(u, psi, cp, mp, Rc)


def _roll_offset(psi, mp):
    """roll() and offset() with fast paths for plain roll and a constant blank offset (same values)."""
    if len(mp["roll"]):
        psi_i, w, dw = roll(psi, mp)
    else:
        psi_i, w, dw = mp["m"] * psi, mp["m"], 0.0
    if len(mp["E_poly"]) or mp.get("E_table") is not None or mp.get("E_rate") is not None:
        E, dE, ddE = offset(psi, mp)
    else:
        E, dE, ddE = mp["E"], 0.0, 0.0
    return psi_i, w, dw, E, dE, ddE


def meshing_coefficients(u, psi, cp, mp, meridian=None):
    """Coefficients of the equation of meshing of generation P cos phi + Q sin phi + R = 0 at (u, psi_c) and their
    partial derivatives w.r.t. u (``P_u`` ...) and psi_c (``P_p`` ...), with the pieces the jets reuse (meridian
    rho, z, chi, dchi of ``meridian(u, cp)`` (default :func:`profile`), roll and offset of the cradle angle).

    The derivative w.r.t. u uses d h/du = -1 + z nr_u - rho nz_u (the meridian tangent has unit length).
    """
    rho, z, chi, dchi = (meridian or profile)(u, cp)
    s, S, g, XB, q = cp["s"], mp["S"], mp["gamma"], mp["XB"], mp["q"]
    psi_i, w, dw, E, dE, ddE = _roll_offset(psi, mp)
    sg, cg = np.sin(g), np.cos(g)
    b0 = np.pi - q + psi
    sb, cb = np.sin(b0), np.cos(b0)
    Ox, Oz, Ox_p, Oz_p = w * cg, 1.0 - w * sg, dw * cg, -dw * sg
    wx, wy, wz = -w * sg * E, -w * cg * XB - dE, -w * cg * E
    nr, nc = np.sin(chi), np.cos(chi)
    nz = s * nc
    h = z * nr - rho * nz
    SOz = S * Oz
    P = nr * (wx - SOz * sb)
    Q = nr * (SOz * cb + wy) - h * Ox
    R = nz * (S * Ox * sb + wz)
    t = dw * E + w * dE
    wx_p, wy_p, wz_p = -sg * t, -cg * XB * dw - ddE, -cg * t
    nr_u, nz_u = nc * dchi, -s * nr * dchi
    P_u = nr_u * (wx - SOz * sb)
    Q_u = nr_u * (SOz * cb + wy) - (-1.0 + z * nr_u - rho * nz_u) * Ox
    R_u = nz_u * (S * Ox * sb + wz)
    P_p = nr * (-S * (Oz_p * sb + Oz * cb) + wx_p)
    Q_p = nr * (S * (Oz_p * cb - Oz * sb) + wy_p) - h * Ox_p
    R_p = nz * (S * (Ox_p * sb + Ox * cb) + wz_p)
    return dict(P=P, Q=Q, R=R, P_u=P_u, Q_u=Q_u, R_u=R_u, P_p=P_p, Q_p=Q_p, R_p=R_p, rho=rho, z=z, chi=chi,
                dchi=dchi, nr=nr, nc=nc, psi_i=psi_i, w=w, dw=dw, E=E, dE=dE, sb=sb, cb=cb, sg=sg, cg=cg)


def _jet(u, psi, cp, mp, Rc):
    u, psi = np.broadcast_arrays(np.asarray(u, float), np.asarray(psi, float))
    shape = u.shape
    u, psi = u.reshape(-1), psi.reshape(-1)
    s, S, g, XB, XD = cp["s"], mp["S"], mp["gamma"], mp["XB"], mp["XD"]
    C = meshing_coefficients(u, psi, cp, mp)
    P, Q, R = C["P"], C["Q"], C["R"]
    rho, z, dchi, nr, nc = C["rho"], C["z"], C["dchi"], C["nr"], C["nc"]
    psi_i, w, E, dE, sb, cb, sg, cg = C["psi_i"], C["w"], C["E"], C["dE"], C["sb"], C["cb"], C["sg"], C["cg"]
    # the root of the equation of meshing, as in solve_contact / reference_angle
    disc = -R / np.hypot(P, Q)
    half = np.arccos(np.clip(disc, -1.0, 1.0))
    base = np.arctan2(Q, P)
    ref = reference_angle(psi, mp, Rc)
    # the root nearer the reference angle: |wrap(base + half - ref)| <= |wrap(base - half - ref)| exactly when
    # sin(base - ref) sin(half) <= 0, and sin(half) >= 0
    phi = np.where(np.sin(base - ref) <= 0.0, base + half, base - half)
    cphi, sphi = np.cos(phi), np.sin(phi)
    # implicit derivatives of the root
    P_u, Q_u, R_u, P_p, Q_p, R_p = C["P_u"], C["Q_u"], C["R_u"], C["P_p"], C["Q_p"], C["R_p"]
    f_phi = Q * cphi - P * sphi
    phi_u = -(P_u * cphi + Q_u * sphi + R_u) / f_phi
    phi_p = -(P_p * cphi + Q_p * sphi + R_p) / f_phi
    # machine frame (Eqs. (9)-(10)): r - A - X_D a, outward normal -s n_h, and their derivatives; e = e(phi),
    # e' = k x e, meridian tangent t_h = s cos(chi) e - sin(chi) k, dn_h/du = dchi s t_h + sin(chi) e' phi_u
    V = np.empty(u.shape + (3, 6))
    rc_, rs_ = rho * cphi, rho * sphi
    V[:, 0, 0] = S * cb + rc_ + XD * cg
    V[:, 1, 0] = S * sb + rs_ - E
    V[:, 2, 0] = z + (XB - XD * sg)
    snr = s * nr
    V[:, 0, 1] = -snr * cphi
    V[:, 1, 1] = -snr * sphi
    V[:, 2, 1] = -nc
    snc = s * nc
    V[:, 0, 2] = snc * cphi - rs_ * phi_u
    V[:, 1, 2] = snc * sphi + rc_ * phi_u
    V[:, 2, 2] = -nr
    V[:, 0, 3] = -S * sb - rs_ * phi_p
    V[:, 1, 3] = S * cb + rc_ * phi_p - dE
    V[:, 2, 3] = 0.0
    a_u, a_p = snr * phi_u, snr * phi_p
    dsnc = dchi * snc
    V[:, 0, 4] = a_u * sphi - dsnc * cphi
    V[:, 1, 4] = -a_u * cphi - dsnc * sphi
    V[:, 2, 4] = dchi * nr
    V[:, 0, 5] = a_p * sphi
    V[:, 1, 5] = -a_p * cphi
    V[:, 2, 5] = 0.0
    M = _to_member_stack(V, psi_i, g, np.array([-cg, 0.0, sg]))
    # the work turns by psi_i(psi_c): d/dpsi_i of R_z(-psi_i) v is (v_y, -v_x, 0)
    M[:, 0, 3] += w * M[:, 1, 0]
    M[:, 1, 3] -= w * M[:, 0, 0]
    M[:, 0, 5] += w * M[:, 1, 1]
    M[:, 1, 5] -= w * M[:, 0, 1]
    return M.reshape(shape + (3, 6)), disc.reshape(shape)
