"""Build of the optional ahead-of-time extension of the compiled kernels (everything else is in pyproject.toml).

``spiralbevel._core._aot`` holds machine code of the kernels Python calls, compiled at install on this machine with
``numba.pycc`` (``src/spiralbevel/_core/aot_build.py``; why: ``src/spiralbevel/_core/jit.py``), so that the first run
after ``pip install`` does not JIT-compile them. It is optional: without a C compiler, or where numba cannot build it,
the install goes on without it, with one notice, and the kernels are JIT-compiled on first use as before.
``SPIRALBEVEL_AOT=0`` at install skips it.
"""

import importlib
import os
import sys
import time
import types

from setuptools import setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


def _notice(message):
    print(f"spiralbevel: {message}; the compiled kernels will be JIT-compiled on first use instead", file=sys.stderr)


def _aot_extension():
    """The extension of ``aot_build.make_cc`` (its exports declared; compiled by ``build_ext``), or None."""
    if os.environ.get("SPIRALBEVEL_AOT") == "0":
        return None
    try:
        # the kernels' modules without the package's __init__ (which imports the user-facing layers)
        if "spiralbevel" not in sys.modules:
            pkg = types.ModuleType("spiralbevel")
            pkg.__path__ = [os.path.join(HERE, "src", "spiralbevel")]
            sys.modules["spiralbevel"] = pkg
        aot_build = importlib.import_module("spiralbevel._core.aot_build")
        cc = aot_build.make_cc()
    except Exception as err:  # noqa: BLE001  (an optional part of the install: any failure means no extension)
        _notice(f"the ahead-of-time extension cannot be prepared ({type(err).__name__}: {err})")
        return None
    ext = cc.distutils_extension()
    ext.optional = True
    # setuptools lists the extension's sources in the package manifest and rejects an absolute path outside the
    # project (the patched copy of pycc's modulemixin.c, aot_build._patch_mixin): the manifest sees pycc's own file,
    # the compile the patched one (_BuildExt)
    ext.compiled_sources = list(ext.sources)
    patched, original = getattr(cc, "patched_mixin", None), getattr(cc, "original_mixin", None)
    ext.sources = [original if s == patched else s for s in ext.sources]
    return ext


class _BuildExt(build_ext):
    """``build_ext`` that leaves the optional extension out on any error (numba's compile, the C compiler)."""

    def build_extension(self, ext):
        t0 = time.perf_counter()
        try:
            if hasattr(ext, "_prepare_object_files"):  # numba.pycc's extension: compile the kernels to an object file
                ext._prepare_object_files(self)
            listed = ext.sources
            ext.sources = getattr(ext, "compiled_sources", listed)
            try:
                super().build_extension(ext)
            finally:
                ext.sources = listed
        except Exception as err:  # noqa: BLE001
            if not getattr(ext, "optional", False):
                raise
            _notice(f"the ahead-of-time extension {ext.name} was not built ({type(err).__name__}: {err})")
            return
        print(f"spiralbevel: built {ext.name} in {time.perf_counter() - t0:.0f} s", file=sys.stderr)


_ext = _aot_extension()
setup(ext_modules=[_ext] if _ext is not None else [], cmdclass={"build_ext": _BuildExt})
