"""The compiled edge contact of TCA (spiralbevel._core.tca_edge) against plain references written here with numpy and
scipy only: the flank boundary margins and their gradients against the surfaces' own ``boundary_margins`` (values)
and fourth-order central differences of them (gradients); the edge Newton against a per-point ``scipy.optimize.root``
of the same five equations assembled from the surfaces' ``evaluate`` and ``boundary_margins`` with difference
derivatives, on many random starts around the edge contacts TCA finds (compiled jets of the face-milled pair and
the log-spiral pair; the crowned log-spiral pinion, which has no compiled jet, runs the numpy-evaluated path)."""

import warnings

import numpy as np
import pytest
from _meshing_helpers import seed001_synthesized_pair
from scipy.optimize import root

from spiralbevel._core import tca_edge as _ke
from spiralbevel._core.generation_blade import blade_jet
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_edge import solve_edge_contacts
from spiralbevel.meshing.tca_result import ContactStatus
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair


def _facemilled():
    c1, c2, kin = seed001_synthesized_pair()
    return c1, c2, kin, dict(start=np.r_[c1.reference_params, c2.reference_params, 0.0])


def _logspiral(crowned):
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    pin = pair.pinion
    if crowned:
        pin = NormalDeviation(pin, quadratic_crowning(pin.reference_params, (0.5, 0.0, 5.0)))
    return pin, pair.gear, kin, {}


CASES = {"facemilled": _facemilled, "logspiral": lambda: _logspiral(False), "crowned": lambda: _logspiral(True)}


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    c1, c2, kin, kw = CASES[request.param]()
    return request.param, c1, c2, kin, solve_tca(c1, c2, kin, **kw)


def _grad4(fun, q, h):
    """Gradient (m, k, 2) of ``fun(q (m, 2)) -> (m, k)`` by fourth-order central differences."""
    out = []
    for j in range(2):
        e = np.zeros(2)
        e[j] = h
        out.append((-fun(q + 2 * e) + 8 * fun(q + e) - 8 * fun(q - e) + fun(q - 2 * e)) / (12 * h))
    return np.stack(out, -1)


def _reference_margins(surface, q):
    """Margins (m, 4) by numpy: the log-spiral box from the surface's ``boundary_margins``; a generated flank's from
    the numpy closed form of the blade jet (``_core.generation_blade``: point and blade parameter u) and its blank
    outline (R, h of the point; rho and z do not change under the mirror and the phasing turn)."""
    if not hasattr(surface, "flank"):
        return surface.boundary_margins(q)
    gen, ol = surface.flank.generator, surface.flank.outline
    with np.errstate(invalid="ignore", divide="ignore"):
        S, u, _ = blade_jet(q[..., 0], q[..., 1], gen.cp, gen.mp)
        r = S[..., 0]
        R, h = ol.Rh(r[..., 2], np.hypot(r[..., 0], r[..., 1]))
        return np.stack([R - ol.Ri, ol.Re - R, ol.h_face(R) - h, u - gen.cp["u_j"]], -1)


def test_compiled_margins_match_the_surfaces(case):
    """Values equal the numpy margins to round-off; gradients match their fourth-order differences (error about
    h^4 |g'''''| + eps |g| / h, below 1e-8 with h = 1e-3 on these flanks)."""
    _, c1, c2, _, res = case
    rng = np.random.default_rng(1)
    for surf, q0 in ((c1, res.params1), (c2, res.params2)):
        base = surf.base if isinstance(surf, NormalDeviation) else surf
        q0 = q0[np.isfinite(q0[..., 0])]
        q = q0[rng.integers(0, len(q0), 200)] + rng.normal(0.0, 0.02, (200, 2))
        kind, prm = base.boundary_jet
        g, dg, _ = _ke.margins_batch(kind, prm, np.ascontiguousarray(q))
        ref = _reference_margins(base, q)
        fin = np.isfinite(ref)
        assert np.array_equal(fin, np.isfinite(g))
        assert np.max(np.abs(g[fin] - ref[fin])) < 1e-12 * max(1.0, np.max(np.abs(ref[fin])))
        dref = _grad4(lambda p, b=base: _reference_margins(b, p), q, 1e-3)
        ok = fin.all(axis=1)
        assert np.max(np.abs(dg[ok] - dref[ok])) < 1e-8 * max(1.0, np.max(np.abs(dref[ok])))


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _reference_residual(prob, phi1_eff, A, e):
    """The edge equations at one system as a plain function of x (5,): point coincidence (3, mm), margin e of member
    A, and tangency n_B . t_A with the tangent t_A = r_A,q0 g_q1 - r_A,q1 g_q0 (member frame, then turned) from
    fourth-order differences of ``evaluate`` and ``boundary_margins``."""
    _, o1, a2, o2, B2 = prob.axes
    K = np.array([[0, -a2[2], a2[1]], [a2[2], 0, -a2[0]], [-a2[1], a2[0], 0]])
    surfs = (prob.pinion, prob.gear)
    h = 1e-3

    def fun(x):
        q = (x[0:2], x[2:4])
        R = (_rz(phi1_eff), (np.eye(3) + np.sin(x[4]) * K + (1 - np.cos(x[4])) * K @ K) @ B2)
        (r1, n1), (r2, n2) = surfs[0].evaluate(q[0]), surfs[1].evaluate(q[1])
        qa = q[A][None]
        dr = _grad4(lambda p: surfs[A].evaluate(p)[0], qa, h)[0]  # (3, 2)
        g = surfs[A].boundary_margins(qa)[0, e]
        dg = _grad4(lambda p: surfs[A].boundary_margins(p)[:, e:e + 1], qa, h)[0, 0]
        t = R[A] @ (dr[:, 0] * dg[1] - dr[:, 1] * dg[0])
        nB = R[1 - A] @ (n2 if A == 0 else n1)
        return np.r_[o1 + R[0] @ r1 - o2 - R[1] @ r2, g, nB @ t / np.linalg.norm(t)]

    return fun


def _margins(surf, q):
    base = surf.base if isinstance(surf, NormalDeviation) else surf
    return _ke.margins_batch(*base.boundary_jet, np.ascontiguousarray(q, float))[0]


def _edge_contacts(c1, c2, res):
    """(position, pair index, member A, boundary index) of every pair in edge contact (selected or not): the member
    and boundary whose margin vanishes there."""
    out = []
    for i, j in zip(*np.nonzero(res.status_pairs == ContactStatus.EDGE)):
        g = [np.abs(_margins(c1, res.params1[i, j][None]))[0], np.abs(_margins(c2, res.params2[i, j][None]))[0]]
        A = int(np.argmin([g[0].min(), g[1].min()]))
        out.append((int(i), int(j), A, int(np.argmin(g[A]))))
    return out


def test_edge_newton_matches_per_point_scipy(case):
    """Random starts around every edge contact TCA found (random pinion rotations within a tenth of the position
    spacing, starts perturbed by 1e-3 in every unknown): the compiled solver and a per-point scipy root of the
    reference equations reach the same root. Measured: 8e-13 (face-milled), 1.4e-12 (log-spiral), 6e-11 (crowned:
    the reference differentiates a normal that is itself a difference quotient); the bound 2e-10 sits above that."""
    name, c1, c2, kin, res = case
    prob = ContactProblem(c1, c2, kin)
    edges = _edge_contacts(c1, c2, res)
    assert edges, f"{name}: TCA found no edge contact to test"
    rng = np.random.default_rng(7)
    pick = rng.integers(0, len(edges), 24)
    dphi = np.diff(res.phi1[:2])[0]
    phi, x0, mem, edge = [], [], [], []
    for a in pick:
        i, j, A, e = edges[a]
        p = res.phi1[i] + res.pairs[j] * 2 * np.pi / prob.z1
        d = rng.uniform(-0.1, 0.1) * dphi
        x = np.r_[res.params1[i, j], res.params2[i, j], res.phi2_pairs[i, j] - res.pairs[j] * 2 * np.pi / prob.z2]
        x[4] -= prob.ratio * d
        phi.append(p + d), x0.append(x + rng.normal(0.0, 1e-3, 5)), mem.append(A), edge.append(e)
    phi, x0, mem, edge = np.array(phi), np.array(x0), np.array(mem), np.array(edge)
    xs, conv, _ = solve_edge_contacts(prob, phi, x0, mem, edge, tol=1e-11)
    assert conv.all()
    worst = 0.0
    for k in range(len(phi)):
        fun = _reference_residual(prob, phi[k], mem[k], edge[k])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            # y = x + 1: see test_tca_engine
            sol = root(lambda y, f=fun: f(y - 1.0), x0[k] + 1.0, method="hybr", tol=1e-14)
        xr = sol.x - 1.0
        assert np.max(np.abs(fun(xr))) < 1e-9
        worst = max(worst, np.max(np.abs(xr - xs[k])))
    assert worst < 2e-10, f"{name}: compiled vs scipy edge roots differ by {worst:.2e}"


def test_edge_contacts_reported_on_their_edge(case):
    """Every edge contact's point lies on its named boundary (compiled margin 0 to 1e-12); a corner's
    ("pinion/gear", "heel/top corner": the pinion's heel meets the gear's top; "pinion", "heel/fillet corner": the
    pinion flank's vertex) on both."""
    _, c1, c2, _, res = case
    for i, k, m, e in res.edges:
        j = list(res.pairs).index(k)
        assert res.status_pairs[i, j] == ContactStatus.EDGE
        mems = m.split("/")
        bnds = e.removesuffix(" corner").split("/")
        for mm, b in zip(mems * 2 if len(mems) == 1 else mems, bnds):
            surf, q = (c1, res.params1[i, j]) if mm == "pinion" else (c2, res.params2[i, j])
            g = _margins(surf, q[None])[0]
            assert abs(g[list(surf.boundary_names).index(b)]) < 1e-12
