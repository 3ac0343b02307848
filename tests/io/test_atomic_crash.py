"""The output swap survives a crash at every step; foreign directories and special files are never replaced;
SIGTERM cleans up like SIGINT.

A crash is simulated for real: a child process writes an output directory and dies with ``os._exit`` (no clean-up
code runs, as with SIGKILL or a power cut) just before, or just after, its k-th file-system call (mkdir, rename,
replace, unlink, rmdir, chmod, fsync), for every k until the swap completes. The next run -- here
``recover_directory``, which every ``atomic_directory`` calls first -- must leave either the complete old output or
the complete new output, and no hidden leftovers.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path
import time

import pytest

from spiralbevel.io.atomic import (OUTPUT_MARKER, ForeignDirectoryError, atomic_directory, recover_directory)

CHILD = textwrap.dedent("""
    import os, shutil, sys
    from pathlib import Path
    k, mode, out, version = int(sys.argv[1]), sys.argv[2], Path(sys.argv[3]), sys.argv[4]
    from spiralbevel.io.atomic import OUTPUT_MARKER, atomic_directory
    count = [0]

    def hooked(fn):
        def call(*args, **kwargs):
            count[0] += 1
            if count[0] == k and mode == "before":
                os._exit(77)
            result = fn(*args, **kwargs)
            if count[0] == k and mode == "after":
                os._exit(77)
            return result
        return call

    for name in ("mkdir", "rename", "replace", "unlink", "rmdir", "chmod", "fsync"):
        setattr(os, name, hooked(getattr(os, name)))
    with atomic_directory(out, marker=OUTPUT_MARKER, manifest={"version": version}) as tmp:
        for i in range(3):
            (tmp / f"f{i}.txt").write_text(version)
        (tmp / "sub").mkdir()
        (tmp / "sub" / "g.txt").write_text(version)
    sys.exit(0)
""")

FILES = [OUTPUT_MARKER, "f0.txt", "f1.txt", "f2.txt", "sub/g.txt"]


def _write(out, version):
    with atomic_directory(out, marker=OUTPUT_MARKER, manifest={"version": version}) as tmp:
        for i in range(3):
            (tmp / f"f{i}.txt").write_text(version)
        (tmp / "sub").mkdir()
        (tmp / "sub" / "g.txt").write_text(version)


def _version(out):
    """The version of a complete output directory, or None when absent; fails on anything partial."""
    if not out.exists():
        return None
    files = sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file())
    assert files == sorted(FILES), files
    versions = {(out / f).read_text() for f in FILES if f != OUTPUT_MARKER}
    assert len(versions) == 1, versions
    (v,) = versions
    assert json.loads((out / OUTPUT_MARKER).read_text())["version"] == v
    return v


@pytest.mark.parametrize("previous", [True, False])
def test_crash_at_every_step_is_recovered(tmp_path, previous):
    out = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    crashes = 0
    for mode in ("before", "after"):
        for k in range(1, 200):
            if out.exists():
                import shutil

                shutil.rmtree(out)
            if previous:
                _write(out, "old")
            proc = subprocess.run([sys.executable, "-c", CHILD, str(k), mode, str(out), "new"], env=env,
                                  capture_output=True, text=True, timeout=60)
            if proc.returncode == 0:
                break
            assert proc.returncode == 77, proc.stderr
            crashes += 1
            recover_directory(out)
            assert _version(out) in (("old", "new") if previous else (None, "new")), (mode, k)
            assert sorted(p.name for p in tmp_path.iterdir()) == (["out"] if out.exists() else []), (mode, k)
            _write(out, "third")                     # the next run works and leaves nothing behind
            assert _version(out) == "third"
            assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
        else:  # pragma: no cover
            pytest.fail("the child never completed")
        assert _version(out) == "new"
    assert crashes >= 10                               # every step of the build and the swap was hit


def test_live_build_of_another_run_is_not_deleted(tmp_path):
    out = tmp_path / "out"
    with atomic_directory(out, marker=OUTPUT_MARKER) as tmp:
        (tmp / "a.txt").write_text("1")
        assert recover_directory(out) == []           # the build is locked by its live owner
        assert tmp.is_dir()
    assert (out / "a.txt").read_text() == "1"


def test_foreign_directory_refused_and_previous_output_replaced(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("user data")
    with pytest.raises(ForeignDirectoryError):
        with atomic_directory(out, marker=OUTPUT_MARKER):
            pytest.fail("the body must not run")
    assert [p.name for p in out.iterdir()] == ["mine.txt"]
    empty = tmp_path / "empty"
    empty.mkdir()
    _write(empty, "1")                                # an empty directory is taken
    _write(empty, "2")                                # a previous output is replaced whole
    assert _version(empty) == "2"
    link = tmp_path / "link"
    link.symlink_to(empty)
    with pytest.raises(FileExistsError, match="symbolic link"):
        _write(link, "3")
    assert _version(empty) == "2"


@pytest.mark.skipif(os.name != "posix", reason="POSIX signals")
@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_signal_during_a_run_leaves_no_leftovers(tmp_path, sig, code):
    # a run whose computation is slow (patched): the signal arrives while the output is being built
    # the child takes SIGINT as a user's Ctrl-C does: a test run started in the background by a non-interactive
    # shell (``pytest &``, no job control) ignores SIGINT, and a child inherits an ignored signal
    script = textwrap.dedent("""
        import signal, sys, time
        signal.signal(signal.SIGINT, signal.default_int_handler)
        import spiralbevel.gearset.blank as blank
        def slow(spec):
            print("started", flush=True)
            time.sleep(60)
        blank.blank_from_design = slow
        from spiralbevel.cli import app
        sys.argv = ["spiralbevel", "run", "-q", "-o", sys.argv[1]]
        app()
    """)
    out = tmp_path / "out"
    _write(out, "old")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    proc = subprocess.Popen([sys.executable, "-c", script, str(out)], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "started"
        time.sleep(0.2)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
    assert proc.returncode == code, err
    assert "Traceback" not in err and ("terminated" in err or "interrupted" in err)
    assert _version(out) == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_previous_output_with_added_user_files_is_refused(tmp_path):
    """A previous output is replaced whole; a file the user added to it (not in its manifest) would be deleted by the
    swap, so the directory is refused, naming the file, and left as it was."""
    out = tmp_path / "out"
    _write(out, "1")
    (out / "notes.txt").write_text("user data")
    (out / "mine").mkdir()
    (out / "mine" / "x.csv").write_text("1,2")
    listed = sorted(json.loads((out / OUTPUT_MARKER).read_text())["files"])
    with pytest.raises(ForeignDirectoryError) as info:
        with atomic_directory(out, marker=OUTPUT_MARKER):
            pytest.fail("the body must not run")
    assert "notes.txt" in str(info.value) and str(Path("mine") / "x.csv") in str(info.value)
    assert (out / "notes.txt").read_text() == "user data" and (out / "mine" / "x.csv").read_text() == "1,2"
    (out / "notes.txt").unlink()
    (out / "mine" / "x.csv").unlink()
    assert _version(out) == "1"                        # the previous output as it was
    _write(out, "2")                                   # only what the manifest lists (and empty folders) left: replaced
    assert _version(out) == "2" and sorted(json.loads((out / OUTPUT_MARKER).read_text())["files"]) == listed


def test_manifest_without_a_file_list_proves_nothing(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / OUTPUT_MARKER).write_text("{}")
    (out / "mine.txt").write_text("user data")
    with pytest.raises(ForeignDirectoryError, match="mine.txt"):
        with atomic_directory(out, marker=OUTPUT_MARKER):
            pytest.fail("the body must not run")
    assert (out / "mine.txt").read_text() == "user data"
