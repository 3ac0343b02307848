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
§9.6: 2a = 2 |delta / A|^(1/2)). delta = 0.00635 mm is Gleason's 0.00025 in (seed 001 §4.3.2, docs/theory/ltca.md, Eq.
(L6) / docs/theory/tca.md, Eq. (T6)).
K must be positive definite; lam_1 = 0 is line contact (a = inf), lam_1 < 0 means the surfaces interfere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from scipy.special import ellipe, ellipk

from .._core.tca import ellipse_axes, relative_curvature, weingarten
from ..errors import DesignError
from .contact_surface import surface_derivatives

__all__ = ["ContactEllipse", "curvature_tensor", "contact_ellipse", "contact_ellipse_from_surfaces",
           "GLEASON_APPROACH", "hertz_semi_axes", "hertz_peak_pressure"]

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


def _hertz_shape(lam):
    """Eccentricity data of the Hertz ellipse for relative curvatures ``lam (..., 2)``, lam_1 <= lam_2, both > 0.

    With A = lam_1/2 <= B = lam_2/2, k = b/a and m = e^2 = 1 - k^2 solve (Johnson, Contact Mechanics, §4.2,
    Eq. (4.39)) B/A = (E(m)/k^2 - K(m)) / (K(m) - E(m)); the right side falls monotonically from +inf (k -> 0) to 1
    (k = 1), so bisection on log k (80 halvings: k to 1e-16 relative) is exact and array-based.
    Returns (m, K(m), E(m), (K - E)/m), the last with its finite limit pi/4 as m -> 0.
    """
    lam = np.asarray(lam, float)
    ratio = lam[..., 1] / lam[..., 0]
    lo, hi = np.full(ratio.shape, np.log(1e-12)), np.zeros(ratio.shape)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        k = np.exp(mid)
        m = 1.0 - k * k
        K, E = ellipk(m), ellipe(m)
        with np.errstate(divide="ignore", invalid="ignore"):
            g = (E / (k * k) - K) / (K - E)
        g = np.where(m < 1e-12, 1.0, g)
        big = g > ratio  # k too small
        lo, hi = np.where(big, mid, lo), np.where(big, hi, mid)
    k = np.exp(0.5 * (lo + hi))
    m = 1.0 - k * k
    K, E = ellipk(m), ellipe(m)
    with np.errstate(divide="ignore", invalid="ignore"):
        kem = np.where(m > 1e-8, (K - E) / np.where(m > 1e-8, m, 1.0), np.pi / 4 * (1 + 3 * m / 8))
    return m, K, E, kem


def hertz_semi_axes(lam, approach):
    """Semi-axes (..., 2) mm (a >= b) of the Hertz contact ellipse at the elastic approach ``approach`` mm.

    The elastic contact (Hertz) is smaller than the geometric ellipse s(xi) = approach of :func:`ellipse_axes`: with
    A = lam_1/2 (Johnson, Contact Mechanics, Eqs. (4.39)-(4.41)) a^2 = approach (K - E) / (A K e^2),
    b = a sqrt(1 - e^2); a sphere (e = 0) gives a^2 = R approach, half of the geometric a^2 = 2 R approach. Non-positive
    lam: inf.
    """
    _check_approach(approach)
    lam = np.asarray(lam, float)
    ok = np.all(lam > 0, axis=-1) & np.all(np.isfinite(lam), axis=-1)
    lam_ok = np.where(ok[..., None], lam, 1.0)
    m, K, _, kem = _hertz_shape(lam_ok)
    a = np.sqrt(approach * kem / (0.5 * lam_ok[..., 0] * K))
    b = a * np.sqrt(1.0 - m)
    return np.where(ok[..., None], np.stack([a, b], -1), np.inf)


def hertz_peak_pressure(lam, force, estar):
    """Hertz peak pressure p0 (N/mm^2) and semi-axes (a, b) mm of an elliptical contact under the normal force
    ``force`` N with contact modulus ``estar`` N/mm^2: a^3 = 3 F (K - E) / (2 pi E* e^2 A), p0 = 3 F / (2 pi a b)
    (Johnson, Contact Mechanics, Eqs. (4.37)-(4.41)). lam (..., 2) must be positive (point contact)."""
    lam = np.asarray(lam, float)
    if not np.all(lam > 0):
        raise DesignError.single("lam", lam.tolist(), "> 0 (point contact)", "1/mm", "Hertz pressure")
    m, K, _, kem = _hertz_shape(lam)
    a = np.cbrt(3.0 * np.asarray(force, float) * kem / (2 * np.pi * estar * 0.5 * lam[..., 0]))
    b = a * np.sqrt(1.0 - m)
    return 3.0 * force / (2 * np.pi * a * b), np.stack([a, b], -1)
