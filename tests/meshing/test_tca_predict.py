"""The compiled path predictor of TCA (``_core/tca_predict``) against the numpy form it replaced (cubic Hermite between
the nodes, the quintic through three nodes from a 6 x 6 linear solve beyond them; kept here as the reference) on many
random node sets, and against polynomials it must reproduce exactly."""

import numpy as np

from spiralbevel._core.tca_predict import predict

_P = np.arange(6)
_PM1 = np.maximum(_P - 1, 0)


def _hermite(o, nodes, X, Xp):
    if len(nodes) == 1:
        return X[0] + (o - nodes[0])[..., None] * Xp[0]
    i = np.clip(np.searchsorted(nodes, o) - 1, 0, len(nodes) - 2)
    h = nodes[i + 1] - nodes[i]
    t = ((o - nodes[i]) / h)[..., None]
    h = h[..., None]
    return ((2 * t**3 - 3 * t**2 + 1) * X[i] + (t**3 - 2 * t**2 + t) * h * Xp[i] + (-2 * t**3 + 3 * t**2) * X[i + 1]
            + (t**3 - t**2) * h * Xp[i + 1])


def _quintic(o_nodes, X, Xp, o):
    on = o_nodes.tolist()
    c = sum(on) / len(on)
    s = (max(on) - min(on)) or 1.0
    t = (o_nodes - c) / s
    A = np.concatenate([t[:, None] ** _P, (_P * t[:, None] ** _PM1) / s], 0)
    coef = np.linalg.solve(A, np.concatenate([X, Xp], 0))
    return (((np.asarray(o, float) - c) / s)[:, None] ** _P) @ coef


def _reference(o, nodes, X, Xp):
    out = _hermite(o, nodes, X, Xp)
    if len(nodes) >= 3:
        for sel, k in ((o < nodes[0], slice(0, 3)), (o > nodes[-1], slice(-3, None))):
            if np.any(sel):
                out[sel] = _quintic(nodes[k], X[k], Xp[k], o[sel])
    return out


def _run(o, nodes, X, Xp):
    out = np.empty((len(o), X.shape[1]))
    predict(o, nodes, X, Xp, out)
    return out


def test_predict_matches_the_numpy_form():
    rng = np.random.default_rng(7)
    worst = 0.0
    for _ in range(300):
        n = int(rng.integers(1, 8))
        step = rng.uniform(0.01, 0.2)
        nodes = (np.arange(n) - rng.integers(0, n)) * step + rng.uniform(-0.3, 0.3, n) * step * (rng.random() < 0.5)
        nodes = np.sort(nodes)
        X, Xp = rng.normal(size=(n, 5)), rng.normal(size=(n, 5))
        # inside, on the nodes, and up to two steps beyond either end (the continuation's reach)
        o = np.concatenate([rng.uniform(nodes[0] - 2 * step, nodes[-1] + 2 * step, 20), nodes])
        got, want = _run(o, nodes, X, Xp), _reference(o, nodes, X, Xp)
        scale = max(1.0, float(np.max(np.abs(want))))
        worst = max(worst, float(np.max(np.abs(got - want))) / scale)
    # two forms of the same polynomials: they differ by round-off (amplified by the extrapolation up to two steps)
    assert worst < 1e-13, worst  # 1.8e-14 with this seed


def test_predict_reproduces_polynomials():
    """Values and slopes of a quintic at three nodes give that quintic beyond them; of a cubic at the nodes, the cubic
    between them."""
    rng = np.random.default_rng(3)
    c5, c3 = rng.normal(size=(6, 2)), rng.normal(size=(4, 2))
    nodes = np.array([-0.2, 0.0, 0.2])
    for c, o in ((c5, np.array([-0.55, -0.3, 0.25, 0.4])), (c3, np.linspace(-0.2, 0.2, 9))):
        p = np.polynomial.polynomial
        X, Xp = p.polyval(nodes, c).T, p.polyval(nodes, p.polyder(c)).T
        np.testing.assert_allclose(_run(o, nodes, X, Xp), p.polyval(o, c).T, rtol=0, atol=1e-13)
