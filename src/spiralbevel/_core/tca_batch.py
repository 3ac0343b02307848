"""Fused kernels of tooth contact analysis for many systems at once: the contact system of seed 001 Eq. (16)
(docs/theory/tca.md, Eq. (T5)) on stacked surface data, the Newton step with an LU fast path, and a batched Newton
driver that drops
hopeless systems early.

Same equations and unknowns as :mod:`spiralbevel._core.tca` (x = (q1, q2, phi2), F in mm); this module only
organizes the arithmetic so that one batched Newton iteration costs a few dozen numpy calls:

* a surface's data at m parameter points is stacked as ``S (m, 3, k)``: columns (r, n) for k = 2, or
  (r, n, r_q0, r_q1, n_q0, n_q1) for k = 6, member frame;
* the pinion rotation R_z(phi1) acts on all columns at once; the gear pose R(a2, phi2) B2 equals B2 R_z(phi2)
  (B2 = R_y(S) maps e_z to a2, so R(a2, phi2) = B2 R_z(phi2) B2^T), and one product with the stacked
  (6, 3) matrix [B2; [a2]x B2] gives the fixed-frame gear data and a2 x (gear data) together;
* the Newton step solves the column-equilibrated 5 x 5 system by LU where it is provably regular and falls back to the
  minimum-norm SVD step only where it may be singular (line contact), see :func:`newton_step`.

Pure functions on float64 arrays (mm, rad, xyz on axis -2 of stacked data).
"""

from __future__ import annotations

import numpy as np

from .tca import minnorm_step, tangent_basis

__all__ = [
    "assembly_constants",
    "stack_state",
    "rotate_z",
    "system_stacked",
    "dF_dphi1_stacked",
    "basis_matrix",
    "newton_step",
    "is_singular",
    "newton_batched",
]

#: |det| of a matrix with unit columns bounds its singular values: s_min / s_max >= |det| / s_max^5 and
#: s_max <= sqrt(5) (Frobenius), so |det| > 5^2.5 * rcond guarantees s_min / s_max > rcond.
_DET_BOUND = 5.0 ** 2.5


def assembly_constants(axes, scale):
    """Constants of the stacked contact system from :func:`spiralbevel._core.tca.assembly_axes` output.

    Returns
    -------
    d : (3,) float, mm
        o1 - o2.
    M2 : (6, 3) float
        [B2; [a2]x B2]: gear member frame (turned by phi2 about its z axis) -> fixed frame, and a2 x that.
    scale : float, mm
    """
    a1, o1, a2, o2, B2 = axes
    if not (a1[0] == 0.0 and a1[1] == 0.0 and a1[2] == 1.0):
        raise ValueError("the pinion axis of the assembly must be +z")
    A2 = np.array([[0.0, -a2[2], a2[1]], [a2[2], 0.0, -a2[0]], [-a2[1], a2[0], 0.0]])
    return np.asarray(o1 - o2, float), np.concatenate([B2, A2 @ B2], 0), float(scale)


def stack_state(r, n, dr=None, dn=None):
    """Stack surface data ``r, n (m, 3)`` (and ``dr, dn (m, 3, 2)``) into ``S (m, 3, 2 or 6)``."""
    if dr is None:
        return np.stack([r, n], -1)
    return np.concatenate([r[..., None], n[..., None], dr, dn], -1)


def rotate_z(S, c, s):
    """R_z(angle) applied to every column of ``S (m, 3, k)``; ``c, s (m, 1)`` cosine and sine of the angle."""
    out = np.empty_like(S)
    x, y = S[..., 0, :], S[..., 1, :]
    out[..., 0, :] = c * x - s * y
    out[..., 1, :] = s * x + c * y
    out[..., 2, :] = S[..., 2, :]
    return out


def basis_matrix(n):
    """Basis ``E (m, 2, 3)`` of the normal equations: rows e_1, e_2 orthogonal to the unit normals ``n (m, 3)``."""
    e1, e2 = tangent_basis(n)
    return np.stack([e1, e2], -2)


def system_stacked(S1, S2, c1, s1, c2, s2, const, E, jac=True):
    """Contact system F (m, 5) mm and Jacobian (m, 5, 5) on stacked surface data.

    Parameters
    ----------
    S1, S2 : (m, 3, k) float
        Pinion and gear data (:func:`stack_state`), member frames; k = 6 when ``jac``.
    c1, s1, c2, s2 : (m, 1) float
        cos, sin of phi1 and of phi2.
    const : tuple
        :func:`assembly_constants`.
    E : (m, 2, 3) float
        Basis of the normal equations.

    Returns
    -------
    F : (m, 5) float, mm
    J : (m, 5, 5) float or None
    S1f : (m, 3, k) float
        Pinion data in the fixed frame (without the apex o1).
    Q : (m, 6, k) float
        Gear data in the fixed frame (rows 0-2, without o2) and a2 x those (rows 3-5).

    Notes
    -----
    F[0:3] = o1 + R1 r1 - o2 - R2 r2, F[3:5] = L E (R1 n1 + R2 n2); dF/dq1 = (R1 r1_q, L E R1 n1_q),
    dF/dq2 = (-R2 r2_q, L E R2 n2_q), dF/dphi2 = (-a2 x R2 r2, L E (a2 x R2 n2)), as in
    :func:`spiralbevel._core.tca.contact_system`.
    """
    d, M2, L = const
    S1f = rotate_z(S1, c1, s1)
    Q = M2 @ rotate_z(S2, c2, s2)
    F = np.empty(S1.shape[:-2] + (5,))
    F[..., :3] = d + S1f[..., :, 0] - Q[..., :3, 0]
    ns = S1f[..., :, 1] + Q[..., :3, 1]
    F[..., 3:] = L * (E @ ns[..., None])[..., 0]
    if not jac:
        return F, None, S1f, Q
    J = np.empty(S1.shape[:-2] + (5, 5))
    J[..., :3, 0:2] = S1f[..., :, 2:4]
    J[..., :3, 2:4] = -Q[..., :3, 2:4]
    J[..., :3, 4] = -Q[..., 3:, 0]
    K = np.concatenate([S1f[..., :, 4:6], Q[..., :3, 4:6], Q[..., 3:, 1:2]], -1)
    J[..., 3:, :] = L * (E @ K)
    return F, J, S1f, Q


def dF_dphi1_stacked(S1f, E, scale):
    """dF/dphi1 (m, 5) mm/rad from the fixed-frame pinion data ``S1f`` (a1 = +z: a1 x v = (-v_y, v_x, 0))."""
    out = np.empty(S1f.shape[:-2] + (5,))
    r, n = S1f[..., :, 0], S1f[..., :, 1]
    out[..., 0] = -r[..., 1]
    out[..., 1] = r[..., 0]
    out[..., 2] = 0.0
    dn = np.stack([-n[..., 1], n[..., 0], np.zeros_like(n[..., 0])], -1)
    out[..., 3:] = scale * (E @ dn[..., None])[..., 0]
    return out


def _equilibrate(J):
    cn = np.sqrt(np.einsum("...ij,...ij->...j", J, J))
    cn = np.where(cn > 0, cn, 1.0)
    return J / cn[..., None, :], cn


def newton_step(J, F, rcond=1e-10):
    """Newton step dx = -J^+ F (m, 5) of :func:`spiralbevel._core.tca.minnorm_step`, by LU where possible.

    With unit columns, |det| > 5^2.5 rcond proves s_min / s_max > rcond, where the pseudo-inverse of the SVD step
    is the inverse: those systems are solved by LU (``numpy.linalg.solve``); the others (rectangular systems, line
    contact) take the minimum-norm SVD step. Non-finite systems give NaN.
    """
    Js, cn = _equilibrate(J)
    m, k = J.shape[-2:]
    dx = np.full(F.shape[:-1] + (k,), np.nan)
    finite = np.isfinite(Js).all(axis=(-1, -2)) & np.isfinite(F).all(axis=-1)
    if m == k:
        with np.errstate(all="ignore"):
            det = np.linalg.det(np.where(finite[..., None, None], Js, 0.0))
        reg = finite & (np.abs(det) > _DET_BOUND * rcond)
    else:
        reg = np.zeros(finite.shape, bool)
    if reg.all():
        dx = np.linalg.solve(Js, -F[..., None])[..., 0]
    else:
        if reg.any():
            dx[reg] = np.linalg.solve(Js[reg], -F[reg][..., None])[..., 0]
        sv = finite & ~reg
        if sv.any():
            with np.errstate(all="ignore"):
                dx[sv] = minnorm_step(Js[sv], F[sv], rcond)[0]
    return dx / cn


def is_singular(J, tol):
    """Whether s_min / s_max of the column-equilibrated ``J (m, 5, 5)`` is below ``tol`` (line contact).

    Certificates first, an SVD only where they do not decide: with unit columns s_max >= 1 and, for the triangular
    factor R of a QR decomposition, s_min <= min_k |R_kk| (an eigenvalue of R bounds s_min from above): singular
    when min_k |R_kk| < tol; regular when |det| = prod_k |R_kk| > 5^2.5 tol (see :func:`newton_step`).
    Non-finite systems are not singular.
    """
    Js, _ = _equilibrate(J)
    finite = np.isfinite(Js).all(axis=(-1, -2))
    out = np.zeros(J.shape[:-2], bool)
    if not finite.any():
        return out
    Jf = Js[finite] if not finite.all() else Js
    d = np.abs(np.diagonal(np.linalg.qr(Jf, mode="r"), axis1=-2, axis2=-1))
    sing = d.min(axis=-1) < tol
    maybe = ~sing & ~(np.prod(d, axis=-1) > _DET_BOUND * tol)
    if maybe.any():
        s = np.linalg.svd(Jf[maybe], compute_uv=False)
        sing[maybe] = s[..., -1] < tol * s[..., 0]
    out[finite] = sing
    return out


def newton_batched(fun, x0, tol, max_iter=30, rcond=1e-10, patience=30, halvings=8):
    """Batched Newton on small systems with analytic or finite-difference Jacobians supplied by ``fun``.

    Parameters
    ----------
    fun : callable
        ``fun(x (m, 5), idx (m,) int) -> (F (m, k), J (m, k, 5), aux)`` for the systems ``idx`` (k >= 5); ``aux``
        is a tuple of arrays with leading length m (e.g. the surface data), kept for the final iterate.
    x0 : (M, 5) float
    tol : float
        Converged when max|F| < tol (units of F).
    max_iter : int
    rcond : float
        See :func:`newton_step`.
    patience : int
        A system whose residual has not halved its best value for ``patience`` consecutive iterations is given up
        (Newton cycling or wandering off the surfaces: no solution near the start).
    halvings : int
        A step that leaves the surfaces (non-finite F or J) is halved up to this many times.

    Returns
    -------
    x : (M, 5) float
    converged : (M,) bool
    residual : (M,) float
        max|F| at the final iterate (inf where the evaluation failed).
    J : (M, k, 5) float
        Jacobian at the final iterate.
    aux : tuple
        ``aux`` of ``fun`` at the final iterate.
    iterations : int
    """
    x = np.array(x0, dtype=float, copy=True)
    M = x.shape[0]
    allidx = np.arange(M)
    with np.errstate(all="ignore"):
        F, J, aux = fun(x, allidx)
    aux = tuple(np.array(a, copy=True) for a in aux)
    res = np.max(np.abs(F), axis=-1)
    ok = np.isfinite(res) & np.isfinite(J).all(axis=(-1, -2))
    res = np.where(ok, res, np.inf)
    best = res.copy()
    stall = np.zeros(M, int)
    halved = np.zeros(M, int)  # > 0: the last step left the surfaces, retry with dx / 2**halved
    dx = np.zeros_like(x)
    active = ok & (res >= tol)
    it = 0
    while it < max_iter and active.any():
        it += 1
        idx = allidx[active]
        fresh = halved[idx] == 0
        if fresh.all():
            with np.errstate(all="ignore"):
                dx[idx] = newton_step(J[idx], F[idx], rcond)
        elif fresh.any():
            with np.errstate(all="ignore"):
                dx[idx[fresh]] = newton_step(J[idx[fresh]], F[idx[fresh]], rcond)
        xn = x[idx] + dx[idx]
        with np.errstate(all="ignore"):
            Fn, Jn, an = fun(xn, idx)
        fin = np.isfinite(Fn).all(axis=-1) & np.isfinite(Jn).all(axis=(-1, -2))
        # a step that leaves the surfaces (non-finite F or J) is halved and retried, up to `halvings` times
        retry = ~fin & (halved[idx] < halvings)
        if retry.any():
            dx[idx[retry]] *= 0.5
            halved[idx[retry]] += 1
        acc = ~retry
        ia = idx[acc]
        x[ia], F[ia], J[ia] = xn[acc], Fn[acc], Jn[acc]
        for a, b in zip(aux, an):
            a[ia] = b[acc]
        halved[ia] = 0
        r = np.where(fin[acc], np.max(np.abs(Fn[acc]), axis=-1), np.inf)
        res[ia] = r
        better = r < 0.5 * best[ia]
        best[ia] = np.minimum(best[ia], r)
        stall[ia] = np.where(better, 0, stall[ia] + 1)
        active[ia] = (r < np.inf) & (r >= tol) & (stall[ia] < patience)
    return x, res < tol, res, J, aux, it
