"""The compiled multi-point control systems (``_core.multipoint_newton``) against a plain per-point reference.

The reference is written independently here: the 6 x 6 system in the (u, psi_c) chart of the numpy generator
(``Generator.evaluate``, the cutter angle of the equation of meshing of generation in closed form, not the compiled
(phi, psi_c) jet), the pinion generated with the local offset law E(p) = E_m1 + E' (p - psi_c1), solved point by
point by ``scipy.optimize.root`` (MINPACK hybrid method, its own finite-difference Jacobian). Random control-point
systems (pinion rotation, TE target, offset rate, mean equation or TE equation) on the seed 001 pair are solved by
both, and so is the continuation march of ``active_range``."""

import copy
import math

import numpy as np
import pytest
from scipy.optimize import root

from spiralbevel._core.rotations import rot_z
from spiralbevel.meshing.synthesis._multipoint_system import MultiPointSystem
from spiralbevel.meshing.synthesis.cmc_design import active_range

ARCSEC = math.pi / (180 * 3600)


def _reference_residual(sysm, y, x, target, rate, phi2_ref, mean):
    """F (6,) mm of one system at y = (u1, psi_c1, u2, psi_c2, phi2, E_m1), numpy generator, (u, psi_c) chart."""
    u1, p1, u2, p2, phi2, e = y
    gen = copy.copy(sysm.gen)
    gen.mp = dict(sysm.gen.mp, E=-(e - rate * p1), E_rate=-rate, E_poly=(), E_table=None)  # kernel sign: negated
    fp1 = gen.evaluate(np.array([u1]), np.array([p1]), curvature=False)
    fp2 = sysm.gear.evaluate(np.array([u2]), np.array([p2]), curvature=False)
    R1 = rot_z(sysm.phi1_mean + x)
    R2 = sysm.kin.gear_to_fixed(phi2)
    d = R1 @ fp1.points[0] - R2 @ fp2.points[0]
    s = R1 @ fp1.normals[0] + R2 @ fp2.normals[0]
    te = sysm.drive * (-(phi2 - phi2_ref) - sysm.ratio * x)
    last = e - sysm.offset0 if mean else te - target
    return np.r_[d, sysm.length * np.array([s @ sysm.t_a, s @ sysm.t_b, last])]


@pytest.fixture(scope="module")
def system(synth_pos):
    return MultiPointSystem(synth_pos)


def test_random_systems_match_the_per_point_scipy_reference(synth_pos, system):
    rng = np.random.default_rng(13)
    lo, hi = active_range(synth_pos)
    m = 40
    x = rng.uniform(lo, hi, m)
    rate = rng.uniform(-0.2, 0.2, m)            # mm/rad: 4x the largest rate of the seed 001 CMC law (0.05 mm/rad)
    mean = rng.random(m) < 0.25
    # every system starts from the nearest station of the compiled march at constant offset (as the continuation of
    # multipoint_control starts its solves near the root); the TE target is the TE there +- 0.5 arcsec (a change of
    # TE of the size multi-point control makes between neighbouring continuation stations)
    T = 2 * math.pi / system.kin.z1
    xs = np.array([np.linspace(T / 24, T / 2, 12), -np.linspace(T / 24, T / 2, 12)])
    zm, _, _ = system.march(xs)
    st_x = np.r_[0.0, xs.ravel()]
    st_z = np.concatenate([system.start()[None], zm.reshape(-1, 6)])
    near = np.argmin(np.abs(x[:, None] - st_x[None, :]), axis=1)
    z0 = st_z[near]
    target = system.te(st_x[near], z0[:, 4], synth_pos.phi2_mean) + rng.uniform(-0.5, 0.5, m) * ARCSEC
    res = system.solve(z0, x, target, rate, synth_pos.phi2_mean, mean)
    assert np.all(res.converged)
    p1, p2 = res.params
    for k in range(m):
        y = np.r_[p1[k], p2[k], res.x[k, 4:6]]
        args = (system, x[k], target[k], rate[k], synth_pos.phi2_mean, mean[k])
        # the compiled root solves the independent residual: |F| 1e-11 mm in the compiled chart; the (u, psi_c)
        # chart's closed-form cutter angle reproduces it to round-off of a 100 mm point (1e-12 relative)
        assert np.max(np.abs(_reference_residual(*args[:1], y, *args[1:]))) < 1e-9
        # per-point scipy root from a start 0.05 mm / 1e-3 rad away: the same root
        start = y + np.array([0.05, 1e-3, -0.05, -1e-3, 1e-4, 0.01]) * rng.choice([-1, 1], 6)
        sol = root(lambda v, a=args: _reference_residual(system, v, *a[1:]), start, method="hybr",
                   options={"xtol": 1e-13})
        assert np.max(np.abs(sol.fun)) < 1e-9       # "xtol too small" is MINPACK's usual end at round-off
        # tolerance: both solve |F| to about 1e-11 mm at a Jacobian of order 1-100 mm per unit: roots agree to 1e-9
        np.testing.assert_allclose(sol.x, y, rtol=0, atol=1e-9)


def test_march_matches_per_point_reference(synth_pos, system):
    """Every station of the compiled continuation of ``active_range`` on the blades of both members is the
    reference root at that station."""
    T = 2 * math.pi / system.kin.z1
    xs = np.array([np.linspace(T / 24, T / 2, 12), -np.linspace(T / 24, T / 2, 12)])
    z, u, count = system.march(xs)
    assert np.all(count >= 4)                   # the seed 001 contact stays on both flanks for > 1/4 cycle each side
    blade = (u[..., 0] >= system.gen.cp["u_j"]) & (u[..., 1] >= system.gear.generator.cp["u_j"])
    checked = 0
    for s in range(2):
        for k in range(count[s]):
            if not blade[s, k]:     # past a fillet junction: the stations active_range refuses (reference: fillet)
                continue
            checked += 1
            y = np.r_[u[s, k, 0], z[s, k, 1], u[s, k, 1], z[s, k, 3], z[s, k, 4:6]]
            args = (xs[s, k], 0.0, 0.0, synth_pos.phi2_mean, True)
            sol = root(lambda v, a=args: _reference_residual(system, v, *a), y + 1e-3, method="hybr",
                       options={"xtol": 1e-13})
            assert np.max(np.abs(sol.fun)) < 1e-9
            np.testing.assert_allclose(sol.x, y, rtol=0, atol=1e-9)   # as above
    assert checked >= 12



def test_control_point_beyond_the_blades_is_refused(synth_pos):
    """A control point whose contact lies below a fillet junction (past the active range, real edge radii) is refused
    with the key named, not solved on the blade continued past the junction."""
    from spiralbevel.errors import DesignError
    from spiralbevel.meshing.motion_curves import seed001_cmc
    from spiralbevel.meshing.synthesis.multipoint import multipoint_control

    lo, hi = active_range(synth_pos)
    T = 2 * math.pi / 23
    beyond = lo - 2 * T / 24                    # two march steps past the last station on both flanks
    with pytest.raises(DesignError, match="control_points"):
        multipoint_control(synth_pos, seed001_cmc(3 * ARCSEC, 23), [beyond, lo / 2, hi / 2],
                           interpolation="spline")


def test_one_compiled_newton_for_march_and_control_points(synth_pos, system):
    """The march (mean equation, a constant flag) and the control-point solves (flags from an array), with one or
    several systems and scalar or array arguments, run the same compiled Newton: one signature each (a second one,
    e.g. for a literal True or a read-only array, costs seconds of compile time on a first run; ``_core/jit.py``)."""
    from spiralbevel._core import multipoint_newton as mpn

    T = 2 * math.pi / system.kin.z1
    system.march(np.array([np.linspace(T / 24, T / 8, 3), -np.linspace(T / 24, T / 8, 3)]))
    y0 = system.start()
    system.solve(y0, 0.0, 0.0, 0.0, synth_pos.phi2_mean, True)
    system.solve(np.tile(y0, (2, 1)), np.zeros(2), np.zeros(2), np.zeros(2), synth_pos.phi2_mean, [False, True])
    for k in (mpn.solve_systems, mpn.march):
        assert len(k.signatures) == 1, (k.py_func.__name__, k.signatures)
    # the callees are compiled (and listed) only when their callers are compiled, not when those are read from the
    # kernel cache: at most one signature (a changed _core source always compiles afresh, so a second one shows there)
    for k in (mpn._newton, mpn._system):
        assert len(k.signatures) <= 1, (k.py_func.__name__, k.signatures)
