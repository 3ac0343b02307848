"""3-D FE stress recovery of the solid tooth model against a known answer, and its load bookkeeping.

Known answer: a prismatic block (thickness h, width b, length L) clamped at one end and loaded at the other by a force
F across its thickness. In the interior, away from the clamp and the load (Saint-Venant), the flexure solution of
elasticity has the exact axial stress sigma_xx = M y / I: on the surfaces 6 F a / (b h^2), a the distance from the
load, independent of Poisson's ratio.
"""

import math

import numpy as np
import pytest

pytest.importorskip("skfem")

from spiralbevel.meshing.ltca.mesher import mesh_tooth_segment  # noqa: E402
from spiralbevel.rating.fe_root_stress import contact_load_cases, member_root_stress  # noqa: E402
from spiralbevel.rating.fe_solid import max_principal, solid_model  # noqa: E402

H, B, L, F = 2.0, 2.0, 12.0, 100.0  # mm, mm, mm, N
X0 = 100.0  # the block stands radially at 100 mm from the member axis (the mesher's frame)


def _block(n, length=L, width=B, x0=X0, rows=None):
    """(lo, hi) flank grids of a block: axis 0 along the width (z), axis 1 along the length (x, root -> top)."""
    nf, npf = n + 1, rows or 6 * n + 1
    Z, X = np.meshgrid(np.linspace(0.0, width, nf), x0 + np.linspace(0.0, length, npf), indexing="ij")
    lo = np.stack([X, np.full_like(X, -H / 2), Z], -1)
    hi = lo.copy()
    hi[..., 1] = H / 2
    return lo, hi


def _cantilever(n):
    lo, hi = _block(n)
    mesh = mesh_tooth_segment(lo, hi, z=10, n_teeth=1, thickness_divisions=n, rim_layers=0)
    model = solid_model(mesh)
    fn = mesh.flank_nodes[(0, "convex")]  # the y = -h/2 face (lower polar angle)
    top = fn[:, -1]
    w = np.ones(len(top))
    w[[0, -1]] = 0.5  # trapezoidal shares: a uniform line load across the width
    Fv = np.zeros((len(mesh.vertices), 3))
    Fv[top, 1] = F * w / w.sum()
    U = model.solve(Fv)
    return mesh, model, Fv, U


@pytest.fixture(scope="module")
def cantilevers():
    # element edge h/n across the thickness and along the block; n = 2, 3, 4 (the finest has 11907 dofs, ~2 s)
    return {n: _cantilever(n) for n in (2, 3, 4)}


def test_flexure_stress_converges_at_second_order(cantilevers):
    ref = 6.0 * F * (L / 2) / (B * H * H)  # mid-length, a = L/2 = 3 h from both the clamp and the load
    err = {}
    for n, (mesh, model, _, U) in cantilevers.items():
        S = model.vertex_stress(U)[0]
        mid_t = mesh.flank_nodes[(0, "convex")][n // 2, 3 * n]  # tension face, mid-width, mid-length
        mid_c = mesh.flank_nodes[(0, "concave")][n // 2, 3 * n]  # compression face
        # tension face +ref, compression face -ref (the flexure field is antisymmetric about the neutral plane)
        err[n] = max(abs(S[mid_t, 0, 0] - ref), abs(S[mid_c, 0, 0] + ref)) / ref
        # the largest principal stress on the tension face is the axial one (the shear is zero on the surface)
        assert max_principal(S[mid_t]) == pytest.approx(S[mid_t, 0, 0], rel=err[n])
    # measured 1.38 %, 0.63 %, 0.36 %: within 5 % on the coarsest mesh, 0.4 % on the finest
    assert err[2] < 0.05 and err[4] < 0.004
    rate23 = math.log(err[2] / err[3]) / math.log(3 / 2)
    rate34 = math.log(err[3] / err[4]) / math.log(4 / 3)
    # quadratic tetrahedra, nodal-averaged gradients: second order (measured 1.99 and 1.91)
    assert rate23 > 1.8 and rate34 > 1.7


def test_reactions_balance_the_loads(cantilevers):
    mesh, model, Fv, _ = cantilevers[2]
    rng = np.random.default_rng(3)
    free_v = np.flatnonzero(~mesh.fixed)
    loads = np.zeros((2, len(mesh.vertices), 3))
    loads[0] = Fv
    loads[1, free_v] = rng.normal(size=(len(free_v), 3))  # any load, all three components
    U = model.solve(loads)
    R = model.reactions(U)
    applied = loads.sum(axis=1)
    assert np.allclose(R, -applied, rtol=0, atol=1e-9 * np.abs(applied).max())


def test_reciprocity_of_the_solve(cantilevers):
    # Maxwell-Betti: the work of load a on the displacements of load b equals that of b on a (symmetric stiffness)
    mesh, model, _, _ = cantilevers[3]
    rng = np.random.default_rng(5)
    free_v = np.flatnonzero(~mesh.fixed)
    loads = np.zeros((2, len(mesh.vertices), 3))
    loads[:, free_v] = rng.normal(size=(2, len(free_v), 3))
    U = model.solve(loads)
    Bv = model.nodal_load_vector(loads)
    assert Bv[:, 0] @ U[:, 1] == pytest.approx(Bv[:, 1] @ U[:, 0], rel=1e-9)


def _segment(n_teeth=3, z=40, n=2):
    lo, hi = _block(n, length=4.0, width=6.0, rows=9)
    return mesh_tooth_segment(lo, hi, z=z, n_teeth=n_teeth, thickness_divisions=2, rim_layers=2)


def test_contact_forces_are_distributed_statically_equivalent():
    mesh = _segment()
    grid = mesh.vertices[mesh.flank_nodes[(0, "convex")]]
    P = np.array([[X0 + 2.3, -H / 2, 1.7], [X0 + 3.1, -H / 2, 4.4]])  # on the y = -h/2 flank of tooth 0
    f = np.array([30.0, 50.0])
    pr = np.array([1, 0])  # pair 0 on tooth -1, pair 1 on tooth 0
    Fv, cases = contact_load_cases(mesh, "convex", [P], [pr], [f], teeth_of_pairs=[-1, 0])
    assert cases == [(0, 0), (0, 1)]
    # case (0, 1): tooth 0 is pair 1 -> its point on tooth 0, pair 0 on tooth -1 (the reference turned by -pitch)
    Fc = Fv[1]
    c, s = math.cos(-mesh.pitch_angle), math.sin(-mesh.pitch_angle)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    inward = np.array([0.0, 1.0, 0.0])  # into the tooth from its y = -h/2 flank
    Fp = np.stack([f[0] * inward, f[1] * (R @ inward)])  # forces at the points
    Pp = np.stack([P[0], R @ P[1]])
    assert np.allclose(Fc.sum(axis=0), Fp.sum(axis=0), atol=1e-9)
    # moment about the origin: the bilinear shares reproduce the point on a plane grid
    assert np.allclose(np.cross(mesh.vertices, Fc).sum(axis=0), np.cross(Pp, Fp).sum(axis=0), atol=1e-7)
    assert np.allclose(grid[0, 0], [X0, -H / 2, 0.0])
    # case (0, 0): tooth 0 is pair 0 (the 50 N point); pair 1 (30 N) goes on tooth +1
    assert np.allclose(Fv[0].sum(axis=0), f[1] * inward + f[0] * (R.T @ inward), atol=1e-9)


def _turn(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_root_stress_follows_the_load_along_the_face():
    z = 40
    out = {}
    for name, zc, turn in (("toe", 1.0, 0.0), ("heel", 5.0, 0.0), ("heel turned", 5.0, 0.7)):
        lo, hi = _block(2, length=4.0, width=6.0, rows=9)
        R = _turn(turn)
        P = [np.array([[X0 + 3.5, -H / 2, zc]]) @ R.T]
        res = member_root_stress("pinion", lo @ R.T, hi @ R.T, z, "convex", 2, P, [np.array([0])],
                                 [np.array([100.0])], [0], np.array([0.0]), fe_options=dict(thickness_divisions=2))
        out[name] = res
        # the fillet rows of the loaded (tension) flank carry the maximum; the loads are in equilibrium
        assert res.side_max == "convex" and res.index_max[1] < 2
        assert np.allclose(res.reaction_force, -res.applied_force, atol=1e-8)
        assert res.load_cases == 1 and res.case_max == (0, 0)
    assert out["toe"].face_fraction < 0.5 < out["heel"].face_fraction
    # the model turned about the member axis with its load: the same stresses (frame invariance), to rounding
    a, b = out["heel"], out["heel turned"]
    assert b.sigma1_max == pytest.approx(a.sigma1_max, rel=1e-9)
    assert b.index_max == a.index_max and b.radius == pytest.approx(a.radius, rel=1e-12)
    for sd in ("convex", "concave"):
        assert np.allclose(b.sigma1[sd], a.sigma1[sd], rtol=0, atol=1e-9 * a.sigma1_max)
    s = a.summary()
    assert s["sigma1_max"] == a.sigma1_max and s["pinion_angle_deg"] == 0.0


def test_points_on_another_tooth_are_brought_back_and_strays_rejected():
    from spiralbevel.errors import DesignError

    mesh = _segment()
    P = np.array([[X0 + 2.3, -H / 2, 1.7], [X0 + 3.1, -H / 2, 4.4]])
    args = ([np.array([0, 0])], [np.array([30.0, 50.0])], [0])
    F0, _ = contact_load_cases(mesh, "convex", [P], *args)
    # the same points left on tooth +1 (one pitch turned): the same loads on tooth 0
    F1, _ = contact_load_cases(mesh, "convex", [P @ _turn(mesh.pitch_angle).T], *args)
    assert np.allclose(F1, F0, atol=1e-9)
    # points on the other flank of the tooth (a side mix-up, h = 2 mm away) are an error naming the key
    with pytest.raises(DesignError, match="ltca points"):
        contact_load_cases(mesh, "convex", [P + [0.0, H, 0.0]], *args)


def test_locate_fallback_finds_the_foot():
    from spiralbevel.rating.fe_loads import locate

    lo, _ = _block(2, length=4.0, width=6.0, rows=9)  # plane y = -h/2, cells 3 mm x 0.5 mm
    P = np.array([[X0 + 0.5 * 2 + 0.5 * 0.6, -H / 2 - 0.2, 3.0 * 0.3]])  # cell (0, 2), xi 0.3, eta 0.6, 0.2 off
    for retry in (1.0, 0.0):  # Gauss-Newton only; the lattice search forced
        i, j, xi, eta, d = locate(lo, P, retry=retry)
        assert (i[0], j[0]) == (0, 2) and d[0] == pytest.approx(0.2, abs=1e-9)
        assert xi[0] == pytest.approx(0.3, abs=1 / 80) and eta[0] == pytest.approx(0.6, abs=1 / 80)
