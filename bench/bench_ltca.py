"""Benchmark of loaded tooth contact analysis (LTCA).

1. FE tooth compliance of a 3-tooth log-spiral pinion segment (quadratic tetrahedra, one sparse factorization,
   many right-hand sides): first build, then the cached read.
2. One loaded mesh cycle (21 positions, 3 pairs) on that compliance, against a baseline measured in the same run:
   the same cycle solved with the primal active-set method alone (no warm-started semismooth iteration).

Run: OPENBLAS_NUM_THREADS=1 python bench/bench_ltca.py   (BLAS threads oversubscribe small dense solves).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "meshing" / "ltca"))

from conftest import logspiral_pair  # noqa: E402
from test_driver import AXIS, synthetic_positions  # noqa: E402

from spiralbevel import Member, Side  # noqa: E402
from spiralbevel._core import ltca as _k  # noqa: E402
from spiralbevel.meshing.ltca import ltca as driver  # noqa: E402
from spiralbevel.meshing.ltca.compliance import tooth_compliance  # noqa: E402
from spiralbevel.meshing.ltca.mesher import mesh_tooth_segment  # noqa: E402


def main():
    pair = logspiral_pair()
    cv = pair.flank(Member.PINION, Side.CONVEX).grid(15, 8).point
    cc = pair.flank(Member.PINION, Side.CONCAVE).grid(15, 8).point
    mesh = mesh_tooth_segment(cv, cc, 23, n_teeth=3, thickness_divisions=3, space_divisions=2, rim_layers=3)
    with tempfile.TemporaryDirectory() as cache:
        t0 = time.perf_counter()
        tc = tooth_compliance(mesh, "concave", cache_dir=cache)
        t1 = time.perf_counter()
        tooth_compliance(mesh, "concave", cache_dir=cache)
        t2 = time.perf_counter()
    print(f"FE compliance: {len(mesh.tets)} tets (P2), {tc.G.shape[0]} load nodes: build {t1 - t0:.2f} s "
          f"(target <= 120 s), cached read {t2 - t1:.3f} s")
    pos = synthetic_positions(tc, 21)
    kw = dict(gear_axis=AXIS, grid=(21, 7), half_length=6.0, half_width=0.6, approach_target=None)
    driver.run_ltca(pos, 2e4, tc, tc, **kw)  # warm-up (imports)
    t0 = time.perf_counter()
    res = driver.run_ltca(pos, 2e4, tc, tc, **kw)
    t1 = time.perf_counter()
    # baseline: identical cycle, primal active set from a cold start at every position
    orig = _k.pdas
    _k.pdas = lambda C, w, h, T, active, **_: (np.zeros(len(w)), None, None, active, 0, False)
    try:
        t2 = time.perf_counter()
        base = driver.run_ltca(pos, 2e4, tc, tc, **kw)
        t3 = time.perf_counter()
    finally:
        _k.pdas = orig
    assert np.allclose(res.te_loaded, base.te_loaded, atol=1e-9)
    n = sum(len(f) for f in res.force) / len(res.force)
    print(f"loaded mesh cycle: 21 positions x 3 pairs (~{n:.0f} potential points per position): {t1 - t0:.3f} s "
          f"(target <= 1 s); primal-active-set baseline {t3 - t2:.3f} s; ratio {(t3 - t2) / (t1 - t0):.1f}x")
    print(f"  loaded TE {res.te_loaded.min():.2f} .. {res.te_loaded.max():.2f} arcsec "
          f"(unloaded {res.te_unloaded.min():.2f} .. {res.te_unloaded.max():.2f}), peak pressure "
          f"{res.peak_pressure:.0f} N/mm^2")
    t0 = time.perf_counter()
    res = driver.run_ltca(pos, 2e4, tc, tc, **{**kw, "approach_target": 0.00635})
    print(f"  torque for 0.00635 mm approach at the mean point: {res.approach_torque:.0f} N mm "
          f"(cycle + root find {time.perf_counter() - t0:.2f} s)")


if __name__ == "__main__":
    main()
