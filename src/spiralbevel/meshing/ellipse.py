"""Instantaneous contact ellipses from the principal curvatures of two surfaces in contact.

Derivation (convex = positive convention of docs/conventions.md, outward normals opposite at the contact point):
take the contact point as origin, n = n1 = -n2 and a tangent-plane offset xi. Surface 1 lies below the tangent
plane at height z1(xi) = -1/2 xi^T K1 xi along n (K1 its curvature tensor w.r.t. its outward normal n1; a convex
surface falls away from its outward normal); surface 2, seen along its own outward normal -n, lies at
-1/2 xi^T K2 xi, i.e. at +1/2 xi^T K2 xi along n. The separation is therefore

    s(xi) = z2 - z1 = 1/2 xi^T (K1 + K2) xi + O(|xi|^3).

With the eigenvalues lam_1 <= lam_2 of K = K1 + K2 (the principal relative curvatures) and Litvin's A = lam_1 / 2,
B = lam_2 / 2, s = A xi_1^2 + B xi_2^2. The elastic approach delta of both bodies closes the gap where s <= delta:
the contact ellipse has semi-axes

    a = sqrt(2 delta / lam_1) = sqrt(delta / A),     b = sqrt(2 delta / lam_2) = sqrt(delta / B),

the major axis along the eigenvector of lam_1 (Litvin & Fuentes, Gear Geometry and Applied Theory, 2nd ed.,
§9.6: 2a = 2 |delta / A|^(1/2)). delta = 0.00635 mm is Gleason's 0.00025 in (seed 001 §4.3.2, ERRATA §1.1).
K must be positive definite; lam_1 = 0 is line contact (a = inf), lam_1 < 0 means the surfaces interfere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._core.tca import ellipse_axes, relative_curvature, weingarten
from ..errors import DesignError
from .contact_surface import surface_derivatives

__all__ = ["ContactEllipse", "curvature_tensor", "contact_ellipse", "contact_ellipse_from_surfaces",
           "GLEASON_APPROACH"]

GLEASON_APPROACH = 0.00635
"""Elastic approach (mm) of the contact-ellipse convention, 0.00025 in (seed 001 §4.3.2)."""


@dataclass(frozen=True)
class ContactEllipse:
    """Contact ellipse(s).

    Attributes
    ----------
    semi_axes : (..., 2) float, mm
        (a, b), a >= b.
    directions : (..., 2, 3) float
        Unit major and minor axis directions (frame of the inputs).
    relative_curvatures : (..., 2) float, 1/mm
        lam_1 <= lam_2.
    approach : float, mm
    """

    semi_axes: np.ndarray
    directions: np.ndarray
    relative_curvatures: np.ndarray
    approach: float

    def outline(self, center, n=73):
        """Ellipse polylines (..., n, 3) mm around ``center (..., 3)``."""
        t = np.linspace(0.0, 2 * np.pi, n)
        a = self.semi_axes[..., 0, None, None]
        b = self.semi_axes[..., 1, None, None]
        d1 = self.directions[..., None, 0, :]
        d2 = self.directions[..., None, 1, :]
        return (np.asarray(center, float)[..., None, :] + a * np.cos(t)[:, None] * d1
                + b * np.sin(t)[:, None] * d2)


def curvature_tensor(k, dirs):
    """Curvature (Weingarten) tensor (..., 3, 3) from principal curvatures ``k (..., 2)`` and unit directions
    ``dirs (..., 2, 3)``: W = k_1 d_1 d_1^T + k_2 d_2 d_2^T."""
    k = np.asarray(k, float)
    d = np.asarray(dirs, float)
    return (k[..., 0, None, None] * d[..., 0, :, None] * d[..., 0, None, :]
            + k[..., 1, None, None] * d[..., 1, :, None] * d[..., 1, None, :])


def _check_approach(approach):
    if not (np.isfinite(approach) and approach > 0):
        raise DesignError.single("approach", approach, "> 0", "mm", "elastic approach of the contact ellipse")


def contact_ellipse(k1, dirs1, k2, dirs2, normal, approach=GLEASON_APPROACH) -> ContactEllipse:
    """Contact ellipse from the principal curvatures and directions of both surfaces.

    Parameters
    ----------
    k1, k2 : (..., 2) float, 1/mm
        Principal curvatures of surfaces 1 and 2, each convex = positive w.r.t. its own outward normal.
    dirs1, dirs2 : (..., 2, 3) float
        Unit principal directions, all in one common frame.
    normal : (..., 3) float
        Contact normal (either surface's).
    approach : float, mm
        Elastic approach delta.
    """
    _check_approach(approach)
    W1 = curvature_tensor(k1, dirs1)
    W2 = curvature_tensor(k2, dirs2)
    lam, d = relative_curvature(W1, W2, np.asarray(normal, float))
    return ContactEllipse(ellipse_axes(lam, approach), d, lam, float(approach))


def contact_ellipse_from_surfaces(surface1, params1, rot1, surface2, params2, rot2,
                                  approach=GLEASON_APPROACH) -> ContactEllipse:
    """Contact ellipse at contact points given by surface parameters and member -> common-frame rotations.

    Parameters
    ----------
    surface1, surface2 : ContactSurface
    params1, params2 : (..., 2) float
    rot1, rot2 : (..., 3, 3) float
        Rotations of the member frames into the common frame (translations do not matter).
    """
    _check_approach(approach)
    r1, n1, dr1, dn1 = surface_derivatives(surface1, params1)
    r2, n2, dr2, dn2 = surface_derivatives(surface2, params2)
    W1 = rot1 @ weingarten(dr1, dn1) @ np.swapaxes(rot1, -1, -2)
    W2 = rot2 @ weingarten(dr2, dn2) @ np.swapaxes(rot2, -1, -2)
    n = np.einsum("...ij,...j->...i", rot1, n1)
    lam, d = relative_curvature(W1, W2, n)
    return ContactEllipse(ellipse_axes(lam, approach), d, lam, float(approach))
