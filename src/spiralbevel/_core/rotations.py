"""Rotations and rigid transforms on arrays with xyz on the trailing axis.

All angles in rad, right-handed: a positive angle turns counterclockwise seen from the tip of the axis.
"""

from __future__ import annotations

import numpy as np


def rot_x(a):
    """Rotation matrices about +x, shape a.shape + (3, 3)."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def rot_y(a):
    """Rotation matrices about +y, shape a.shape + (3, 3)."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def rot_z(a):
    """Rotation matrices about +z, shape a.shape + (3, 3)."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def rot_axis(axis, a):
    """Rotation matrices about a unit ``axis (3,)`` by angles ``a`` (Rodrigues), shape a.shape + (3, 3)."""
    k = np.asarray(axis, dtype=float)
    k = k / np.linalg.norm(k)
    a = np.asarray(a, dtype=float)[..., None, None]
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(a) * K + (1.0 - np.cos(a)) * (K @ K)


def apply(R, v):
    """Apply matrices ``R (..., 3, 3)`` to vectors ``v (..., 3)`` with broadcasting."""
    return np.einsum("...ij,...j->...i", R, v)


def unit(v):
    """Normalize vectors along the trailing axis."""
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def dot(a, b):
    """Row-wise dot product over the trailing axis."""
    return np.einsum("...i,...i->...", a, b)
