"""Numerical curvature tensor of a parametric surface (test helper, independent of the curvature transfer)."""

import numpy as np

_D1 = {1: 4 / 5, 2: -1 / 5, 3: 4 / 105, 4: -1 / 280}                 # 8th-order central differences
_D2 = {0: -205 / 72, 1: 8 / 5, 2: -1 / 5, 3: 8 / 315, 4: -1 / 560}


def curvature_tensor_fd(f, u, v, n_out, hu=0.01, hv=4e-4):
    """3 x 3 curvature tensor K (t.K.t = normal curvature, convex = positive w.r.t. ``n_out``) of f(u, v) -> (3,).

    K = J I^-1 II I^-1 J^T with J = [r_u, r_v], I and II the fundamental forms (II taken with -n_out), all from
    8th-order central differences of f.
    """
    def d1(g, h):
        return sum(w * (g(k * h) - g(-k * h)) for k, w in _D1.items()) / h

    def d2(g, h):
        return (_D2[0] * g(0.0) + sum(w * (g(k * h) + g(-k * h)) for k, w in _D2.items() if k)) / h**2

    ru = d1(lambda s: f(u + s, v), hu)
    rv = d1(lambda s: f(u, v + s), hv)
    ruu = d2(lambda s: f(u + s, v), hu)
    rvv = d2(lambda s: f(u, v + s), hv)
    ruv = d1(lambda s: d1(lambda t: f(u + s, v + t), hv), hu)
    n = np.asarray(n_out, float)
    J = np.stack([ru, rv], -1)
    I = J.T @ J
    II = -np.array([[ruu @ n, ruv @ n], [ruv @ n, rvv @ n]])
    Ii = np.linalg.inv(I)
    return J @ Ii @ II @ Ii @ J.T, np.cross(ru, rv) / np.linalg.norm(np.cross(ru, rv))


def tangent_eigen(K, n):
    """Eigenvalues (ascending) and eigenvectors (2, 3) of a tangent-plane tensor at unit normal n."""
    a = np.cross(n, [1.0, 0.0, 0.0])
    a /= np.linalg.norm(a)
    B = np.stack([a, np.cross(n, a)])
    lam, vec = np.linalg.eigh(B @ K @ B.T)
    return lam, vec.T @ B
