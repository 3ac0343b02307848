"""Shared flank cases for the draft and tool-path tests: any object with rho0, base_cone_angle, spiral_angle."""

from __future__ import annotations

import math
from dataclasses import dataclass

from spiralbevel.geometry.domain import ParallelogramDomain


@dataclass(frozen=True)
class Flank:
    rho0: float
    base_cone_angle: float
    spiral_angle: float


DELTA = math.radians(20.0)
BETA = math.radians(32.6146071483)  # docs/theory/logspiral.md, Eq. (S12), example: beta_plane of Z 23/65, beta_m 35 deg


def make(beta_sign: int, psi_sign: int, psi=(0.3, 0.5), phi=(0.0, 0.6), rho0=100.0, delta=DELTA, beta=BETA):
    """Flank and domain for one hand (beta_sign) and branch (psi_sign); the domain is mirrored with the hand so that
    (beta, psi, phi) -> (-beta, -psi, -phi) is the left-hand mirror image of the right-hand flank."""
    lo, hi = sorted((psi_sign * psi[0], psi_sign * psi[1]))
    plo, phi_hi = sorted((beta_sign * phi[0], beta_sign * phi[1]))
    return Flank(rho0, delta, beta_sign * beta), ParallelogramDomain(plo, phi_hi, lo, hi, delta)
