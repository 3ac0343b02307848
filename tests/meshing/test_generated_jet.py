"""The compiled jet of the face-milled generated flank (``_core.generation_blade_jet``, kind GENERATED of
``_core.jets``) against the numpy closed form ``_core.generation_blade.blade_jet``, and TCA of the face-milled pair
with and without it."""

import dataclasses

import numpy as np
import pytest
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core import generation as _g
from spiralbevel._core import generation_blade_jet as _gbj
from spiralbevel._core import jets as _jets
from spiralbevel._core.generation_blade import blade_jet
from spiralbevel._core.rotations import rot_z
from spiralbevel.conventions import Hand
from spiralbevel.generation import generate_flank
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings
from spiralbevel.meshing.generated_surface import GeneratedSurface
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ContactStatus

#: both forms evaluate the same expressions in a different order (Horner vs numpy.polyval, per-point Newton stop vs
#: batch stop of the arc blade): differences are a few ulp of the point coordinates (|r| ~ 100 mm, ulp ~ 1.4e-14 mm)
TOL_R, TOL_N = 1e-12, 1e-13


def _reference(q, cp, mp, mirror, rotation):
    """numpy jet in the member's own frame: blade_jet, then the mirror (right hand) and the phasing turn."""
    with np.errstate(all="ignore"):
        S, u, _ = blade_jet(q[:, 0], q[:, 1], cp, mp)
    Rm = rot_z(rotation) * np.array([1.0, -1.0, 1.0]) if mirror else rot_z(rotation)
    return Rm @ S, u


def _compiled(q, cp, mp, mirror, rotation):
    prm = _gbj.parameters(cp, mp, mirror, rotation)
    out, u = np.empty((len(q), 3, 6)), np.empty(len(q))
    _gbj.jet_batch(prm, np.ascontiguousarray(q), out, u)
    # the TCA dispatch gives the same jet
    one = np.empty((3, 6))
    _jets.surface_jet(_jets.GENERATED, prm, q[0, 0], q[0, 1], one)
    assert np.array_equal(one, out[0], equal_nan=True)
    return out, u


def _compare(S, u, S0, u0, scale):
    ok = np.isfinite(u0)
    assert ok.sum() > 0.8 * len(u0)
    assert np.array_equal(np.isfinite(u), ok)
    assert np.all(np.isnan(S[~ok]))
    d = np.abs(S[ok] - S0[ok])
    # point columns scale with |r| (mm); normal columns are of order 1
    assert d[:, :, [0, 2, 3]].max() <= TOL_R * scale and d[:, :, [1, 4, 5]].max() <= TOL_N * max(scale / 100, 1.0)
    assert np.abs(u[ok] - u0[ok]).max() <= TOL_R * scale


@pytest.fixture(scope="module")
def seed001_flanks():
    b = seed001_blank()
    st = seed001_settings()
    out = []
    for key, (cutter, settings) in st.items():
        out.append(generate_flank(cutter, settings, b, *key))
        # the same flank cut with circular-arc blades (profile radius 400 mm through the blade point 3 mm deep)
        arc = dataclasses.replace(cutter, profile_radius=400.0, profile_ref=3.0)
        out.append(generate_flank(arc, settings, b, *key))
    return out


def test_compiled_jet_matches_numpy_on_seed001_flanks(seed001_flanks):
    """Both members (left-hand gear, right-hand pinion), seed 001 straight blades and the same flanks cut with arc
    blades, two phasing turns, 500 random (phi, psi_c) each, through ``GeneratedSurface`` (the public path TCA and
    ``derivatives`` use)."""
    hands, arcs = set(), 0
    rng = np.random.default_rng(13)
    for fl in seed001_flanks:
        gen = fl.generator
        hands.add(gen.hand)
        arcs += np.isfinite(gen.cp["rp"])
        for rot in (0.0, 2.1):
            s = GeneratedSurface(fl, rotation=rot)
            q = s.reference_params + rng.uniform(-0.3, 0.3, size=(500, 2))
            S0, u0 = _reference(q, gen.cp, gen.mp, gen.hand is Hand.RIGHT, rot)
            r, n, dr, dn = s.derivatives(q)
            S = np.concatenate([r[..., None], n[..., None], dr, dn], -1)
            _, u, _ = s._jet(q)
            _compare(S, u, S0, u0, 200.0)
            kind, prm = s.jet
            ref = _gbj.parameters(gen.cp, gen.mp, gen.hand is Hand.RIGHT, rot)
            assert kind == _jets.GENERATED and np.array_equal(prm, ref, equal_nan=True)
    assert hands == {Hand.LEFT, Hand.RIGHT} and arcs == 2


def _machine_cases():
    """Straight and arc blades, both blade sides, with every machine motion of the kernel: modified roll, offset
    polynomial, cubic and piecewise-linear offset tables (nodes off the sample grid and at psi_c = 0), a scalar
    offset rate; and a plain machine (no motion terms)."""
    plain = dict(S=62.0, q=1.0, gamma=0.45, XD=0.3, XB=0.2, E=1.5, m=2.1, roll=(), E_poly=())
    full = dict(plain, roll=(0.05, -0.2, 0.4, 0.1), E_poly=(0.3, -0.8),
                E_table=(np.array([-0.37, 0.13, 0.41]), np.array([0.0, 0.02, -0.01]), np.array([0.0, 0.3, 0.0])))
    linear = dict(plain, roll=(0.07,), E_table=(np.array([-0.2, 0.0, 0.25]), np.array([0.01, 0.0, -0.02])),
                  E_rate=0.4)
    for s_blade in (1.0, -1.0):
        for rp in (np.inf, 400.0):
            cp = _g.cutter_params(s_blade, 0.35, 60.0, 1.2, profile_radius=rp, profile_ref=3.0)
            for mp in (plain, full, linear):
                yield cp, mp


def test_compiled_jet_matches_numpy_with_arc_blades_and_machine_motions():
    rng = np.random.default_rng(7)
    for cp, mp in _machine_cases():
        Rc = 60.0
        psi = rng.uniform(-0.35, 0.35, 400)
        psi[:5] = [0.0, 0.13, -0.2, 0.25, 0.41]  # table nodes: the side rule of the linear law
        phi = _g.reference_angle(psi, mp, Rc) + rng.uniform(-0.25, 0.25, 400)
        q = np.stack([phi, psi], -1)
        for mirror, rot in ((False, 0.0), (True, -0.8)):
            S, u = _compiled(q, cp, mp, mirror, rot)
            S0, u0 = _reference(q, cp, mp, mirror, rot)
            _compare(S, u, S0, u0, 100.0)


def test_singular_chart_and_per_system_offsets():
    cp = _g.cutter_params(1.0, 0.35, 60.0, 1.2)
    mp = dict(S=62.0, q=1.0, gamma=0.45, XD=0.3, XB=0.2, E=1.5, m=2.1, roll=(), E_poly=())
    # phi = 0: the blade parameter's coefficient Omega_x sin(phi) vanishes, u is not finite, the jet is NaN
    S, u = _compiled(np.array([[0.0, 0.1]]), cp, mp, False, 0.0)
    assert not np.isfinite(u[0]) and np.all(np.isnan(S))
    # an offset law per system (arrays, batched synthesis) has no compiled jet: the caller keeps the numpy form
    assert _gbj.parameters(cp, dict(mp, E=np.array([1.0, 2.0])), False, 0.0) is None
    assert _gbj.parameters(cp, dict(mp, E_rate=np.array([0.1, 0.2])), False, 0.0) is None


class _NumpyJet(GeneratedSurface):
    """The same flank without a compiled jet: TCA evaluates it with the numpy closed form between compiled steps."""

    jet = None

    def _prm(self):
        return None


def test_tca_roots_identical_with_and_without_the_compiled_jet():
    """Seed 001 synthesized drive pair (41 positions x 3 pairs, edge contacts included) through the fully compiled
    Newton and through the mixed path with numpy flank evaluation: the same roots."""
    c1, c2, kin = seed001_synthesized_pair()
    assert c1.jet is not None and c2.jet is not None
    n1, n2 = _NumpyJet(c1.flank, c1.rotation), _NumpyJet(c2.flank, c2.rotation)
    start = np.r_[c1.reference_params, c2.reference_params, 0.0]
    a = solve_tca(c1, c2, kin, n_positions=41, start=start)
    b = solve_tca(n1, n2, kin, n_positions=41, start=start)
    assert np.array_equal(a.status_pairs, b.status_pairs) and np.array_equal(a.pair, b.pair)
    ok = a.status_pairs == ContactStatus.OK
    edge = a.status_pairs == ContactStatus.EDGE
    assert ok.sum() > 40 and edge.sum() > 0
    for name in ("params1", "params2", "phi2_pairs"):
        x, y = getattr(a, name), getattr(b, name)
        assert np.array_equal(np.isfinite(x), np.isfinite(y))
        # real contacts: the same iterates up to round-off of the jets (measured 2e-15 rad)
        assert np.max(np.abs(x - y)[ok]) < 1e-12, name
        # EDGE pairs are solutions of the analytically extended flanks off the real flank (never reported); their
        # systems are less well conditioned there, the round-off of the jets shows at ~1e-12 rad (measured 1.3e-12)
        assert np.max(np.abs(x - y)[edge]) < 1e-11, name
    assert np.nanmax(np.abs(a.te_pairs - b.te_pairs)) < 1e-14  # rad; measured 6e-16
    assert np.array_equal(np.isfinite(a.semi_axes), np.isfinite(b.semi_axes))
    assert np.nanmax(np.abs(a.semi_axes - b.semi_axes)) < 1e-12  # mm; measured 8e-14
