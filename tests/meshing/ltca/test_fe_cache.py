"""The FE compliance cache: keyed by inputs and code, every kind of bad entry recomputed with a warning, never fatal.

Poisoned entries of the campaign: a truncated file (BadZipFile), a wrong-shape matrix (IndexError), and a same-shape
matrix scaled by 0.5, which once moved the approach torque 48.93 -> 66.42 N m without a word.
"""

import os
import warnings

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.errors import CacheWarning
from spiralbevel.meshing.ltca import fe_cache
from spiralbevel.meshing.ltca.compliance import tooth_compliance
from spiralbevel.meshing.ltca.mesher import mesh_tooth_segment

pytest.importorskip("skfem")


def _spd(n, seed=0):
    a = np.random.default_rng(seed).normal(size=(n, n))
    return a @ a.T + n * np.eye(n)


def _coupled_too_strongly(G):
    """Positive diagonal, symmetric, but indefinite: |G01| > sqrt(G00 G11)."""
    M = G.copy()
    M[0, 1] = M[1, 0] = 10 * np.sqrt(M[0, 0] * M[1, 1])
    return M


@pytest.fixture()
def cache(tmp_path):
    return tmp_path / "cache"


def _bad(cache, key, n):
    with pytest.warns(CacheWarning, match="recomputing") as rec:
        assert fe_cache.load_matrix(cache, key, n) is None
    assert not fe_cache.entry_path(cache, key).exists()          # the bad entry is gone
    return " ".join(str(w.message) for w in rec if issubclass(w.category, CacheWarning))


def test_roundtrip_and_every_poisoned_entry(cache):
    G = _spd(12)
    key = fe_cache.cache_key([G], "test")
    path = fe_cache.store_matrix(cache, key, G, 1e-15)
    got, asym = fe_cache.load_matrix(cache, key, 12)
    assert np.array_equal(got, G) and asym == 1e-15

    def rewrite(**fields):
        fe_cache.store_matrix(cache, key, G, 0.0)
        with np.load(path) as d:
            data = {k: d[k] for k in d.files}
        data.update(fields)
        np.savez(path, **data)

    rewrite(G=0.5 * G)                                    # scaled, checksum of the original: caught by the checksum
    assert "checksum" in _bad(cache, key, 12)
    bad_shapes = {"shape": G[:, :11], "symmetric": G + np.triu(np.ones_like(G)), "finite": np.where(G > 0, np.nan, G),
                  "positive definite": _coupled_too_strongly(G)}
    for what, M in bad_shapes.items():                    # content checks, with a checksum that matches the content
        rewrite(G=M, checksum=fe_cache._checksum(M))
        assert what in _bad(cache, key, 12)
    rewrite(key="another key")
    assert "key" in _bad(cache, key, 12)
    fe_cache.store_matrix(cache, key, G, 0.0)
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])   # truncated: BadZipFile inside
    assert "unreadable" in _bad(cache, key, 12)
    path.write_bytes(b"not a zip file at all")
    assert "unreadable" in _bad(cache, key, 12)
    assert fe_cache.load_matrix(cache, key, 12) is None   # missing: silently None


def test_zero_rows_of_clamped_nodes_are_valid(cache):
    G = _spd(6)
    G[2, :] = G[:, 2] = 0.0
    key = fe_cache.cache_key([G], "clamped")
    fe_cache.store_matrix(cache, key, G, 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.array_equal(fe_cache.load_matrix(cache, key, 6)[0], G)


def test_key_depends_on_code_version(monkeypatch):
    a = fe_cache.cache_key([np.arange(3.0)], "x")
    monkeypatch.setattr(fe_cache, "__version__", "999.0")
    assert fe_cache.cache_key([np.arange(3.0)], "x") != a


def test_unwritable_cache_is_a_warning(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with pytest.warns(CacheWarning, match="cannot write"):
        assert fe_cache.store_matrix(blocker / "cache", "k", _spd(3), 0.0) is None
    assert blocker.read_text() == "not a directory"


def test_unique_temporary_names_and_size_cap(cache, monkeypatch):
    seen = []
    real = os.replace

    def spy(src, dst):
        seen.append(os.path.basename(src))
        return real(src, dst)

    monkeypatch.setattr(os, "replace", spy)
    G = _spd(64)
    for i in range(4):
        fe_cache.store_matrix(cache, f"k{i}", G, 0.0)
    monkeypatch.undo()
    assert len(set(seen)) == 4 and all(s.endswith(".tmp") for s in seen)
    size = fe_cache.entry_path(cache, "k0").stat().st_size
    monkeypatch.setenv("SPIRALBEVEL_CACHE_MAX_MB", str(2.5 * size / 2**20))
    os.utime(fe_cache.entry_path(cache, "k1"), (1, 1))     # least recently used
    fe_cache.store_matrix(cache, "k4", G, 0.0)
    left = sorted(p.name for p in cache.glob(fe_cache.PATTERN))
    assert len(left) == 2 and "ltca_fe_k4.npz" in left and "ltca_fe_k1.npz" not in left
    assert sorted(p.name for p in cache.iterdir()) == left  # no temporary file left


def test_cli_cache_info_and_clear(cache, monkeypatch):
    from spiralbevel.cli import app

    monkeypatch.setenv("SPIRALBEVEL_CACHE", str(cache))
    fe_cache.store_matrix(cache, "k", _spd(8), 0.0)
    (cache / "README.user").write_text("not ours")
    runner = CliRunner()
    res = runner.invoke(app, ["cache", "info"])
    assert res.exit_code == 0 and "1 entries" in res.output and str(cache) in res.output
    res = runner.invoke(app, ["cache", "clear"])
    assert res.exit_code == 0 and "removed 1" in res.output
    assert [p.name for p in cache.iterdir()] == ["README.user"]


def test_poisoned_compliance_is_recomputed(cache):
    # a small box "tooth" (the cantilever of test_compliance) through tooth_compliance: the same matrix after a
    # poisoned entry as from a clean solve
    def flank(y):
        Z, X = np.meshgrid(np.linspace(0, 8, 3), 100 + np.linspace(0, 20, 4), indexing="ij")
        return np.stack([X, np.full_like(X, y), Z], -1)

    mesh = mesh_tooth_segment(flank(-4.0), flank(4.0), z=40, n_teeth=1, thickness_divisions=1, rim_layers=0)
    clean = tooth_compliance(mesh, "convex", order=1, cache_dir=cache)
    path = fe_cache.entry_path(cache, clean.key)
    with np.load(path) as d:
        data = {k: d[k] for k in d.files}
    data["G"] = 0.5 * data["G"]
    np.savez(path, **data)
    with pytest.warns(CacheWarning, match="checksum"):
        again = tooth_compliance(mesh, "convex", order=1, cache_dir=cache)
    assert np.array_equal(again.G, clean.G)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                   # the recomputed entry is good again
        assert np.array_equal(tooth_compliance(mesh, "convex", order=1, cache_dir=cache).G, clean.G)
