"""The compiled blade locator (``_core.blade_locate``) against the plain numpy Newton it replaced.

Reference: ``_core.newton.solve_batched`` (forward-difference Jacobian) on the numpy blade chart
(``Generator.blade_axial_radial``, ``_core.generation_blade``), from the same starts. Targets: random blade points of
the four seed 001 basic flanks (both members and sides; straight and arc blades), located from starts 0.02 rad
off. Both must converge on the same systems and to the same (phi, psi_c)."""

import math

import numpy as np
import pytest
from conftest import CASES, basic_flank

from spiralbevel._core import blade_locate, generation_blade_jet
from spiralbevel._core.newton import solve_batched
from spiralbevel.conventions import TOL

MAX_STEP = np.array([0.05, 0.05])


@pytest.mark.parametrize("rp", [math.inf, 300.0])
@pytest.mark.parametrize("member, side", CASES)
def test_compiled_locate_matches_numpy_newton(member, side, rp):
    flank = basic_flank(member, side, rp=rp)
    gen = flank.generator
    mp = flank.mean_point()
    phi_m = mp.theta + math.pi - gen.mp["q"] + mp.psi_c
    rng = np.random.default_rng(3)
    m = 60
    x_true = np.stack([phi_m + rng.uniform(-0.1, 0.1, m), mp.psi_c + rng.uniform(-0.15, 0.15, m)], -1)
    ax, rad, u = gen.blade_axial_radial(x_true[:, 0], x_true[:, 1])
    assert np.all(np.isfinite(u))
    x0 = x_true + rng.uniform(-0.02, 0.02, x_true.shape)

    def fun(x):
        a, r, _ = gen.blade_axial_radial(x[..., 0], x[..., 1])
        return np.stack([r - rad, a - ax], -1)

    ref = solve_batched(fun, x0, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter, max_step=MAX_STEP)
    prm = generation_blade_jet.parameters(gen.cp, gen.mp, False, 0.0)
    x, uc, conv, res = blade_locate.locate_axial_radius(prm, x0, ax, rad, TOL.newton_abs * 10, TOL.max_iter,
                                                        MAX_STEP)
    np.testing.assert_array_equal(conv, ref.converged)
    assert np.all(conv)
    # both stop at |F| < 1e-10 mm; at |dr/dq| of order 10-100 mm/rad the roots agree to about 1e-11 rad
    np.testing.assert_allclose(x, ref.x, rtol=0, atol=1e-10)
    np.testing.assert_allclose(uc, gen.blade_axial_radial(x[:, 0], x[:, 1])[2], rtol=0, atol=1e-9)


@pytest.mark.parametrize("rp", [math.inf, 300.0])
@pytest.mark.parametrize("member, side", CASES)
def test_compiled_R_u_locate_matches_numpy_newton(member, side, rp):
    """The (R, u) system of the junction line: compiled (u row by central differences) vs the numpy Newton."""
    flank = basic_flank(member, side, rp=rp)
    gen, ol = flank.generator, flank.outline
    mp = flank.mean_point()
    phi_m = mp.theta + math.pi - gen.mp["q"] + mp.psi_c
    rng = np.random.default_rng(5)
    m = 40
    x_true = np.stack([phi_m + rng.uniform(-0.1, 0.1, m), mp.psi_c + rng.uniform(-0.15, 0.15, m)], -1)
    ax, rad, u = gen.blade_axial_radial(x_true[:, 0], x_true[:, 1])
    R, _ = ol.Rh(ax, rad)
    x0 = x_true + rng.uniform(-0.02, 0.02, x_true.shape)

    def fun(x):
        a, r, uu = gen.blade_axial_radial(x[..., 0], x[..., 1])
        return np.stack([ol.Rh(a, r)[0] - R, uu - u], -1)

    ref = solve_batched(fun, x0, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter, max_step=MAX_STEP)
    prm = generation_blade_jet.parameters(gen.cp, gen.mp, False, 0.0)
    x, uc, conv, res = blade_locate.locate_R_u(prm, x0, R, u, math.sin(ol.delta), math.cos(ol.delta),
                                               TOL.newton_abs * 10, TOL.max_iter, MAX_STEP)
    np.testing.assert_array_equal(conv, ref.converged)
    assert np.all(conv)
    np.testing.assert_allclose(x, ref.x, rtol=0, atol=1e-10)      # as above
