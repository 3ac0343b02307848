"""Conjugacy check of a designed log-spiral pair: envelope of each pinion flank vs the mating gear flank.

Uses the general envelope solver (it does not know the surfaces are log spirals): for an exact design the envelope
lies on the gear flank to round-off; a design error (for example an inconsistent base cone) shows as a distance.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._core.rotations import rot_z
from ..conventions import Member, Side
from ..meshing.conjugate import compare_conjugate
from ..meshing.envelope import solve_envelope
from ..meshing.kinematics import BevelPairKinematics


def _surface(flank):
    """(u = phi, v = psi) -> (points, outward normals) of a placed flank in its member frame."""
    s = math.sin(flank.surface.base_cone_angle)

    def surface(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        g = flank.evaluate(u + v / s, u)
        return g.point, g.normal

    return surface


def _bounds(flank, margin=0.15):
    d = flank.domain
    dphi, dpsi = margin * (d.phi_max - d.phi_min), margin * (d.psi_max - d.psi_min)
    return (d.phi_min - dphi, d.phi_max + dphi), (d.psi_min - dpsi, d.psi_max + dpsi)


def conjugacy_report(pair, n_face: int = 9, n_profile: int = 5) -> dict:
    """For each pinion side, the deviation of its envelope on the gear from the mating gear flank.

    Returns
    -------
    dict
        ``{pinion_side: {"gear_side", "max_distance_mm", "rms_distance_mm", "max_normal_mismatch", "conjugate",
        "points"}}``; the envelope is taken on the plane of action that carries the pair of flanks.
    """
    kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
    pitch = 2.0 * math.pi / pair.gear.teeth
    out: dict[str, dict[str, Any]] = {}
    for side in (Side.CONVEX, Side.CONCAVE):
        pf, gf = pair.flank(Member.PINION, side), pair.flank(Member.GEAR, side.mate)
        d = pf.domain
        u = np.linspace(d.phi_min, d.phi_max, n_face)[:, None]
        v = np.linspace(d.psi_min, d.psi_max, n_profile)[None, :]
        cand = _surface(gf)
        az_c = math.atan2(*gf.evaluate(*pair.mean_parameters(Member.GEAR, side.mate)).point[[1, 0]])
        best = None
        for branch in (1, -1):
            env = solve_envelope(_surface(pf), kin, u, v, branch=branch, strict=False)
            ok = env.converged
            if not np.any(ok):
                continue
            pts, nrm = env.points[ok], env.normals[ok]
            c = pts.mean(axis=0)
            k = round(math.remainder(math.atan2(c[1], c[0]) - az_c, 2 * math.pi) / pitch)
            R = rot_z(-k * pitch)
            rep = compare_conjugate(pts @ R.T, nrm @ R.T, cand, _bounds(gf), distance_tol=1e-6)
            if best is None or rep.max_distance < best[1].max_distance:
                best = (branch, rep, int(ok.sum()))
        if best is None:
            out[side.value] = {"gear_side": side.mate.value, "conjugate": False, "points": 0}
            continue
        _, rep, n = best
        out[side.value] = {
            "gear_side": side.mate.value, "max_distance_mm": rep.max_distance, "rms_distance_mm": rep.rms_distance,
            "max_normal_mismatch": rep.max_normal_mismatch, "conjugate": bool(rep.max_distance < 1e-6), "points": n,
        }
    return out
