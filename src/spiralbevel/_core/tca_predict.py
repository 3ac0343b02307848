"""Compiled predictor of the TCA solution path (:mod:`spiralbevel.meshing.tca`): Hermite interpolation of the path
x(o) (o: offset of the effective pinion rotation from the mean position, rad) from nodes with values and slopes.

Between two nodes the cubic Hermite polynomial; beyond the outer nodes, when there are three or more, the quintic
Hermite polynomial through the three nodes nearest that end (values and slopes), in the Lagrange form

    p(o) = sum_k L_k(o)^2 [X_k (1 - 2 c_k (o - o_k)) + X'_k (o - o_k)],   c_k = sum_{j != k} 1 / (o_k - o_j)

(L_k the quadratic Lagrange basis of the three nodes: p and p' take the values and slopes at the nodes, and the
polynomial of degree 5 with these six conditions is unique); with fewer nodes, the Hermite cubic of the end interval
(one node: the tangent line).
"""

from __future__ import annotations

from .jit import kernel

__all__ = ["predict"]


@kernel
def predict(o, nodes, X, Xp, out):
    """Predicted path ``out (m, d)`` at offsets ``o (m,)`` from sorted ``nodes (n,)`` (n >= 1) with values
    ``X (n, d)`` and slopes ``Xp (n, d)`` (module docstring)."""
    n = nodes.shape[0]
    d = X.shape[1]
    for i in range(o.shape[0]):
        oi = o[i]
        if n >= 3 and (oi < nodes[0] or oi > nodes[n - 1]):
            # the quintic Hermite polynomial through the three nodes nearest that end (Lagrange form)
            b = 0 if oi < nodes[0] else n - 3
            for j in range(d):
                out[i, j] = 0.0
            for k in range(b, b + 3):
                lk, ck = 1.0, 0.0
                for m in range(b, b + 3):
                    if m != k:
                        lk *= (oi - nodes[m]) / (nodes[k] - nodes[m])
                        ck += 1.0 / (nodes[k] - nodes[m])
                dk = oi - nodes[k]
                wx = lk * lk * (1.0 - 2.0 * ck * dk)
                wp = lk * lk * dk
                for j in range(d):
                    out[i, j] += wx * X[k, j] + wp * Xp[k, j]
            continue
        if n == 1:
            for j in range(d):
                out[i, j] = X[0, j] + (oi - nodes[0]) * Xp[0, j]
            continue
        k = 0  # the interval [nodes[k], nodes[k + 1]] of oi (the end interval beyond the ends)
        while k < n - 2 and nodes[k + 1] < oi:
            k += 1
        h = nodes[k + 1] - nodes[k]
        t = (oi - nodes[k]) / h
        t2 = t * t
        t3 = t2 * t
        h00 = 2.0 * t3 - 3.0 * t2 + 1.0
        h10 = t3 - 2.0 * t2 + t
        h01 = -2.0 * t3 + 3.0 * t2
        h11 = t3 - t2
        for j in range(d):
            out[i, j] = h00 * X[k, j] + h10 * h * Xp[k, j] + h01 * X[k + 1, j] + h11 * h * Xp[k + 1, j]
