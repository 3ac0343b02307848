"""The surface protocol of tooth contact analysis, and numerical differential geometry on it.

A tooth flank enters TCA through :class:`ContactSurface`: a map from two surface parameters to points and outward
unit normals in the member frame (docs/conventions.md). Anything with an ``evaluate`` method plugs in: the
log-spiral flank (seed 000), a face-milled generated flank (seed 001; parameters (theta, psi_c), with the equation of
meshing of generation solved inside ``evaluate``), or a modified surface (:class:`NormalDeviation`).

Optional members are used when present:

* ``derivatives(params) -> (r, n, dr, dn)`` with ``dr, dn (..., 3, 2)``: analytic first derivatives of the point
  and of the outward normal with respect to the two parameters (the Jacobian of TCA and the curvatures need them;
  central differences of ``evaluate`` are used otherwise);
* ``contains(params) -> (...) bool``: whether parameters lie on the flank (toe/heel, root/top); everything is
  inside when absent;
* ``reference_params`` (2,) float: a parameter pair near the mean contact point (start of TCA);
* ``fd_step`` (2,) float: step of the central differences, in parameter units.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

from .._core.tca import cross, tangent_basis, weingarten

__all__ = [
    "ContactSurface",
    "surface_derivatives",
    "surface_contains",
    "surface_on_sheet",
    "surface_edge",
    "principal_curvatures",
    "NormalDeviation",
    "quadratic_crowning",
]


@runtime_checkable
class ContactSurface(Protocol):
    """A tooth flank as TCA sees it (see the module docstring for the optional members)."""

    def evaluate(self, params):
        """Points (..., 3) mm and outward unit normals (..., 3) in the member frame at ``params (..., 2)``."""
        ...


def surface_derivatives(surface, params, step=None):
    """Point, outward normal and their first derivatives, analytic when the surface provides them.

    Parameters
    ----------
    surface : ContactSurface
    params : (..., 2) float
        Surface parameters (the surface's units).
    step : (2,) float, optional
        Central-difference step; defaults to ``surface.fd_step`` or 1e-5.

    Returns
    -------
    r, n : (..., 3) float, mm and -
    dr, dn : (..., 3, 2) float
        d r / d params and d n / d params (columns = parameters).
    """
    params = np.asarray(params, float)
    if hasattr(surface, "derivatives"):
        return surface.derivatives(params)
    if step is None:
        step = getattr(surface, "fd_step", (1e-5, 1e-5))
    h = np.asarray(step, float)
    # one stacked call: centre, +h0, -h0, +h1, -h1
    stack = np.stack([params] * 5, 0)
    stack[1, ..., 0] += h[0]
    stack[2, ..., 0] -= h[0]
    stack[3, ..., 1] += h[1]
    stack[4, ..., 1] -= h[1]
    R, N = surface.evaluate(stack)
    dr = np.stack([(R[1] - R[2]) / (2 * h[0]), (R[3] - R[4]) / (2 * h[1])], -1)
    dn = np.stack([(N[1] - N[2]) / (2 * h[0]), (N[3] - N[4]) / (2 * h[1])], -1)
    return R[0], N[0], dr, dn


def surface_contains(surface, params):
    """``surface.contains(params)`` or all True, shape params.shape[:-1]."""
    params = np.asarray(params, float)
    if hasattr(surface, "contains"):
        return np.asarray(surface.contains(params), bool)
    return np.ones(params.shape[:-1], bool)


def surface_on_sheet(surface, params):
    """``surface.on_sheet(params)`` (not past a limit line of generation) or all True, shape params.shape[:-1]."""
    params = np.asarray(params, float)
    if hasattr(surface, "on_sheet"):
        with np.errstate(invalid="ignore"):
            return np.asarray(surface.on_sheet(params), bool)
    return np.ones(params.shape[:-1], bool)


def surface_edge(surface, params):
    """Name of the flank boundary that ``params (..., 2)`` lie beyond (the most violated one), "" where inside or
    where the surface does not name its boundaries (``boundary_margins(params) -> (..., k)`` signed margins, >= 0
    inside, and ``boundary_names`` (k,)), "flank" where it has only ``contains``."""
    params = np.asarray(params, float)
    shape = params.shape[:-1]
    out = np.full(shape, "", dtype=object)
    if hasattr(surface, "boundary_margins"):
        with np.errstate(invalid="ignore"):
            g = np.asarray(surface.boundary_margins(params), float)
        g = np.where(np.isfinite(g), g, -np.inf)
        k = np.argmin(g, axis=-1)
        names = np.asarray(surface.boundary_names, dtype=object)
        out = np.where(np.min(g, axis=-1) < 0, names[k], out)
    elif hasattr(surface, "contains"):
        out = np.where(surface_contains(surface, params), "", "flank").astype(object)
    return out


def principal_curvatures(surface, params):
    """Principal curvatures (convex = positive, w.r.t. the outward normal) and directions in the member frame.

    Returns
    -------
    k : (..., 2) float, 1/mm
        k[..., 0] <= k[..., 1].
    dirs : (..., 2, 3) float
        Unit principal directions; dirs[..., 0] belongs to k[..., 0].
    """
    r, n, dr, dn = surface_derivatives(surface, params)
    W = weingarten(dr, dn)
    e1, e2 = tangent_basis(n)
    T = np.stack([e1, e2], -1)
    K = np.swapaxes(T, -1, -2) @ W @ T
    k, v = np.linalg.eigh(0.5 * (K + np.swapaxes(K, -1, -2)))
    return k, np.swapaxes(T @ v, -1, -2)


class NormalDeviation:
    """A surface displaced along its outward normal: r' = r + w(q) n (crowning, ease-off, flank modification).

    Parameters
    ----------
    base : ContactSurface
        The unmodified flank.
    deviation : callable
        ``deviation(params (..., 2)) -> (w (...), grad (..., 2))``: the displacement along the outward normal in mm
        (negative = material removed) and its gradient with respect to the parameters.

    Notes
    -----
    r'_i = r_i + w_i n + w n_i; n' = unit(r'_0 x r'_1) oriented like n. The normal needs the base's first
    derivatives; the derivatives of n' for the TCA Jacobian are taken by central differences. With a
    :func:`quadratic_crowning` of a log-spiral flank the surface has a compiled ``jet`` (the same
    expressions and differences, :mod:`spiralbevel._core.normal_deviation_jet`), so that TCA runs wholly compiled.
    """

    def __init__(self, base, deviation, fd_step=None):
        self.base = base
        self.deviation = deviation
        self.fd_step = fd_step if fd_step is not None else getattr(base, "fd_step", (1e-5, 1e-5))
        if hasattr(base, "reference_params"):
            self.reference_params = base.reference_params
        if hasattr(base, "contains"):
            self.contains = base.contains
        if hasattr(base, "boundary_margins"):
            self.boundary_margins, self.boundary_names = base.boundary_margins, base.boundary_names
        if getattr(base, "boundary_jet", None) is not None:
            self.boundary_jet = base.boundary_jet  # the margins are the base's (parameters unchanged)

    @property
    def jet(self):
        """``(kind, prm)`` of the compiled jet (:mod:`spiralbevel._core.normal_deviation_jet`) where the base is a
        log-spiral flank with a compiled jet and the deviation a :func:`quadratic_crowning` (``deviation.quadratic``),
        else None (numpy)."""
        base = getattr(self.base, "jet", None)
        quad = getattr(self.deviation, "quadratic", None)
        if base is None or quad is None or int(base[0]) != 0:  # LOGSPIRAL of _core.jets
            return None
        from .._core import normal_deviation_jet as _nd  # numba stays off the import path of the CLI

        from .._core.jets import NORMAL_QUADRATIC

        return NORMAL_QUADRATIC, _nd.parameters(base[0], base[1], quad[0], quad[1], self.fd_step)

    def evaluate(self, params):
        r, n, dr, dn = surface_derivatives(self.base, params)
        w, g = self.deviation(np.asarray(params, float))
        w = np.asarray(w, float)
        g = np.asarray(g, float)
        with np.errstate(all="ignore"):
            return self._modify(r, n, dr, dn, w, g)

    @staticmethod
    def _modify(r, n, dr, dn, w, g):
        t0 = dr[..., 0] + g[..., 0, None] * n + w[..., None] * dn[..., 0]
        t1 = dr[..., 1] + g[..., 1, None] * n + w[..., None] * dn[..., 1]
        m = cross(t0, t1)
        m /= np.linalg.norm(m, axis=-1, keepdims=True)
        m *= np.sign(np.einsum("...i,...i->...", m, n))[..., None]
        return r + w[..., None] * n, m


def quadratic_crowning(center, coeffs):
    """Deviation function w(q) = -(c00 dq0^2 + 2 c01 dq0 dq1 + c11 dq1^2), dq = q - center, for NormalDeviation.

    Parameters
    ----------
    center : (2,) float
        Parameters of the untouched point.
    coeffs : (c00, c01, c11) float, mm per (parameter unit)^2
        Positive definite for material removed all around the centre (a crowned flank).
    """
    c = np.asarray(center, float)
    c00, c01, c11 = (float(v) for v in coeffs)

    def deviation(params):
        d = np.asarray(params, float) - c
        w = -(c00 * d[..., 0] ** 2 + 2 * c01 * d[..., 0] * d[..., 1] + c11 * d[..., 1] ** 2)
        g = -2.0 * np.stack([c00 * d[..., 0] + c01 * d[..., 1], c01 * d[..., 0] + c11 * d[..., 1]], -1)
        return w, g

    deviation.quadratic = (c.copy(), (c00, c01, c11))  # read by NormalDeviation.jet
    return deviation
