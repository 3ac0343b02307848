"""Numerical differential geometry of a parametric surface map (test helper, independent of the transfer formula)."""

import numpy as np

# 8th-order central-difference weights
_D1 = {1: 4 / 5, 2: -1 / 5, 3: 4 / 105, 4: -1 / 280}
_D2 = {0: -205 / 72, 1: 8 / 5, 2: -1 / 5, 3: 8 / 315, 4: -1 / 560}


def derivatives(f, u, v, hu, hv):
    """r_u, r_v, r_uu, r_uv, r_vv of f(u, v) -> (..., 3) by 8th-order central differences."""
    u, v, hu, hv = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, v, hu, hv)))
    f0 = f

    def f(a, b):
        return f0(a, b)

    Hu, Hv = hu[..., None], hv[..., None]
    ru = sum(w * (f(u + k * hu, v) - f(u - k * hu, v)) for k, w in _D1.items()) / Hu
    rv = sum(w * (f(u, v + k * hv) - f(u, v - k * hv)) for k, w in _D1.items()) / Hv
    ruu = _D2[0] * f(u, v) + sum(w * (f(u + k * hu, v) + f(u - k * hu, v)) for k, w in _D2.items() if k)
    rvv = _D2[0] * f(u, v) + sum(w * (f(u, v + k * hv) + f(u, v - k * hv)) for k, w in _D2.items() if k)

    def fv(uu):
        return sum(w * (f(uu, v + k * hv) - f(uu, v - k * hv)) for k, w in _D1.items()) / Hv

    ruv = sum(w * (fv(u + k * hu) - fv(u - k * hu)) for k, w in _D1.items()) / Hu
    return ru, rv, ruu / Hu**2, ruv, rvv / Hv**2


def principal_curvatures(f, u, v, n_out, hu, hv):
    """Principal curvatures (convex = positive w.r.t. the outward normal n_out), sorted descending."""
    ru, rv, ruu, ruv, rvv = derivatives(f, u, v, hu, hv)
    n = np.cross(ru, rv)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    n *= np.sign(np.sum(n * n_out, axis=-1))[..., None]
    E, F, G = (np.sum(a * b, -1) for a, b in ((ru, ru), (ru, rv), (rv, rv)))
    # convex = positive w.r.t. n_out: kappa = -II(n_out)/I
    L, M, N = (-np.sum(a * n, -1) for a in (ruu, ruv, rvv))
    I = np.stack([np.stack([E, F], -1), np.stack([F, G], -1)], -2)
    II = np.stack([np.stack([L, M], -1), np.stack([M, N], -1)], -2)
    k = np.linalg.eigvals(np.linalg.solve(I, II)).real
    return -np.sort(-k, axis=-1), n
