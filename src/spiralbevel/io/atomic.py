"""Write files and output directories whole or not at all.

A file is written to a temporary sibling in the same directory, flushed and fsync'ed, then moved over the target with
:func:`os.replace`, which is atomic on POSIX and Windows when both live on the same file system. A reader therefore
sees either the old content or the new content, never a half-written file, and an exception (or a crash) while
writing leaves the old file untouched.

:func:`atomic_directory` does the same for a whole output directory: the caller builds the output in a temporary
sibling directory; on success the old directory (if any) is moved aside, the new one renamed into place and the old
one removed. On an exception the temporary directory is deleted and the old directory stays as it was.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path
from typing import Iterator

__all__ = ["atomic_write_text", "atomic_write_bytes", "atomic_directory"]


def _default_mode(target: Path) -> int:
    """Permission bits for a new file: those of the file it replaces, else 0o666 minus the umask."""
    try:
        return target.stat().st_mode & 0o7777
    except FileNotFoundError:
        return 0o666 & ~_umask()


def _fsync_dir(directory: Path) -> None:
    """Flush a directory entry to disk where the platform allows it (POSIX); a no-op elsewhere."""
    if os.name != "posix":  # pragma: no cover - Windows cannot open directories
        return
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    except OSError:  # pragma: no cover - some file systems refuse fsync on directories
        pass
    finally:
        os.close(fd)


def atomic_write_bytes(path: "str | os.PathLike[str]", data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically.

    Parameters
    ----------
    path : str or PathLike
        Target file. Its directory must exist.
    data : bytes
        Whole content.

    Returns
    -------
    pathlib.Path
        The target path.

    Notes
    -----
    The temporary file ``.<name>.<random>.tmp`` lives in the target's directory (so :func:`os.replace` never crosses
    file systems) and is removed if anything fails. The permission bits of an existing target are kept.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, _default_mode(target))
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise
    _fsync_dir(directory)
    return target


def atomic_write_text(path: "str | os.PathLike[str]", text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically (see :func:`atomic_write_bytes`).

    Parameters
    ----------
    path : str or PathLike
        Target file. Its directory must exist.
    text : str
        Whole content; written as is (no newline translation), so ``"\\n"`` stays ``"\\n"`` on every platform.
    encoding : str
        Text encoding, UTF-8 by default.

    Returns
    -------
    pathlib.Path
        The target path.
    """
    return atomic_write_bytes(path, text.encode(encoding))


@contextlib.contextmanager
def atomic_directory(path: "str | os.PathLike[str]") -> Iterator[Path]:
    """Build an output directory in a temporary sibling and swap it in only if the ``with`` body succeeds.

    Parameters
    ----------
    path : str or PathLike
        The final directory. Its parent must exist. If it already exists it is replaced as a whole on success and
        left untouched on failure.

    Yields
    ------
    pathlib.Path
        The temporary directory to write into (a sibling ``.<name>.<random>.tmp`` of ``path``).

    Notes
    -----
    The swap is two renames (old → ``.<name>.<random>.old``, new → ``path``) followed by removal of the old tree; if
    the second rename fails the old directory is renamed back. Between the two renames (microseconds) ``path`` does
    not exist; it never holds a partial output. ``path`` must not be an existing regular file.

    Examples
    --------
    >>> with atomic_directory("out") as tmp:          # doctest: +SKIP
    ...     (tmp / "report.json").write_text("{}")
    """
    target = Path(path)
    parent = target.parent if str(target.parent) else Path(".")
    if target.exists() and not target.is_dir():
        raise FileExistsError(f"{target} exists and is not a directory")
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".tmp", dir=parent))
    try:
        yield tmp
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    try:
        os.chmod(tmp, 0o777 & ~_umask())
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".old", dir=parent))
            os.replace(target, old / "d")
            try:
                os.replace(tmp, target)
            except BaseException:
                os.replace(old / "d", target)
                shutil.rmtree(old, ignore_errors=True)
                raise
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    _fsync_dir(parent)


def _umask() -> int:
    """The process umask (read by setting and restoring it)."""
    umask = os.umask(0)
    os.umask(umask)
    return umask
