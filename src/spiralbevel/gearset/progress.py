"""A progress bar over the named steps of a job (rich), or silence."""

from __future__ import annotations

from contextlib import contextmanager


class Steps:
    """Counts steps and shows them on a rich progress bar when enabled."""

    def __init__(self, total: int, enabled: bool):
        self.total = total
        self.enabled = enabled
        self._progress = None
        self._task = None
        self.current = "starting"
        self.sub: "tuple[str, int, int] | None" = None   # the last sub-progress of the current step

    def __enter__(self):
        if self.enabled:
            from rich import get_console
            from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

            # redrawn by a background thread only on a terminal: to a file or pipe rich writes the bar once, in its
            # final state, so the thread would only rebuild it unseen 10 times a second for the whole run
            self._progress = Progress(TextColumn("{task.description:<38}"), BarColumn(),
                                      TextColumn("{task.completed}/{task.total}"),
                                      TimeElapsedColumn(), transient=False, auto_refresh=get_console().is_terminal)
            self._progress.__enter__()
            self._task = self._progress.add_task("starting", total=self.total)
        return self

    def __exit__(self, *exc):
        if self._progress is not None:
            self._progress.__exit__(*exc)
        return False

    @contextmanager
    def step(self, description: str):
        """Run one step, labelled ``description``; sub-progress that the library reports during the step (see
        :mod:`spiralbevel._progress`) is shown after the label."""
        from .._progress import listening

        self.current = description
        if self._progress is not None:
            self._progress.update(self._task, description=description)

        def sub(stage: str, done: int, total: int) -> None:
            self.sub = (stage, done, total)
            if self._progress is not None:
                self._progress.update(self._task, description=f"{description} | {stage} {done}/{total}")

        with listening(sub):
            yield
        self.sub = None
        if self._progress is not None:
            self._progress.advance(self._task)
