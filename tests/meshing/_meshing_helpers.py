"""Test helpers: log-spiral flanks from the closed-form ``_core`` kernel and the pairs of docs/theory/gearing.md, Eqs.
(M1)-(M8)"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spiralbevel._core import logspiral as ls
from spiralbevel._core import meshing as _m
from spiralbevel.meshing.kinematics import BevelPairKinematics

#: (shaft angle deg, z1, z2, beta deg) — pairs named in docs/theory/gearing.md, Eqs. (M1)-(M8), beta = spiral parameter
# of Eq. (16)
PAIRS = [
    (90.0, 23, 65, 35.0),
    (90.0, 23, 65, -30.0),
    (75.0, 17, 41, 30.0),
    (75.0, 17, 41, -35.0),
    (105.0, 12, 31, 25.0),
    (105.0, 12, 31, -25.0),
]
ALPHA_T = np.radians(20.0)  # transverse: sin d_i = sin g_i cos alpha_t (docs/theory/logspiral.md, Eq. (S12))


def flank(rho0, delta, beta):
    """Seed-000 flank as a black-box surface(u = phi, v = psi) -> (points, outward normals sign(psi) n)."""

    def surface(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        g = ls.geometry(u + v / np.sin(delta), u, rho0, delta, beta)
        return g["r"], np.sign(v)[..., None] * g["n"]

    return surface


def flank_points_only(rho0, delta, beta):
    """The same flank returning points only (the solver then differentiates numerically)."""
    surf = flank(rho0, delta, beta)
    return lambda u, v: surf(u, v)[0]


@dataclass
class Case:
    kin: BevelPairKinematics
    delta1: float
    delta2: float
    beta: float
    surface: object
    u: np.ndarray  # phi grid (column)
    v: np.ndarray  # psi grid (row)


def make_case(shaft_deg, z1, z2, beta_deg, rho0=100.0, n_u=31, n_v=15):
    kin = BevelPairKinematics(np.radians(shaft_deg), z1, z2)
    d1 = np.arcsin(np.sin(kin.pitch_angle_pinion) * np.cos(ALPHA_T))
    d2 = np.arcsin(np.sin(kin.pitch_angle_gear) * np.cos(ALPHA_T))
    beta = np.radians(beta_deg)
    u = np.linspace(-0.3, 0.3, n_u)[:, None]
    v = np.linspace(0.05, 0.4, n_v)[None, :]
    return Case(kin, d1, d2, beta, flank(rho0, d1, beta), u, v)


def gear_candidate(points, delta2, beta2, psi_sign=1.0, margin=0.2):
    """Seed-000 gear flank through the points (rho0 fitted from the invariant) and a parameter box around them.

    Returns ``(surface, bounds)`` for :func:`spiralbevel.meshing.conjugate.compare_conjugate`.
    """
    k = np.sin(delta2) / np.tan(beta2)
    inv_raw, psi2, _, _ = _m.logspiral_invariant(points, delta2, beta2, psi_sign)
    period = 2 * np.pi * abs(k)
    ln_rho0 = np.median(_m.reduce_periodic(inv_raw, period))
    phi2 = (np.log(np.linalg.norm(points, axis=-1)) - ln_rho0) / k
    a = np.abs(psi2)
    psi_box = (max(a.min() - 0.5 * margin, 1e-3), a.max() + 0.5 * margin)
    if psi_sign < 0:
        psi_box = (-psi_box[1], -psi_box[0])
    bounds = ((phi2.min() - margin, phi2.max() + margin), psi_box)
    return flank(np.exp(ln_rho0), delta2, beta2), bounds


def wrap(x):
    """Angle difference wrapped to (-pi, pi]."""
    return (np.asarray(x) + np.pi) % (2 * np.pi) - np.pi


def seed001_synthesized_pair():
    """Seed 001 drive pair: Table 4 gear convex flank and the pinion concave flank from local synthesis (eta = 6 deg,
    a = 3.7 mm, 3 arcsec parabolic TE), phased for meshing. Returns (pinion surface, gear surface, kinematics)."""
    import math

    from spiralbevel.conventions import Member, Side
    from spiralbevel.machine import seed001_blank, seed001_settings
    from spiralbevel.meshing.generated_surface import phased_for_pair
    from spiralbevel.meshing.synthesis import synthesize_pinion

    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    r = synthesize_pinion(gc, gs, blank, side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7,
                          te_magnitude=3.0 * math.pi / 648000.0)
    c1, c2 = phased_for_pair(r.pinion_flank, r.gear_flank)
    return c1, c2, BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
