"""Benchmark: local synthesis of the seed 001 pinion (Tables 1, 2, 4) — the whole ``synthesize_pinion`` call, and its
settings fit (7 x 7: six machine quantities and the point's cutter angle; compiled residual from the first-order jet
of the generated flank, compiled Newton with a central-difference Jacobian, ``_core.settings_fit``) against the best
simple alternative: ``scipy.optimize.fsolve`` on the numpy residual (build the cutter and settings, evaluate the
generated point with curvatures by the curvature-transfer relations) from the same start, located on the target
circle by the flank's locator (``ToothFlank.locate``, about 1.7 ms of the baseline's time; the fit finds the same
start by one compiled Newton solve, with that locator as its fallback). Both timed the same way:
median of N runs (bench/_timing.py), CPU time of this process (``time.process_time``: single-threaded work on a
machine shared by several engineers; its load is printed). The numpy residual lives here only, as the baseline.
Run: ``python bench/bench_synthesis.py [N]``. Target (issue 13): synthesis <= 5 ms on one core. Of what is left after
the compiled fit, most is the numpy location of the gear's mean point (``mean_contact``); the multi-point control
and ``active_range`` are in ``bench_cmc.py``.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
from _timing import median_time, report
from scipy.optimize import fsolve

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import SpiralBevelError
from spiralbevel.generation import generate_flank
from spiralbevel.generation.meshing import Generator
from spiralbevel.machine import MachineSettings, seed001_blank, seed001_settings
from spiralbevel.meshing.synthesis import FREE_OFFSET, fit_settings, synthesize_pinion
from spiralbevel.meshing.synthesis._relations import curvature_tensor, tangent_components
from spiralbevel.meshing.synthesis.machine_fit import blade_point, build

ARCSEC = math.pi / (180 * 3600)


N = int(sys.argv[1]) if len(sys.argv) > 1 else 21


def timed(fun, repeat=None):
    """Median CPU time of ``repeat`` runs (default N) and the last output."""
    return median_time(fun, repeat or N, cpu=True)


def main():
    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    kw = dict(side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7, te_magnitude=3 * ARCSEC)
    print(f"machine load {os.getloadavg()[0]:.1f} at start (shared machine: CPU times of this process); "
          f"median of {N} runs each")
    synthesize_pinion(gc, gs, blank, **kw)   # compiled kernels loaded from the cache (or compiled) before timing
    t_all, r = timed(lambda: synthesize_pinion(gc, gs, blank, **kw))
    print(f"synthesize_pinion (seed 001, eta = 6 deg, a = 3.7 mm, 3 arcsec): {t_all * 1e3:.2f} ms, "
          f"{r.iterations} Newton iterations, residual {r.residual:.1e}")

    K1 = r.relative_tensor - r.mean.gear_tensor
    target, nt = tangent_components(r.mean.point, r.mean.normal, K1)
    c0 = r.gear_flank.cutter.__class__(gc.nominal_radius + 0.5 * gc.point_width, gc.blade_angle, gc.point_width,
                                       gc.edge_radius, "outer")
    s0 = MachineSettings.from_blank(blank, Member.PINION, Side.CONCAVE, c0)
    t_fit, (c, s, u, info) = timed(lambda: fit_settings(c0, s0, blank, Side.CONCAVE, target, nt, FREE_OFFSET))

    # baseline: fsolve (forward differences) on the numpy residual, from the fit's own start
    w = np.array([1.0, 1.0, blank.Rm, blank.Rm, blank.Rm**2, blank.Rm**2, blank.Rm**2])
    flank0 = generate_flank(c0, s0, blank, Member.PINION, Side.CONCAVE)
    hand = flank0.hand

    def start():
        theta0 = float(generate_flank(c0, s0, blank, Member.PINION, Side.CONCAVE)
                       .locate(target[0], target[1], curvature=False).theta)
        return np.array([c0.point_radius, c0.blade_angle, s0.radial_setting, s0.cradle_angle, s0.ratio_of_roll,
                         s0.blank_offset, theta0])

    def fun(x):
        try:
            cc, ss = build(c0, s0, FREE_OFFSET, x[:6])
            fp = blade_point(Generator(cc, ss, hand), x[6])
        except SpiralBevelError:
            return np.full(7, 1e6)
        inv, _ = tangent_components(fp.points, fp.normals, curvature_tensor(np.array([fp.k1, fp.k2]),
                                                                            np.stack([fp.e1, fp.e2])))
        return (inv - target) * w

    t_base, xb = timed(lambda: fsolve(fun, start(), xtol=1e-13))
    ref = np.array([c.point_radius, c.blade_angle, s.radial_setting, s.cradle_angle, s.ratio_of_roll,
                    s.blank_offset, info["theta"]])
    d = xb - ref
    d[6] = (d[6] + math.pi) % (2 * math.pi) - math.pi
    print(f"  compiled fit: {info['iterations']} iterations, scaled residual {info['residual']:.1e}; "
          f"fsolve: scaled residual {np.abs(fun(xb)).max():.1e}, max |x_fsolve - x_fit| {np.abs(d).max():.1e}")
    report("settings fit (7 x 7, compiled)", t_fit, t_base, "fsolve on the numpy residual", N)
    print(f"machine load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
