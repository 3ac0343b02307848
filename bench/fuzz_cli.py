"""Fuzz campaign of the CLI: generated design files and arguments; counts tracebacks, hangs and stray writes.

Run:  python bench/fuzz_cli.py [--n 2000] [--seed 1] [--timeout 10]

Every input runs in this process through typer's CliRunner, inside a sandbox directory (the current directory,
``$HOME`` and ``$SPIRALBEVEL_CACHE`` point into it). Inputs are mutations of the four bundled designs (values replaced
by extreme, non-finite, malformed or hostile ones -- including long digit strings, DMS strings, deep nesting, unknown
keys, other encodings, truncation, random bytes) and random arguments of ``check``, ``blank``, ``machine``, ``run``,
``sweep``, ``correct`` and ``cache`` (output paths that are foreign directories, FIFOs, symbolic links, ``.``,
missing parents; sweep values and scheduler addresses).

Reported (and the exit status is 1 unless all are 0):

- tracebacks: an exception escaping the CLI, exit code 4 (internal error), or "Traceback" in the output;
- hangs: an input that used more than ``--timeout`` seconds of CPU time (stopped by SIGPROF; CPU time, not wall
  time, so that the figure does not depend on what else the shared machine runs), or more than ``--wall`` seconds
  of wall time (stopped by SIGALRM: a hang that sleeps or waits);
- exit codes outside the documented set {0, 1, 2, 3};
- touched: a file or directory of the sandbox outside the command's output (the OUT of ``run``, the ``--output``
  file) and the cache (``$SPIRALBEVEL_CACHE``, and matplotlib's font cache ``$MPLCONFIGDIR`` in it) that was created,
  changed or deleted (the sandbox holds decoy files: a user's project directory, a FIFO, a link and its target), and
  any new entry in the system temporary directory.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import json
import os
import random
import re
import signal
import stat
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")

HOSTILE = ["nan", "inf", "-inf", "1e300", "-1e300", "0", "-1", "1e-300", '"' + "1" * 1500 + 'x"', '"22.5.5"',
           '"20.5 30"', '"59°20\'07\\""', '"°"', '""', "true", "[1, 2]", "{a = 1}", '"' + "9" * 70 + '"',
           '"-0"', "3.5", "400", "90", "89.999", "1e6", '"59 20 7 1"', '"1_0"', '"٣"', '"22d30m15s"']
OUT_KINDS = ("new", "previous", "foreign", "empty", "dot", "file", "missing_parent", "symlink")


class Hang(BaseException):
    """Raised by SIGPROF or SIGALRM: not an Exception, so no handler of the CLI catches it."""


def _on_alarm(signum, frame):
    raise Hang("cpu" if signum == signal.SIGPROF else "wall")


def mutate_design(rng: random.Random, texts: list) -> bytes:
    """One generated design file (bytes)."""
    text = rng.choice(texts)
    lines = text.splitlines()
    for _ in range(rng.choice((0, 0, 1, 1, 2, 3, 5))):
        if not lines:
            break
        i = rng.randrange(len(lines))
        ln = lines[i]
        op = rng.random()
        if "=" in ln and not ln.lstrip().startswith("#") and op < 0.55:
            key = ln.split("=", 1)[0]
            if rng.random() < 0.5:
                value = rng.choice(HOSTILE)
            else:
                value = repr(rng.choice([rng.uniform(-1e3, 1e3), rng.uniform(-10, 10), rng.randint(-5, 500)]))
            lines[i] = f"{key}= {value}"
        elif op < 0.65:
            del lines[i]
        elif op < 0.75:
            lines.insert(i, f"unknown_{rng.randrange(1000)} = {rng.randrange(10)}")
        elif op < 0.8:
            lines.insert(i, lines[i])
        elif op < 0.85:
            lines.insert(i, f"[section_{rng.randrange(5)}]")
        elif op < 0.9 and "=" in ln:
            key = ln.split("=", 1)[0]
            depth = rng.choice((3, 20, 5000))
            lines[i] = f"{key}= " + "[" * depth + "1" + "]" * depth
        else:
            lines[i] = ln[: rng.randrange(len(ln) + 1)]
    data = "\n".join(lines) + "\n"
    r = rng.random()
    if r < 0.04:
        return data.encode("utf-16")
    if r < 0.08:
        return (data + "# Zahnräder\n").encode("latin-1", "replace")
    if r < 0.11:
        raw = bytearray(data.encode())
        for _ in range(rng.randrange(1, 20)):
            raw[rng.randrange(len(raw))] = rng.randrange(256)
        return bytes(raw)
    if r < 0.13:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
    if r < 0.15:
        return data.encode()[: rng.randrange(len(data))]
    return data.encode()


def _sweep_value(rng):
    r = rng.random()
    if r < 0.4:
        return ",".join(f"{rng.uniform(-0.08, 0.08):.3f}" for _ in range(rng.randint(1, 2)))
    if r < 0.6:
        return f"{rng.uniform(-0.05, 0):.3f}:{rng.uniform(0, 0.05):.3f}:{rng.choice([1, 2, 0, -1, 100000000])}"
    return rng.choice(["nan", "inf", "1e300", "90", "a,b", "", ":", "1:2", "1:2:3:4", "0:1:1e3", ",,", "-0", "5"])


def _scheduler(rng):
    return rng.choice(["sequential", "bogus", "tcp://", "tcp://localhost", "tcp://localhost:99999", "tcp://:80",
                       "http://127.0.0.1:8786", "tcp://127.0.0.1:0", "tcp://a b:1", "inproc://", "sequential"])


class Sandbox:
    """A directory tree with decoys; snapshots of everything outside the allowed paths."""

    def __init__(self, root: Path):
        self.root = root
        self.cwd = root / "cwd"
        self.cwd.mkdir()
        (self.cwd / "notes.txt").write_text("user notes")
        self.project = root / "project"
        self.project.mkdir()
        (self.project / "thesis.tex").write_text("years of work")
        self.victim = root / "victim.txt"
        self.victim.write_text("precious")
        (root / "link.json").symlink_to(self.victim)
        if hasattr(os, "mkfifo"):
            os.mkfifo(root / "fifo.json")
        (root / "home").mkdir()
        self.cache = root / "cache"
        self.allowed = [root / "out", root / "cache", root / "designs"]
        (root / "designs").mkdir()
        self.tmp = root / "tmp"                  # the temporary directory of the process (tempfile.tempdir)
        self.tmp.mkdir()

    def snapshot(self, outputs=()) -> dict:
        """{path: (mode, size, mtime)} of everything outside the cache, the inputs and ``outputs``."""
        allowed = self.allowed + [Path(o) for o in outputs]
        snap = {}
        for dirpath, dirnames, filenames in os.walk(self.root):
            p = Path(dirpath)
            if any(p == a or a in p.parents for a in allowed):
                dirnames[:] = []
                continue
            for name in dirnames + filenames:
                q = p / name
                if any(q == a or a in q.parents for a in allowed):
                    continue
                st = os.lstat(q)
                # a directory is compared by its entries (each listed here), not by its mtime, which changes when an
                # allowed output is created inside it
                snap[str(q)] = (st.st_mode,) if stat.S_ISDIR(st.st_mode) else (st.st_mode, st.st_size, st.st_mtime_ns)
        return snap


def strip_sections(text: bytes, names) -> bytes:
    """TOML text without the tables ``[name]`` and ``[name.*]`` of ``names`` (line by line)."""
    out, skip = [], False
    for line in text.split(b"\n"):
        head = re.match(rb"\s*\[\[?\s*([\w.-]+)", line)
        if head:
            skip = head[1].split(b".")[0] in names
        if not skip:
            out.append(line)
    return b"\n".join(out)


def outputs_of(argv, cwd: Path) -> list:
    """The paths a command may write: the OUT of ``run`` (``-o``/``--out``, default ``out``) and the ``--output``
    file of ``blank`` and ``sweep``, relative to ``cwd``."""
    outs = []
    if argv and argv[0] == "run":
        value = "out"
        for i, a in enumerate(argv[:-1]):
            if a in ("-o", "--out"):
                value = argv[i + 1]
        outs.append(value)
    for i, a in enumerate(argv[:-1]):
        if a == "--output":
            outs.append(argv[i + 1])
    return [Path(os.path.abspath(cwd / o)) for o in outs]


def make_case(rng: random.Random, texts: list, box: Sandbox, k: int):
    """(argv, description) of one generated input."""
    design = box.root / "designs" / f"d{k % 50}.toml"
    design.write_bytes(mutate_design(rng, texts))
    design_arg = str(design) if rng.random() < 0.9 else rng.choice(
        ["aviation_23x65_logspiral", "/nonexistent/aviation_23x65_logspiral.toml", "aviation_23x65_cmc.toml", "."])
    out = box.root / "out"
    kind = rng.choice(OUT_KINDS)
    if kind == "previous":
        out_arg = str(out)
    elif kind == "foreign":
        out_arg = str(box.project)
    elif kind == "empty":
        out_arg = str(out / "empty")
    elif kind == "dot":
        out_arg = "."
    elif kind == "file":
        out_arg = str(box.victim)
    elif kind == "missing_parent":
        out_arg = str(out / "no" / "such" / "dir")
    elif kind == "symlink":
        out_arg = str(box.root / "link.json")
    else:
        out_arg = str(out / f"o{k % 7}")
    single = rng.choice([str(out / "b.json"), str(box.root / "fifo.json"), str(box.root / "link.json"),
                         str(box.root / "cwd"), str(out / "none" / "b.json")])
    cmd = rng.choices(["check", "blank", "machine", "run", "sweep", "correct", "cache", "args"],
                      weights=[45, 12, 6, 6, 12, 4, 2, 3])[0]
    if cmd == "check":
        return ["check", design_arg]
    if cmd == "blank":
        return ["blank", design_arg] + (["--json"] if rng.random() < 0.5 else []) + (
            ["--output", single] if rng.random() < 0.6 else [])
    if cmd == "machine":
        return ["machine", design_arg]
    if cmd == "run":
        # outputs, the loaded TCA (a FE solve of about 40 s) and the crowning of the forged example (about 14 s of
        # crowning design and misalignment TCA) off, and a small grid, keep a valid run to a few seconds: the output
        # path is the point here, not the length of legitimate analyses
        text = strip_sections(design.read_bytes(), (b"ltca", b"crowning"))
        for key in (b"plots", b"stl", b"step", b"toolpaths", b"draft"):
            text = text.replace(key + b" = true", key + b" = false")
        design.write_bytes(text.replace(b"grid = [31, 15]", b"grid = [5, 3]"))
        if not design_arg.startswith("/nonexistent"):
            design_arg = str(design)         # a bundled name would run every output and the FE solve
        return ["run", design_arg, "-q", "-o", out_arg]
    if cmd == "sweep":
        args = ["sweep", rng.choice([design_arg, "aviation_23x65_synthesized"])]
        for opt in ("--pinion-axial", "--gear-axial", "--offset", "--shaft-angle"):
            if rng.random() < 0.3:
                args += [opt, _sweep_value(rng)]
        args += ["--scheduler", _scheduler(rng)]
        if rng.random() < 0.2:
            args += ["--side", rng.choice(["drive", "coast", "x"])]
        if rng.random() < 0.3:
            args += ["--output", single]
        return args
    if cmd == "correct":
        csv = box.root / "designs" / "m.csv"
        csv.write_bytes(mutate_design(rng, ["label,deviation_mm\nF1P1,0.001\nF9P5,x\n",
                                            "label,row,column,x_mm,y_mm,z_mm,nx,ny,nz,deviation_mm\n"
                                            "F1P1,1,1,0,0,0,0,0,1,0.01\n"]))
        return ["correct", design_arg, "--measured", str(csv), "--member", rng.choice(["gear", "pinion", "x"]),
                "--side", rng.choice(["convex", "concave", "y"])]
    if cmd == "cache":
        return ["cache", rng.choice(["info", "clear", "bogus"])]
    return [rng.choice(["run", "check", "sweep", "blank"]), *(rng.choice(["--bogus", "-o", "", "--", "-q", "x"])
                                                               for _ in range(rng.randint(0, 3)))]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=10.0, help="CPU seconds per input that count as a hang")
    ap.add_argument("--wall", type=float, default=60.0, help="wall seconds per input that count as a hang")
    ap.add_argument("--keep", action="store_true", help="keep the sandbox")
    args = ap.parse_args(argv)

    from typer.testing import CliRunner

    from spiralbevel.cli import app
    from spiralbevel.io.design_file import bundled_designs

    texts = [p.read_text(encoding="utf-8") for p in bundled_designs().values()]
    rng = random.Random(args.seed)
    root = Path(tempfile.mkdtemp(prefix="spiralbevel-fuzz-"))
    box = Sandbox(root)
    os.environ["HOME"] = str(root / "home")
    os.environ["SPIRALBEVEL_CACHE"] = str(box.cache)
    # matplotlib's own font cache (written once, by the first plot) counts with the cache
    os.environ["MPLCONFIGDIR"] = str(box.cache / "matplotlib")
    os.chdir(box.cwd)
    tmpdir = Path(tempfile.gettempdir())
    tempfile.tempdir = str(box.tmp)
    runner = CliRunner()
    codes = collections.Counter()
    tracebacks, hangs, touched, bad_codes = [], [], [], []
    slowest = (0.0, None)
    signal.signal(signal.SIGALRM, _on_alarm)
    signal.signal(signal.SIGPROF, _on_alarm)
    slowest_cpu = 0.0
    t_start = time.perf_counter()
    for k in range(args.n):
        argv_k = make_case(rng, texts, box, k)
        outputs = outputs_of(argv_k, box.cwd)
        before = box.snapshot(outputs)
        t0, c0 = time.perf_counter(), time.process_time()
        signal.setitimer(signal.ITIMER_PROF, args.timeout)
        signal.setitimer(signal.ITIMER_REAL, args.wall)
        try:
            res = runner.invoke(app, argv_k, catch_exceptions=True)
            code, output, exc = res.exit_code, res.output, res.exception
        except Hang as h:
            hangs.append({"argv": argv_k, "kind": str(h)})
            print(f"hang ({h}): {argv_k}", flush=True)
            code, output, exc = None, "", None
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
            signal.setitimer(signal.ITIMER_REAL, 0)
        if code in (130, 143):
            # the CLI turned a SIGINT or SIGTERM sent to this driver into an exit code: stop the campaign
            print(f"interrupted (exit {code}) after {k} inputs", flush=True)
            return 2
        dt = time.perf_counter() - t0
        slowest_cpu = max(slowest_cpu, time.process_time() - c0)
        slowest = max(slowest, (dt, argv_k[:2]), key=lambda t: t[0])
        codes[code] += 1
        if code == 4 or "Traceback" in output or (exc is not None and not isinstance(exc, SystemExit)):
            tracebacks.append({"argv": argv_k, "exc": repr(exc), "output": output[-500:]})
        elif code is not None and code not in (0, 1, 2, 3):
            bad_codes.append({"argv": argv_k, "code": code})
        after = box.snapshot(outputs)
        changed = sorted(set(before) ^ set(after) | {p for p in before if p in after and before[p] != after[p]})
        if changed:
            touched.append({"argv": argv_k, "paths": changed[:5]})
        if (k + 1) % 200 == 0:
            print(f"{k + 1} inputs, {time.perf_counter() - t_start:.0f} s, exit codes {dict(codes)}", flush=True)
    new_tmp = sorted(p.name for p in box.tmp.iterdir())
    decoys_ok = (box.victim.read_text() == "precious" and (box.project / "thesis.tex").read_text() == "years of work"
                 and sorted(p.name for p in box.project.iterdir()) == ["thesis.tex"])
    summary = {
        "inputs": args.n, "seed": args.seed, "seconds": round(time.perf_counter() - t_start, 1),
        "exit_codes": {str(c): n for c, n in sorted(codes.items(), key=lambda t: str(t[0]))},
        "tracebacks": len(tracebacks), "hangs": len(hangs), "undocumented_exit_codes": len(bad_codes),
        "touched_outside_out_and_cache": len(touched), "left_in_temporary_directory": new_tmp,
        "decoys_intact": decoys_ok, "slowest_wall_s": round(slowest[0], 2), "slowest_command": slowest[1],
        "slowest_cpu_s": round(slowest_cpu, 2),
    }
    print(json.dumps(summary, indent=1))
    for name, items in (("traceback", tracebacks), ("hang", hangs), ("touched", touched), ("exit code", bad_codes)):
        for item in items[:10]:
            print(f"{name}: {item}")
    if not args.keep:
        import shutil

        os.chdir(tmpdir)
        with contextlib.suppress(OSError):
            shutil.rmtree(root)
    ok = not (tracebacks or hangs or touched or bad_codes or new_tmp) and decoys_ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
