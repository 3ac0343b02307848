"""Write files and output directories whole or not at all.

A file is written to a temporary sibling in the same directory, flushed and fsync'ed, then moved over the target with
:func:`os.replace`, which is atomic on POSIX and Windows when both live on the same file system. A reader therefore
sees either the old content or the new content, never a half-written file, and an exception (or a crash) while
writing leaves the old file untouched.

:func:`atomic_directory` does the same for a whole output directory: the caller builds the output in a temporary
sibling directory; on success the old directory (if any) is moved aside, the new one renamed into place and the old
one removed. On an exception the temporary directory is deleted and the old directory stays as it was.

Crash safety of the directory swap (``kill -9``, power loss, a failure at any step): every step leaves a state that
:func:`recover_directory` -- called at the start of every :func:`atomic_directory` -- turns back into "the old output
or the new output, and no leftovers":

1. build in ``.<name>.spiralbevel-<r>.tmp`` (locked with ``flock`` while its process lives, so that a concurrent run
   never deletes another run's build); a dead build is deleted;
2. rename the old output to ``.<name>.spiralbevel-<r>.old``; if ``<name>`` is then missing, the old output is renamed
   back;
3. rename the build to ``<name>``;
4. delete the ``.old`` tree; a partly deleted ``.old`` next to an existing ``<name>`` is deleted.

Steps 2-4 and the recovery run under an exclusive ``flock`` of the parent directory, with SIGINT and SIGTERM held back
until the renames are done. With ``marker`` set, the directory is marked by a small manifest, and an existing
non-empty directory without that manifest is refused (:class:`ForeignDirectoryError`), and so is a previous output
that holds files its manifest does not list (a user's notes added to it): the swap never deletes files that
spiralbevel did not write.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import signal
import stat
import threading
import shutil
import tempfile
from pathlib import Path
from typing import Iterator

__all__ = ["atomic_write_text", "atomic_write_bytes", "atomic_directory", "recover_directory", "check_output_file",
           "NotRegularFileError",
           "ForeignDirectoryError", "OUTPUT_MARKER"]

#: name of the manifest that marks a directory as a spiralbevel output (written last, before the swap)
OUTPUT_MARKER = ".spiralbevel-output.json"
#: middle part of the names of the swap's hidden siblings: ``.<name>.spiralbevel-<random>.tmp`` / ``.old``
_TAG = "spiralbevel-"


class NotRegularFileError(FileExistsError):
    """An output path names something other than a regular file (link, directory, FIFO, device); left untouched."""


class ForeignDirectoryError(FileExistsError):
    """An output directory is not empty and was not written by spiralbevel; left untouched."""


def check_output_file(path: "str | os.PathLike[str]") -> Path:
    """Check, before any work, that ``path`` can take a single-file output: its directory exists and ``path`` is
    missing or a regular file (not a link, directory, FIFO or device). Returns the path.

    Raises
    ------
    NotRegularFileError, FileNotFoundError
    """
    target = Path(path)
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(errno.ENOENT, "its directory does not exist", str(target))
    _check_replaceable_file(target)
    return target


def _check_replaceable_file(target: Path) -> None:
    try:
        st = os.lstat(target)
    except FileNotFoundError:
        return
    if not stat.S_ISREG(st.st_mode):
        kind = ("a symbolic link" if stat.S_ISLNK(st.st_mode) else "a directory" if stat.S_ISDIR(st.st_mode)
                else "a FIFO" if stat.S_ISFIFO(st.st_mode) else "a socket" if stat.S_ISSOCK(st.st_mode)
                else "a device node" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode) else "not a regular file")
        raise NotRegularFileError(errno.EEXIST, f"exists and is {kind}; only a regular file is replaced", str(target))


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

    Only a regular file is ever replaced: an existing symbolic link, directory, FIFO, socket or device node at
    ``path`` raises :class:`NotRegularFileError` (a ``FileExistsError``) and is left as it is, so ``--output /dev/null``
    can never replace the real ``/dev/null``.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    _check_replaceable_file(target)
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


def _lock(fd: int, blocking: bool = True) -> bool:
    """flock ``fd`` exclusively (POSIX); True when held. Without fcntl (Windows) nothing is locked."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows
        return True
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if blocking else fcntl.LOCK_NB))
        return True
    except BlockingIOError:
        return False
    except OSError:  # pragma: no cover - file systems without flock: proceed unlocked
        return True


@contextlib.contextmanager
def _dir_lock(directory: Path) -> Iterator[None]:
    """Exclusive lock of a directory for the recovery and the swap (short critical sections)."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:  # pragma: no cover - unreadable parent: proceed unlocked
        yield
        return
    try:
        _lock(fd)
        yield
    finally:
        os.close(fd)


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back (delivered on exit) so the renames of the swap are not cut in the middle."""
    held = {signal.SIGINT, getattr(signal, "SIGTERM", signal.SIGINT)}
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _leftovers(parent: Path, name: str, suffix: str) -> list:
    prefix = f".{name}.{_TAG}"
    try:
        entries = list(os.scandir(parent))
    except OSError:
        return []
    return sorted(Path(e.path) for e in entries
                  if e.name.startswith(prefix) and e.name.endswith(suffix) and e.is_dir(follow_symlinks=False))


def recover_directory(path: "str | os.PathLike[str]") -> list:
    """Finish or undo an interrupted :func:`atomic_directory` swap of ``path``.

    Parameters
    ----------
    path : str or PathLike
        The output directory.

    Returns
    -------
    list of str
        What was done, one line per action (empty when there was nothing to do).

    Notes
    -----
    A moved-aside old output (``.<name>.spiralbevel-<r>.old``) is renamed back when ``path`` is missing, else
    deleted; a build directory (``.tmp``) whose process no longer holds its lock is deleted. Builds of live
    concurrent runs are left alone.
    """
    target = Path(os.path.abspath(path))
    parent, name = target.parent, target.name
    done = []
    with _dir_lock(parent):
        for old in _leftovers(parent, name, ".old"):
            if not os.path.lexists(target):
                os.rename(old, target)
                done.append(f"restored the previous output {target} from {old.name}")
            else:
                shutil.rmtree(old, ignore_errors=True)
                done.append(f"removed {old.name} (an old output already replaced)")
        for tmp in _leftovers(parent, name, ".tmp"):
            try:
                fd = os.open(tmp, os.O_RDONLY)
            except OSError:
                continue
            try:
                if not _lock(fd, blocking=False):
                    continue                      # a live run is building it
                shutil.rmtree(tmp, ignore_errors=True)
                done.append(f"removed {tmp.name} (an interrupted build)")
            finally:
                os.close(fd)
    return done


def _check_target(target: Path, marker) -> None:
    if not os.path.lexists(target):
        return
    if os.path.islink(target):
        raise NotRegularFileError(errno.EEXIST, "is a symbolic link; give the real directory", str(target))
    if not target.is_dir():
        raise FileExistsError(errno.EEXIST, "exists and is not a directory", str(target))
    if marker is None:
        return
    with os.scandir(target) as it:
        empty = next(it, None) is None
    if not empty and not (target / marker).is_file():
        raise ForeignDirectoryError(
            errno.EEXIST, f"is a non-empty directory that is not a spiralbevel output (no {marker}); refusing to "
                          "replace it: give a new or empty directory", str(target))
    if not empty:
        foreign = _unlisted_files(target, marker)
        if foreign:
            shown = ", ".join(foreign[:5]) + (f" and {len(foreign) - 5} more" if len(foreign) > 5 else "")
            raise ForeignDirectoryError(
                errno.EEXIST, f"is a previous spiralbevel output that now also holds files it did not write ({shown}); "
                              "refusing to replace it, which would delete them: move them out or give another "
                              "directory", str(target))


def _unlisted_files(target: Path, marker: str) -> list:
    """Files (and links) under ``target`` that its manifest ``marker`` does not list, as sorted relative paths: files a
    user added to a previous output, which replacing it would delete. A manifest that cannot be read or lists no files
    proves nothing: then every file but the manifest counts."""
    try:
        listed = json.loads((target / marker).read_text(encoding="utf-8")).get("files")
    except (OSError, ValueError, AttributeError):
        listed = None
    listed = {str(Path(f)) for f in listed if isinstance(f, str)} if isinstance(listed, list) else set()
    present = (p for p in target.rglob("*") if p.is_symlink() or not p.is_dir())
    return sorted(rel for rel in (str(p.relative_to(target)) for p in present) if rel != marker and rel not in listed)


@contextlib.contextmanager
def atomic_directory(path: "str | os.PathLike[str]", marker: "str | None" = None,
                     manifest: "dict | None" = None) -> Iterator[Path]:
    """Build an output directory in a temporary sibling and swap it in only if the ``with`` body succeeds.

    Parameters
    ----------
    path : str or PathLike
        The final directory. Its parent must exist. If it already exists it is replaced as a whole on success and
        left untouched on failure.
    marker : str, optional
        File name of the manifest that marks the directory as owned (e.g. :data:`OUTPUT_MARKER`). When given, an
        existing non-empty ``path`` without it is refused before anything is written, and the manifest is written
        into the new directory (last, just before the swap).
    manifest : dict, optional
        Extra content of the manifest (JSON). Its ``"files"`` entry is filled with the files of the new directory.

    Yields
    ------
    pathlib.Path
        The temporary directory to write into (a sibling ``.<name>.spiralbevel-<random>.tmp`` of ``path``).

    Raises
    ------
    ForeignDirectoryError
        ``marker`` is set and ``path`` is a non-empty directory without it, or with it but holding files that its
        manifest does not list (the error names them).
    FileExistsError
        ``path`` is a file or a symbolic link.
    FileNotFoundError
        The parent of ``path`` does not exist (nothing is created).

    Notes
    -----
    The swap is two renames (old -> ``.<name>.spiralbevel-<random>.old``, new -> ``path``) followed by removal of the
    old tree; if the second rename fails the old directory is renamed back. A crash at any step is repaired by the next
    call (:func:`recover_directory`; module docstring).

    Examples
    --------
    >>> with atomic_directory("out") as tmp:          # doctest: +SKIP
    ...     (tmp / "report.json").write_text("{}")
    """
    target = Path(os.path.abspath(path))
    parent, name = target.parent, target.name
    if not name:
        raise FileExistsError(errno.EEXIST, "is the root directory", str(target))
    if not parent.is_dir():  # else mkdtemp's error would name the hidden temporary sibling, not the user's path
        raise FileNotFoundError(errno.ENOENT, f"its parent directory {parent} does not exist; create it first",
                                str(target))
    recover_directory(target)
    _check_target(target, marker)
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.{_TAG}", suffix=".tmp", dir=parent))
    try:
        fd = os.open(tmp, os.O_RDONLY)
    except OSError:  # pragma: no cover - Windows cannot open directories: no lock
        fd = None
    try:
        if fd is not None:
            _lock(fd, blocking=False)
        try:
            yield tmp
            if marker is not None:
                files = sorted(str(p.relative_to(tmp)) for p in tmp.rglob("*") if p.is_file())
                atomic_write_text(tmp / marker, json.dumps(dict(manifest or {}, files=files), indent=1) + "\n")
            os.chmod(tmp, 0o777 & ~_umask())
            with _dir_lock(parent), _signals_held():
                _check_target(target, marker)        # a concurrent writer may have changed it meanwhile
                old = None
                if os.path.lexists(target):
                    old = tmp.with_name(tmp.name.removesuffix(".tmp") + ".old")
                    os.replace(target, old)
                    try:
                        os.replace(tmp, target)
                    except BaseException:
                        os.replace(old, target)
                        raise
                else:
                    os.replace(tmp, target)
                _fsync_dir(parent)
                if old is not None:
                    shutil.rmtree(old, ignore_errors=True)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
    finally:
        if fd is not None:
            os.close(fd)


def _umask() -> int:
    """The process umask (read by setting and restoring it)."""
    umask = os.umask(0)
    os.umask(umask)
    return umask
