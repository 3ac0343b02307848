"""Compiled contact geometry of TCA on batches of contact points: assembly poses, Weingarten tensors, principal
relative curvatures and directions (the only implementation: :mod:`spiralbevel._core.tca` delegates here).

Per point, in the convex = positive convention of docs/conventions.md (outward normals):

* pose: R1 = R_z(phi1), R2 = R(a2, phi2) B2 with R(a, t) = I + sin t [a]x + (1 - cos t) [a]x^2 (Rodrigues);
* Weingarten tensor W = dn (dr^T dr)^-1 dr^T, symmetrized (W dr_i = dn_i on the tangent plane, W n = 0);
* relative curvature: K = T^T (W1 + W2) T, symmetrized, on the tangent basis T = (e1, e2) of the contact normal
  (:func:`spiralbevel._core.tca.tangent_basis`); its eigenvalues lam_1 <= lam_2 and unit eigenvectors (a 2 x 2
  symmetric eigenproblem solved by one Jacobi rotation, exact up to round-off), mapped back by T, signed so that
  dirs[1] = n x dirs[0];
* the ellipse semi-axes follow from lam (:func:`spiralbevel._core.tca.ellipse_axes`).

Loops over points with scalar arithmetic (no BLAS or LAPACK binding: 3 x 3 products, a 2 x 2 inverse and a 2 x 2
eigenproblem in closed form keep the compile time small). The contact ellipses of a TCA cycle are two calls:
:func:`weingarten_batch` of both members (turned into the fixed frame) and :func:`relative_curvature_batch`.
Float64, mm and rad, xyz on the axis named in each docstring.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["pose_batch", "weingarten_batch", "relative_curvature_batch"]


@kernel
def pose_batch(phi1, phi2, a2, B2, R1, R2):
    """Member -> fixed rotations ``R1, R2 (m, 3, 3)`` of the pinion (about +z by ``phi1 (m,)``) and of the gear
    (``R(a2, phi2) B2``, ``a2 (3,)`` the gear axis, normalized here, ``B2 (3, 3)``)."""
    nrm = math.sqrt(a2[0] * a2[0] + a2[1] * a2[1] + a2[2] * a2[2])
    k0, k1, k2 = a2[0] / nrm, a2[1] / nrm, a2[2] / nrm
    K = np.empty((3, 3))
    K[0, 0], K[0, 1], K[0, 2] = 0.0, -k2, k1
    K[1, 0], K[1, 1], K[1, 2] = k2, 0.0, -k0
    K[2, 0], K[2, 1], K[2, 2] = -k1, k0, 0.0
    KK = np.empty((3, 3))
    for a in range(3):
        for b in range(3):
            KK[a, b] = K[a, 0] * K[0, b] + K[a, 1] * K[1, b] + K[a, 2] * K[2, b]
    A = np.empty((3, 3))
    for i in range(phi1.shape[0]):
        c, s = math.cos(phi1[i]), math.sin(phi1[i])
        R1[i, 0, 0], R1[i, 0, 1], R1[i, 0, 2] = c, -s, 0.0
        R1[i, 1, 0], R1[i, 1, 1], R1[i, 1, 2] = s, c, 0.0
        R1[i, 2, 0], R1[i, 2, 1], R1[i, 2, 2] = 0.0, 0.0, 1.0
        sn, cc = math.sin(phi2[i]), 1.0 - math.cos(phi2[i])
        for a in range(3):
            for b in range(3):
                A[a, b] = (1.0 if a == b else 0.0) + sn * K[a, b] + cc * KK[a, b]
        for a in range(3):
            for b in range(3):
                R2[i, a, b] = A[a, 0] * B2[0, b] + A[a, 1] * B2[1, b] + A[a, 2] * B2[2, b]


@kernel
def _weingarten(dr, dn, W):
    """Weingarten tensor ``W (3, 3)`` of one point from ``dr, dn (3, 2)`` (module docstring)."""
    g00 = dr[0, 0] * dr[0, 0] + dr[1, 0] * dr[1, 0] + dr[2, 0] * dr[2, 0]
    g01 = dr[0, 0] * dr[0, 1] + dr[1, 0] * dr[1, 1] + dr[2, 0] * dr[2, 1]
    g11 = dr[0, 1] * dr[0, 1] + dr[1, 1] * dr[1, 1] + dr[2, 1] * dr[2, 1]
    det = g00 * g11 - g01 * g01
    i00, i01, i11 = g11 / det, -g01 / det, g00 / det
    for a in range(3):
        # row a of dn G^-1
        u0 = dn[a, 0] * i00 + dn[a, 1] * i01
        u1 = dn[a, 0] * i01 + dn[a, 1] * i11
        for b in range(3):
            W[a, b] = u0 * dr[b, 0] + u1 * dr[b, 1]
    for a in range(3):
        for b in range(a + 1, 3):
            w = 0.5 * (W[a, b] + W[b, a])
            W[a, b] = w
            W[b, a] = w


@kernel
def weingarten_batch(dr, dn, R, rotate, W):
    """Weingarten tensors ``W (m, 3, 3)`` from ``dr, dn (m, 3, 2)``; with ``rotate``, turned into a common frame by
    the member -> common rotations ``R (m, 3, 3)`` (R W R^T), else ``R`` is not read."""
    Wm = np.empty((3, 3))
    RW = np.empty((3, 3))
    for i in range(dr.shape[0]):
        if not rotate:
            _weingarten(dr[i], dn[i], W[i])
            continue
        _weingarten(dr[i], dn[i], Wm)
        for a in range(3):
            for b in range(3):
                RW[a, b] = R[i, a, 0] * Wm[0, b] + R[i, a, 1] * Wm[1, b] + R[i, a, 2] * Wm[2, b]
        for a in range(3):
            for b in range(3):
                W[i, a, b] = RW[a, 0] * R[i, b, 0] + RW[a, 1] * R[i, b, 1] + RW[a, 2] * R[i, b, 2]


@kernel(inline="always")   # one call site (relative_curvature_batch): inlined there
def _relative_curvature(W, n, lam, dirs):
    """Eigenvalues ``lam (2,)`` (ascending) and unit eigenvectors ``dirs (2, 3)`` of the tangent-plane restriction of
    the symmetric ``W (3, 3)`` (= W1 + W2) at the unit normal ``n (3,)`` (module docstring)."""
    # tangent basis: e1 = n x h / |n x h| with h = e_x where |n_x| < 0.6, else e_y; e2 = n x e1
    if abs(n[0]) < 0.6:
        a0, a1, a2 = 0.0, n[2], -n[1]
    else:
        a0, a1, a2 = -n[2], 0.0, n[0]
    nrm = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    a0, a1, a2 = a0 / nrm, a1 / nrm, a2 / nrm
    b0 = n[1] * a2 - n[2] * a1
    b1 = n[2] * a0 - n[0] * a2
    b2 = n[0] * a1 - n[1] * a0
    # K = T^T W T
    wa0 = W[0, 0] * a0 + W[0, 1] * a1 + W[0, 2] * a2
    wa1 = W[1, 0] * a0 + W[1, 1] * a1 + W[1, 2] * a2
    wa2 = W[2, 0] * a0 + W[2, 1] * a1 + W[2, 2] * a2
    wb0 = W[0, 0] * b0 + W[0, 1] * b1 + W[0, 2] * b2
    wb1 = W[1, 0] * b0 + W[1, 1] * b1 + W[1, 2] * b2
    wb2 = W[2, 0] * b0 + W[2, 1] * b1 + W[2, 2] * b2
    p = a0 * wa0 + a1 * wa1 + a2 * wa2
    q = 0.5 * ((a0 * wb0 + a1 * wb1 + a2 * wb2) + (b0 * wa0 + b1 * wa1 + b2 * wa2))
    r = b0 * wb0 + b1 * wb1 + b2 * wb2
    # one Jacobi rotation diagonalizes [[p, q], [q, r]]: eigenvalues p - t q (vector (c, -s)), r + t q ((s, c))
    if q == 0.0:
        t = 0.0
    else:
        theta = (r - p) / (2.0 * q)
        t = 1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0))
        if theta < 0.0:
            t = -t
    c = 1.0 / math.sqrt(t * t + 1.0)
    s = t * c
    l0, v00, v01 = p - t * q, c, -s
    l1 = r + t * q
    if l1 < l0:
        l0, v00, v01, l1 = l1, s, c, l0
    # the second direction is n x the first ((e1, e2, n) is right-handed: n x (a e1 + b e2) = a e2 - b e1)
    v10, v11 = -v01, v00
    lam[0], lam[1] = l0, l1
    dirs[0, 0], dirs[0, 1], dirs[0, 2] = v00 * a0 + v01 * b0, v00 * a1 + v01 * b1, v00 * a2 + v01 * b2
    dirs[1, 0], dirs[1, 1], dirs[1, 2] = v10 * a0 + v11 * b0, v10 * a1 + v11 * b1, v10 * a2 + v11 * b2


@kernel
def relative_curvature_batch(W1, W2, n, lam, dirs):
    """Principal relative curvatures ``lam (m, 2)`` and directions ``dirs (m, 2, 3)`` from the Weingarten tensors
    ``W1, W2 (m, 3, 3)`` (common frame) and the unit normals ``n (m, 3)``."""
    W = np.empty((3, 3))
    for i in range(n.shape[0]):
        for a in range(3):
            for b in range(3):
                W[a, b] = W1[i, a, b] + W2[i, a, b]
        _relative_curvature(W, n[i], lam[i], dirs[i])
