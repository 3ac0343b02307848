"""Atomic file and directory writes: whole or not at all."""

from __future__ import annotations

import os
import stat

import pytest

from spiralbevel.io.atomic import atomic_directory, atomic_write_bytes, atomic_write_text


def _siblings(d):
    return sorted(p.name for p in d.iterdir())


def test_write_text_creates_and_replaces(tmp_path):
    f = tmp_path / "a.txt"
    atomic_write_text(f, "one\n")
    assert f.read_text() == "one\n"
    atomic_write_text(f, "two\r\nthree\n")
    assert f.read_bytes() == b"two\r\nthree\n"  # no newline translation
    assert _siblings(tmp_path) == ["a.txt"]  # no temp file left behind


def test_write_bytes_roundtrip_and_encoding(tmp_path):
    f = tmp_path / "b.bin"
    data = bytes(range(256)) * 3
    assert atomic_write_bytes(f, data) == f
    assert f.read_bytes() == data
    atomic_write_text(f, "Σ = 90°", encoding="utf-16")
    assert f.read_text(encoding="utf-16") == "Σ = 90°"


def test_failed_write_keeps_old_content_and_leaves_no_temp(tmp_path, monkeypatch):
    f = tmp_path / "c.txt"
    f.write_text("old")

    def boom(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError, match="disk full"):
        atomic_write_text(f, "new")
    monkeypatch.undo()
    assert f.read_text() == "old"
    assert _siblings(tmp_path) == ["c.txt"]


def test_unencodable_text_leaves_old_file(tmp_path):
    f = tmp_path / "d.txt"
    f.write_text("old")
    with pytest.raises(UnicodeEncodeError):
        atomic_write_text(f, "Σ", encoding="ascii")
    assert f.read_text() == "old"
    assert _siblings(tmp_path) == ["d.txt"]


@pytest.mark.skipif(os.name != "posix", reason="POSIX permission bits")
def test_permissions_kept_on_replace_and_umask_on_create(tmp_path):
    f = tmp_path / "e.txt"
    f.write_text("x")
    os.chmod(f, 0o640)
    atomic_write_text(f, "y")
    assert stat.S_IMODE(f.stat().st_mode) == 0o640
    g = tmp_path / "g.txt"
    old = os.umask(0o022)
    try:
        atomic_write_text(g, "z")
    finally:
        os.umask(old)
    assert stat.S_IMODE(g.stat().st_mode) == 0o644  # not mkstemp's 0o600


def test_directory_created_on_success(tmp_path):
    out = tmp_path / "out"
    with atomic_directory(out) as tmp:
        assert tmp.parent == tmp_path and tmp != out
        (tmp / "report.json").write_text("{}")
        (tmp / "sub").mkdir()
        (tmp / "sub" / "x.csv").write_text("1")
        assert not out.exists()  # nothing visible before the swap
    assert (out / "report.json").read_text() == "{}"
    assert (out / "sub" / "x.csv").read_text() == "1"
    assert _siblings(tmp_path) == ["out"]


def test_directory_replaced_whole(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "stale.txt").write_text("stale")
    with atomic_directory(out) as tmp:
        (tmp / "fresh.txt").write_text("fresh")
    assert _siblings(out) == ["fresh.txt"]
    assert _siblings(tmp_path) == ["out"]


def test_directory_exception_leaves_old_untouched(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("keep")
    with pytest.raises(RuntimeError, match="solver failed"):
        with atomic_directory(out) as tmp:
            (tmp / "partial.txt").write_text("half")
            raise RuntimeError("solver failed")
    assert _siblings(out) == ["keep.txt"]
    assert _siblings(tmp_path) == ["out"]


def test_directory_exception_without_old_leaves_nothing(tmp_path):
    out = tmp_path / "new"
    with pytest.raises(KeyboardInterrupt):
        with atomic_directory(out) as tmp:
            (tmp / "partial.txt").write_text("half")
            raise KeyboardInterrupt
    assert _siblings(tmp_path) == []


def test_directory_failed_swap_restores_old(tmp_path, monkeypatch):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("keep")
    real = os.replace
    calls = []

    def flaky(src, dst):
        calls.append((src, dst))
        if len(calls) == 2:  # the rename of the new tree into place
            raise OSError("rename failed")
        return real(src, dst)

    monkeypatch.setattr(os, "replace", flaky)
    with pytest.raises(OSError, match="rename failed"):
        with atomic_directory(out) as tmp:
            (tmp / "fresh.txt").write_text("fresh")
    monkeypatch.undo()
    assert _siblings(out) == ["keep.txt"]
    assert _siblings(tmp_path) == ["out"]


def test_directory_target_is_a_file(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(FileExistsError):
        with atomic_directory(f):
            pass
    assert f.read_text() == "x"


def test_directory_missing_parent_names_the_users_path(tmp_path):
    out = tmp_path / "missing" / "out"
    with pytest.raises(FileNotFoundError) as info:
        with atomic_directory(out):
            pass
    # the error names the path asked for and its missing parent, not the hidden temporary sibling
    assert info.value.filename == str(out)
    assert "missing" in str(info.value) and ".tmp" not in str(info.value)
    assert list(tmp_path.iterdir()) == []
