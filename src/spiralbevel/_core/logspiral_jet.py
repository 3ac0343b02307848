"""Compiled first-order jet of the log-spiral flank: point, outward normal and their parameter derivatives.

Seed 000 Eq. (16) with the outward normal and the analytic derivatives of docs/theory/logspiral.md, Eqs. (S3)-(S9),
parameters q = (varphi, phi), member frame, the flank turned by an azimuth about +z (phasing):

    psi = (varphi - phi) sin(delta),  rho = rho0 exp(phi sin(delta) / tan(beta)),  s = sign(psi) (+1 at psi = 0)
    r = rho cos(psi) t + rho sin(psi) w                     t = (sd c, sd s, cd), w = (s_v, -c_v, 0)
    n_out = s (cos(psi - beta) w - sin(psi - beta) t)       m = (cd c, cd s, -sd), c, s_v = cos, sin(varphi)
    r_varphi = rho sin(psi) cos(delta) m,  r_phi = rho sin(delta) / sin(beta) e2
    e2 = cos(psi - beta) t + sin(psi - beta) w
    n_varphi = s cos(delta) cos(psi - beta) m,  n_phi = s sin(delta) e2

The jet is written into ``out (3, 6)`` with the columns (r, n, r_q0, r_q1, n_q0, n_q1): the layout that the compiled
TCA Newton (:mod:`spiralbevel._core.tca_newton`) reads through :mod:`spiralbevel._core.jets`.

``prm`` = (rho0 mm, delta rad, beta rad, cos(azimuth), sin(azimuth)); see :func:`parameters`.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["parameters", "logspiral_jet", "jet_batch"]


def parameters(rho0, delta, beta, azimuth):
    """Parameter vector ``prm (5,) float`` of :func:`logspiral_jet`."""
    return np.array([rho0, delta, beta, math.cos(azimuth), math.sin(azimuth)], float)


@kernel
def logspiral_jet(prm, q0, q1, out):
    """Jet of the flank at one parameter point (varphi, phi) = (q0, q1) rad into ``out (3, 6)`` (see module)."""
    rho0, d, b, ca, sa = prm[0], prm[1], prm[2], prm[3], prm[4]
    sd, cd = math.sin(d), math.cos(d)
    c, s = math.cos(q0), math.sin(q0)
    psi = (q0 - q1) * sd
    rho = rho0 * math.exp(q1 * (sd / math.tan(b)))
    cp, sp = math.cos(psi), math.sin(psi)
    cpb, spb = math.cos(psi - b), math.sin(psi - b)
    sg = 1.0 if psi >= 0 else -1.0
    a1, a2 = rho * cp, rho * sp
    out[0, 0] = a1 * sd * c + a2 * s
    out[1, 0] = a1 * sd * s - a2 * c
    out[2, 0] = a1 * cd
    out[0, 1] = sg * (cpb * s - spb * sd * c)
    out[1, 1] = sg * (-cpb * c - spb * sd * s)
    out[2, 1] = sg * (-spb * cd)
    f = rho * sp * cd  # r_varphi = f m
    out[0, 2] = f * cd * c
    out[1, 2] = f * cd * s
    out[2, 2] = -f * sd
    e2x = cpb * sd * c + spb * s
    e2y = cpb * sd * s - spb * c
    e2z = cpb * cd
    g = rho * sd / math.sin(b)  # r_phi = g e2
    out[0, 3] = g * e2x
    out[1, 3] = g * e2y
    out[2, 3] = g * e2z
    h = sg * cd * cpb  # n_varphi = s cd cpb m
    out[0, 4] = h * cd * c
    out[1, 4] = h * cd * s
    out[2, 4] = -h * sd
    k = sg * sd  # n_phi = s sd e2
    out[0, 5] = k * e2x
    out[1, 5] = k * e2y
    out[2, 5] = k * e2z
    if sa != 0.0:  # azimuth: R_z applied to every column
        for j in range(6):
            x, y = out[0, j], out[1, j]
            out[0, j] = ca * x - sa * y
            out[1, j] = sa * x + ca * y


@kernel
def jet_batch(prm, q, out):
    """:func:`logspiral_jet` at every row of ``q (m, 2)`` into ``out (m, 3, 6)``."""
    for i in range(q.shape[0]):
        logspiral_jet(prm, q[i, 0], q[i, 1], out[i])
