"""FE tooth compliance: cantilever against Euler-Bernoulli + Timoshenko, reciprocity, SPD, cache, dependency."""

import sys
import time

import numpy as np
import pytest

from spiralbevel.errors import DesignError, MissingDependencyError
from spiralbevel.meshing.ltca.compliance import tooth_compliance
from spiralbevel.meshing.ltca.halfspace import STEEL, Material
from spiralbevel.meshing.ltca.locate import locate_on_grid
from spiralbevel.meshing.ltca.mesher import mesh_tooth_segment

pytest.importorskip("skfem")

L, THICK, WIDTH, X0 = 40.0, 8.0, 8.0, 100.0


def _box_flank(y, nf, nl):
    """Flank grid of a box 'tooth': face (axis 0) along z, profile (axis 1) along x from root x0 to tip x0 + L."""
    Z, X = np.meshgrid(np.linspace(0, WIDTH, nf + 1), X0 + np.linspace(0, L, nl + 1), indexing="ij")
    return np.stack([X, np.full_like(X, y), Z], -1)


def _beam(x):
    """Tip-loaded cantilever deflection at x: Euler-Bernoulli bending + Timoshenko shear with Cowper's
    coefficient for a rectangle, kappa = 10(1 + nu)/(12 + 11 nu) (Cowper, J. Appl. Mech. 33 (1966) 335)."""
    E, nu = STEEL.youngs_modulus, STEEL.poisson_ratio
    G, I, A = E / (2 * (1 + nu)), WIDTH * THICK**3 / 12, WIDTH * THICK
    kappa = 10 * (1 + nu) / (12 + 11 * nu)
    return x**2 * (3 * L - x) / (6 * E * I) + x / (kappa * G * A)


def _cantilever(nf, nl, nt, order=2):
    mesh = mesh_tooth_segment(_box_flank(-THICK / 2, nf, nl), _box_flank(THICK / 2, nf, nl), z=40, n_teeth=1,
                              thickness_divisions=nt, rim_layers=0)
    tc = tooth_compliance(mesh, "convex", order=order, use_cache=False)
    wf = np.full(nf + 1, 1.0)
    wf[[0, -1]] = 0.5
    wf /= wf.sum()  # trapezoidal share of a unit tip load across the width
    idx = lambda j: np.arange(nf + 1) * (nl + 1) + j  # noqa: E731
    # deflection of the flank at x = 0.75 L (one thickness from the load line, outside its local field)
    return wf @ tc.G[np.ix_(idx(3 * nl // 4), idx(nl))] @ wf, tc


def test_cantilever_converges_to_beam_theory():
    ref = _beam(0.75 * L)
    vals = [(_cantilever(nf, nl, nt)[0]) for nf, nl, nt in ((1, 4, 1), (2, 8, 2), (4, 16, 4))]
    err = [v / ref - 1 for v in vals]
    # measured: -6.7 %, -2.8 %, -1.8 % (quadratic tetrahedra); the 3-D clamped root is slightly stiffer than
    # the Timoshenko beam, so the limit sits about 1.5 % below it
    assert abs(err[-1]) < 0.03
    rate = np.log2((vals[1] - vals[0]) / (vals[2] - vals[1]))
    assert rate > 1.5  # observed order ~2 of the mesh-size convergence
    # linear tetrahedra lock in bending on the same mesh (why order=2 is the default)
    p1, _ = _cantilever(2, 8, 2, order=1)
    assert p1 < 0.6 * vals[1]


def test_reciprocity_and_spd_on_tooth_segment(pinion_segment):
    mesh, tc = pinion_segment
    assert tc.asymmetry < 1e-12
    assert np.allclose(tc.G, tc.G.T, rtol=0, atol=0)
    assert np.linalg.eigvalsh(tc.G).min() > 0
    n = tc.G.shape[0] // 3
    own = np.diag(tc.G)[n:2 * n]
    assert np.all(own > 0)
    assert np.max(np.abs(tc.G[n:2 * n, :n])) < own.max()  # neighbour teeth couple through the rim, less


def test_cache_roundtrip(tmp_path, pinion_mesh):
    t0 = time.perf_counter()
    first = tooth_compliance(pinion_mesh, "concave", cache_dir=tmp_path)
    t1 = time.perf_counter()
    second = tooth_compliance(pinion_mesh, "concave", cache_dir=tmp_path)
    t2 = time.perf_counter()
    assert len(list(tmp_path.glob("ltca_fe_*.npz"))) == 1
    assert np.array_equal(first.G, second.G) and first.key == second.key
    assert t2 - t1 < 0.2 * (t1 - t0)
    other = tooth_compliance(pinion_mesh, "concave", material=Material(103000.0, 0.3), cache_dir=tmp_path)
    assert other.key != first.key
    # linear elasticity with the same nu: flexibility scales exactly with 1/E
    assert np.max(np.abs(other.G - 2.0 * first.G)) < 1e-9 * np.max(np.abs(first.G))


def test_point_weights_reproduce_nodal_values(pinion_segment):
    _, tc = pinion_segment
    grid = tc.grids[0]
    W = tc.weights(0, grid[3, 2][None])
    assert W.max() == pytest.approx(1.0, abs=1e-9)
    mid = 0.25 * (grid[3, 2] + grid[4, 2] + grid[3, 3] + grid[4, 3])
    i, j, xi, eta, inside = locate_on_grid(grid, mid[None])
    assert (i[0], j[0]) == (3, 2) and inside[0]
    C = tc.flexibility([0, 0], np.stack([grid[3, 2], mid]))
    node = int(np.prod(tc.grid_shape)) + 3 * tc.grid_shape[1] + 2  # tooth 0 is the second block
    assert np.allclose(C, C.T) and C[0, 0] == pytest.approx(tc.G[node, node], rel=1e-9)
    # the cell-centre load is the mean of the four corner loads (bilinear weights 1/4)
    corners = [node, node + tc.grid_shape[1], node + 1, node + tc.grid_shape[1] + 1]
    assert C[1, 1] == pytest.approx(tc.G[np.ix_(corners, corners)].sum() / 16, rel=1e-6)
    with pytest.raises(DesignError, match="tooth"):
        tc.flexibility([5], grid[3, 2][None])


def test_missing_scikit_fem(monkeypatch, pinion_mesh, tmp_path):
    monkeypatch.setitem(sys.modules, "skfem", None)
    with pytest.raises(MissingDependencyError, match=r"spiralbevel\[fem\]"):
        tooth_compliance(pinion_mesh, "concave", use_cache=False)


def test_mesher_bad_input():
    g = _box_flank(0.0, 2, 2)
    with pytest.raises(DesignError, match="flank grids"):
        mesh_tooth_segment(g, g[:, :2], z=20)
    with pytest.raises(DesignError, match="n_teeth"):
        mesh_tooth_segment(g, _box_flank(1.0, 2, 2), z=20, n_teeth=0)


@pytest.mark.parametrize("order", [1, 2])
def test_vectorized_stiffness_equals_scikit_fem_assembly(pinion_mesh, order):
    """The one-pass stiffness assembly gives scikit-fem's own ``asm(linear_elasticity)`` (default quadrature) and the
    LU with symmetric-mode options gives the default ``splu`` solution, on a small segment mesh."""
    import skfem
    from scipy.sparse.linalg import splu
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    from spiralbevel.meshing.ltca.compliance import factorize, stiffness_matrix

    m = skfem.MeshTet(pinion_mesh.vertices.T.copy(), pinion_mesh.tets.T.copy())
    elem = skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1()
    lam, mu = lame_parameters(STEEL.youngs_modulus, STEEL.poisson_ratio)
    ref_basis = skfem.Basis(m, skfem.ElementVector(elem))  # scikit-fem's default quadrature (order 2p)
    K_ref = skfem.asm(linear_elasticity(lam, mu), ref_basis).tocsc()
    vb = skfem.Basis(m, skfem.ElementVector(elem), intorder=max(1, 2 * (order - 1)))
    K = stiffness_matrix(skfem.Basis(m, elem, intorder=max(1, 2 * (order - 1))), vb.element_dofs, vb.N, lam, mu)
    assert np.array_equal(vb.element_dofs, ref_basis.element_dofs)
    # both quadratures are exact for the stiffness of affine elements: equal to rounding (measured 1e-15)
    assert abs(K - K_ref).max() <= 1e-12 * abs(K_ref).max()
    free = np.setdiff1d(np.arange(vb.N), vb.nodal_dofs[:, pinion_mesh.fixed].ravel())
    A = K_ref[free][:, free].tocsc()
    b = np.random.default_rng(0).standard_normal((len(free), 3))
    u_ref = splu(A).solve(b)
    # condition number of the clamped segment ~1e7: solutions agree to ~1e-10 relative (measured 3e-13)
    assert np.max(np.abs(factorize(K[free][:, free].tocsc()).solve(b) - u_ref)) <= 1e-9 * np.max(np.abs(u_ref))


def test_fe_build_reports_sub_progress_to_the_job_progress_bar():
    """The FE compliance build reports its factorization and its unit-load solves (one report per block of 64), so
    the progress bar moves during the minutes it takes; the same matrix with and without a listener."""
    from spiralbevel._progress import listening
    from spiralbevel.job.progress import Steps

    seen = []
    with listening(lambda stage, done, total: seen.append((stage, done, total))):
        _, tc = _cantilever(16, 8, 1, order=1)
    n = tc.G.shape[0]
    assert seen[0][0].endswith("factorizing") and seen[0][1:] == (0, n)
    done = [d for s, d, t in seen if s.endswith("unit loads")]
    assert done == sorted(done) and done[-1] == n and len(done) == -(-n // 64)
    _, plain = _cantilever(16, 8, 1, order=1)
    np.testing.assert_array_equal(plain.G, tc.G)
    with Steps(1, enabled=True) as steps:
        with steps.step("loaded TCA"):
            _cantilever(16, 8, 1, order=1)
            assert steps.sub is not None and steps.sub[1:] == (n, n)
            task = steps._progress.tasks[0]
            assert task.description == f"loaded TCA | {steps.sub[0]} {n}/{n}"
        assert steps.sub is None
