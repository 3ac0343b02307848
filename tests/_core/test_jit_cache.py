"""The compiled kernels' disk cache is keyed by the source of every ``_core`` module (numba's own cache only sees the
file of the decorated function, so a change of a kernel it calls from another file would load stale machine code)."""

import numpy as np

from spiralbevel._core import jit


def test_key_changes_with_any_source_file(tmp_path):
    a, b = tmp_path / "a.py", tmp_path / "b.py"
    a.write_text("x = 1\n")
    b.write_text("y = 2\n")
    k0 = jit.sources_key([a, b])
    assert jit.sources_key([b, a]) == k0            # order of the listing does not matter
    b.write_text("y = 3\n")                          # a change in the *other* file than the kernel's
    assert jit.sources_key([a, b]) != k0


def test_cache_dir_under_the_project_cache_and_keyed(monkeypatch, tmp_path):
    monkeypatch.setenv("SPIRALBEVEL_CACHE", str(tmp_path))
    d = jit.cache_dir()
    assert d.parent == tmp_path / "numba"
    assert d.name.endswith(jit.sources_key((jit.Path(jit.__file__).parent).glob("*.py")))


def test_kernels_cache_there_and_restore_numba_config(monkeypatch, tmp_path):
    before = jit.numba.config.CACHE_DIR
    monkeypatch.setattr(jit, "_CACHE", tmp_path / "k")

    @jit.kernel
    def f(a):
        return 2.0 * a

    assert f(1.5) == 3.0
    assert jit.numba.config.CACHE_DIR == before          # the user's own numba settings are left as they were
    assert any((tmp_path / "k").rglob("*.nbi"))           # the index went to our keyed directory


def test_unwritable_cache_compiles_in_memory(monkeypatch, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setattr(jit, "_CACHE", blocker / "sub")   # a path below a regular file cannot be created

    @jit.kernel
    def g(a):
        return a + 1.0

    assert g(np.float64(1.0)) == 2.0
