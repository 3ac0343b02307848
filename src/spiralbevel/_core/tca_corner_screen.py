"""Compiled proof that a corner of TCA cannot lie on the flanks: the pinion's fillet junction against a boundary of the
gear (toe, heel or top edge), :mod:`spiralbevel._core.tca_corner`.

The gear's toe, heel and top margins of a face-milled flank depend only on the point's place in the gear's axial plane
(radius rho about the gear axis and axial position z): R - R_i, R_e - R and h_face(R) - h with R = rho sin(delta) +
z cos(delta), h = rho cos(delta) - z sin(delta) and h_face linear (:func:`spiralbevel._core.tca_edge.margins`). Turning
the gear about its axis changes neither, so at a given pinion rotation phi1 the corner's gear margin is a function of
the pinion point alone,

    f(P) = a rho(v) + b z(v) + c,     v = B2^T (d + R_z(phi1) P)     (the point in the gear's frame),

and a corner of the pinion's fillet junction with that gear boundary is a zero of f along the junction curve (the gear
rotation then follows). ``meshing.tca_edge_solve`` samples the pinion's junction curve once per flank (a 2-D Newton on
u = u_j and the cone distance R, marched from toe to heel and 1.5 face widths beyond each); :func:`corner_excluded`
proves at one pinion rotation that f has no zero along it:

* f has one sign s at every sample (else no proof);
* g = s f is a convex function of P where s a > 0 (rho is a norm of an affine image of P) and concave where s a <= 0.
  On the chord between two samples a concave g is at least its smaller end value; a convex g is at least the larger
  of its two tangent planes at the ends (tangent planes under-estimate a convex function everywhere), whose minimum
  over the chord is at an end or where they cross;
* the curve between two samples stays within delta of their chord; delta is bounded by the sagitta from the second
  differences of the samples (|P_{k-1} - 2 P_k + P_{k+1}| / 8 is the sagitta of a curve of constant second
  derivative), with a safety factor of 4; g changes by at most K delta over that distance (K = |grad f| = 1 for the toe
  and heel, sqrt(1 + tan^2(delta_a - delta)) for the top: rho and z are 1-Lipschitz and orthogonal).

The lower bound minus K delta above 1e-9 mm on every segment proves that no corner lies on the sampled stretch of the
junction curve: none on the flanks, nor within 1.5 face widths beyond them. TCA does not solve such corner systems
(:func:`spiralbevel._core.tca_edge_screen.edge_try`). A corner of the extended surfaces far beyond the flanks is no
contact, but its solution seeds the flank's vertex (:mod:`spiralbevel.meshing.tca_edge`): the stretch is long enough
that every such seed of the test pairs is still solved (tests/meshing/test_tca_corner_screen.py: the proof against a
dense brute-force sampling, and TCA with and without it bit for bit).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["corner_excluded", "FILLET", "SAFETY", "BEYOND", "N_SAMPLES"]

#: the fillet junction's index among the margins of a generated flank (toe, heel, top, fillet)
FILLET = 3
#: factor on the sagitta estimate of the curve's distance from its chords
SAFETY = 4.0
#: the junction curve is sampled from BEYOND face widths (w = R_e - R_i) before the toe to BEYOND past the heel, at
#: N_SAMPLES points
BEYOND = 1.5
N_SAMPLES = 129


@kernel(inline="always")
def _gear_margin(mprm2, e, v0, v1, v2, grad):
    """Gear margin ``e`` (0 toe, 1 heel, 2 top) at the gear-frame point v and its gradient w.r.t. v into ``grad``;
    returns (value, coefficient a of rho)."""
    sd, cd = mprm2[0], mprm2[1]
    rho = math.hypot(v0, v1)
    R = rho * sd + v2 * cd
    h = rho * cd - v2 * sd
    if e == 0:
        val, a, b = R - mprm2[2], sd, cd
    elif e == 1:
        val, a, b = mprm2[3] - R, -sd, -cd
    else:
        tn = mprm2[6]
        val, a, b = mprm2[4] + (R - mprm2[5]) * tn - h, tn * sd - cd, tn * cd + sd
    grad[0] = a * v0 / rho
    grad[1] = a * v1 / rho
    grad[2] = b
    return val, a


@kernel
def corner_excluded(P, c1, s1, d, M2, mprm2, e):
    """True where the proof of the module docstring shows that gear margin ``e`` (0 toe, 1 heel, 2 top; gear margins
    ``mprm2`` of kind ``MARGIN_GENERATED``) has no zero along the pinion's junction curve sampled at ``P (n, 3)``
    (pinion frame, mm) at the pinion rotation with cos, sin ``c1``, ``s1`` (assembly constants ``d``, ``M2`` of
    :mod:`spiralbevel._core.tca_newton`: the gear point is v = B2^T (d + R_z(phi1) P))."""
    n = P.shape[0]
    if n < 3 or e < 0 or e > 2:
        return False
    tn = mprm2[6]
    K = math.sqrt(1.0 + tn * tn) if e == 2 else 1.0
    V = np.empty((n, 3))    # the samples in the gear frame
    G = np.empty((n, 3))    # gradients of s f w.r.t. the pinion-frame point (fixed frame then pinion: rotations)
    f = np.empty(n)
    grad = np.empty(3)
    sgn = 0.0
    a = 0.0
    for k in range(n):
        x = c1 * P[k, 0] - s1 * P[k, 1] + d[0]
        y = s1 * P[k, 0] + c1 * P[k, 1] + d[1]
        z = P[k, 2] + d[2]
        for i in range(3):
            V[k, i] = M2[0, i] * x + M2[1, i] * y + M2[2, i] * z
        f[k], a = _gear_margin(mprm2, e, V[k, 0], V[k, 1], V[k, 2], grad)
        if not math.isfinite(f[k]) or f[k] == 0.0:
            return False
        s = 1.0 if f[k] > 0.0 else -1.0
        if sgn == 0.0:
            sgn = s
        elif s != sgn:
            return False
        # the gradient w.r.t. P: grad_v f . dv/dP, dv/dP = B2^T R_z(phi1)
        gx = M2[0, 0] * grad[0] + M2[0, 1] * grad[1] + M2[0, 2] * grad[2]
        gy = M2[1, 0] * grad[0] + M2[1, 1] * grad[1] + M2[1, 2] * grad[2]
        gz = M2[2, 0] * grad[0] + M2[2, 1] * grad[1] + M2[2, 2] * grad[2]
        G[k, 0] = sgn * (c1 * gx + s1 * gy)
        G[k, 1] = sgn * (-s1 * gx + c1 * gy)
        G[k, 2] = sgn * gz
        f[k] *= sgn
    convex = sgn * a > 0.0
    for k in range(n - 1):
        # distance of the curve from the chord: sagitta of the second differences at both ends of the segment
        sag = 0.0
        for j in (k, k + 1):
            if 1 <= j <= n - 2:
                q = 0.0
                for i in range(3):
                    t = P[j - 1, i] - 2.0 * P[j, i] + P[j + 1, i]
                    q += t * t
                sag = max(sag, math.sqrt(q) / 8.0)
        lo = min(f[k], f[k + 1])
        if convex:   # the larger of the two tangent planes, minimised over the chord
            t0 = 0.0
            t1 = 0.0
            for i in range(3):
                dl = P[k + 1, i] - P[k, i]
                t0 += G[k, i] * dl
                t1 += G[k + 1, i] * dl
            # L0(l) = f_k + l t0, L1(l) = f_k+1 - (1 - l) t1 on l in [0, 1]
            lo = min(max(f[k], f[k + 1] - t1), max(f[k] + t0, f[k + 1]))
            den = t0 - t1
            if den != 0.0:
                lam = (f[k + 1] - t1 - f[k]) / den
                if 0.0 < lam < 1.0:
                    lo = min(lo, f[k] + lam * t0)
        if not lo - K * SAFETY * sag > 1e-9:
            return False
    return True
