"""Build the ahead-of-time extension ``spiralbevel._core._aot`` of the kernels Python calls (``numba.pycc``).

Used at install time by ``setup.py`` (never at run time). For every kernel and argument signature of the generated
table ``aot_table.SIGNATURES`` the module exports a thin wrapper ``def w(a0, a1, ...): return kernel(a0, a1, ...)``:
the wrapper is compiled by pycc, the kernel below it by the kernel's own dispatcher with the kernel's own options
(``error_model="numpy"``, no fastmath: ``jit._OPTIONS``), and its LLVM IR is linked into the extension, so the
extension runs the same code as the JIT. ``aot_key()`` of the extension returns the key of the ``_core`` sources
and the numba version it was built from; ``jit`` ignores an extension whose key is not the current one (a developer
edited ``_core`` after the install: the JIT compiles, as without the extension). Why and how: ``_core/jit.py``.
"""

from __future__ import annotations

import importlib
import os
import pkgutil
from pathlib import Path

from . import aot_table, jit

EXTENSION = "_aot"

#: kernels of the table left to the JIT where pycc's module initialisation is not patched (``_patch_mixin``), with the
#: reason: they reach a ``numba.objmode`` block (a call back into Python) inside a callee
JIT_ONLY = {
    "settings_fit.newton": "reaches a numba.objmode call-back (settings_fit._lstsq)",
}

#: numba.pycc's module initialisation (modulemixin.c, numba 0.68.1) releases the environment object of every compiled
#: function that is not itself exported (a callee) right after storing it in the function's global: the environment
#: (its constants, e.g. the dtype an object-mode block boxes an array with) is freed while the code still uses it
#: (then "TypeError: expected dtype object, got 'str'", or a crash). The patch keeps that reference (the environment
#: then lives as long as the process, as an exported function's does through its function object).
_MIXIN_BUG = """        // Store the environment pointer into the global
        *envgvs[i] = envobj;
        Py_DECREF(envobj);
    }
    Py_DECREF(docobj);"""
_MIXIN_FIX = """        // Store the environment pointer into the global (the reference is kept: spiralbevel's patch)
        *envgvs[i] = envobj;
    }
    Py_DECREF(docobj);"""


def export_name(qualified: str, i: int) -> str:
    """Name of the exported wrapper of signature ``i`` of kernel ``qualified`` (``module.function``)."""
    return f"{qualified.replace('.', '__')}__{i}"


def kernel_modules():
    """Import every module of ``spiralbevel._core`` (the kernels register their dispatchers on import)."""
    package = importlib.import_module(__package__)
    names = sorted(m.name for m in pkgutil.iter_modules(package.__path__)
                   if not m.name.startswith("aot_") and m.name != EXTENSION)
    return {n: importlib.import_module(f"{__package__}.{n}") for n in names}


def _wrapper(dispatcher, n_args: int):
    """``def w(a0, ..., a{n-1}): return kernel(a0, ..., a{n-1})``, with the kernel as a global of ``w``."""
    args = ", ".join(f"a{i}" for i in range(n_args))
    ns: dict = {"_kernel": dispatcher}
    exec(f"def wrapper({args}):\n    return _kernel({args})\n", ns)  # noqa: S102  (a fixed template)
    return ns["wrapper"]


def make_cc(output_dir: str | os.PathLike | None = None, target_cpu: str = "host"):
    """The ``numba.pycc.CC`` of the extension, with every exported wrapper declared (not yet compiled).

    The kernels are compiled here by their JIT dispatchers, in memory: ``jit`` is told not to use its disk cache
    (machine code read from a cache has no LLVM IR left to link into the extension) nor an existing extension.
    """
    os.environ["SPIRALBEVEL_AOT"] = "0"
    jit._BUILDING = True
    from numba import types
    from numba.pycc import CC

    modules = kernel_modules()
    cc = CC(EXTENSION, source_module=__name__)
    cc.target_cpu = target_cpu
    if output_dir is not None:
        cc.output_dir = str(output_dir)
    patched = _patch_mixin(cc)
    for qualified, signatures in sorted(aot_table.SIGNATURES.items()):
        if qualified in JIT_ONLY and not patched:
            continue
        module, name = qualified.split(".")
        dispatcher = getattr(modules[module], name)
        for i, (args, ret) in enumerate(signatures):
            argtypes = aot_table.parse(args)
            cc.export(export_name(qualified, i), aot_table.parse(ret)(*argtypes))(_wrapper(dispatcher, len(argtypes)))
    key = aot_key()
    cc.export("aot_key", types.unicode_type())(_constant(key))
    return cc


def _patch_mixin(cc) -> bool:
    """Build ``cc`` with a copy of pycc's ``modulemixin.c`` that has ``_MIXIN_FIX``; False where the numba at hand has
    no ``_MIXIN_BUG`` (changed or fixed: nothing patched, ``JIT_ONLY`` left out)."""
    import tempfile

    import numba.pycc

    here = Path(numba.pycc.__file__).parent
    text = (here / "modulemixin.c").read_text()
    if text.count(_MIXIN_BUG) != 1:
        return False
    d = Path(tempfile.mkdtemp(prefix="spiralbevel-pycc-")) / "pycc"
    d.mkdir()
    (d / "modulemixin.c").write_text(text.replace(_MIXIN_BUG, _MIXIN_FIX))
    sources, includes = cc._get_mixin_sources, cc._toolchain.get_python_include_dirs
    # the copy's relative includes ("../_helperlib.c") resolve through numba's own pycc directory
    cc._get_mixin_sources = lambda: [str(d / "modulemixin.c") if s.endswith("modulemixin.c") else os.path.normpath(s)
                                     for s in sources()]
    cc._toolchain.get_python_include_dirs = lambda: [*includes(), str(here)]
    cc.patched_mixin, cc.original_mixin = str(d / "modulemixin.c"), str(here / "modulemixin.c")
    return True


def _constant(value: str):
    ns: dict = {}
    exec(f"def aot_key():\n    return {value!r}\n", ns)  # noqa: S102
    return ns["aot_key"]


def aot_key() -> str:
    """Key of an extension built from the current ``_core`` sources with the current numba."""
    import numba

    return f"{numba.__version__}-{jit.sources_key(Path(jit.__file__).parent.glob('*.py'))}"
