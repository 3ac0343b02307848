"""Initial separations of two tooth surfaces along the common normal around a contact point.

A grid of points q = P + s e1 + t e2 lies in the common tangent plane at the unloaded contact point P (normal n0,
outward from body 1 toward body 2). The line q + zeta n0 meets surface 1 at zeta1 and surface 2 at zeta2; the
separation is w = zeta2 - zeta1 (mm, >= 0 when the surfaces are apart). Each intersection is one small nonlinear
system (u, v, zeta), all solved at once by :func:`spiralbevel._core.newton.solve_batched`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..._core.newton import solve_batched
from ...errors import ConvergenceError, DesignError

__all__ = ["SeparationGrid", "surface_separations", "posed_separations", "quadratic_separations"]

SurfaceFn = Callable[[np.ndarray, np.ndarray], "tuple[np.ndarray, np.ndarray]"]


@dataclass(frozen=True)
class SeparationGrid:
    """Separations on a tangent-plane grid.

    Attributes
    ----------
    s, t : (ns,), (nt,) float, mm
        Grid coordinates along e1 and e2.
    w : (ns, nt) float, mm
        Separation along n0 (NaN where a surface could not be reached, e.g. outside its domain).
    points1, points2 : (ns, nt, 3) float, mm
        Foot points on surfaces 1 and 2.
    normals1, normals2 : (ns, nt, 3) float
        Outward unit normals there.
    params1, params2 : (ns, nt, 2) float
        Surface parameters of the foot points.
    """

    s: np.ndarray
    t: np.ndarray
    w: np.ndarray
    points1: np.ndarray
    points2: np.ndarray
    normals1: np.ndarray
    normals2: np.ndarray
    params1: np.ndarray
    params2: np.ndarray


def _foot(surface, q, n0, uv0, tol):
    """Intersections of the lines q + zeta n0 with surface(u, v); returns (uv, zeta, ok)."""

    def fun(x):
        r, _ = surface(x[..., 0], x[..., 1])
        return r - q - x[..., 2:3] * n0

    x0 = np.concatenate([uv0, np.zeros(uv0.shape[:-1] + (1,))], axis=-1)
    res = solve_batched(fun, x0, tol=tol, max_iter=40)
    return res.x[..., :2], res.x[..., 2], res.converged & np.all(np.isfinite(res.x), axis=-1)


def surface_separations(surface1: SurfaceFn, surface2: SurfaceFn, point, normal, e1, s, t, uv1, uv2,
                        tol=1e-11) -> SeparationGrid:
    """Separations w(s, t) of two surfaces along the common normal (exact surfaces, no quadratic approximation).

    Parameters
    ----------
    surface1, surface2 : callable
        ``surface(u, v) -> (points (..., 3) mm, outward unit normals (..., 3))`` in one common frame.
    point : (3,) float, mm
        Unloaded contact point P.
    normal : (3,) float
        Unit normal n0 at P, outward from body 1 (toward body 2).
    e1 : (3,) float
        First tangent direction (made orthogonal to n0); e2 = n0 x e1.
    s, t : (ns,), (nt,) float, mm
        Grid coordinates along e1 and e2.
    uv1, uv2 : (2,) float
        Surface parameters of P on each surface (starting guesses).
    tol : float, mm
        Residual tolerance of the intersections.

    Returns
    -------
    SeparationGrid
    """
    P = np.asarray(point, float)
    n0 = np.asarray(normal, float)
    n0 = n0 / np.linalg.norm(n0)
    e1 = np.asarray(e1, float) - np.dot(e1, n0) * n0
    if np.linalg.norm(e1) < 1e-12:
        raise DesignError.single("e1", list(np.ravel(e1)), "not parallel to the normal", "-", "separation grid")
    e1 = e1 / np.linalg.norm(e1)
    e2 = np.cross(n0, e1)
    s = np.atleast_1d(np.asarray(s, float))
    t = np.atleast_1d(np.asarray(t, float))
    S, Tt = np.meshgrid(s, t, indexing="ij")
    q = P + S[..., None] * e1 + Tt[..., None] * e2
    out = {}
    for k, (surf, uv) in enumerate(((surface1, uv1), (surface2, uv2)), start=1):
        uv = np.asarray(uv, float)
        r, _ = surf(np.array([uv[0]]), np.array([uv[1]]))
        if np.linalg.norm(r[0] - P) > 1e-6 * (1 + np.linalg.norm(P)):
            raise DesignError.single(f"uv{k}", list(uv), "parameters of the contact point", "-",
                                     f"surface {k} at uv{k} is {np.linalg.norm(r[0] - P):.3e} mm from the point")
        # linear first guess of the parameters from the tangent plane at P
        h = 1e-6 * (1 + np.abs(uv))
        ru = (surf(np.array([uv[0] + h[0]]), np.array([uv[1]]))[0][0] - r[0]) / h[0]
        rv = (surf(np.array([uv[0]]), np.array([uv[1] + h[1]]))[0][0] - r[0]) / h[1]
        J = np.stack([ru, rv], axis=1)
        duv = np.linalg.lstsq(J, (q - P).reshape(-1, 3).T, rcond=None)[0].T.reshape(q.shape[:-1] + (2,))
        uvq, zeta, ok = _foot(surf, q, n0, uv + duv, tol)
        pts, nrm = surf(uvq[..., 0], uvq[..., 1])
        zeta = np.where(ok, zeta, np.nan)
        out[k] = (uvq, zeta, pts, nrm)
    w = out[2][1] - out[1][1]
    if not np.isfinite(w[np.argmin(np.abs(s)), np.argmin(np.abs(t))]):
        raise ConvergenceError("separation at the contact point could not be computed", 40, float("nan"))
    return SeparationGrid(s, t, w, out[1][2], out[2][2], out[1][3], out[2][3], out[1][0], out[2][0])


def quadratic_separations(curvature, s, t) -> np.ndarray:
    """Second-order separation w = 1/2 [s t] K [s t]^T on a tangent-plane grid [mm].

    Parameters
    ----------
    curvature : (2, 2) float, 1/mm
        Relative normal-curvature matrix K = K1 + K2 in the (e1, e2) basis, convex = positive for each body
        (docs/conventions.md), so K is positive semi-definite for surfaces that touch at one point.
    s, t : (ns,), (nt,) float, mm

    Returns
    -------
    (ns, nt) float, mm
    """
    K = np.asarray(curvature, float)
    S, Tt = np.meshgrid(np.asarray(s, float), np.asarray(t, float), indexing="ij")
    return 0.5 * (K[0, 0] * S**2 + (K[0, 1] + K[1, 0]) * S * Tt + K[1, 1] * Tt**2)


def posed_separations(surface1, surface2, poses1, poses2, uv1, uv2, point, normal, e1, s, t,
                      tol=1e-10) -> SeparationGrid:
    """Separations of many contacts at once, each between two member-frame surfaces placed by its own poses.

    The batched form of :func:`surface_separations` for the pairs of a mesh cycle: contact m has the pinion
    (surface 1) placed by ``poses1[m] = (R, o)`` (fixed point = o + R r) and the gear by ``poses2[m]``; one Newton
    solve (:func:`spiralbevel._core.newton.solve_batched`, Jacobian from the surface derivatives) covers every
    contact and grid point.

    Parameters
    ----------
    surface1, surface2 : ContactSurface
        Member-frame surfaces (``evaluate(params) -> (r, n_out)``; ``derivatives`` used when present).
    poses1, poses2 : ((m, 3, 3), (m, 3)) float
        Rotations and origins member -> common frame.
    uv1, uv2 : (m, 2) float
        Surface parameters of the contact points.
    point, normal, e1 : (m, 3) float
        Contact points (mm), unit normals outward from body 1, and first tangent directions (common frame).
    s, t : (ns,), (nt,) or (m, ns), (m, nt) float, mm
        Grid coordinates along e1 and e2 = normal x e1 (one grid for all contacts, or one per contact).
    tol : float, mm
        Residual tolerance of the intersections.

    Returns
    -------
    SeparationGrid
        With a leading contact axis: w (m, ns, nt), points/normals (m, ns, nt, 3) in the common frame, params
        (m, ns, nt, 2); NaN where a surface could not be reached.
    """
    from ..contact_surface import surface_derivatives

    P = np.asarray(point, float)
    n0 = np.asarray(normal, float)
    n0 = n0 / np.linalg.norm(n0, axis=-1, keepdims=True)
    e1 = np.asarray(e1, float)
    e1 = e1 - np.sum(e1 * n0, -1, keepdims=True) * n0
    e1 = e1 / np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(n0, e1)
    s = np.atleast_1d(np.asarray(s, float))
    t = np.atleast_1d(np.asarray(t, float))
    # one grid for all contacts (ns,), (nt,) or one per contact (m, ns), (m, nt)
    S = s[..., :, None] * np.ones(t.shape[-1])
    Tt = t[..., None, :] * np.ones((s.shape[-1], 1))
    S, Tt = np.broadcast_to(S, (len(P),) + S.shape[-2:]), np.broadcast_to(Tt, (len(P),) + Tt.shape[-2:])
    q = P[:, None, None] + S[..., None] * e1[:, None, None] + Tt[..., None] * e2[:, None, None]
    shape = q.shape[:-1]
    N = int(np.prod(shape))
    qf = q.reshape(N, 3)
    nf = np.broadcast_to(n0[:, None, None, :], q.shape).reshape(N, 3)
    out = []
    for surf, (R, o), uv in ((surface1, poses1, uv1), (surface2, poses2, uv2)):
        R = np.asarray(R, float)
        o = np.asarray(o, float).reshape(-1, 3)
        uv = np.asarray(uv, float)
        with np.errstate(all="ignore"):
            _, _, dr0, _ = surface_derivatives(surf, uv)
        J0 = np.einsum("mij,mjk->mik", R, dr0)  # (m, 3, 2)
        duv = np.einsum("mij,mabj->mabi", np.linalg.pinv(J0), q - P[:, None, None])
        x0 = np.concatenate([uv[:, None, None] + duv, np.zeros(shape + (1,))], -1).reshape(N, 3)
        Rf = np.broadcast_to(R[:, None, None], shape + (3, 3)).reshape(N, 3, 3)
        of = np.broadcast_to(o[:, None, None], q.shape).reshape(N, 3)
        x, ok = _posed_newton(surf, Rf, of, qf, nf, x0, tol)
        with np.errstate(all="ignore"):
            r, nrm = surf.evaluate(x[:, :2])
        pts = of + np.einsum("nij,nj->ni", Rf, r)
        nrm = np.einsum("nij,nj->ni", Rf, nrm)
        out.append((x[:, :2].reshape(shape + (2,)), np.where(ok, x[:, 2], np.nan).reshape(shape),
                    pts.reshape(q.shape), nrm.reshape(q.shape)))
    w = out[1][1] - out[0][1]
    return SeparationGrid(s, t, w, out[0][2], out[1][2], out[0][3], out[1][3], out[0][0], out[1][0])



def _posed_newton(surf, R, o, q, n0, x, tol, max_iter=30, diverged=1e3):
    """Newton on o + R r(u, v) - q - zeta n0 = 0 for flat batches, iterating only the unconverged systems and
    dropping those that leave the surface (NaN) or run away (residual > ``diverged`` mm)."""
    from ..contact_surface import surface_derivatives

    x = np.array(x, float)
    ok = np.zeros(len(x), bool)
    act = np.arange(len(x))
    with np.errstate(all="ignore"):
        for _ in range(max_iter + 1):
            if act.size == 0:
                break
            r, _, dr, _ = surface_derivatives(surf, x[act, :2])
            f = o[act] + np.einsum("nij,nj->ni", R[act], r) - q[act] - x[act, 2:3] * n0[act]
            res = np.max(np.abs(f), axis=-1)
            done = res < tol
            ok[act[done]] = True
            keep = ~done & np.isfinite(res) & (res < diverged)
            act, f, dr = act[keep], f[keep], dr[keep]
            if act.size == 0:
                break
            J = np.concatenate([np.einsum("nij,njk->nik", R[act], dr), -n0[act][..., None]], -1)
            dx = np.linalg.solve(J, -f[..., None])[..., 0]
            x[act] += np.where(np.isfinite(dx), dx, 0.0)
    return x, ok
