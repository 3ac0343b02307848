"""Shared test helper: brute force on the material a face-milling blade sweeps over the roll (straight blade), for
the tests of generated flanks (tests/generation/test_fold.py, tests/meshing/test_tca_limit_line.py)."""

from __future__ import annotations

import numpy as np

from spiralbevel._core import generation as _g


def to_machine(p, psi, mp):
    """Canonical member-frame points -> machine frame at cradle angle psi (inverse of
    ``_core.generation.to_member``)."""
    g = mp["gamma"]
    psi_i, _, _ = _g.roll(psi, mp)
    E, _, _ = _g.offset(psi, mp)
    c, s = np.cos(psi_i), np.sin(psi_i)
    xb, yb, zb = c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]
    v = np.stack([xb * np.sin(g) - zb * np.cos(g), yb, xb * np.cos(g) + zb * np.sin(g)], -1)
    return v + np.stack([np.zeros_like(E), E, np.full_like(E, -mp["XB"])], -1) + mp["XD"] * _g.work_axis(mp)


def penetration(gen, points, psis):
    """Largest depth (mm, radial to the cutter axis) by which the straight blade of generator ``gen`` reaches into
    member-frame ``points (..., 3)`` over the cradle angles ``psis``: s (rho_blade(z) - rho) > 0 inside the cutter's
    material side (rho the distance from the cutter axis at height z), counted on the blade above the fillet and
    within 5 mm of it; -inf where the blade never comes near."""
    cp, mp = gen.cp, gen.mp
    s, c0 = cp["s"], cp["chi0"]
    p = gen._mirror(np.asarray(points, float).reshape(-1, 3))       # the canonical (left-hand) machine's member frame
    pen = np.full(len(p), -np.inf)
    for psi in psis:
        r = to_machine(p, np.full(len(p), psi), mp)
        C = mp["S"] * np.array([np.cos(np.pi - mp["q"] + psi), np.sin(np.pi - mp["q"] + psi)])
        rho = np.hypot(r[:, 0] - C[0], r[:, 1] - C[1])
        rho_b = cp["Rh"] - s * r[:, 2] / np.sin(c0) * np.cos(c0)      # u = -z / sin(chi0) on the straight blade
        near = (r[:, 2] < -cp["u_j"] * np.sin(c0)) & (np.abs(rho_b - rho) < 5.0)   # this blade, above the fillet
        pen = np.maximum(pen, np.where(near, s * (rho_b - rho), -np.inf))
    return pen.reshape(np.shape(points)[:-1])
