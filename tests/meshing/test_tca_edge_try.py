"""The one-call compiled solve and screen of TCA's edge systems (``_core.tca_edge_screen.edge_try``) against the
separate steps it fuses, kept as the reference: the edge Newton (``solve_edge_contacts``), the margins of both points
(``margins_of``), the TE (``ContactProblem.gear_angle`` in numpy), the flank tests (the surfaces' ``contains``) and the
compiled screen, on many random systems around the edge contacts of the face-milled pair; and the whole TCA with the
fused call against the TCA that runs the separate steps. The same decisions and numbers, bit for bit: both evaluate
the same compiled functions in the same operation order."""

import dataclasses

import numpy as np
import pytest
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core import tca_edge_screen as ks
from spiralbevel.meshing import tca_edge as te_mod
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import surface_contains
from spiralbevel.meshing.generated_surface import EDGE_TOL, GeneratedSurface
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_edge_solve import (_H_TAU, _RCOND, compiled_args, corner_index, margins_of,
                                                solve_edge_contacts)
from spiralbevel.meshing.tca_result import ContactStatus


@pytest.fixture(scope="module")
def facemilled():
    c1, c2, kin = seed001_synthesized_pair()
    kw = dict(start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    return c1, c2, kin, kw, solve_tca(c1, c2, kin, **kw)


def _margins_only(monkeypatch):
    """The generated flank's ``contains`` as its margin test alone (no limit-line test ``on_sheet``): the flanks for
    which TCA runs the one-call edge solve (``compiled_args``)."""
    def contains(self, params):
        with np.errstate(invalid="ignore"):
            return np.all(self.boundary_margins(params) >= -EDGE_TOL, axis=-1)

    monkeypatch.setattr(GeneratedSurface, "contains", contains)
    monkeypatch.delattr(GeneratedSurface, "on_sheet")


def test_flanks_with_a_limit_line_test_run_the_separate_steps(facemilled):
    c1, c2, kin, _, _ = facemilled
    assert compiled_args(ContactProblem(c1, c2, kin))[5].tolist() == [-1.0, -1.0]


def _reference(prob, phi1, pairs, ii, jj, mem, ee, x0, floor, te_edge, x_edge, drive, phi2_mean, phi1_mean):
    """The separate steps (the TCA path of surfaces without a margin test as ``contains``)."""
    T1 = 2 * np.pi / prob.z1
    _, k1, K, _, _ = te_mod._setup(prob)
    xs, conv, ndot = solve_edge_contacts(prob, phi1[ii] + pairs[jj] * T1, x0, mem, ee, tol=1e-11)
    gg = [np.ascontiguousarray(margins_of(prob, m, xs[:, 2 * m:2 * m + 2])) for m in (0, 1)]
    with np.errstate(invalid="ignore"):
        te = drive * (-(prob.gear_angle(xs[:, 4], pairs[jj]) - phi2_mean) - prob.ratio * (phi1[ii] - phi1_mean))
    k = len(ii)
    C = [np.zeros(k, bool), np.zeros(k, bool)]
    ic = np.flatnonzero(conv)
    for m in (0, 1):
        C[m][ic] = surface_contains((prob.pinion, prob.gear)[m], xs[ic, 2 * m:2 * m + 2])
    out = [np.empty(k, bool)] + [np.empty(k, np.int64) for _ in range(4)] + [np.empty(k, bool) for _ in range(4)]
    ks.screen(gg[0], gg[1], mem, ee, k1, K, conv, ndot, np.ascontiguousarray(te), np.pi / prob.z2, 1e-9, C[0], C[1],
              ii, jj, xs, floor, te_edge, x_edge, np.empty(floor.shape, np.int64), *out)
    return xs, conv, ndot, gg, te, out


def test_edge_try_matches_the_separate_steps(facemilled, monkeypatch):
    c1, c2, kin, _, res = facemilled
    _margins_only(monkeypatch)
    prob = ContactProblem(c1, c2, kin)
    args = compiled_args(prob)
    assert args is not None and min(args[5]) > 0  # generated flanks: compiled jets, margins and contains
    rng = np.random.default_rng(13)
    n, P = res.te_pairs.shape
    phi1, pairs = res.phi1, res.pairs
    # starts: the TCA's solutions of every kind (edge, surface) perturbed, on random edges and corners
    x_all = np.concatenate([res.params1, res.params2, res.phi2_pairs[..., None]], -1)
    fin = np.argwhere(np.isfinite(x_all[..., 0]))
    m = 400
    pick = fin[rng.integers(0, len(fin), m)]
    ii, jj = pick[:, 0].astype(np.int64), pick[:, 1].astype(np.int64)
    x0 = x_all[ii, jj] - (2 * np.pi / prob.z2) * pairs[jj][:, None] * np.eye(5)[4]  # phi2 back to phi2_eff
    x0 = x0 + rng.normal(0.0, 1.0, (m, 5)) * np.array([0.02, 0.02, 0.02, 0.02, 0.002])
    mem = rng.integers(0, 2, m).astype(np.int64)
    ee = rng.integers(0, 4, m).astype(np.int64)
    cor = rng.random(m) < 0.25  # corners of random pairs of boundaries of both members
    a = rng.integers(0, 8, m)
    b = rng.integers(0, 8, m)
    for r in np.flatnonzero(cor & (a != b)):
        mem[r], ee[r] = 0, corner_index(prob, (a[r] // 4, a[r] % 4), (b[r] // 4, b[r] % 4))
    floor = np.where(rng.random((n, P)) < 0.3, rng.normal(0.0, 1e-4, (n, P)), -np.inf)
    te0 = np.where(rng.random((n, P)) < 0.3, rng.normal(0.0, 1e-4, (n, P)), np.nan)
    x_e0 = np.where(np.isfinite(te0)[..., None], rng.normal(size=(n, P, 5)), np.nan)
    drive, phi2_mean, phi1_mean = res.drive_sign, res.phi2_mean, res.phi1_mean
    te_r, xe_r = te0.copy(), x_e0.copy()
    xs_r, conv_r, nd_r, gg_r, tev_r, out_r = _reference(prob, phi1, pairs, ii, jj, mem, ee, x0, floor, te_r, xe_r,
                                                         drive, phi2_mean, phi1_mean)
    # the fused call
    kinds, p1, mp1, p2, mp2, ctol = args
    d, M2, _ = prob._const
    phi_eff = phi1[ii] + pairs[jj] * (2 * np.pi / prob.z1)
    tep = np.array([drive, phi2_mean, prob.ratio, phi1_mean, prob.z2, np.pi / prob.z2])
    xs = np.array(x0, order="C")
    te_f, xe_f = te0.copy(), x_e0.copy()
    G0, G1, tev, conv, nd = np.empty((m, 4)), np.empty((m, 4)), np.empty(m), np.empty(m, bool), np.empty(m)
    out = [np.empty(m, bool)] + [np.empty(m, np.int64) for _ in range(4)] + [np.empty(m, bool) for _ in range(4)]
    ks.edge_try(kinds, p1, mp1, p2, mp2, ctol, np.cos(phi_eff), np.sin(phi_eff), xs, mem, ee, d, M2, _H_TAU, 1e-11,
                30, _RCOND, 1, tep, np.ascontiguousarray(phi1), pairs.astype(float), ii, jj, floor, te_f, xe_f,
                np.empty((n, P), np.int64), G0, G1, tev, conv, nd, *out)
    # the random systems cover converged and failed solves, accepted and rejected rows, edges and corners
    assert 0.1 * m < conv.sum() < m and out_r[7].sum() > 5 and cor.sum() > 50
    assert np.array_equal(xs, xs_r, equal_nan=True) and np.array_equal(conv, conv_r)
    assert np.array_equal(nd, nd_r, equal_nan=True)
    assert np.array_equal(G0, gg_r[0], equal_nan=True) and np.array_equal(G1, gg_r[1], equal_nan=True)
    assert np.array_equal(tev, tev_r, equal_nan=True)
    for u, v in zip(out, out_r):
        assert np.array_equal(u, v)
    assert np.array_equal(te_f, te_r, equal_nan=True) and np.array_equal(xe_f, xe_r, equal_nan=True)


def test_tca_with_the_fused_call_equals_the_separate_steps(facemilled, monkeypatch):
    """Whole TCA, aligned and misaligned (more edge contacts), with and without the fused call: identical results."""
    c1, c2, kin, kw, _ = facemilled
    _margins_only(monkeypatch)
    assert min(compiled_args(ContactProblem(c1, c2, kin))[5]) > 0
    mis = Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04, shaft_angle=0.0)
    fused = [solve_tca(c1, c2, kin, **kw), solve_tca(c1, c2, kin, misalignment=mis, **kw)]
    monkeypatch.setattr(te_mod, "compiled_args", lambda prob: None)
    steps = [solve_tca(c1, c2, kin, **kw), solve_tca(c1, c2, kin, misalignment=mis, **kw)]
    for a, b in zip(fused, steps):
        assert np.sum(a.status_pairs == ContactStatus.EDGE) >= 5  # edge contacts are exercised
        assert a.edges == b.edges
        for f in dataclasses.fields(a):
            u, v = getattr(a, f.name), getattr(b, f.name)
            if isinstance(u, np.ndarray):
                assert np.array_equal(u, v, equal_nan=True), f.name
