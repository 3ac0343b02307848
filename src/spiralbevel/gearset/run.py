"""The report directory of a gear set (``spiralbevel run``, ``GearSet.report``): design → blank → flanks → analyses
→ files, written whole or not at all."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from .. import __version__
from ..io.design_schema import DesignFile
from .blank import LOGSPIRAL_NO_OFFSET, blank_section, require_no_offset
from ..errors import DesignError
from .partial import PartialLog
from .problems import with_design_keys
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
    partial : PartialLog
        Secondary analyses that failed (each has a report entry with its reason); non-empty means "completed with
        warnings".
    """

    out: Path
    files: list = field(default_factory=list)
    highlights: list = field(default_factory=list)
    report: dict = field(default_factory=dict)
    partial: PartialLog = field(default_factory=PartialLog)


def write_run(gearset, out, progress: bool = True) -> RunSummary:
    """Compute everything the design of ``gearset`` (a :class:`~spiralbevel.gearset.GearSet`) asks for and write it
    to the directory ``out`` (``spiralbevel run``, :meth:`GearSet.report <spiralbevel.gearset.GearSet.report>`).

    The directory is built aside and swapped in only when every file was written (``io.atomic.atomic_directory``):
    a failure leaves any previous ``out`` untouched and no partial output. ``out`` must be new, empty, or a previous
    spiralbevel output (marked by the manifest ``io.atomic.OUTPUT_MARKER``); any other existing directory is refused
    with :class:`~spiralbevel.io.atomic.ForeignDirectoryError` before any computation.

    A failing secondary analysis (conjugacy check, TCA of one side, loaded TCA, a misalignment case) does not stop the
    run: its report entry says ``"status": "failed"`` with the reason, and ``summary.partial`` lists it.
    """
    spec: DesignFile = gearset.design
    out = Path(out)
    summary = RunSummary(out=out)
    kind = spec.flank.kind
    if kind == "log-spiral":
        n_steps = 2 + _logspiral_steps(spec)
    elif spec.gear_set.hypoid_offset != 0.0:
        from .run_hypoid import hypoid_steps

        n_steps = 2 + hypoid_steps(spec)
    else:
        n_steps = 2 + _facemilled_steps(spec)
    manifest = {"written_by": "spiralbevel", "spiralbevel_version": __version__, "title": spec.title}
    section = "gear_set" if kind == "log-spiral" else "face_milling"
    steps = Steps(n_steps, progress)
    try:
        return _run(gearset, out, summary, kind, steps, manifest)
    except DesignError as err:
        raise with_design_keys(err, section, f"in the step '{steps.current}'") from err


def _run(gs, out, summary, kind, steps, manifest):
    from ..io.atomic import OUTPUT_MARKER, atomic_directory
    from ..io.report import write_report
    from ..io.report_html import write_run_report_html

    with atomic_directory(out, marker=OUTPUT_MARKER, manifest=manifest) as tmp, steps:
        tmp = Path(tmp)
        with steps.step("blank geometry (ISO 23509)"):
            blank = gs.blank
        spec = gs.design
        report = {
            "spiralbevel_version": __version__,
            "design": spec.model_dump(mode="json"),
            "blank": blank_section(blank),
        }
        summary.highlights.append(
            f"blank: delta1 = {math.degrees(blank.delta1):.4f} deg, delta2 = {math.degrees(blank.delta2):.4f} deg, "
            f"Rm = {blank.Rm:.4f} mm")
        rating_report(spec, blank, report, summary)
        if kind == "log-spiral":
            from .run_logspiral import run_logspiral

            require_no_offset(blank, "spiralbevel run on a log-spiral design", LOGSPIRAL_NO_OFFSET)
            run_logspiral(gs, tmp, steps, report, summary)
        elif blank.a != 0.0:
            from .run_hypoid import run_hypoid

            run_hypoid(gs, tmp, steps, report, summary)
        else:
            from .run_facemilled import run_facemilled

            run_facemilled(gs, tmp, steps, report, summary)
        with steps.step("report.json, report.html"):
            summary.files += ["report.json", "report.html"]
            report["files"] = sorted(summary.files)
            report["failed_analyses"] = [{"analysis": a, "reason": r} for a, r in summary.partial.failed]
            write_report(tmp / "report.json", report)
            write_run_report_html(tmp, report, {"pinion": blank.z1, "gear": blank.z2}, blank.Sigma)
        summary.report = report
    return summary


def _logspiral_steps(spec) -> int:
    o = spec.output
    extra = 2 * int(spec.crowning is not None) + int(bool(o.draft and spec.manufacturing.forging_relief))
    return 4 + int(o.plots) + int(o.draft) + int(o.toolpaths) + int(o.stl) + int(o.step) + extra


def _facemilled_steps(spec) -> int:
    o = spec.output
    return 5 + int(spec.ltca is not None) + int(o.plots) + int(o.stl) + int(o.step)
