"""Command-line interface ``spiralbevel``: parses, calls public functions, prints. Computes nothing itself.

Bad input exits with code 2 and lists every problem (dotted field path, value, allowed range, unit), no traceback.

Exit codes (also in the README):

===  =====================================================================================================
0    success
1    a computation failed (solver did not converge, no contact in a primary analysis); nothing was written
2    bad input: design file, option, measured CSV, or an output path that is refused; nothing was written
3    completed with warnings: the output was written, but a secondary analysis failed (its report entry says why)
4    internal error (a bug: please report it); nothing was written
130  interrupted by SIGINT (Ctrl-C); 143: terminated by SIGTERM. A previous output is left as it was
===  =====================================================================================================
"""

from __future__ import annotations

import functools
import json
import signal
import sys
import threading
import warnings
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from .errors import (ConvergenceError, DesignError, MissingDependencyError, NoContactError, SpiralBevelError,
                     SpiralBevelWarning)

#: exit codes (module docstring, README "Exit codes")
EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_WARNINGS, EXIT_INTERNAL = 0, 1, 2, 3, 4
EXIT_SIGINT, EXIT_SIGTERM = 128 + int(signal.SIGINT), 128 + int(getattr(signal, "SIGTERM", 15))


class _Terminated(KeyboardInterrupt):
    """SIGTERM, raised like Ctrl-C so that every ``finally`` and the output swap's clean-up run."""

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="spiralbevel: design, manufacture and contact analysis of spiral bevel gears.",
)


#: console width when the stream is not a terminal: wide enough that no line or table wraps (a pipe or a log file gets
#: one line per message)
PLAIN_WIDTH = 10_000


def _make_console(stderr: bool = False) -> Console:
    """A rich console that never turns user text into emoji; plain and unwrapped when its stream is not a terminal
    (no colour codes, no wrapping mid-sentence)."""
    stream = sys.stderr if stderr else sys.stdout
    tty = bool(getattr(stream, "isatty", lambda: False)())
    if tty:
        return Console(stderr=stderr, emoji=False, highlight=False, soft_wrap=stderr)
    return Console(stderr=stderr, emoji=False, highlight=False, soft_wrap=True, width=PLAIN_WIDTH,
                   color_system=None, force_terminal=False)


console = _make_console()
err_console = _make_console(stderr=True)


def _reset_consoles() -> None:
    """Re-create both consoles for the streams of this invocation (a test runner swaps ``sys.stdout``)."""
    global console, err_console
    console, err_console = _make_console(), _make_console(stderr=True)


def _version_callback(value: bool):
    if value:
        from . import __version__

        sys.stdout.write(f"spiralbevel {__version__}\n")
        raise typer.Exit()


#: thresholds of CPython's cyclic garbage collector in the command's process (default (700, 10, 10)). numba's type
#: system and matplotlib leave hundreds of thousands of long-lived objects that the collector traverses again in every
#: older-generation collection, while the figures and the kernels' compilation allocate millions of short-lived ones:
#: at the default, collecting took 0.5-0.6 s of the 3.4-4 s CPU of the default `spiralbevel run` (5 full collections)
#: and 3.4 s of 35 s of a cold CMC run (18). With 10,000 allocations per young collection and 50 of those per middle
#: one, the default run spends under 0.1 s collecting and makes no full collection (measured with ``gc.callbacks``).
#: Set for every command; the library leaves the interpreter's settings alone.
GC_THRESHOLDS = (10_000, 50, 10)


def _freeze_at_exit() -> None:
    """Register, once per process, a last exit handler that moves every live object to the collector's permanent
    generation (``gc.freeze``).

    When the interpreter shuts down it clears every module and then collects the cycles this leaves: a full pass over
    the hundreds of thousands of objects that numba, matplotlib and scipy keep, which frees them one by one only for
    the process to end. That took 0.5-0.7 s CPU of the default ``spiralbevel run`` (3.3-4 s in all), after its last
    output was written. Frozen objects are not collected, so the process ends without that pass; everything else of
    the shutdown runs as before (the other exit handlers, which ran before this one, closing the streams). The
    command's outputs are complete before: files are closed by ``with`` blocks and directories swapped in by
    ``io.atomic``, never left to a finaliser.
    """
    import atexit
    import gc

    global _FROZEN_AT_EXIT
    if not _FROZEN_AT_EXIT:
        _FROZEN_AT_EXIT = True
        atexit.register(gc.freeze)  # registered first: runs after every later-registered handler


_FROZEN_AT_EXIT = False


@app.callback()
def _main(version: bool = typer.Option(False, "--version", callback=_version_callback, is_eager=True,
                                       help="Print the version and exit.")):
    """spiralbevel: design, manufacture and contact analysis of spiral bevel gears."""
    import gc

    gc.set_threshold(*GC_THRESHOLDS)
    _freeze_at_exit()


DesignArg = typer.Argument(None, help="Design file (TOML), or the name of a bundled example (see "
                                       "'spiralbevel examples'). Default: the bundled aviation 23/65 log-spiral set.")


def _load(design):
    """A design file path, or the bare name of a bundled example (``aviation_23x65_cmc``, with or without
    ``.toml``, no directory part) when no such file exists. A path with a directory that does not exist is an error."""
    from .io.design_file import bundled_designs, load_design

    if design is not None and not Path(design).exists() and len(Path(design).parts) == 1:
        names = bundled_designs()
        stem = str(design).removesuffix(".toml")
        if stem in names:
            return load_design(names[stem])
    return load_design(design)


def _design_text(design) -> str:
    """The TOML text ``_load`` read (empty when it cannot be read: its error was reported already)."""
    from .io.design_file import bundled_designs, default_design_text

    if design is None:
        return default_design_text()
    p = Path(design)
    if not p.exists() and len(p.parts) == 1 and str(design).removesuffix(".toml") in bundled_designs():
        p = bundled_designs()[str(design).removesuffix(".toml")]
    try:
        return p.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeError):
        return ""


def _guard(fn):
    """Turn spiralbevel errors into a clean message and exit code 2 (input) or 1 (computation); print each design
    warning once, after the command."""

    def error(text):
        err_console.print("[bold red]error:[/] ", end="")
        err_console.print(text, markup=False, highlight=False)

    def on_sigterm(signum, frame):
        raise _Terminated()

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        _reset_consoles()
        main = threading.current_thread() is threading.main_thread() and hasattr(signal, "SIGTERM")
        previous = signal.signal(signal.SIGTERM, on_sigterm) if main else None
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", SpiralBevelWarning)
            try:
                return fn(*args, **kwargs)
            except typer.Exit:
                raise
            except _Terminated:
                error("terminated (SIGTERM); nothing was written and any previous output is as it was")
                raise typer.Exit(code=EXIT_SIGTERM) from None
            except KeyboardInterrupt:
                error("interrupted; nothing was written and any previous output is as it was")
                raise typer.Exit(code=EXIT_SIGINT) from None
            except DesignError as err:
                error(f"{len(err.problems)} problem(s) in the input")
                for p in err.problems:
                    err_console.print(f"  - {p}", markup=False, highlight=False)
                raise typer.Exit(code=2) from None
            except MissingDependencyError as err:
                error(str(err))
                raise typer.Exit(code=2) from None
            except (ConvergenceError, NoContactError, SpiralBevelError) as err:
                error(str(err))
                raise typer.Exit(code=1) from None
            except OSError as err:
                error(f"{err.filename}: {err.strerror or err}" if getattr(err, "filename", None) else str(err))
                raise typer.Exit(code=2) from None
            except Exception as err:  # noqa: BLE001 - the last line of defence: a message, never a traceback
                error(f"internal error ({type(err).__name__}: {str(err)[:300]}); this is a bug, please report it "
                      "with the design file")
                raise typer.Exit(code=EXIT_INTERNAL) from None
            finally:
                if main and previous is not None:
                    signal.signal(signal.SIGTERM, previous)
                seen = set()
                for w in caught:
                    text = str(w.message)
                    if issubclass(w.category, SpiralBevelWarning) and text not in seen:
                        seen.add(text)
                        err_console.print("[yellow]warning:[/] ", end="")
                        err_console.print(text, markup=False, highlight=False)

    return wrapper


@app.command()
@_guard
def run(
    design: Optional[Path] = DesignArg,
    out: Path = typer.Option(Path("out"), "-o", "--out", help="Output directory (written whole or not at all)."),
    quiet: bool = typer.Option(False, "-q", "--quiet", help="No progress bar."),
    cache_dir: Optional[Path] = typer.Option(None, "--cache-dir", help="Directory of the FE compliance cache of the "
                                             "loaded TCA (default $SPIRALBEVEL_CACHE, else ~/.cache/spiralbevel)."),
):
    """Compute everything the design asks for and write report.json, plots, STL, STEP and tool paths.

    OUT must be new, empty, or a previous spiralbevel output (it holds the manifest .spiralbevel-output.json) with no
    files added to it; any other directory is refused (exit 2). OUT is replaced whole, or not at all."""
    _use_cache_dir(cache_dir)
    spec = _load(design)
    from .job import run_design

    summary = run_design(spec, out, progress=not quiet)
    console.print(f"[green]wrote[/] {escape(str(out))}/ ({len(summary.files)} files)")
    for line in summary.highlights:
        console.print(f"  {line}", markup=False, highlight=False)
    if summary.partial.failed:
        err_console.print(f"[yellow]completed with warnings:[/] {len(summary.partial.failed)} analysis/analyses "
                          "failed (see 'failed_analyses' in report.json)")
        raise typer.Exit(code=EXIT_WARNINGS)


@app.command()
@_guard
def blank(
    design: Optional[Path] = DesignArg,
    as_json: bool = typer.Option(False, "--json", help="Print the dimension sheet as JSON (ISO symbols, degrees)."),
    output: Optional[Path] = typer.Option(None, "--output", help="Write the JSON to this file instead of stdout."),
):
    """Print the ISO 23509 dimension sheet of pinion and gear."""
    from .io.dimension_sheet import dimension_sheet_json, dimension_sheet_rows
    from .gearset.blank import blank_from_design

    if output is not None:
        from .io.atomic import check_output_file

        check_output_file(output)
    spec = _load(design)
    result = blank_from_design(spec)
    if as_json or output is not None:
        text = json.dumps(dimension_sheet_json(result), indent=2)
        if output is not None:
            from .io.atomic import atomic_write_text

            atomic_write_text(output, text + "\n")
            console.print(f"[green]wrote[/] {escape(str(output))}")
        else:
            sys.stdout.write(text + "\n")
        return
    table = Table(title=f"Dimension sheet (ISO 23509): {escape(spec.title)}")
    for col in ("symbol", "quantity", "unit", "pinion", "gear"):
        table.add_column(col, justify="right" if col in ("pinion", "gear") else "left")
    for sym, desc, unit, v1, v2 in dimension_sheet_rows(result):
        table.add_row(*(escape(t) for t in (sym, desc, unit, _fmt(v1), _fmt(v2))))
    console.print(table)


@app.command()
@_guard
def rate(
    design: Optional[Path] = DesignArg,
    as_json: bool = typer.Option(False, "--json", help="Print the rating as JSON keyed by ISO symbol (degrees)."),
    output: Optional[Path] = typer.Option(None, "--output", help="Write the JSON to this file instead of stdout."),
):
    r"""Print the ISO 10300 (Method B1) load capacity rating sheet of a design with a \[rating] section."""
    from .gearset.rating import rating_from_design

    spec = _load(design)
    res = rating_from_design(spec)
    if as_json or output is not None:
        text = json.dumps({"standard": "ISO 10300:2014 Method B1", **res.to_dict()}, indent=2)
        if output is not None:
            from .io.atomic import atomic_write_text

            atomic_write_text(output, text + "\n")
            console.print(f"[green]wrote[/] {escape(str(output))}")
        else:
            sys.stdout.write(text + "\n")
        return
    titles = {"load": "Load", "virtual": "Virtual cylindrical gears (ISO 10300-1 Annex A)",
              "factors": "Load factors (ISO 10300-1)", "pitting": "Pitting (ISO 10300-2, Method B1)",
              "root": "Tooth root (ISO 10300-3, Method B1)"}
    tables: dict[str, Table] = {}
    for section, sym, desc, unit, value in res.rows():
        if section not in tables:
            title = f"{titles[section]}: {escape(spec.title)}" if not tables else titles[section]
            t = tables[section] = Table(title=title)
            for col in ("symbol", "quantity", "unit", "value"):
                t.add_column(col, justify="right" if col == "value" else "left")
        tables[section].add_row(sym, desc, unit, f"{value:.4f}")
    for t in tables.values():
        console.print(t)
    console.print(f"S_H = {res['S_H']:.3f}   S_F1 = {res['S_F1']:.3f}   S_F2 = {res['S_F2']:.3f}",
                  markup=False, highlight=False)
    for note in res.notes:
        console.print(f"note: {note}", markup=False, highlight=False)


#: the design ``spiralbevel machine`` summarizes when none is named (the bundled default is a log-spiral set, which has
#: no machine settings)
MACHINE_DEFAULT = "aviation_23x65_facemilled"


@app.command()
@_guard
def machine(design: Optional[Path] = typer.Argument(
        None, help=f"Face-milled design file, or a bundled example's name. Default: the bundled {MACHINE_DEFAULT}.")):
    """Print the machine summary sheet (cutter and cradle settings per member and side) of a face-milled design."""
    from .gearset.gearset import GearSet

    spec = _load(MACHINE_DEFAULT if design is None else design)
    if spec.flank.kind != "face-milled":
        raise DesignError.single("flank.kind", spec.flank.kind, "'face-milled' for a machine summary", "-")
    # the flanks of `spiralbevel run` (a hypoid: basic settings at each member's mean cone distance, the pinion by
    # hypoid local synthesis)
    for (m, s), st in GearSet(spec).setups.items():
        table = Table(title=f"{m.value} {s.value} ({st.source})")
        table.add_column("setting")
        table.add_column("value", justify="right")
        table.add_column("unit")
        for label, value, unit in st.settings.summary_rows(st.cutter):
            table.add_row(label, value, unit)
        console.print(table)


@app.command()
@_guard
def correct(
    design: Path = typer.Argument(..., help="Face-milled design file (or bundled example name) the part was cut to; "
                                  "spiral bevel or hypoid."),
    measured: Path = typer.Option(..., "--measured", help="CSV of the 9 x 5 grid with a deviation_mm column "
                                  "(positive = material added), as written by the main job and filled in by the CMM."),
    member: str = typer.Option(..., "--member", help="pinion or gear"),
    side: str = typer.Option(..., "--side", help="convex or concave"),
    parameters: Optional[str] = typer.Option(None, "--parameters",
                                             help="Comma-separated settings to correct, from: radial_setting, "
                                                  "cradle_angle, machine_root_angle, sliding_base, "
                                                  "machine_centre_to_back, blank_offset, ratio_of_roll, "
                                                  "modified_roll_2C, modified_roll_6D, blade_angle, point_radius "
                                                  "(default: radial_setting, cradle_angle, machine_root_angle, "
                                                  "ratio_of_roll, modified_roll_2C, modified_roll_6D)."),
    regularization: float = typer.Option(0.0, "--regularization", help="Tikhonov parameter (relative), >= 0."),
    write: Optional[Path] = typer.Option(None, "--write", help="Write a corrected design file here (every flank's "
                                         "cutter and settings explicit). A new file: an existing file is replaced "
                                         "only if 'correct --write' wrote it."),
):
    """Corrective machine settings from measured flank deviations (least squares on the settings' sensitivities)."""
    from .job.correction import (check_write_target, correct_from_measurement, corrected_design_text,
                                 correction_rows, verify_corrected_design)

    if write is not None:
        check_write_target(write, design if design is not None and Path(design).exists() else None)
    spec = _load(design)
    params = [p.strip() for p in parameters.split(",")] if parameters else None
    st, res, setups = correct_from_measurement(spec, member, side, measured, params, regularization,
                                               with_setups=True)
    table = Table(title=f"Corrected settings, {member} {side}: rms {1000 * res.rms_before:.2f} -> "
                        f"{1000 * res.rms_after:.2f} um (condition number {res.condition_number_used:.3g})")
    for col in ("setting", "nominal", "corrected", "change", "unit"):
        table.add_column(col, justify="left" if col in ("setting", "unit") else "right")
    for name, a, b, d, unit in correction_rows(st, res):
        table.add_row(name, f"{a:.6f}", f"{b:.6f}", f"{d:+.6f}", unit)
    console.print(table)
    if res.not_identifiable:
        console.print(f"[yellow]not identifiable from this measurement (left unchanged):[/] "
                      f"{escape(', '.join(res.not_identifiable))}")
    if write is not None:
        from .io.atomic import atomic_write_text

        text = corrected_design_text(_design_text(design), setups, member, side, res, source=str(design))
        verify_corrected_design(text, setups, member, side, res)
        atomic_write_text(write, text)
        console.print(f"[green]wrote[/] {escape(str(write))}")


@app.command()
@_guard
def sweep(
    design: Path = typer.Argument(..., help="Face-milled design file (spiral bevel, or hypoid: misalignments on top of "
                                  "the offset), or a log-spiral one with [crowning] (the side of its crowned pinion "
                                  "flank), or a bundled example name."),
    pinion_axial: Optional[str] = typer.Option(None, help="Delta A1 values, mm: 'v1,v2,...' or 'start:stop:count'."),
    gear_axial: Optional[str] = typer.Option(None, help="Delta A2 values, mm."),
    offset: Optional[str] = typer.Option(None, help="Delta E values, mm."),
    shaft_angle: Optional[str] = typer.Option(None, help="Delta gamma values, deg."),
    side: Optional[str] = typer.Option(None, help="drive or coast (default: drive; for a log-spiral design the side "
                                       "of its crowned pinion flank)"),
    scheduler: Optional[str] = typer.Option(None, help="'sequential', or a dask scheduler address "
                                            "(tcp://host:port); default: dask's local processes if installed."),
    output: Optional[Path] = typer.Option(None, "--output", help="Write the records as JSON to this file."),
):
    """TCA over a grid of misalignments (TE level and contact shift), in parallel with dask (extra 'dist')."""
    from .job.sweep import check_scheduler, misalignment_sweep, parse_values

    texts = {"pinion_axial": pinion_axial, "gear_axial": gear_axial, "offset": offset, "shaft_angle": shaft_angle}
    grid = {k: parse_values(k, v) for k, v in texts.items() if v is not None}
    if side not in (None, "drive", "coast"):
        raise DesignError.single("--side", side, "'drive' or 'coast'", "-")
    check_scheduler(scheduler)
    if output is not None:
        from .io.atomic import check_output_file

        check_output_file(output)
    spec = _load(design)
    if side is None:
        from .job.sweep import default_side

        side = default_side(spec)
    records = misalignment_sweep(spec, grid, side=side, scheduler=scheduler)
    table = Table(title=f"Misalignment sweep, {side} side ({len(records)} TCA runs)")
    for col in ("dA1 mm", "dA2 mm", "dE mm", "dgamma deg", "TE p-p arcsec", "contact R mm", "contact h mm", "edge"):
        table.add_column(col, justify="right")
    for r in records:
        if "error" in r:
            table.add_row(*(f"{r[k]:g}" for k in ("pinion_axial", "gear_axial", "offset", "shaft_angle")),
                          "no contact", "", "", "")
            continue
        table.add_row(*(f"{r[k]:g}" for k in ("pinion_axial", "gear_axial", "offset", "shaft_angle")),
                      f"{r['peak_to_peak_arcsec']:.3f}", f"{r['mean_contact_R_mm']:.3f}",
                      f"{r['mean_contact_h_mm']:.3f}", str(r["edge_contact_positions"]))
    console.print(table)
    if output is not None:
        from .io.atomic import atomic_write_text
        from .io.report import dumps_report

        atomic_write_text(output, dumps_report({"side": side, "units": {"pinion_axial": "mm", "gear_axial": "mm",
                                                "offset": "mm", "shaft_angle": "deg", "te": "arcsec"},
                                                "records": records}))
        console.print(f"[green]wrote[/] {escape(str(output))}")


@app.command()
@_guard
def check(design: Optional[Path] = DesignArg):
    """Validate a design file: its schema, the ISO blank, and the flanks it defines (without the analyses)."""
    from .job.check import check_design, schema_and_design_problems

    try:
        spec = _load(design)
    except DesignError as err:
        raise schema_and_design_problems(err, _design_text(design)) from None
    check_design(spec)
    console.print(f"[green]ok[/] {escape(spec.title)}")


def _use_cache_dir(cache_dir: Optional[Path]) -> None:
    """``--cache-dir``: the FE cache of this process lives there (it sets ``$SPIRALBEVEL_CACHE``, which the cache reads
    on every use)."""
    if cache_dir is not None:
        import os

        if cache_dir.exists() and not cache_dir.is_dir():
            raise DesignError.single("--cache-dir", str(cache_dir), "a directory (or a path that does not exist yet)",
                                     "-")
        os.environ["SPIRALBEVEL_CACHE"] = str(cache_dir)


CacheDirOption = typer.Option(None, "--cache-dir", help="Cache directory (default $SPIRALBEVEL_CACHE, else "
                                                        "~/.cache/spiralbevel).")

cache_app = typer.Typer(no_args_is_help=True, help="The on-disk FE compliance cache of the loaded TCA "
                                                      "($SPIRALBEVEL_CACHE, default ~/.cache/spiralbevel).")
app.add_typer(cache_app, name="cache")


@cache_app.command("info")
@_guard
def cache_info_cmd(cache_dir: Optional[Path] = CacheDirOption):
    """Where the cache is, how many entries and bytes it holds, and its size cap ($SPIRALBEVEL_CACHE_MAX_MB)."""
    from .meshing.ltca.fe_cache import cache_info

    _use_cache_dir(cache_dir)
    info = cache_info()
    console.print(f"cache: {info['path']}", markup=False, highlight=False)
    console.print(f"  {info['entries']} entries, {info['bytes'] / 2**20:.1f} MB (cap {info['max_bytes'] / 2**20:.0f} "
                  "MB; the least recently used entries are removed beyond it)", markup=False, highlight=False)


@cache_app.command("clear")
@_guard
def cache_clear_cmd(cache_dir: Optional[Path] = CacheDirOption):
    """Delete every cache entry (other files in the directory are left alone)."""
    from .meshing.ltca.fe_cache import cache_info, clear_cache

    _use_cache_dir(cache_dir)
    n = clear_cache()
    console.print(f"removed {n} entries from {cache_info()['path']}", markup=False, highlight=False)


@app.command()
def examples():
    """List the bundled example designs (run one with 'spiralbevel run NAME')."""
    _reset_consoles()
    from .io.design_file import bundled_designs, parse_design

    table = Table(title="Bundled example designs")
    table.add_column("name")
    table.add_column("flanks")
    table.add_column("title")
    for name, path in bundled_designs().items():
        spec = parse_design(path.read_text(encoding="utf-8"), source=str(path))
        table.add_row(escape(name), escape(spec.flank.kind), escape(spec.title))
    console.print(table)


def _fmt(v) -> str:
    if v is None or v == "":
        return ""
    if isinstance(v, float):
        return f"{v:.4f}"
    return str(v)


def main():  # pragma: no cover - console entry point
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
