"""``spiralbevel run``: the design file's gear set writes its report directory."""

from __future__ import annotations

from ..gearset import GearSet
from ..gearset.run import RunSummary
from ..io.design_schema import DesignFile


def run_design(spec: DesignFile, out, progress: bool = True) -> RunSummary:
    """Compute everything ``spec`` asks for and write it to the directory ``out``.

    The directory is built aside and swapped in only when every file was written (``io.atomic.atomic_directory``):
    a failure leaves any previous ``out`` untouched and no partial output. ``out`` must be new, empty, or a previous
    spiralbevel output (marked by the manifest ``io.atomic.OUTPUT_MARKER``); any other existing directory is refused
    with :class:`~spiralbevel.io.atomic.ForeignDirectoryError` before any computation.

    A failing secondary analysis (conjugacy check, TCA of one side, loaded TCA, a misalignment case) does not stop the
    run: its report entry says ``"status": "failed"`` with the reason, and ``summary.partial`` lists it.

    Parameters
    ----------
    spec : DesignFile
        The validated design.
    out : str or Path
        Output directory.
    progress : bool
        Show a progress bar.

    Returns
    -------
    RunSummary
    """
    return GearSet(spec).report(out, progress=progress)
