"""The compiled screen and acceptance of solved edge/corner systems (``_core/tca_edge_screen``) against the numpy and
Python loops they replaced in ``meshing/tca_edge.py`` (kept here as the reference), on many random inputs: the same
decisions, bit for bit (both only compare and copy floats)."""

import numpy as np

from spiralbevel._core import tca_edge_screen as ks


def _corner_split(member, edge, k1, K):
    """The reference decoding of corner rows (``meshing.tca_edge_solve.corner_split``)."""
    corner = (member == 0) & (edge >= k1)
    c = np.where(corner, edge - k1, 0)
    a, b = c // K, c % K
    ma, mb = (a >= k1).astype(int), (b >= k1).astype(int)
    return corner, ma, a - k1 * ma, mb, b - k1 * mb


def _reference_screen(gg, mem, ee, k1, K, conv, ndot, te, te_lim, contains):
    """The screen as numpy code (the previous ``try_solve``): ``contains[m]`` answers for the rows asked."""
    tolm = 1e-9
    ok = conv.copy()
    corner, ma, ea, mb, eb = _corner_split(mem, ee, k1, K)
    held = [np.zeros(g.shape, bool) for g in gg]
    r = np.arange(len(mem))
    for m in (0, 1):
        s_ = ~corner & (mem == m)
        held[m][r[s_], ee[s_]] = True
        for mc, ec in ((ma, ea), (mb, eb)):
            s_ = corner & (mc == m)
            held[m][r[s_], ec[s_]] = True
    for m in (0, 1):
        own = held[m].any(axis=1)
        with np.errstate(invalid="ignore"):
            inside = np.all((gg[m] >= -tolm) | held[m], axis=1)
        free = np.flatnonzero(~own & ok)
        if free.size:
            inside[free] = contains[m][free]
        ok &= inside
    with np.errstate(invalid="ignore"):
        good = conv & (ndot < -0.5) & (np.abs(te) < te_lim)
    return ok & good, good, (corner, ma, ea, mb, eb)


def _reference_accept(ok, te, ii, jj, xs, floor, te_edge, x_edge):
    """The acceptance loop of the previous ``try_solve``: returns new (m,) and the row that set each pair's label."""
    new = np.zeros(len(ii), bool)
    labelled = {}
    for a in np.flatnonzero(ok):
        i, j = int(ii[a]), int(jj[a])
        if te[a] <= floor[i, j]:
            continue
        if not np.isfinite(te_edge[i, j]) or te[a] > te_edge[i, j]:
            te_edge[i, j], x_edge[i, j] = te[a], xs[a]
            labelled[(i, j)] = a
            new[a] = True
    return new, labelled


def _random_case(rng):
    k1, k2 = int(rng.integers(3, 6)), int(rng.integers(3, 6))
    K = k1 + k2
    m = int(rng.integers(1, 40))
    mem = rng.integers(0, 2, m)
    ee = np.where(mem == 0, rng.integers(0, k1, m), rng.integers(0, k2, m))
    corner = (mem == 0) & (rng.random(m) < 0.3)
    ee = np.where(corner, k1 + rng.integers(0, K, m) * K + rng.integers(0, K, m), ee)
    gg = []
    for k in (k1, k2):
        g = np.abs(rng.normal(0.0, 1.0, (m, k))) * rng.choice([1.0, 1e-9, 1e-12], (m, k))  # some within 1e-9
        g[rng.random((m, k)) < 0.05] *= -1.0
        g[rng.random((m, k)) < 0.05] = np.nan
        gg.append(g)
    conv = rng.random(m) < 0.8
    ndot = rng.uniform(-1.0, 0.2, m)
    ndot[rng.random(m) < 0.05] = np.nan
    te = rng.normal(0.0, 0.015, m)
    te[rng.random(m) < 0.05] = np.nan
    contains = [rng.random(m) < 0.7, rng.random(m) < 0.7]
    return k1, K, mem, ee, gg, conv, ndot, te, contains


def test_screen_and_accept_match_the_reference_loops():
    rng = np.random.default_rng(20261124)
    te_lim = 0.03
    n_ok = n_new = 0
    for _ in range(400):
        k1, K, mem, ee, gg, conv, ndot, te, contains = _random_case(rng)
        m = len(mem)
        ok_ref, good_ref, split = _reference_screen(gg, mem, ee, k1, K, conv, ndot, te, te_lim, contains)
        out = [np.empty(m, bool) for _ in range(2)] + [np.empty(m, np.int64) for _ in range(4)]
        good, ok = np.empty(m, bool), np.empty(m, bool)
        # the compiled screen reads contains only where converged (the caller evaluates it there alone); its
        # acceptance is checked below, here against pairs that accept nothing (floor +inf)
        C = [np.where(conv, c, False) for c in contains]
        z = np.zeros(m, np.int64)
        ks.screen(np.ascontiguousarray(gg[0]), np.ascontiguousarray(gg[1]), mem.astype(np.int64),
                  ee.astype(np.int64), k1, K, conv, ndot, te, te_lim, 1e-9, C[0], C[1], z, z, np.zeros((m, 5)),
                  np.full((1, 1), np.inf), np.full((1, 1), np.nan), np.full((1, 1, 5), np.nan),
                  np.empty((1, 1), np.int64), out[0], *out[2:], good, ok, np.empty(m, bool), np.empty(m, bool))
        np.testing.assert_array_equal(ok, ok_ref)
        np.testing.assert_array_equal(good, good_ref)
        corner, ma, ea, mb, eb = split
        np.testing.assert_array_equal(out[0], corner)
        for got, want in zip(out[2:], (ma, ea, mb, eb)):
            np.testing.assert_array_equal(got[corner], want[corner])
        n_ok += int(ok.sum())
        # acceptance against the pairs' best contacts so far (several rows per pair, some trailing the floor)
        n, P = 4, 3
        ii, jj = rng.integers(0, n, m), rng.integers(0, P, m)
        xs = rng.normal(size=(m, 5))
        floor = np.where(rng.random((n, P)) < 0.3, rng.normal(0.0, 0.02, (n, P)), -np.inf)
        te_edge = np.where(rng.random((n, P)) < 0.5, rng.normal(0.0, 0.02, (n, P)), np.nan)
        x_edge = np.where(np.isfinite(te_edge)[..., None], rng.normal(size=(n, P, 5)), np.nan)
        te_ref, x_ref = te_edge.copy(), x_edge.copy()
        new_ref, labelled = _reference_accept(ok, te, ii, jj, xs, floor, te_ref, x_ref)
        new, win = np.empty(m, bool), np.empty(m, bool)
        ks.accept(ok, te, ii.astype(np.int64), jj.astype(np.int64), xs, floor, te_edge, x_edge,
                  np.empty((n, P), np.int64), new, win)
        np.testing.assert_array_equal(te_edge, te_ref)
        np.testing.assert_array_equal(x_edge, x_ref)
        np.testing.assert_array_equal(new, new_ref)
        assert sorted(np.flatnonzero(win).tolist()) == sorted(labelled.values())
        n_new += int(new.sum())
    # the random cases exercise both outcomes often
    assert n_ok > 600 and n_new > 400  # 1286 and 790 with this seed
