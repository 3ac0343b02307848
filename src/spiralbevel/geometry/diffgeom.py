"""Generic differential geometry of a vectorized parametric surface r = f(u, v), by numerical differentiation.

Nothing here knows about log spirals or gears: any ``f(u, v) -> (..., 3)`` that broadcasts over its arguments works
(closed-form flanks, generated face-milled flanks, test surfaces). Derivatives come from central differences refined
by Richardson extrapolation (steps h, h/2, h/4, ... ; the error terms of central differences are even powers of h,
so ``levels`` steps give an O(h^(2 levels)) result). With the default h = 4e-2 and 3 levels the derivatives of a
smooth surface of unit-order parameter scale are accurate to about 1e-10 relative (roundoff dominated).

Sign conventions (docs/conventions.md): the unit normal n is sign * (r_u x r_v)/|r_u x r_v| or the orientation
closest to a user-given reference direction; the second fundamental form is taken as II = dr . dn, i.e.
L = -r_uu . n, M = -r_uv . n, N = -r_vv . n, so that a curvature is **positive when the surface is convex seen from
the side n points into** (a sphere with outward normal has +1/R). Principal curvatures are the eigenvalues of
I^-1 II, computed without assuming F = 0 or M = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SurfaceDerivatives", "SurfaceGeometry", "derivatives", "surface_geometry", "shape_operator_eigen"]


@dataclass(frozen=True, eq=False)
class SurfaceDerivatives:
    """Point and partial derivatives up to second order, each (..., 3), in the units of f per parameter unit."""

    r: np.ndarray
    r_u: np.ndarray
    r_v: np.ndarray
    r_uu: np.ndarray
    r_uv: np.ndarray
    r_vv: np.ndarray


def _richardson(values, levels):
    """Extrapolate a list of estimates at h, h/2, h/4, ... with even-power error expansion."""
    table = list(values)
    for j in range(1, levels):
        factor = 4.0**j - 1.0
        table = [table[k] + (table[k] - table[k - 1]) / factor for k in range(1, len(table))]
    return table[-1]


def derivatives(f, u, v, step=4e-2, levels=3) -> SurfaceDerivatives:
    """Partial derivatives of ``f`` at broadcastable ``u, v`` by Richardson-extrapolated central differences.

    Parameters
    ----------
    f : callable
        ``f(u, v) -> (..., 3)``, vectorized (broadcasts over u and v).
    u, v : array_like float
        Parameter values (any units); broadcast together.
    step : float or (2,) float
        Largest step (hu, hv) in the parameter units. The finest step is step / 2**(levels - 1).
    levels : int
        Number of step halvings combined (1 = plain central differences, O(h^2)).

    Returns
    -------
    SurfaceDerivatives
        r, r_u, r_v, r_uu, r_uv, r_vv, each (..., 3).

    Notes
    -----
    All 8 * levels + 1 evaluations are made in one call of ``f`` on a stacked parameter array. Stencils:
    r_u = (f(u+h) - f(u-h)) / 2h, r_uu = (f(u+h) - 2f + f(u-h)) / h^2, r_uv = (f(u+h,v+k) - f(u+h,v-k) - f(u-h,v+k)
    + f(u-h,v-k)) / 4hk; all have error series in even powers of the step.
    """
    u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    hu, hv = np.broadcast_to(np.asarray(step, float), (2,))
    offsets = [(0.0, 0.0)]
    for k in range(levels):
        a, b = hu / 2**k, hv / 2**k
        offsets += [(a, 0.0), (-a, 0.0), (0.0, b), (0.0, -b), (a, b), (a, -b), (-a, b), (-a, -b)]
    du = np.array([o[0] for o in offsets]).reshape((-1,) + (1,) * u.ndim)
    dv = np.array([o[1] for o in offsets]).reshape((-1,) + (1,) * u.ndim)
    pts = np.asarray(f(u[None] + du, v[None] + dv), float)
    r0 = pts[0]
    ru, rv, ruu, rvv, ruv = [], [], [], [], []
    for k in range(levels):
        a, b = hu / 2**k, hv / 2**k
        pu, mu, pv, mv, pp, pm, mp, mm = pts[1 + 8 * k: 9 + 8 * k]
        ru.append((pu - mu) / (2 * a))
        rv.append((pv - mv) / (2 * b))
        ruu.append((pu - 2 * r0 + mu) / (a * a))
        rvv.append((pv - 2 * r0 + mv) / (b * b))
        ruv.append((pp - pm - mp + mm) / (4 * a * b))
    return SurfaceDerivatives(r0, _richardson(ru, levels), _richardson(rv, levels), _richardson(ruu, levels),
                              _richardson(ruv, levels), _richardson(rvv, levels))


def shape_operator_eigen(E, F, G, L, M, N, r_u, r_v, normal):
    """Principal curvatures and unit principal directions from the fundamental forms (no F = M = 0 assumption).

    Parameters
    ----------
    E, F, G : (...) float
        First fundamental form.
    L, M, N : (...) float
        Second fundamental form (any sign convention: the eigenvalues of I^-1 II follow it).
    r_u, r_v : (..., 3) float
        Tangent vectors.
    normal : (..., 3) float
        Unit normal, used to orient the second direction.

    Returns
    -------
    k1, k2 : (...) float
        Eigenvalues of I^-1 II; k1 belongs to the principal direction closer to r_u (smaller angle).
    e1, e2 : (..., 3) float
        Unit principal directions, e1 . r_u > 0, e2 = normal x e1 (so e1 x e2 = normal).

    Notes
    -----
    With the orthonormal tangent frame a = r_u/|r_u|, b = n x a, written as a = P[:,0] . (r_u, r_v) and
    b = P[:,1] . (r_u, r_v), the shape operator is the symmetric 2x2 matrix W = P^T II P. Its eigenvectors are at the
    angle theta = atan2(2 W_ab, W_aa - W_bb)/2 from a (and theta + pi/2); the one with |theta| <= pi/4 is e1 and its
    Rayleigh quotient is k1; k2 = trace W - k1. This is stable at umbilics.
    """
    det = E * G - F * F
    sqE = np.sqrt(E)
    a = r_u / sqE[..., None]
    b = np.cross(normal, a)
    bv = np.einsum("...i,...i->...", b, r_v)
    # b = cu r_u + cv r_v with I (cu, cv) = (b.r_u, b.r_v) = (0, bv)
    cu, cv = -F * bv / det, E * bv / det
    au = 1.0 / sqE
    waa = L * au * au
    wab = (L * cu + M * cv) * au
    wbb = L * cu * cu + 2.0 * M * cu * cv + N * cv * cv
    theta = 0.5 * np.arctan2(2.0 * wab, waa - wbb)
    theta = np.where(theta > np.pi / 4, theta - np.pi / 2, np.where(theta < -np.pi / 4, theta + np.pi / 2, theta))
    c, s = np.cos(theta), np.sin(theta)
    k1 = waa * c * c + 2.0 * wab * c * s + wbb * s * s
    k2 = waa + wbb - k1
    e1 = c[..., None] * a + s[..., None] * b
    e2 = np.cross(normal, e1)
    return k1, k2, e1, e2


@dataclass(frozen=True, eq=False)
class SurfaceGeometry:
    """Differential geometry of a surface at a set of points (see :func:`surface_geometry`).

    Attributes
    ----------
    point, r_u, r_v : (..., 3) float
        Point and first derivatives.
    normal : (..., 3) float
        Unit normal with the requested orientation.
    E, F, G, L, M, N : (...) float
        Fundamental forms; L = -r_uu . normal etc. (convex seen from the normal side = positive).
    k1, k2 : (...) float
        Principal curvatures; k1 along the principal direction closer to r_u.
    e1, e2 : (..., 3) float
        Unit principal directions, e1 . r_u > 0, e1 x e2 = normal.
    """

    point: np.ndarray
    r_u: np.ndarray
    r_v: np.ndarray
    normal: np.ndarray
    E: np.ndarray
    F: np.ndarray
    G: np.ndarray
    L: np.ndarray
    M: np.ndarray
    N: np.ndarray
    k1: np.ndarray
    k2: np.ndarray
    e1: np.ndarray
    e2: np.ndarray

    @property
    def gaussian_curvature(self):
        """K = (LN - M^2)/(EG - F^2) = k1 k2."""
        return (self.L * self.N - self.M**2) / (self.E * self.G - self.F**2)

    @property
    def mean_curvature(self):
        """H = (EN - 2FM + GL) / (2(EG - F^2)) = (k1 + k2)/2, positive when convex seen from the normal side."""
        return (self.E * self.N - 2 * self.F * self.M + self.G * self.L) / (2 * (self.E * self.G - self.F**2))

    @property
    def k_max(self):
        """Larger principal curvature."""
        return np.maximum(self.k1, self.k2)

    @property
    def k_min(self):
        """Smaller principal curvature."""
        return np.minimum(self.k1, self.k2)


def surface_geometry(f, u, v, normal_sign=1.0, reference=None, step=4e-2, levels=3) -> SurfaceGeometry:
    """Normals, fundamental forms and principal curvatures of the surface ``f`` at ``(u, v)``, numerically.

    Parameters
    ----------
    f : callable
        ``f(u, v) -> (..., 3)``, vectorized.
    u, v : array_like float
        Parameters (broadcast together).
    normal_sign : float or array_like
        +1 for n along r_u x r_v, -1 for the opposite (broadcast over the points). Ignored when ``reference`` is given.
    reference : (..., 3) float, optional
        Orient n so that n . reference > 0 (for example a point known to lie in the tooth space minus r).
    step, levels
        Passed to :func:`derivatives`.

    Returns
    -------
    SurfaceGeometry
    """
    d = derivatives(f, u, v, step=step, levels=levels)
    cr = np.cross(d.r_u, d.r_v)
    n = cr / np.linalg.norm(cr, axis=-1, keepdims=True)
    if reference is not None:
        sign = np.where(np.einsum("...i,...i->...", n, np.asarray(reference, float)) < 0, -1.0, 1.0)
    else:
        sign = np.asarray(normal_sign, float)
    n = n * sign[..., None]

    def dot(a, b):
        return np.einsum("...i,...i->...", a, b)

    E, F, G = dot(d.r_u, d.r_u), dot(d.r_u, d.r_v), dot(d.r_v, d.r_v)
    L, M, N = -dot(d.r_uu, n), -dot(d.r_uv, n), -dot(d.r_vv, n)
    k1, k2, e1, e2 = shape_operator_eigen(E, F, G, L, M, N, d.r_u, d.r_v, n)
    return SurfaceGeometry(d.r, d.r_u, d.r_v, n, E, F, G, L, M, N, k1, k2, e1, e2)
