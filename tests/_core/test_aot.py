"""The ahead-of-time extension of the kernels (``_core/_aot``, built at install by ``setup.py``): the same results as
the JIT, bit for bit, on many random inputs; Python calls answered by it without a compile; a stale or disabled
extension ignored; and the check that keeps the signature table (``_core/aot_table.py``) complete.

The whole test suite runs with ``SPIRALBEVEL_AOT_STRICT=1`` (``tests/conftest.py``): a kernel called from the package
with argument types missing from the table fails the test that made the call (``jit._Kernel``)."""

import math

import numba
import numpy as np
import pytest

from spiralbevel._core import aot_table, jit
from spiralbevel._core import tca_ellipse as E
from spiralbevel._core.aot_build import export_name
from spiralbevel._core.tca_predict import predict

needs_aot = pytest.mark.skipif(not jit.aot_module(), reason="the ahead-of-time extension spiralbevel._core._aot is not "
                               "built or not current (built by 'pip install -e .'; SPIRALBEVEL_AOT=0 disables it)")


def _pair(kernel):
    """The extension's function of ``kernel`` (its one table signature) and a fresh JIT dispatcher of the same Python
    function with the kernels' options (its callees are the package's dispatchers)."""
    name = jit.qualified_name(kernel.py_func)
    assert len(aot_table.SIGNATURES[name]) == 1
    return getattr(jit.aot_module(), export_name(name, 0)), numba.njit(**jit._OPTIONS)(kernel.py_func)


def _same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    assert a.dtype == b.dtype and a.shape == b.shape
    assert np.array_equal(a.view(np.uint8), b.view(np.uint8))  # NaN payloads and signed zeros included


def _rotations(rng, m):
    q, _ = np.linalg.qr(rng.standard_normal((m, 3, 3)))
    return q * np.sign(np.linalg.det(q))[:, None, None]


def _twice(kernel, make_args, outs, pair=None):
    """Run ``kernel`` through the extension and through the JIT on the same inputs (fresh output arrays each)."""
    aot, jitted = pair or _pair(kernel)
    results = []
    for f in (aot, jitted):
        args = make_args()
        ret = f(*args)
        results.append((ret, [args[i] for i in outs]))
    (r0, o0), (r1, o1) = results
    if r0 is not None or r1 is not None:
        _same_bits(r0, r1)
    for a, b in zip(o0, o1):
        _same_bits(a, b)
    return o0


@needs_aot
def test_contact_geometry_kernels_same_bits_as_jit():
    # the ellipses' kernels of TCA on 2000 random frames: rotations, Weingarten tensors (explicit 2 x 2 inverses,
    # possibly near-singular metrics), relative curvatures (Jacobi rotations, a double eigenvalue in 100 rows)
    rng = np.random.default_rng(20261124)
    m = 2000
    phi1, phi2 = rng.uniform(-math.pi, math.pi, (2, m))
    a2, B2 = rng.standard_normal(3), _rotations(rng, 1)[0]
    _twice(E.pose_batch, lambda: (phi1, phi2, a2, B2, np.empty((m, 3, 3)), np.empty((m, 3, 3))), (4, 5))
    dr, dn = rng.standard_normal((m, 3, 2)), rng.standard_normal((m, 3, 2))
    dr[:50, :, 1] = dr[:50, :, 0] * (1 + 1e-9)  # nearly parallel tangents: ill-conditioned metric
    R = _rotations(rng, m)
    W1, = _twice(E.weingarten_batch, lambda: (dr, dn, R, True, np.empty((m, 3, 3))), (4,))
    W2 = rng.standard_normal((m, 3, 3))
    W2 = W2 + np.swapaxes(W2, -1, -2)
    W2[:100] = np.eye(3) - W1[:100]
    n = rng.standard_normal((m, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    _twice(E.relative_curvature_batch, lambda: (W1, W2, n, np.empty((m, 2)), np.empty((m, 2, 3))), (3, 4))


@needs_aot
def test_path_predictor_same_bits_as_jit():
    # cubic Hermite inside the nodes, the quintic (6 x 6 solve) beyond them: 200 random node sets
    rng = np.random.default_rng(5)
    pair = _pair(predict)
    for _ in range(200):
        k = int(rng.integers(1, 8))
        nodes = np.sort(rng.uniform(-1, 1, k))
        X, Xp = rng.standard_normal((k, 5)), rng.standard_normal((k, 5))
        o = rng.uniform(-2, 2, int(rng.integers(1, 30)))
        _twice(predict, lambda o=o, nodes=nodes, X=X, Xp=Xp: (o, nodes, X, Xp, np.empty((len(o), 5))), (4,), pair)


@needs_aot
def test_python_calls_run_the_extension():
    # a Python call with the table's signature is answered by the extension: nothing is compiled in this process
    rng = np.random.default_rng(1)
    m = 7
    before = dict(E.weingarten_batch.overloads)
    W = np.empty((m, 3, 3))
    E.weingarten_batch(rng.standard_normal((m, 3, 2)), rng.standard_normal((m, 3, 2)), _rotations(rng, m), True, W)
    assert dict(E.weingarten_batch.overloads) == before
    assert np.all(np.isfinite(W))
    assert len(E.weingarten_batch.signatures) == 1  # the extension's signature is listed


@needs_aot
def test_stale_or_disabled_extension_is_ignored(monkeypatch):
    monkeypatch.setattr(jit, "_AOT", None)
    monkeypatch.setattr(jit, "_KEY", "0123456789abcdef")  # as if a _core source had changed since the install
    assert jit.aot_module() is False
    monkeypatch.setattr(jit, "_AOT", None)
    monkeypatch.setattr(jit, "_KEY", None)
    monkeypatch.setenv("SPIRALBEVEL_AOT", "0")
    assert jit.aot_module() is False


def test_missing_signature_of_a_package_call_fails(monkeypatch, tmp_path):
    # the table check (SPIRALBEVEL_AOT_STRICT): a call from the package's code with argument types missing from
    # the table fails; the same call from a test (not the package) compiles as usual
    monkeypatch.setenv("SPIRALBEVEL_AOT_STRICT", "1")
    monkeypatch.delenv("SPIRALBEVEL_AOT_RECORD", raising=False)  # (set while aot_record runs the suite)
    monkeypatch.setattr(jit, "_CACHE", tmp_path)

    @jit.kernel
    def twice(a):
        return 2.0 * a

    assert twice(1.5) == 3.0
    ns = {"__name__": "spiralbevel.fake_module", "twice": twice}
    exec("def call(x):\n    return twice(x)\n", ns)
    with pytest.raises(AssertionError, match="not in _core/aot_table.py"):
        ns["call"](np.ones(2))


@needs_aot
def test_every_table_kernel_is_exported():
    # all of them where pycc's module initialisation could be patched (aot_build._patch_mixin), else all but the
    # kernels that reach an object-mode block
    from spiralbevel._core import aot_build

    text = (jit.Path(numba.__file__).parent / "pycc" / "modulemixin.c").read_text()
    left_out = set() if text.count(aot_build._MIXIN_BUG) == 1 else set(aot_build.JIT_ONLY)
    for name, sigs in aot_table.SIGNATURES.items():
        for i in range(len(sigs)):
            assert hasattr(jit.aot_module(), export_name(name, i)) == (name not in left_out), name


def test_table_entries_parse_to_numba_types():
    for name, sigs in aot_table.SIGNATURES.items():
        assert sigs, name
        for args, ret in sigs:
            assert all(isinstance(t, numba.core.types.Type) for t in aot_table.parse(args)), name
            assert isinstance(aot_table.parse(ret), numba.core.types.Type), name
