"""Point-to-surface distance, log-spiral invariant and the conjugacy report."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from _meshing_helpers import flank
from spiralbevel._core import logspiral as ls
from spiralbevel.errors import ConvergenceError, DesignError
from spiralbevel.meshing.conjugate import compare_conjugate, logspiral_invariant, nearest_points

R_SPHERE = 50.0


def sphere(u, v):
    """Sphere of radius 50 mm: u = polar angle, v = azimuth; outward normals."""
    n = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u) * np.ones_like(v)], -1)
    return R_SPHERE * n, n


def test_nearest_points_on_sphere_match_radial_projection():
    rng = np.random.default_rng(1)
    dirs = sphere(rng.uniform(0.1, 1.0, 200), rng.uniform(-2.5, 2.5, 200))[1]
    radii = R_SPHERE + rng.uniform(-5.0, 5.0, 200)
    query = dirs * radii[:, None]
    foot = nearest_points(query, sphere, ((0.0, 1.2), (-3.0, 3.0)))
    assert foot.converged.all() and foot.inside.all()
    # exact: signed distance |x| - R along the outward normal, foot = R x / |x|
    assert np.max(np.abs(foot.distance - (radii - R_SPHERE))) < 1e-11
    assert np.max(np.abs(foot.points - R_SPHERE * dirs)) < 1e-11
    assert np.max(np.abs(foot.normals - dirs)) < 1e-12


def test_nearest_points_with_numerical_normals_and_start_values():
    def plane(u, v):
        return np.stack([u, v, 0.1 * u + 0.2 * v], -1)  # points only
    q = np.array([[1.0, 2.0, 5.0], [-3.0, 0.5, -2.0]])
    foot = nearest_points(q, plane, ((-10, 10), (-10, 10)), uv0=[[0.0, 0.0], [0.0, 0.0]])
    nrm = np.array([-0.1, -0.2, 1.0]) / np.linalg.norm([-0.1, -0.2, 1.0])
    assert np.allclose(foot.distance, (q @ nrm), atol=1e-11)  # plane through the origin, normal r_u x r_v


def test_nearest_points_errors():
    with pytest.raises(DesignError, match="bounds"):
        nearest_points([[0, 0, 60.0]], sphere, ((1.0, 0.0), (0.0, 1.0)))
    with pytest.raises(ConvergenceError, match="foot point"):
        nearest_points([[3.0, 1.0, 60.0]], sphere, ((0.0, 1.0), (-3.0, 3.0)), max_iter=1, tol=1e-30)


@settings(max_examples=25, deadline=None)
@given(st.floats(0.2, 0.5), st.floats(0.3, 0.7), st.sampled_from([1.0, -1.0]), st.sampled_from([1.0, -1.0]))
def test_logspiral_invariant_is_ln_rho0_on_the_flank(delta, beta_abs, hand, sign):
    beta = hand * beta_abs
    phi = np.linspace(-0.4, 0.4, 9)[:, None]
    psi = sign * np.linspace(0.05, 0.6, 7)[None, :]
    r = ls.point(phi + psi / np.sin(delta), phi, 80.0, delta, beta)
    inv = logspiral_invariant(r, delta, beta, psi_sign=sign)
    period = 2 * np.pi * np.sin(delta) / abs(np.tan(beta))
    k = np.round((inv - np.log(80.0)) / period)
    assert np.max(np.abs(inv - k * period - np.log(80.0))) < 1e-12
    assert np.ptp(inv) < 1e-12


def test_report_flags_a_displaced_surface():
    # the candidate's own points shifted by 0.01 mm along its normal: distance 0.01 mm, normals equal
    delta, beta = 0.35, 0.6
    cand = flank(100.0, delta, beta)
    u, v = np.meshgrid(np.linspace(-0.2, 0.2, 9), np.linspace(0.1, 0.4, 6), indexing="ij")
    r, n = cand(u, v)
    bounds = ((-0.5, 0.5), (0.02, 0.7))
    good = compare_conjugate(r, n, cand, bounds, invariant=lambda x: logspiral_invariant(x, delta, beta))
    assert good.is_conjugate and good.max_distance < 1e-11 and good.invariant_spread < 1e-12
    bad = compare_conjugate(r + 0.01 * n, n, cand, bounds)
    assert bad.max_distance == pytest.approx(0.01, abs=1e-11)
    assert bad.max_normal_mismatch < 1e-12
    assert bad.invariant_spread is None and not bad.is_conjugate
    assert "NOT CONJUGATE" in bad.summary() and "1.000e-02 mm" in bad.summary()
    # a candidate that does not cover the points is flagged too
    small = compare_conjugate(r, n, cand, ((-0.1, 0.1), (0.02, 0.7)))
    assert small.n_outside > 0 and not small.is_conjugate
