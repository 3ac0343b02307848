"""Fast closed-form kernel of the log-spiral flank in the public conventions (outward normal, convex = positive).

Same surface as :mod:`spiralbevel._core.logspiral` (seed 000 Eq. (16), docs/theory/logspiral.md, Eq. (S2)), but:

* the normal is the **outward** normal n_out = sign(psi) n (docs/theory/logspiral.md, Eq. (S9) (#flank-types)), n the
  corrected Eq. (21);
* L, M, N are taken with the sign convention II = dr . dn_out (i.e. L = -r_uu . n_out), so that the eigenvalues of
  I^-1 II are the reported curvatures, **convex = positive** (docs/conventions.md);
* e1 = r_varphi/|r_varphi| = sign(psi) m, e2 = cos(psi-beta) t + sin(psi-beta) w (toe -> heel, e2 . r > 0), and
  e1 x e2 = n_out.

Closed forms used (docs/theory/logspiral.md, Eqs. (S3)-(S9), converted with s = sign(psi)):

    E = (rho sin(psi) cos(delta))^2,  F = 0,  G = (rho sin(delta) / sin(beta))^2
    L = rho |sin psi| cos(psi-beta) cos^2(delta),  M = 0,  N = s rho sin^2(delta) / sin(beta)
    k1 = L/E = cos(psi-beta) / (rho |sin psi|),     k2 = N/G = s sin(beta) / rho

The kernel trusts its input: psi must be nonzero (checked by the caller). It uses five transcendental calls per
point (cos/sin of varphi and psi, one exp) and works in cache-sized chunks to limit memory traffic.
"""

from __future__ import annotations

import numpy as np

FIELDS_VEC = ("point", "normal", "e1", "e2")
FIELDS_SCALAR = ("E", "F", "G", "L", "M", "N", "k1", "k2", "psi", "rho")

_CHUNK = 8192


def allocate(n):
    """Output buffers for ``n`` points: vectors (n, 3) and scalars (n,), all float64."""
    out = {k: np.empty((n, 3)) for k in FIELDS_VEC}
    out.update({k: np.empty(n) for k in FIELDS_SCALAR})
    return out


def flank_flat(varphi, phi, rho0, delta, beta, out=None):
    """Evaluate the flank at flat parameter arrays.

    Parameters
    ----------
    varphi, phi : (n,) float, rad
        Rolling angle and spiral parameter (seed 000 Eq. (16)); psi = (varphi - phi) sin(delta) must be nonzero.
    rho0 : float, mm
    delta, beta : float, rad
        Base-cone angle and spiral parameter (beta < 0: left hand).
    out : dict, optional
        Buffers from :func:`allocate`; allocated when omitted.

    Returns
    -------
    dict of arrays
        Keys of ``FIELDS_VEC`` ((n, 3)) and ``FIELDS_SCALAR`` ((n,)).
    """
    varphi = np.ascontiguousarray(varphi, dtype=float).ravel()
    phi = np.ascontiguousarray(phi, dtype=float).ravel()
    n = varphi.size
    if out is None:
        out = allocate(n)
    sd, cd = np.sin(delta), np.cos(delta)
    sb, cb = np.sin(beta), np.cos(beta)
    growth = sd * cb / sb
    out["F"][:] = 0.0
    out["M"][:] = 0.0
    for lo in range(0, n, _CHUNK):
        hi = min(lo + _CHUNK, n)
        _chunk(varphi[lo:hi], phi[lo:hi], rho0, sd, cd, sb, cb, growth, {k: v[lo:hi] for k, v in out.items()})
    return out


def _chunk(vp, ph, rho0, sd, cd, sb, cb, growth, o):
    psi = o["psi"]
    np.subtract(vp, ph, out=psi)
    psi *= sd
    rho = o["rho"]
    np.multiply(ph, growth, out=rho)
    np.exp(rho, out=rho)
    rho *= rho0
    cf, sf = np.cos(vp), np.sin(vp)
    cp, sp = np.cos(psi), np.sin(psi)
    s = np.sign(psi)
    # cos(psi - beta), sin(psi - beta) by the addition theorems (no extra transcendental calls)
    cpb = cp * cb
    tmp = sp * sb
    cpb += tmp
    spb = sp * cb
    np.multiply(cp, sb, out=tmp)
    spb -= tmp
    # point = rho (cos psi t + sin psi w), t = (sd cf, sd sf, cd), w = (sf, -cf, 0)
    a = rho * cp
    b = rho * sp
    p = o["point"]
    np.multiply(a, cd, out=p[:, 2])
    a *= sd
    np.multiply(a, cf, out=tmp)
    np.multiply(b, sf, out=p[:, 0])
    p[:, 0] += tmp
    np.multiply(a, sf, out=tmp)
    np.multiply(b, cf, out=p[:, 1])
    np.subtract(tmp, p[:, 1], out=p[:, 1])
    # e2 = cpb t + spb w
    e2 = o["e2"]
    np.multiply(cpb, cd, out=e2[:, 2])
    np.multiply(cpb, sd, out=a)  # a := cpb sd
    np.multiply(a, cf, out=tmp)
    np.multiply(spb, sf, out=e2[:, 0])
    e2[:, 0] += tmp
    np.multiply(a, sf, out=tmp)
    np.multiply(spb, cf, out=e2[:, 1])
    np.subtract(tmp, e2[:, 1], out=e2[:, 1])
    # e1 = s m, m = (cd cf, cd sf, -sd)
    e1 = o["e1"]
    np.multiply(s, -sd, out=e1[:, 2])
    np.multiply(s, cd, out=a)  # a := s cd
    np.multiply(a, cf, out=e1[:, 0])
    np.multiply(a, sf, out=e1[:, 1])
    # n_out = s (cpb w - spb t) = e1 x e2
    nrm = o["normal"]
    np.multiply(s, cpb, out=a)  # a := s cpb
    np.multiply(s, spb, out=b)  # b := s spb
    np.multiply(b, -cd, out=nrm[:, 2])
    b *= sd
    np.multiply(a, sf, out=nrm[:, 0])
    np.multiply(b, cf, out=tmp)
    nrm[:, 0] -= tmp
    np.multiply(a, cf, out=nrm[:, 1])
    np.multiply(b, sf, out=tmp)
    nrm[:, 1] += tmp
    np.negative(nrm[:, 1], out=nrm[:, 1])
    # fundamental forms (convex-positive II) and curvatures
    asp = np.abs(sp, out=sp)  # |sin psi|
    np.multiply(rho, asp, out=a)  # a := rho |sin psi|
    np.multiply(a, cd, out=b)
    np.multiply(b, b, out=o["E"])
    np.multiply(a, cpb, out=b)
    np.multiply(b, cd * cd, out=o["L"])
    np.divide(cpb, a, out=o["k1"])
    np.multiply(rho, sd / sb, out=b)
    np.multiply(b, b, out=o["G"])
    np.multiply(s, sb, out=a)
    np.divide(a, rho, out=o["k2"])
    np.multiply(b, sd, out=b)
    np.multiply(b, s, out=o["N"])
