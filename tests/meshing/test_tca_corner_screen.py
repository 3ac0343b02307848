"""The proof that TCA's corner of the pinion's fillet junction against the gear's toe, heel or top edge has no root
(``_core.tca_corner_screen``), checked independently: the junction curve against the numpy reference of the generated
flank, the proof's verdict against a dense brute-force sampling of the gear margin along that curve (the numpy
outline and the pair's pose), the corner Newton without the proof against it, and TCA with and without it bit for
bit."""

import dataclasses

import numpy as np
import pytest
from _interference_pair import coast_pair as interference_pair
from _limit_line_pair import coast_pair as limit_line_pair
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core import tca_corner_screen as kc
from spiralbevel._core.generation_blade import blade_jet
from spiralbevel.meshing import tca_edge_solve as tes
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_edge_solve import corner_index, junction_samples, solve_edge_contacts

_PAIRS = {"seed001": seed001_synthesized_pair, "folded": interference_pair, "limit_line": limit_line_pair}
_CACHE = {}
_MIS = Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04, shaft_angle=0.0)


def _pair(name):
    if name not in _CACHE:
        c1, c2, kin = _PAIRS[name]()
        _CACHE[name] = (c1, c2, kin, dict(start=np.r_[c1.reference_params, c2.reference_params, 0.0]))
    return _CACHE[name]


def _codes(prob):
    """The corner codes of the pinion's fillet junction with the gear's toe, heel and top."""
    return [corner_index(prob, (0, kc.FILLET), (1, e)) for e in range(3)]


def _reference_u_R(surface, q):
    """Blade parameter u (mm) and cone distance R (mm) at (phi, psi_c) ``q (k, 2)`` by the numpy reference."""
    gen, ol = surface.flank.generator, surface.flank.outline
    with np.errstate(invalid="ignore", divide="ignore"):
        S, u, _ = blade_jet(q[:, 0], q[:, 1], gen.cp, gen.mp)
    r = S[:, :, 0]
    return u, ol.Rh(r[:, 2], np.hypot(r[:, 0], r[:, 1]))[0], r @ surface._Rm.T


def _dense_junction(surface, q0, R):
    """Junction points (k, 3) mm (member frame) at cone distances ``R (k,)``: u = u_j and R(q) = R solved by a
    vectorized Newton on the numpy reference with central differences, from the starts ``q0 (k, 2)``."""
    u_j, h = surface.flank.generator.cp["u_j"], 1e-6
    q = q0.copy()
    for _ in range(20):
        u, Rq, _ = _reference_u_R(surface, q)
        F = np.stack([u - u_j, Rq - R], -1)
        if np.max(np.abs(F)) < 1e-10:
            break
        J = np.empty((len(q), 2, 2))
        for j in range(2):
            e = np.zeros(2)
            e[j] = h
            up, Rp, _ = _reference_u_R(surface, q + e)
            um, Rm, _ = _reference_u_R(surface, q - e)
            J[:, 0, j], J[:, 1, j] = (up - um) / (2 * h), (Rp - Rm) / (2 * h)
        q = q - np.linalg.solve(J, F[..., None])[..., 0]
    u, Rq, P = _reference_u_R(surface, q)
    assert np.max(np.abs(u - u_j)) < 1e-9 and np.max(np.abs(Rq - R)) < 1e-9
    return P, q


def _gear_margin(prob, P, phi1, e):
    """Gear margin e (0 toe, 1 heel, 2 top) at the pinion points P (k, 3) at rotation phi1, by the numpy outline of
    the gear and the pair's pose (the gear frame at phi2 = 0; the margins do not depend on phi2)."""
    R1, R2, o1, o2 = prob.pose(np.array([phi1]), np.array([0.0]))
    v = (o1[0] + P @ R1[0].T - o2[0]) @ R2[0]
    ol = prob.gear.flank.outline
    R, h = ol.Rh(v[:, 2], np.hypot(v[:, 0], v[:, 1]))
    return [R - ol.Ri, ol.Re - R, ol.h_face(R) - h][e]


@pytest.mark.parametrize("name", ["seed001", "folded"])
def test_junction_curve_against_the_numpy_reference(name):
    c1, c2, kin, _ = _pair(name)
    prob = ContactProblem(c1, c2, kin)
    P = junction_samples(prob, np.array([0]), np.array([_codes(prob)[2]]))
    assert P.shape == (kc.N_SAMPLES, 3)
    ol = c1.flank.outline
    w = ol.Re - ol.Ri
    R = np.linspace(ol.Ri - kc.BEYOND * w, ol.Re + kc.BEYOND * w, kc.N_SAMPLES)
    Pd, _ = _dense_junction(c1, c1._junction_src[2], R)
    # the same points to the Newton tolerances (1e-11 of the margins; the reference's own derivatives are
    # differences)
    assert np.max(np.abs(Pd - P)) < 1e-8


@pytest.mark.parametrize("name, mis", [("seed001", None), ("seed001", _MIS), ("folded", None)])
def test_proof_against_dense_sampling(name, mis):
    """At 24 pinion rotations over two mesh cycles and for each gear boundary: where the proof excludes a corner,
    the gear margin at 16 times denser points of the junction curve keeps one sign and stays clear of zero; both
    verdicts occur."""
    c1, c2, kin, _ = _pair(name)
    prob = ContactProblem(c1, c2, kin, mis)
    codes = _codes(prob)
    P = junction_samples(prob, np.array([0]), np.array([codes[2]]))
    ol = c1.flank.outline
    w = ol.Re - ol.Ri
    k = 16 * (kc.N_SAMPLES - 1) + 1
    R = np.linspace(ol.Ri - kc.BEYOND * w, ol.Re + kc.BEYOND * w, k)
    qs = c1._junction_src[2]   # the proof's samples' parameters: starts of the dense solve
    q0 = np.stack([np.interp(np.arange(k) / 16, np.arange(kc.N_SAMPLES), qs[:, j]) for j in (0, 1)], -1)
    Pd, _ = _dense_junction(c1, q0, R)
    d, M2, _ = prob._const
    verdicts = []
    for phi1 in np.linspace(-2, 2, 24) * 2 * np.pi / prob.z1:
        for e in range(3):
            ex = kc.corner_excluded(P, np.cos(phi1), np.sin(phi1), d, M2, c2.boundary_jet[1], e)
            f = _gear_margin(prob, Pd, phi1, e)
            verdicts.append(ex)
            if ex:
                assert np.all(f > 1e-9) or np.all(f < -1e-9), (phi1, e)
            # a sign change of the dense samples: never proved absent
            if np.any(f > 0) and np.any(f < 0):
                assert not ex
    assert any(verdicts) and not all(verdicts)


@pytest.mark.parametrize("name", ["seed001", "folded"])
def test_corner_newton_finds_no_root_where_the_proof_excludes_one(name, monkeypatch):
    """The corner systems (pinion fillet junction, gear toe/heel/top) from random starts around the flank at random
    rotations, solved without the proof: where the proof excludes a root on the sampled stretch, the Newton converges
    nowhere on it."""
    c1, c2, kin, _ = _pair(name)
    monkeypatch.setattr(tes, "CORNER_PROOF", False)
    prob = ContactProblem(c1, c2, kin)
    codes = _codes(prob)
    rng = np.random.default_rng(3)
    m = 300
    phi1 = rng.uniform(-1.5, 1.5, m) * 2 * np.pi / prob.z1
    x0 = np.concatenate([c1.reference_params + rng.normal(0, 0.05, (m, 2)),
                         c2.reference_params + rng.normal(0, 0.05, (m, 2)), -prob.ratio * phi1[:, None]], -1)
    e = rng.integers(0, 3, m)
    x, conv, _ = solve_edge_contacts(prob, phi1, x0, np.zeros(m, int), np.array(codes)[e], tol=1e-11)
    monkeypatch.setattr(tes, "CORNER_PROOF", True)
    P = junction_samples(ContactProblem(c1, c2, kin), np.array([0]), np.array([codes[2]]))
    d, M2, _ = prob._const
    ex = np.array([kc.corner_excluded(P, np.cos(p), np.sin(p), d, M2, c2.boundary_jet[1], k) for p, k in zip(phi1, e)])
    ol = c1.flank.outline
    w = ol.Re - ol.Ri
    r = c1.evaluate(x[:, 0:2])[0]
    R = ol.Rh(r[:, 2], np.hypot(r[:, 0], r[:, 1]))[0]
    on_stretch = (R >= ol.Ri - kc.BEYOND * w) & (R <= ol.Re + kc.BEYOND * w)
    assert ex.sum() >= 3 and (conv & ~ex).sum() >= 3, (ex.sum(), (conv & ~ex).sum())   # both kinds occur
    assert not np.any(conv & ex & on_stretch)


@pytest.mark.parametrize("name, mis, n", [("seed001", None, 41), ("seed001", _MIS, 41), ("folded", None, 41),
                                          ("folded", _MIS, 81), ("limit_line", None, 81)])
def test_tca_with_and_without_the_proof_bit_for_bit(name, mis, n, monkeypatch):
    c1, c2, kin, kw = _pair(name)
    try:
        a = solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, **kw)
    except Exception as err:   # no contact of the misaligned pair: the same without the proof
        monkeypatch.setattr(tes, "CORNER_PROOF", False)
        with pytest.raises(type(err)):
            solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, **kw)
        return
    monkeypatch.setattr(tes, "CORNER_PROOF", False)
    b = solve_tca(c1, c2, kin, misalignment=mis, n_positions=n, **kw)
    assert a.edges == b.edges
    for f in dataclasses.fields(a):
        u, v = getattr(a, f.name), getattr(b, f.name)
        if isinstance(u, np.ndarray):
            assert np.array_equal(u, v, equal_nan=True), f.name
