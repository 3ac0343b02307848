"""Benchmark: the CMC design chain of seed 001 (``design_seed001_style``: local synthesis, ``active_range``, multi-point
control with 11 control points and a spline law, TCA of the final pair over 61 positions x 3 pairs) on the bundled
seed 001 data with real edge radii, and its contact-tracing stages against what a competent scipy user would write.

Run:  python bench/bench_cmc.py [N]
Target (issue 13): the whole CMC multi-point control <= 0.3 s on one core (the CMC example's job runs the chain twice:
real flanks, and seed 001's straight-blade model for the paper's figure).

Baseline: the same stages with one ``scipy.optimize.root`` (MINPACK hybrid, its own finite-difference Jacobian) per
position on a plain numpy residual of the same 6 x 6 system (numpy generator, (u, psi_c) chart):
* ``active_range``: the contact traced serially station by station outward from M on both sides (secant predictor,
  as the package), each station one ``root`` call, stopping at the first station off a flank;
* the control-point systems of the last fixed-point pass of ``multipoint_control``: one ``root`` per control point
  from the same starts as the compiled batch.
Both must reach the same roots (printed). Both sides are timed the same way: median of N runs, CPU time of this
process (``time.process_time``; single-threaded work; the machine is shared by several engineers, so wall time
means little; its load is printed). The compiled kernels are warmed up (cached) before timing.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_v] = "1"

import copy  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402

import numpy as np  # noqa: E402
from _timing import fmt, median_time, report  # noqa: E402
from scipy.optimize import root  # noqa: E402

from spiralbevel._core.rotations import rot_z  # noqa: E402
from spiralbevel.conventions import Member, Side  # noqa: E402
from spiralbevel.machine import seed001_blank, seed001_settings  # noqa: E402
from spiralbevel.meshing.motion_curves import seed001_cmc  # noqa: E402
from spiralbevel.meshing.synthesis import synthesize_pinion  # noqa: E402
from spiralbevel.meshing.synthesis._multipoint_system import MultiPointSystem  # noqa: E402
from spiralbevel.meshing.synthesis.cmc_design import active_range, design_seed001_style  # noqa: E402
from spiralbevel.meshing.synthesis.multipoint import _Surface, multipoint_control  # noqa: E402

ARCSEC = math.pi / (180 * 3600)


def residual(sysm, y, x, target, rate, phi2_ref, mean):
    """F (6,) mm of one control-point system at y = (u1, psi_c1, u2, psi_c2, phi2, E_m1), plain numpy."""
    u1, p1, u2, p2, phi2, e = y
    gen = copy.copy(sysm.gen)
    gen.mp = dict(sysm.gen.mp, E=-(e - rate * p1), E_rate=-rate, E_poly=(), E_table=None)
    fp1 = gen.evaluate(np.array([u1]), np.array([p1]), curvature=False)
    fp2 = sysm.gear.evaluate(np.array([u2]), np.array([p2]), curvature=False)
    R1 = rot_z(sysm.phi1_mean + x)
    R2 = sysm.kin.gear_to_fixed(phi2)
    d = R1 @ fp1.points[0] - R2 @ fp2.points[0]
    s = R1 @ fp1.normals[0] + R2 @ fp2.normals[0]
    last = e - sysm.offset0 if mean else sysm.drive * (-(phi2 - phi2_ref) - sysm.ratio * x) - target
    return np.r_[d, sysm.length * np.array([s @ sysm.t_a, s @ sysm.t_b, last])]


def baseline_active_range(synth):
    """``active_range`` written plainly: a serial march, one scipy root per station."""
    sysm = MultiPointSystem(synth)
    T = 2 * math.pi / sysm.kin.z1
    h = T / 24
    pin = _Surface(synth.pinion_flank, 0.0, synth.pinion_params)
    gear = _Surface(synth.gear_flank, 0.0, synth.mean.gear_params)
    y0 = np.r_[synth.pinion_params[:2], synth.mean.gear_params, synth.phi2_mean, sysm.offset0]
    last = [0.0, 0.0]
    for side, d in enumerate((1.0, -1.0)):
        prev, y, k = y0, y0, 0
        while k * h < T / 2:
            k += 1
            x = d * min(k * h, T / 2)
            guess = 2 * y - prev if k > 1 else y
            sol = root(lambda v, x=x: residual(sysm, v, x, 0.0, 0.0, synth.phi2_mean, True), guess, method="hybr",
                       options={"xtol": 1e-13})
            ok = np.max(np.abs(sol.fun)) < 1e-9
            if not (ok and pin.contains(sol.x[0:2]) and gear.contains(sol.x[2:4])):
                break
            last[side] = x
            prev, y = y, sol.x
    return last[1], last[0]


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    kw = dict(side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7, te_magnitude=3 * ARCSEC)
    print(f"machine load {os.getloadavg()[0]:.1f} at start (shared by several engineers: CPU times of this process); "
          f"median of {n} runs each")
    design_seed001_style(gc, gs, blank, n_control=11, **kw)           # warm-up: compiled kernels from the cache
    t_all, d = median_time(lambda: design_seed001_style(gc, gs, blank, n_control=11, **kw), n, cpu=True)
    print(f"design_seed001_style (synthesis + active_range + multi-point control + TCA 61 x 3): {fmt(t_all)}")
    t_sb, _ = median_time(lambda: design_seed001_style(gc, gs, blank, n_control=11, straight_blades=True, **kw), n,
                          cpu=True)
    print(f"  the same on straight blades (seed 001's model, whole cycle, no active_range): {fmt(t_sb)}; both, as "
          f"the CMC example's job runs them: {fmt(t_all + t_sb)} (target 0.3 s)")
    synth = synthesize_pinion(gc, gs, blank, **kw)
    t_ar, rng_pkg = median_time(lambda: active_range(synth), n, cpu=True)
    t_ar_b, rng_b = median_time(lambda: baseline_active_range(synth), max(1, n // 2), cpu=True)
    print(f"  active_range {rng_pkg} vs baseline {rng_b} (rad)")
    report("active_range (contact traced from M, both sides)", t_ar, t_ar_b, "serial scipy root per station",
           n)
    lo, hi = rng_pkg
    x = np.linspace(lo, hi, 11)
    cmc = seed001_cmc(3 * ARCSEC, 23)
    t_mp, mp = median_time(lambda: multipoint_control(synth, cmc, x, interpolation="spline"), n, cpu=True)
    print(f"  multipoint_control (11 points, spline, incl. regenerating the pinion and verifying by TCA): {fmt(t_mp)}")
    # the control-point systems of the final fixed-point pass: compiled batch vs one scipy root per point
    sysm = MultiPointSystem(synth)
    i0 = mp.mean_index
    xs, tgt, rate = mp.control_points, mp.target, mp.law.rate(mp.psi_c1)
    mean = xs == 0.0
    phi1 = sysm.gen.contact(mp.pinion_params[:, 0], mp.pinion_params[:, 1])["phi"]
    phi2g = sysm.gear.generator.contact(mp.gear_params[:, 0], mp.gear_params[:, 1])["phi"]
    z = np.c_[phi1, mp.psi_c1, phi2g, mp.gear_params[:, 1], mp.phi2, mp.offsets]
    rng = np.random.default_rng(1)
    dz = rng.uniform(-1, 1, z.shape) * np.array([1e-3, 1e-4, 1e-3, 1e-4, 1e-5, 1e-3])
    y_b = np.c_[mp.pinion_params, mp.gear_params, mp.phi2, mp.offsets]
    dy = rng.uniform(-1, 1, y_b.shape) * np.array([1e-2, 1e-4, 1e-2, 1e-4, 1e-5, 1e-3])
    phi2_ref = mp.phi2[i0]

    def pkg():
        return sysm.solve(z + dz, xs, tgt, rate, phi2_ref, mean)

    def base():
        return np.array([root(lambda v, k=k: residual(sysm, v, xs[k], tgt[k], rate[k], phi2_ref, mean[k]),
                              y_b[k] + dy[k], method="hybr", options={"xtol": 1e-13}).x for k in range(xs.size)])

    t_s, r = median_time(pkg, n, cpu=True)
    t_b, yb = median_time(base, n, cpu=True)
    p1, p2 = r.params
    diff = np.max(np.abs(np.c_[p1, p2, r.x[:, 4:6]] - yb))
    print(f"  {xs.size} control-point systems: all converged {bool(np.all(r.converged))}, "
          f"max |root - scipy root| {diff:.1e}")
    report(f"{xs.size} control-point systems (6 x 6)", t_s, t_b, "scipy root per point", n)


if __name__ == "__main__":
    main()
