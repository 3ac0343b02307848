"""Benchmark: local synthesis of the seed 001 pinion (Tables 1, 2, 4) — the whole ``synthesize_pinion`` call, and its
settings fit (7 x 7 Newton, forward-difference Jacobian, ``_core.newton.solve_batched``) against
``scipy.optimize.fsolve`` on the same residual from the same start (forward differences on both sides: the settings
have no analytic Jacobian). Both timed the same way: median of N runs (bench/_timing.py), CPU time of this process
(``time.process_time``: single-threaded work on a machine shared by several engineers; its load is printed).
Run: ``python bench/bench_synthesis.py [N]``. Target (issue 13): synthesis <= 5 ms on one core (not met: about 25 ms,
of which the settings fit is about 70 %: 41 residual calls of about 0.5 ms, each generating a flank and locating
the mean point in numpy; the multi-point control and ``active_range`` are in ``bench_cmc.py``).
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
from _timing import report, median_time
from scipy.optimize import fsolve

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import SpiralBevelError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import MachineSettings, seed001_blank, seed001_settings
from spiralbevel.meshing.synthesis import FREE_OFFSET, fit_settings, synthesize_pinion
from spiralbevel.meshing.synthesis._relations import tangent_components
from spiralbevel.meshing.synthesis.machine_fit import build, point_invariants

ARCSEC = math.pi / (180 * 3600)


N = int(sys.argv[1]) if len(sys.argv) > 1 else 7


def best_of(fun, repeat=None):
    """Median CPU time of ``repeat`` runs (default N) and the last output."""
    return median_time(fun, repeat or N, cpu=True)


def main():
    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    kw = dict(side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7, te_magnitude=3 * ARCSEC)
    print(f"machine load {os.getloadavg()[0]:.1f} at start (shared machine: CPU times of this process); "
          f"median of {N} runs each")
    t_all, r = best_of(lambda: synthesize_pinion(gc, gs, blank, **kw))
    print(f"synthesize_pinion (seed 001, eta = 6 deg, a = 3.7 mm, 3 arcsec): {t_all * 1e3:.1f} ms, "
          f"{r.iterations} Newton iterations, residual {r.residual:.1e}")

    K1 = r.relative_tensor - r.mean.gear_tensor
    target, nt = tangent_components(r.mean.point, r.mean.normal, K1)
    c0 = r.gear_flank.cutter.__class__(gc.nominal_radius + 0.5 * gc.point_width, gc.blade_angle, gc.point_width,
                                       gc.edge_radius, "outer")
    s0 = MachineSettings.from_blank(blank, Member.PINION, Side.CONCAVE, c0)
    t_fit, (c, s, u, _) = best_of(lambda: fit_settings(c0, s0, blank, Side.CONCAVE, target, nt, FREE_OFFSET))

    w = np.array([1.0, 1.0, blank.Rm, blank.Rm, blank.Rm**2, blank.Rm**2, blank.Rm**2])
    x0 = np.array([c0.point_radius, c0.blade_angle, s0.radial_setting, s0.cradle_angle, s0.ratio_of_roll,
                   s0.blank_offset, float(generate_flank(c0, s0, blank, Member.PINION, Side.CONCAVE)
                                          .locate(target[0], target[1], curvature=False).u)])

    def fun(x):
        try:
            cc, ss = build(c0, s0, FREE_OFFSET, x[:6])
            inv, _ = point_invariants(generate_flank(cc, ss, blank, Member.PINION, Side.CONCAVE), x[6])
        except SpiralBevelError:
            return np.full(7, 1e6)
        return (inv - target) * w

    t_base, xb = best_of(lambda: fsolve(fun, x0, xtol=1e-13))
    ok = np.abs(fun(xb)).max()
    ref = np.array([c.point_radius, c.blade_angle, s.radial_setting, s.cradle_angle, s.ratio_of_roll,
                    s.blank_offset, u])
    print(f"  fsolve: residual {ok:.1e}, max |x - x_newton| {np.abs(xb - ref).max():.1e}")
    report("settings fit (7 x 7, forward differences)", t_fit, t_base, "scipy fsolve", N)


if __name__ == "__main__":
    main()
