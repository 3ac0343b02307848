"""What the command's process does around its work: the exit handler that spares the interpreter's final collection,
and the progress bar's redraw thread only where someone can see it."""

import io
import os
import subprocess
import sys

import rich
from rich.console import Console

from spiralbevel import cli
from spiralbevel.gearset.progress import Steps


def test_freeze_handler_is_registered_once(monkeypatch):
    registered = []
    monkeypatch.setattr("atexit.register", registered.append)
    monkeypatch.setattr(cli, "_FROZEN_AT_EXIT", False)
    cli._freeze_at_exit()
    cli._freeze_at_exit()
    import gc

    assert registered == [gc.freeze]


def test_objects_are_frozen_after_the_other_exit_handlers_and_output_is_complete():
    """A real process: an exit handler registered before the command runs after the freeze (handlers run last-in,
    first-out) and sees the objects frozen; the command's output arrived whole."""
    code = ("import atexit, gc, sys\n"
            "atexit.register(lambda: print('frozen', gc.get_freeze_count() > 0, flush=True))\n"
            "from spiralbevel.cli import app\n"
            "sys.argv = ['spiralbevel', 'examples']\n"
            "app()\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                         env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[-1] == "frozen True"
    assert any("aviation_23x65_logspiral" in line for line in lines[:-1])


def test_progress_bar_redraws_in_the_background_only_on_a_terminal(monkeypatch):
    monkeypatch.setattr(rich, "_console", Console(file=io.StringIO(), force_terminal=False))
    with Steps(2, enabled=True) as steps:
        assert steps._progress.live.auto_refresh is False
        with steps.step("one"):
            pass
    assert "one" in rich._console.file.getvalue()          # the final state is still written, once
    monkeypatch.setattr(rich, "_console", Console(file=io.StringIO(), force_terminal=True))
    with Steps(2, enabled=True) as steps:
        assert steps._progress.live.auto_refresh is True
