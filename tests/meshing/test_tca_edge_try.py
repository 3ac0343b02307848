"""The one-call compiled solve and screen of TCA's edge systems (``_core.tca_edge_screen.edge_try``) against the
separate steps it fuses, kept as the reference: the edge Newton (``solve_edge_contacts``), the limit-line test of the
generated flanks (``on_sheet``), the margins of both points (``margins_of``), the TE (``ContactProblem.gear_angle`` in
numpy), the flank tests (the surfaces' ``contains``) and the compiled screen, on many random systems around the edge
contacts of the face-milled pair and of a pair whose gear flank folds past a limit line of generation; and the whole
TCA with the fused call against the TCA that runs the separate steps. The same decisions and numbers, bit for bit:
both evaluate the same compiled functions in the same operation order."""

import dataclasses

import numpy as np
import pytest
from _interference_pair import coast_pair as interference_pair
from _limit_line_pair import coast_pair as limit_line_pair
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core import tca_edge_screen as ks
from spiralbevel.meshing import tca_edge as te_mod
from spiralbevel.meshing import tca_edge_solve as tes_mod
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import surface_contains, surface_on_sheet
from spiralbevel.meshing.generated_surface import EDGE_TOL, GeneratedSurface, _orientation
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_edge_solve import (_H_TAU, _RCOND, compiled_args, corner_index, junction_samples,
                                                margins_of, solve_edge_contacts)
from spiralbevel.meshing.tca_result import ContactStatus

_PAIRS = {"seed001": seed001_synthesized_pair, "folded": interference_pair, "limit_line": limit_line_pair}
_CACHE = {}


def _pair(name):
    """(pinion, gear, kinematics, solve_tca keywords, TCA result) of a named pair, built once per session."""
    if name not in _CACHE:
        c1, c2, kin = _PAIRS[name]()
        kw = dict(start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        _CACHE[name] = (c1, c2, kin, kw, solve_tca(c1, c2, kin, **kw))
    return _CACHE[name]


def _margins_only(monkeypatch):
    """The generated flank's ``contains`` as its margin test alone (no limit-line test ``on_sheet``)."""
    def contains(self, params):
        with np.errstate(invalid="ignore"):
            return np.all(self.boundary_margins(params) >= -EDGE_TOL, axis=-1)

    monkeypatch.setattr(GeneratedSurface, "contains", contains)
    monkeypatch.delattr(GeneratedSurface, "on_sheet")


def test_generated_flanks_run_the_fused_call_with_their_limit_line_test():
    c1, c2, kin, _, _ = _pair("seed001")
    ctol = compiled_args(ContactProblem(c1, c2, kin))[5]
    assert ctol[:2].tolist() == [EDGE_TOL, EDGE_TOL]
    # the sheet sign of each flank: that of the orientation at its mean point, by the numpy form
    for c, s in zip((c1, c2), ctol[2:]):
        S = c.derivatives(c.reference_params[None])
        o = _orientation(np.concatenate([S[0][..., None], S[1][..., None], S[2], S[3]], -1))[0]
        assert s == np.sign(o) and abs(s) == 1.0


def test_orientation_kernel_matches_numpy():
    rng = np.random.default_rng(5)
    S = rng.normal(size=(200, 3, 6))
    ref = _orientation(S)
    assert np.array_equal(np.array([ks.orientation(s) for s in S]), ref)


def _random_systems(prob, res, m=400):
    """Random edge and corner systems around the TCA's solutions ``res`` of every kind (edge, surface), perturbed,
    on random edges and corners, with random acceptance floors and previous contacts:
    (m, ii, jj, x0, member, edge, corner, floor, te_edge, x_edge)."""
    rng = np.random.default_rng(13)
    n, P = res.te_pairs.shape
    pairs = res.pairs
    x_all = np.concatenate([res.params1, res.params2, res.phi2_pairs[..., None]], -1)
    fin = np.argwhere(np.isfinite(x_all[..., 0]))
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
    return m, ii, jj, x0, mem, ee, cor, floor, te0, x_e0


def _reference(prob, phi1, pairs, ii, jj, mem, ee, x0, floor, te_edge, x_edge, drive, phi2_mean, phi1_mean):
    """The separate steps (the TCA path without the fused call): the Newton, then a converged solution off the sheet
    of either flank counts as not converged, the flank tests are the surfaces' ``contains``."""
    T1 = 2 * np.pi / prob.z1
    _, k1, K, _, _ = te_mod._setup(prob)
    xs, conv_newton, ndot = solve_edge_contacts(prob, phi1[ii] + pairs[jj] * T1, x0, mem, ee, tol=1e-11)
    conv = conv_newton & surface_on_sheet(prob.pinion, xs[:, 0:2]) & surface_on_sheet(prob.gear, xs[:, 2:4])
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
    return xs, conv_newton, conv, ndot, gg, te, out


@pytest.mark.parametrize("name, sheet", [("seed001", True), ("folded", True), ("folded", False)])
def test_edge_try_matches_the_separate_steps(name, sheet, monkeypatch):
    c1, c2, kin, _, res = _pair(name)
    if not sheet:
        _margins_only(monkeypatch)
    prob = ContactProblem(c1, c2, kin)
    args = compiled_args(prob)
    assert args is not None and min(args[5][:2]) > 0  # generated flanks: compiled jets, margins and contains
    assert (np.abs(args[5][2:]) == 1.0).all() if sheet else (args[5][2:] == 0.0).all()
    n, P = res.te_pairs.shape
    phi1, pairs = res.phi1, res.pairs
    m, ii, jj, x0, mem, ee, cor, floor, te0, x_e0 = _random_systems(prob, res)
    drive, phi2_mean, phi1_mean = res.drive_sign, res.phi2_mean, res.phi1_mean
    te_r, xe_r = te0.copy(), x_e0.copy()
    xs_r, convn_r, conv_r, nd_r, gg_r, tev_r, out_r = _reference(prob, phi1, pairs, ii, jj, mem, ee, x0, floor, te_r,
                                                                  xe_r, drive, phi2_mean, phi1_mean)
    # the fused call
    kinds, p1, mp1, p2, mp2, ctol = args
    d, M2, _ = prob._const
    phi_eff = phi1[ii] + pairs[jj] * (2 * np.pi / prob.z1)
    tep = np.array([drive, phi2_mean, prob.ratio, phi1_mean, prob.z2, np.pi / prob.z2])
    xs = np.array(x0, order="C")
    te_f, xe_f = te0.copy(), x_e0.copy()
    G0, G1, tev, conv, nd = np.empty((m, 4)), np.empty((m, 4)), np.empty(m), np.empty(m, bool), np.empty(m)
    out = [np.empty(m, bool)] + [np.empty(m, np.int64) for _ in range(4)] + [np.empty(m, bool) for _ in range(4)]
    ks.edge_try(kinds, p1, mp1, p2, mp2, ctol, junction_samples(prob, mem, ee), np.cos(phi_eff), np.sin(phi_eff), xs,
                mem, ee, d, M2, _H_TAU, 1e-11,
                30, _RCOND, 1, tep, np.ascontiguousarray(phi1), pairs.astype(float), ii, jj, floor, te_f, xe_f,
                np.empty((n, P), np.int64), G0, G1, tev, conv, nd, *out)
    # the random systems cover converged and failed solves, accepted and rejected rows, edges and corners, and on the
    # folded pair converged solutions past its limit line
    assert 0.1 * m < conv.sum() < m and out_r[7].sum() > 5 and cor.sum() > 50
    if name == "folded" and sheet:
        assert (convn_r & ~conv_r).sum() >= 20, (convn_r & ~conv_r).sum()
    assert np.array_equal(xs, xs_r, equal_nan=True) and np.array_equal(conv, conv_r)
    assert np.array_equal(nd, nd_r, equal_nan=True)
    assert np.array_equal(G0, gg_r[0], equal_nan=True) and np.array_equal(G1, gg_r[1], equal_nan=True)
    assert np.array_equal(tev, tev_r, equal_nan=True)
    for u, v in zip(out, out_r):
        assert np.array_equal(u, v)
    assert np.array_equal(te_f, te_r, equal_nan=True) and np.array_equal(xe_f, xe_r, equal_nan=True)


_MIS = Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04, shaft_angle=0.0)


@pytest.mark.parametrize("name, mis, n", [("seed001", None, 41), ("seed001", _MIS, 41), ("folded", None, 41),
                                          ("limit_line", None, 81)])
def test_tca_with_the_fused_call_equals_the_separate_steps(name, mis, n, monkeypatch):
    """Whole TCA, aligned and misaligned (more edge contacts), and on the two pairs whose gear flank folds (the
    contact runs onto the fold), with and without the fused call: identical results."""
    c1, c2, kin, kw, _ = _pair(name)
    assert min(compiled_args(ContactProblem(c1, c2, kin))[5][:2]) > 0
    fused = solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, **kw)
    monkeypatch.setattr(te_mod, "compiled_args", lambda prob: None)
    steps = solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, **kw)
    if name == "seed001":
        assert np.sum(fused.status_pairs == ContactStatus.EDGE) >= 5  # edge contacts are exercised
    assert fused.edges == steps.edges
    for f in dataclasses.fields(fused):
        u, v = getattr(fused, f.name), getattr(steps, f.name)
        if isinstance(u, np.ndarray):
            assert np.array_equal(u, v, equal_nan=True), f.name


@pytest.mark.parametrize("name", ["seed001", "folded"])
def test_edge_newton_sharing_the_jet_of_the_margins_changes_nothing(name, monkeypatch):
    """The margins of a generated flank evaluate its own jet (``_shares``: the same parameters, NaN slots of a straight
    blade included): the edge Newton then reads the jet from the margins' evaluation instead of evaluating it twice,
    with the same roots bit for bit."""
    c1, c2, kin, _, res = _pair(name)
    prob = ContactProblem(c1, c2, kin)
    assert te_mod._setup(prob)[4] == (True, True)
    m, ii, jj, x0, mem, ee, _, _, _, _ = _random_systems(prob, res)
    phi_eff = res.phi1[ii] + res.pairs[jj] * (2 * np.pi / prob.z1)
    shared = solve_edge_contacts(prob, phi_eff, x0, mem, ee, tol=1e-11)
    monkeypatch.setattr(tes_mod, "_shares", lambda *a: False)
    prob = ContactProblem(c1, c2, kin)
    assert te_mod._setup(prob)[4] == (False, False)
    twice = solve_edge_contacts(prob, phi_eff, x0, mem, ee, tol=1e-11)
    assert 0.1 * m < shared[1].sum() < m
    for u, v in zip(shared, twice):
        assert np.array_equal(u, v, equal_nan=True)


@pytest.mark.parametrize("name", ["seed001", "folded"])
def test_compiled_flank_test_equals_contains(name):
    """``flank_contains`` (the compiled margins and limit-line test, as the edge screen applies them) against the
    generated flank's own ``contains`` (margins, then ``on_sheet`` by numpy) on random points around and beyond both
    flanks: inside, past every boundary, past the limit line (the folded gear) and off the chart (NaN)."""
    c1, c2, kin, _, res = _pair(name)
    rng = np.random.default_rng(7)
    for c, q in ((c1, res.params1), (c2, res.params2)):
        q = q[np.isfinite(q[..., 0])]
        lo, hi = q.min(0), q.max(0)
        w = hi - lo
        pts = lo - 0.5 * w + rng.random((4000, 2)) * 2.0 * w
        ref = c.contains(pts)
        got = tes_mod.flank_contains(c, pts)
        assert 200 < ref.sum() < 3800
        assert np.array_equal(got, ref)
    off = ~c2.on_sheet(pts) & np.all(c2.boundary_margins(pts) >= 0, -1)
    assert off.any() == (name == "folded")
