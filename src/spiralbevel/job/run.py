"""Orchestration of ``spiralbevel run``: design file → blank → flanks → analyses → files, written whole or not at
all."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__
from ..io.design_schema import DesignFile
from .blank import blank_from_design, require_no_offset
from .rating import rating_report
from .progress import Steps


@dataclass
class RunSummary:
    """What a run wrote and the lines worth printing.

    Attributes
    ----------
    out : Path
    files : list of str
        Names of the files written inside ``out``.
    highlights : list of str
        One-line results for the terminal.
    report : dict
        The content of report.json.
    """

    out: Path
    files: list = field(default_factory=list)
    highlights: list = field(default_factory=list)
    report: dict = field(default_factory=dict)


def run_design(spec: DesignFile, out, progress: bool = True) -> RunSummary:
    """Compute everything ``spec`` asks for and write it to the directory ``out``.

    The directory is built aside and swapped in only when every file was written (``io.atomic.atomic_directory``):
    a failure leaves any previous ``out`` untouched and no partial output.
    """
    from ..io.atomic import atomic_directory
    from ..io.dimension_sheet import dimension_sheet_json
    from ..io.report import write_report

    out = Path(out)
    summary = RunSummary(out=out)
    kind = spec.flank.kind
    n_steps = 2 + (_logspiral_steps(spec) if kind == "log-spiral" else _facemilled_steps(spec))
    with Steps(n_steps, progress) as steps, atomic_directory(out) as tmp:
        tmp = Path(tmp)
        with steps.step("blank geometry (ISO 23509)"):
            blank = blank_from_design(spec)
            require_no_offset(blank, "spiralbevel run")
        report = {
            "spiralbevel_version": __version__,
            "title": spec.title,
            "design": spec.model_dump(mode="json"),
            "blank": dimension_sheet_json(blank),
            "blank_warnings": list(getattr(blank, "warnings", ())),
        }
        summary.highlights.append(
            f"blank: delta1 = {math.degrees(blank.delta1):.4f} deg, delta2 = {math.degrees(blank.delta2):.4f} deg, "
            f"Rm = {blank.Rm:.4f} mm")
        rating_report(spec, blank, report, summary)
        if kind == "log-spiral":
            from .run_logspiral import run_logspiral

            run_logspiral(spec, blank, tmp, steps, report, summary)
        else:
            from .run_facemilled import run_facemilled

            run_facemilled(spec, blank, tmp, steps, report, summary)
        with steps.step("report.json"):
            summary.files.append("report.json")
            report["files"] = sorted(summary.files)
            write_report(tmp / "report.json", report)
        summary.report = report
    return summary


def _logspiral_steps(spec) -> int:
    o = spec.output
    extra = 2 * int(spec.crowning is not None) + int(bool(o.draft and spec.manufacturing.forging_relief))
    return 4 + int(o.plots) + int(o.draft) + int(o.toolpaths) + int(o.stl) + int(o.step) + extra


def _facemilled_steps(spec) -> int:
    o = spec.output
    return 5 + int(spec.ltca is not None) + int(o.plots) + int(o.stl) + int(o.step)
