"""Local contact flattening: Boussinesq half-space influence of uniform-pressure rectangular cells (Love's closed
form), combined for the two bodies through the contact modulus E*.

The potential contact points of one tooth pair form a regular grid in the common tangent plane; each point carries
its normal force as a uniform pressure on its cell. The approach of the two surfaces at cell i per unit force on cell
j is (Johnson, Contact Mechanics, Eq. (3.25))

    C_ij = I(x_i - x_j, y_i - y_j; dx/2, dy/2) / (pi E* dx dy),   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2

with I the integral of 1/r over the cell (:func:`spiralbevel._core.ltca.rect_integral`).
"""

from __future__ import annotations

import numpy as np

from ..._core import ltca as _k
from ...errors import DesignError

__all__ = ["Material", "STEEL", "contact_modulus", "halfspace_flexibility"]

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    """Linear-elastic isotropic material.

    Parameters
    ----------
    youngs_modulus : float, N/mm^2
        E (> 0).
    poisson_ratio : float, -
        nu, -1 < nu < 0.5.
    """

    youngs_modulus: float = 206000.0
    poisson_ratio: float = 0.3

    def __post_init__(self):
        E, nu = self.youngs_modulus, self.poisson_ratio
        if not (np.isfinite(E) and E > 0):
            raise DesignError.single("youngs_modulus", E, "> 0", "N/mm^2", "material")
        if not (np.isfinite(nu) and -1.0 < nu < 0.5):
            raise DesignError.single("poisson_ratio", nu, "-1 < value < 0.5", "-", "material")


STEEL = Material()


def contact_modulus(material1: Material = STEEL, material2: Material = STEEL) -> float:
    """Contact modulus E* [N/mm^2]: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson, Contact Mechanics, Eq. (4.22))."""
    inv = sum((1.0 - m.poisson_ratio**2) / m.youngs_modulus for m in (material1, material2))
    return 1.0 / inv


def halfspace_flexibility(xy, dx, dy, estar) -> np.ndarray:
    """Flexibility matrix [mm/N] of cells on a regular tangent-plane grid from the half-space solution.

    Parameters
    ----------
    xy : (n, 2) float, mm
        Cell centres in the common tangent plane.
    dx, dy : float, mm
        Cell sizes along the two tangent-plane axes (> 0).
    estar : float, N/mm^2
        Contact modulus (see :func:`contact_modulus`).

    Returns
    -------
    (n, n) float, mm/N
        Symmetric positive definite for a regular grid.
    """
    for name, v in (("dx", dx), ("dy", dy), ("estar", estar)):
        if not (np.isfinite(v) and v > 0):
            raise DesignError.single(name, v, "> 0", "N/mm^2" if name == "estar" else "mm", "half-space influence")
    xy = np.asarray(xy, float).reshape(-1, 2)
    return _k.halfspace_matrix(xy, float(dx), float(dy), float(estar))
