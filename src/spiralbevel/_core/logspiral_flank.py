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
point (cos/sin of varphi and psi, one exp) in one compiled pass over the points (no temporaries).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

FIELDS_VEC = ("point", "normal", "e1", "e2")
FIELDS_SCALAR = ("E", "F", "G", "L", "M", "N", "k1", "k2", "psi", "rho")


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
    _flank_loop(varphi, phi, float(rho0), sd, cd, sb, cb, growth, out["point"], out["normal"], out["e1"], out["e2"],
                out["E"], out["G"], out["L"], out["N"], out["k1"], out["k2"], out["psi"], out["rho"])
    return out


@kernel
def _flank_loop(vp, ph, rho0, sd, cd, sb, cb, growth, p, nrm, e1, e2, E, G, L, N, k1, k2, psi_o, rho_o):
    """One pass over the points (compiled): the closed forms of the module docstring."""
    for i in range(vp.shape[0]):
        psi = (vp[i] - ph[i]) * sd
        rho = rho0 * math.exp(ph[i] * growth)
        psi_o[i], rho_o[i] = psi, rho
        cf, sf = math.cos(vp[i]), math.sin(vp[i])
        cp, sp = math.cos(psi), math.sin(psi)
        s = 1.0 if psi > 0 else (-1.0 if psi < 0 else 0.0)
        # cos(psi - beta), sin(psi - beta) by the addition theorems (no extra transcendental calls)
        cpb = cp * cb + sp * sb
        spb = sp * cb - cp * sb
        # point = rho (cos psi t + sin psi w), t = (sd cf, sd sf, cd), w = (sf, -cf, 0)
        a, b = rho * cp, rho * sp
        p[i, 0] = b * sf + a * sd * cf
        p[i, 1] = a * sd * sf - b * cf
        p[i, 2] = a * cd
        # e2 = cpb t + spb w
        e2[i, 0] = spb * sf + cpb * sd * cf
        e2[i, 1] = cpb * sd * sf - spb * cf
        e2[i, 2] = cpb * cd
        # e1 = s m, m = (cd cf, cd sf, -sd)
        e1[i, 0] = s * cd * cf
        e1[i, 1] = s * cd * sf
        e1[i, 2] = -s * sd
        # n_out = s (cpb w - spb t) = e1 x e2
        nrm[i, 0] = s * cpb * sf - s * spb * sd * cf
        nrm[i, 1] = -(s * cpb * cf + s * spb * sd * sf)
        nrm[i, 2] = -s * spb * cd
        # fundamental forms (convex-positive II) and curvatures
        ra = rho * abs(sp)
        E[i] = (ra * cd) ** 2
        L[i] = ra * cpb * (cd * cd)
        k1[i] = cpb / ra
        g = rho * (sd / sb)
        G[i] = g * g
        k2[i] = s * sb / rho
        N[i] = g * sd * s
