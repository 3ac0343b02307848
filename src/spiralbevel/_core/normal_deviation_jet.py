"""Compiled jet of a flank displaced along its normal by a quadratic crowning: r' = r + w(q) n.

The same surface as :class:`spiralbevel.meshing.contact_surface.NormalDeviation` with the deviation of
:func:`~spiralbevel.meshing.contact_surface.quadratic_crowning`, in the same operation order:

    w(q) = -(c00 d0^2 + 2 c01 d0 d1 + c11 d1^2),  d = q - centre,  w_q = -2 (c00 d0 + c01 d1, c01 d0 + c11 d1)
    t_i = r_i + w_i n + w n_i  (i = 0, 1),  n' = unit(t_0 x t_1), turned to the side of n

with the first-order jet (r, n, r_q0, r_q1, n_q0, n_q1) of the base flank, a log-spiral flank
(:mod:`spiralbevel._core.logspiral_jet`; the crowned flanks of the package are log-spiral ones: a generated base would
link the face-milled jet into this kernel too, and every kernel that evaluates flanks compiles this one). The parameter
derivatives of r' and n' are central differences of r', n' with the steps (h0, h1), as
:func:`~spiralbevel.meshing.contact_surface.surface_derivatives` takes them for the numpy surface
(the derivatives of n' need second derivatives of the base, which its jet does not carry).

``prm`` = (base kind 0, centre q0, centre q1, c00, c01, c11, h0, h1, then the base jet's parameters); see
:func:`parameters`. Output ``out (3, 6)``: columns (r', n', r'_q0, r'_q1, n'_q0, n'_q1), member frame.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel
from .logspiral_jet import logspiral_jet

__all__ = ["parameters", "normal_quadratic_jet"]

#: the base kind (LOGSPIRAL of :mod:`spiralbevel._core.jets`, which imports this module)
_LOGSPIRAL = 0


def parameters(base_kind, base_prm, centre, coeffs, step):
    """Parameter vector ``prm`` of :func:`normal_quadratic_jet` (module docstring)."""
    head = [float(base_kind), float(centre[0]), float(centre[1]), *(float(c) for c in coeffs), float(step[0]),
            float(step[1])]
    return np.concatenate([np.array(head, float), np.asarray(base_prm, float)])


@kernel
def normal_quadratic_jet(prm, q0, q1, out):
    """Jet of the crowned flank at (q0, q1) into ``out (3, 6)`` (module docstring); NaN for an unknown base kind."""
    kind = prm[0]
    c00, c01, c11 = prm[3], prm[4], prm[5]
    h0, h1 = prm[6], prm[7]
    base = prm[8:]
    S = np.empty((3, 6))
    P = np.empty((5, 2, 3))  # r', n' at the centre, +h0, -h0, +h1, -h1
    for k in range(5):
        a, b = q0, q1
        if k == 1:
            a = q0 + h0
        elif k == 2:
            a = q0 - h0
        elif k == 3:
            b = q1 + h1
        elif k == 4:
            b = q1 - h1
        if kind == _LOGSPIRAL:
            logspiral_jet(base, a, b, S)
        else:
            for i in range(3):
                for j in range(6):
                    out[i, j] = math.nan
            return
        d0, d1 = a - prm[1], b - prm[2]
        w = -(c00 * (d0 * d0) + 2.0 * c01 * d0 * d1 + c11 * (d1 * d1))
        g0 = -2.0 * (c00 * d0 + c01 * d1)
        g1 = -2.0 * (c01 * d0 + c11 * d1)
        t00 = S[0, 2] + g0 * S[0, 1] + w * S[0, 4]
        t01 = S[1, 2] + g0 * S[1, 1] + w * S[1, 4]
        t02 = S[2, 2] + g0 * S[2, 1] + w * S[2, 4]
        t10 = S[0, 3] + g1 * S[0, 1] + w * S[0, 5]
        t11 = S[1, 3] + g1 * S[1, 1] + w * S[1, 5]
        t12 = S[2, 3] + g1 * S[2, 1] + w * S[2, 5]
        m0 = t01 * t12 - t02 * t11
        m1 = t02 * t10 - t00 * t12
        m2 = t00 * t11 - t01 * t10
        nm = math.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
        m0, m1, m2 = m0 / nm, m1 / nm, m2 / nm
        dot = m0 * S[0, 1] + m1 * S[1, 1] + m2 * S[2, 1]
        sg = 1.0 if dot > 0 else (-1.0 if dot < 0 else (0.0 if dot == 0 else math.nan))
        P[k, 1, 0], P[k, 1, 1], P[k, 1, 2] = m0 * sg, m1 * sg, m2 * sg
        for i in range(3):
            P[k, 0, i] = S[i, 0] + w * S[i, 1]
    for i in range(3):
        out[i, 0] = P[0, 0, i]
        out[i, 1] = P[0, 1, i]
        out[i, 2] = (P[1, 0, i] - P[2, 0, i]) / (2 * h0)
        out[i, 3] = (P[3, 0, i] - P[4, 0, i]) / (2 * h1)
        out[i, 4] = (P[1, 1, i] - P[2, 1, i]) / (2 * h0)
        out[i, 5] = (P[3, 1, i] - P[4, 1, i]) / (2 * h1)
