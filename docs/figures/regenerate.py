"""Regenerate the PNG figures of ``docs/figures`` (README.md, docs/rating.md) from the current code.

Each figure is made the way a user would make it, and copied here under its docs name:

* ``seed001_cmc.png``, ``seed001_te.png``, ``seed001_contact.png``, ``seed001_blank_offset.png``:
  ``python examples/seed001_cmc.py OUT --figures docs/figures`` (the seed 001 example end to end);
* ``tca_synthesized_drive.png``, ``easeoff_synthesized_drive.png``, ``ltca_synthesized_drive.png``:
  ``spiralbevel run aviation_23x65_synthesized -o OUT``, its ``tca_drive.png``, ``easeoff_drive.png``, ``ltca.png``;
* ``root_stress_synthesized.png``: the same design with the rating data quoted in docs/rating.md (T1 = 200 N m,
  n1 = 3000 1/min, grade 6, sigma_Hlim = 1500, sigma_Flim = 480 N/mm^2, oil 100 mm^2/s) and its loaded TCA at that
  torque (gear torque 200 * 65 / 23 N m), the job's ``root_stress.png``. Its FE root stress takes about a minute.

Run from the repository root: ``python docs/figures/regenerate.py [--only NAME ...] [--cache-dir DIR] [--keep DIR]``
(NAME: a file name above without ``.png``; ``--keep``: leave the runs' output directories, with their report.json,
in DIR). A failed step stops the script and leaves the figures of the steps before it written.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
CLI = [sys.executable, "-m", "spiralbevel"]

SEED001 = ("seed001_cmc", "seed001_te", "seed001_contact", "seed001_blank_offset")
#: docs name: name in the job's output directory (aviation_23x65_synthesized)
SYNTHESIZED = {"tca_synthesized_drive": "tca_drive", "easeoff_synthesized_drive": "easeoff_drive",
               "ltca_synthesized_drive": "ltca"}
ROOT_STRESS = "root_stress_synthesized"

#: the rating data of docs/rating.md's measured root stresses (tests/rating/test_examples_rate.py, COMMON)
RATING = """
[rating]
pinion_torque = 200.0
pinion_speed = 3000.0
accuracy_grade = 6
sigma_Hlim = 1500.0
sigma_Flim = 480.0
oil_viscosity = 100.0
"""


def _run(cmd, **kw):
    print("+", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, cwd=ROOT, **kw)


def _job(design, out: Path, cache_dir):
    extra = ["--cache-dir", cache_dir] if cache_dir else []
    # exit code 3: completed with warnings (a failed secondary analysis); the figures asked for are still checked below
    r = subprocess.run([*CLI, "run", design, "-q", "-o", out, *extra], cwd=ROOT)
    if r.returncode not in (0, 3):
        raise SystemExit(f"spiralbevel run {design} failed (exit {r.returncode})")


def _copy(src: Path, name: str):
    if not src.is_file():
        raise SystemExit(f"{src} was not written")
    shutil.copyfile(src, HERE / f"{name}.png")
    print(f"  {name}.png <- {src.name}")


def root_stress_design(tmp: Path) -> Path:
    """aviation_23x65_synthesized with the rating data and the LTCA at T1 = 200 N m (gear torque)."""
    from spiralbevel.io.design_file import bundled_designs

    text = bundled_designs()["aviation_23x65_synthesized"].read_text(encoding="utf-8")
    old = 'torque = "approach"'
    if text.count(old) != 1:
        raise SystemExit(f"aviation_23x65_synthesized.toml: expected one line {old!r} in [ltca]")
    text = text.replace(old, f"torque = {200.0 * 65 / 23!r}") + RATING
    path = tmp / "synthesized_rated.toml"
    path.write_text(text, encoding="utf-8")
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", nargs="*", default=None, help="figure names (without .png); default: all")
    ap.add_argument("--cache-dir", default=None, help="spiralbevel cache (compiled kernels, FE compliance)")
    ap.add_argument("--keep", default=None, help="directory to keep the runs' outputs in (default: removed)")
    a = ap.parse_args(argv)
    known = (*SEED001, *SYNTHESIZED, ROOT_STRESS)
    want = set(a.only) if a.only else set(known)
    if want - set(known):
        raise SystemExit(f"unknown figure(s) {sorted(want - set(known))}; known: {', '.join(known)}")
    with tempfile.TemporaryDirectory() as scratch:
        tmp = Path(a.keep) if a.keep else Path(scratch)
        tmp.mkdir(parents=True, exist_ok=True)
        if want & set(SEED001):
            _run([sys.executable, "examples/seed001_cmc.py", tmp / "seed001", "--figures", tmp / "seed001"])
            for name in SEED001:
                if name in want:
                    _copy(tmp / "seed001" / f"{name}.png", name)
        if want & set(SYNTHESIZED):
            _job("aviation_23x65_synthesized", tmp / "synthesized", a.cache_dir)
            for name, src in SYNTHESIZED.items():
                if name in want:
                    _copy(tmp / "synthesized" / f"{src}.png", name)
        if ROOT_STRESS in want:
            _job(root_stress_design(tmp), tmp / "rated", a.cache_dir)
            _copy(tmp / "rated" / "root_stress.png", ROOT_STRESS)


if __name__ == "__main__":
    main()
