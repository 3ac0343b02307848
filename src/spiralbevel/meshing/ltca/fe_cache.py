"""The on-disk cache of FE tooth compliances: keyed by inputs and code, checked on load, never fatal.

A cache entry is an ``.npz`` file ``ltca_fe_<key>.npz`` in :func:`default_cache_dir` holding the flexibility matrix
``G`` (mm/N), the reciprocity check ``asymmetry``, the key, the code version and a SHA-256 checksum of ``G``.

- **Key**: a SHA-256 of the inputs (mesh, loaded flank nodes, side, material, element order) *and* of the code that
  computes the matrix (the package version and the source of the FE solver), so a solver change never serves a stale
  matrix.
- **Checked on load**: shape, dtype, finiteness, exact symmetry (entries are stored symmetrized), positive diagonal,
  positive definiteness (Cholesky) on the loaded nodes (rows of clamped nodes are zero), and the stored checksum.
  A bad or unreadable entry (truncated, wrong shape, scaled, not a zip file) is deleted and recomputed with a
  :class:`~spiralbevel.errors.CacheWarning`.
- **Written safely**: a unique temporary name in the cache directory, then :func:`os.replace`; a cache that cannot be
  created or written is a warning, never a failed run.
- **Bounded**: after each write the oldest entries are removed until the directory holds at most
  :func:`max_cache_bytes` (``$SPIRALBEVEL_CACHE_MAX_MB``, default 512 MB). ``spiralbevel cache info|clear`` shows
  and empties it.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from ... import __version__
from ...errors import CacheWarning

__all__ = ["default_cache_dir", "max_cache_bytes", "cache_key", "load_matrix", "store_matrix", "cache_info",
           "clear_cache", "PATTERN"]

log = logging.getLogger(__name__)

#: file names of cache entries
PATTERN = "ltca_fe_*.npz"
_FORMAT = 2                                    # layout of an entry; bump when the stored fields change


def default_cache_dir() -> Path:
    """``$SPIRALBEVEL_CACHE`` or ``~/.cache/spiralbevel``."""
    return Path(os.environ.get("SPIRALBEVEL_CACHE", Path.home() / ".cache" / "spiralbevel"))


def max_cache_bytes() -> int:
    """Size cap of the cache directory, bytes: ``$SPIRALBEVEL_CACHE_MAX_MB`` (default 512) times 2**20."""
    try:
        mb = float(os.environ.get("SPIRALBEVEL_CACHE_MAX_MB", "512"))
    except ValueError:
        mb = 512.0
    return int(max(mb, 0.0) * (1 << 20))


def _code_version() -> str:
    """The package version and a hash of the FE solver's source (compliance.py)."""
    h = hashlib.sha256(f"{__version__}|format {_FORMAT}".encode())
    try:
        h.update((Path(__file__).with_name("compliance.py")).read_bytes())
    except OSError:  # pragma: no cover - source not shipped: the version alone
        pass
    return h.hexdigest()[:16]


def cache_key(arrays, text: str) -> str:
    """Key of an entry: SHA-256 of the input ``arrays`` (bytes, in order), a text of scalar inputs and the code
    version; 24 hex digits."""
    h = hashlib.sha256()
    for arr in arrays:
        a = np.ascontiguousarray(arr)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    h.update(f"{text}|code {_code_version()}".encode())
    return h.hexdigest()[:24]


def _checksum(G: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(G, dtype=np.float64).tobytes()).hexdigest()


def entry_path(cache_dir, key: str) -> Path:
    """The file of an entry."""
    return Path(cache_dir or default_cache_dir()) / f"ltca_fe_{key}.npz"


def _invalid(G, n: int) -> str:
    """Why a matrix cannot be a compliance of ``n`` load nodes ('' when it can)."""
    if G.dtype != np.float64 or G.shape != (n, n):
        return f"matrix of shape {G.shape} and dtype {G.dtype}, expected ({n}, {n}) float64"
    if not np.all(np.isfinite(G)):
        return "non-finite entries"
    if not np.array_equal(G, G.T):
        return "not symmetric"
    d = np.diag(G)
    live = d != 0.0
    if np.any(d < 0) or np.any(G[~live] != 0.0):
        return "negative diagonal, or a zero diagonal with non-zero coupling"
    try:
        np.linalg.cholesky(G[np.ix_(live, live)])
    except np.linalg.LinAlgError:
        return "not positive definite"
    return ""


def load_matrix(cache_dir, key: str, n: int):
    """The cached ``(G, asymmetry)`` of ``key``, or ``None`` (missing, or bad: then deleted, with a warning).

    Parameters
    ----------
    cache_dir : path or None
    key : str
    n : int
        Number of load nodes (``G`` must be ``(n, n)``).
    """
    path = entry_path(cache_dir, key)
    if not path.is_file():
        return None
    try:
        with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as data:
            G = np.array(data["G"])
            asym = float(data["asymmetry"])
            stored = str(data["checksum"])
            stored_key = str(data["key"])
        why = ("key mismatch" if stored_key != key else "checksum mismatch" if stored != _checksum(G)
               else _invalid(G, n))
    except Exception as err:  # noqa: BLE001 - a cache read may fail in any way (zip, zlib, OS); it is only a cache
        why = f"unreadable ({type(err).__name__}: {err})"
    if why:
        warnings.warn(f"FE cache entry {path} is bad ({why}); recomputing it", CacheWarning, stacklevel=3)
        with contextlib.suppress(OSError):
            path.unlink()
        return None
    with contextlib.suppress(OSError):
        os.utime(path)                         # most recently used: pruned last
    log.info("FE tooth compliance read from %s", path)
    return G, asym


def store_matrix(cache_dir, key: str, G: np.ndarray, asymmetry: float) -> "Path | None":
    """Write an entry (unique temporary name, then an atomic rename) and prune the cache to its cap.

    Returns the path, or ``None`` with a :class:`~spiralbevel.errors.CacheWarning` when it cannot be written.
    """
    path = entry_path(cache_dir, key)
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".tmp", dir=path.parent)
        with os.fdopen(fd, "wb") as fh:
            np.savez(fh, G=G, asymmetry=asymmetry, checksum=_checksum(G), key=key, code=_code_version())
        os.replace(tmp, path)
        tmp = None
    except OSError as err:
        warnings.warn(f"cannot write the FE cache in {path.parent} ({err.strerror or err}); the result is used "
                      "but not kept", CacheWarning, stacklevel=3)
        return None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
    prune(path.parent, keep=path)
    return path


def _entries(cache_dir) -> list:
    d = Path(cache_dir or default_cache_dir())
    try:
        return [p for p in d.glob(PATTERN) if p.is_file()]
    except OSError:
        return []


def prune(cache_dir=None, limit: "int | None" = None, keep: "Path | None" = None) -> int:
    """Remove the least recently used entries until the cache holds at most ``limit`` bytes (default
    :func:`max_cache_bytes`), and temporary files older than an hour; returns the number removed."""
    limit = max_cache_bytes() if limit is None else limit
    d = Path(cache_dir or default_cache_dir())
    removed = 0
    with contextlib.suppress(OSError):
        for tmp in d.glob(".ltca_fe_*.tmp"):
            if time.time() - tmp.stat().st_mtime > 3600:
                tmp.unlink()
                removed += 1
    stats = []
    for p in _entries(d):
        with contextlib.suppress(OSError):
            st = p.stat()
            stats.append((st.st_mtime, st.st_size, p))
    total = sum(s for _, s, _ in stats)
    for _, size, p in sorted(stats, key=lambda t: t[0]):
        if total <= limit:
            break
        if keep is not None and p == keep:
            continue
        with contextlib.suppress(OSError):
            p.unlink()
            total -= size
            removed += 1
    return removed


def cache_info(cache_dir=None) -> dict:
    """``{"path", "entries", "bytes", "max_bytes"}`` of the cache directory."""
    entries = _entries(cache_dir)
    size = 0
    for p in entries:
        with contextlib.suppress(OSError):
            size += p.stat().st_size
    return {"path": str(Path(cache_dir or default_cache_dir())), "entries": len(entries), "bytes": size,
            "max_bytes": max_cache_bytes()}


def clear_cache(cache_dir=None) -> int:
    """Delete every cache entry (and stray temporary file); returns the number of entries deleted. Other files in
    the directory are left alone."""
    n = 0
    for p in _entries(cache_dir):
        with contextlib.suppress(OSError):
            p.unlink()
            n += 1
    d = Path(cache_dir or default_cache_dir())
    with contextlib.suppress(OSError):
        for tmp in d.glob(".ltca_fe_*.tmp"):
            tmp.unlink()
    return n
