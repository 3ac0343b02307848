"""Compiled bookkeeping of the exact transfer points of TCA: the Illinois variant of regula falsi on all transfers at
once (:mod:`spiralbevel.meshing.tca_transfer`; the function values, TE differences of two contacts solved at a trial
pinion rotation, come from the caller).

Each bracket [lo, hi] holds a sign change of d = TE_b - TE_a with the values d_lo, d_hi; ``side`` is the end kept at
the last update (1: the root was in [p, hi], -1: in [lo, p], 0: none yet). Illinois: when the same end is kept twice
in a row, its stored value is halved, which restores superlinear convergence where plain regula falsi stalls.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["illinois_propose", "illinois_accept"]

#: |d| below which a crossing is found (rad): 5e-11 rad = 1e-5 arcsec; with TE slopes of the order of 100 arcsec/rad
#: the crossing's TE is then within 1e-5 arcsec too. A bracket narrower than _WIDTH (rad) also ends.
_D_TOL = 5e-11
_WIDTH = 1e-12


@kernel
def illinois_propose(lo, hi, d_lo, d_hi, c):
    """Trial rotations ``p (len(c),)`` of the active brackets ``c``: the regula falsi point, or the midpoint where it
    is not strictly inside the bracket."""
    p = np.empty(c.shape[0])
    for k in range(c.shape[0]):
        i = c[k]
        q = hi[i] - d_hi[i] * (hi[i] - lo[i]) / (d_hi[i] - d_lo[i])
        p[k] = q if (math.isfinite(q) and lo[i] < q < hi[i]) else 0.5 * (lo[i] + hi[i])
    return p


@kernel
def illinois_accept(c, p, ta, tb, lo, hi, d_lo, d_hi, side, phi_t, te_t, cross, good):
    """Apply the TE values ``ta``, ``tb`` of both pairs at the trial rotations ``p`` of the brackets ``c``: record the
    estimate (rotation, larger TE), update the brackets (Illinois), end the brackets that converged or lost a contact
    (``cross`` False); ``good (len(c),)`` receives which trials had both contacts (their solutions are kept by the
    caller)."""
    for k in range(c.shape[0]):
        i = c[k]
        d = tb[k] - ta[k]
        good[k] = math.isfinite(d)
        phi_t[i] = p[k]
        if not good[k]:
            te_t[i] = math.nan
            cross[i] = False  # lost a contact inside the interval: stop at the best estimate
            continue
        te_t[i] = max(ta[k], tb[k])
        done = abs(d) < _D_TOL or (hi[i] - lo[i]) < _WIDTH
        if (d > 0) == (d_lo[i] > 0) and (d < 0) == (d_lo[i] < 0):  # same sign as at lo: root in [p, hi]
            lo[i], d_lo[i] = p[k], d
            if side[i] == 1:
                d_hi[i] *= 0.5
            side[i] = 1
        else:
            hi[i], d_hi[i] = p[k], d
            if side[i] == -1:
                d_lo[i] *= 0.5
            side[i] = -1
        if done:
            cross[i] = False
