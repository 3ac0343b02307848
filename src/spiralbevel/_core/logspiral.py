"""Closed-form kernels of the logarithmic-spiral bevel tooth surface (seed 000 Eq. (16), corrected in
docs/theory/logspiral.md, Eq. (S2)).

Frame: base-cone apex at the origin, gear axis +z, base-cone half-angle ``delta``. ``beta`` is the spiral angle of the
planar log spiral in the rolling (base-cone tangent) plane; beta > 0 is a right-hand flank, beta < 0 a left-hand one.
Parameters: ``varphi`` (rolling angle, rad) and ``phi`` (spiral parameter, rad); psi = (varphi - phi) sin(delta).

All functions broadcast over ``varphi`` and ``phi``; vectors have xyz on the trailing axis.
"""

from __future__ import annotations

import numpy as np


def frame_tw_m(varphi, delta):
    """Unit vectors t (generatrix), w (in the rolling plane, perpendicular to t) and m (plane normal).

    (t, w, m) is right-handed: t x w = m. docs/theory/logspiral.md, Eq. (S1)
    """
    c, s = np.cos(varphi), np.sin(varphi)
    sd, cd = np.sin(delta), np.cos(delta)
    z = np.zeros_like(c)
    t = np.stack([sd * c, sd * s, cd * np.ones_like(c)], -1)
    w = np.stack([s, -c, z], -1)
    m = np.stack([cd * c, cd * s, -sd * np.ones_like(c)], -1)
    return t, w, m


def psi_rho(varphi, phi, rho0, delta, beta):
    """psi = (varphi - phi) sin(delta) [rad] and rho = rho0 exp(phi sin(delta) cot(beta)) [mm]."""
    sd = np.sin(delta)
    psi = (np.asarray(varphi, float) - np.asarray(phi, float)) * sd
    rho = rho0 * np.exp(np.asarray(phi, float) * sd / np.tan(beta))
    return psi, rho


def point(varphi, phi, rho0, delta, beta):
    """Surface point r(varphi, phi) in mm, seed 000 Eq. (16)."""
    varphi, phi = np.broadcast_arrays(np.asarray(varphi, float), np.asarray(phi, float))
    psi, rho = psi_rho(varphi, phi, rho0, delta, beta)
    t, w, _ = frame_tw_m(varphi, delta)
    return rho[..., None] * (np.cos(psi)[..., None] * t + np.sin(psi)[..., None] * w)


def geometry(varphi, phi, rho0, delta, beta):
    """Point, derivatives, unit normal n (Eq. 21 corrected), fundamental forms and principal data w.r.t. n.

    Returns
    -------
    dict of arrays
        ``r, r_varphi, r_phi, n`` (..., 3); ``E, F, G, L, M, N`` (...); ``k1, k2`` (...) 1/mm, curvatures positive
        when the surface bends toward ``n`` (the convention of docs/theory/logspiral.md#flank-types); ``e1 = m``, ``e2 =
        r_phi/|r_phi|`` (...,3);
        ``psi, rho`` (...).

    Notes
    -----
    docs/theory/logspiral.md, Eqs. (S3)-(S8): r_varphi = rho sin(psi) cos(delta) m; r_phi = rho sin(delta)/sin(beta)
    [cos(psi-beta) t +
    sin(psi-beta) w]; n = cos(psi-beta) w - sin(psi-beta) t; E = rho^2 sin^2 psi cos^2 delta; G = rho^2 sin^2 delta /
    sin^2 beta; L = -rho sin psi cos(psi-beta) cos^2 delta; N = -rho sin^2 delta / sin beta; k1 = L/E, k2 = N/G.
    e1 = m and e2 = sign(sin beta) r_phi/|r_phi| = cos(psi-beta) t + sin(psi-beta) w, so that e1 x e2 = n.
    """
    varphi, phi = np.broadcast_arrays(np.asarray(varphi, float), np.asarray(phi, float))
    psi, rho = psi_rho(varphi, phi, rho0, delta, beta)
    t, w, m = frame_tw_m(varphi, delta)
    sd, cd, sb = np.sin(delta), np.cos(delta), np.sin(beta)
    cp, sp = np.cos(psi), np.sin(psi)
    cpb, spb = np.cos(psi - beta), np.sin(psi - beta)
    r = rho[..., None] * (cp[..., None] * t + sp[..., None] * w)
    r_varphi = (rho * sp * cd)[..., None] * m
    e2 = cpb[..., None] * t + spb[..., None] * w
    r_phi = (rho * sd / sb)[..., None] * e2
    n = cpb[..., None] * w - spb[..., None] * t
    E = rho**2 * sp**2 * cd**2
    G = rho**2 * sd**2 / sb**2 * np.ones_like(E)
    L = -rho * sp * cpb * cd**2
    N = -rho * sd**2 / sb * np.ones_like(E)
    zero = np.zeros_like(E)
    with np.errstate(divide="ignore", invalid="ignore"):
        k1 = -cpb / (rho * sp)
    k2 = -sb / rho
    return dict(
        r=r, r_varphi=r_varphi, r_phi=r_phi, n=n, E=E, F=zero, G=G, L=L, M=zero, N=N,
        k1=k1, k2=k2 * np.ones_like(E), e1=m, e2=e2, psi=psi, rho=rho,
    )
