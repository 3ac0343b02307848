"""Loaded TCA of a hypoid pair with FE tooth compliance: the tooth segments of both members are built in their own
member frames and placed by the offset kinematics (ISO 23509 Sample 2, pinion concave by hypoid local synthesis,
coarse 9 x 6 FE flank grids).

Checks: offset zero through the hypoid path gives the spiral bevel FE loaded TCA to round-off; the contact forces
(along the common normals) balance the gear torque about the wheel axis, and their moment about the pinion's own
(offset) axis is the gear torque times the instantaneous velocity ratio of the unloaded TCA; the loaded TE tends to
the unloaded TE as the torque vanishes; at a one-pair position the peak pressure is Hertz's."""

import dataclasses
import math
import types
import warnings
from pathlib import Path

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.gearset.facemilled import tooth_rotation
from spiralbevel.gearset.ltca import _tooth_grids
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks, phased_for_hypoid_pair
from spiralbevel.meshing.ltca import ltca_model
from spiralbevel.meshing.ltca.ltca import ContactPosition
from spiralbevel.meshing.pair import meshing_pair
from spiralbevel.meshing.synthesis.hypoid_local import synthesize_hypoid_pinion, tca_surfaces
from spiralbevel.meshing.tca import solve_tca
from _hypoid_sample2 import SAMPLE2

pytest.importorskip("skfem")

DATA = Path(__file__).parents[3] / "src" / "spiralbevel" / "data"
FE_GRID = (9, 6)   # coarse FE flank grids: the checks below hold for any mesh (balance, limits, identity at E = 0)


def _grids(blank, flanks, c1, c2, s1=Side.CONCAVE, s2=Side.CONVEX):
    """(convex, concave) FE grids of one tooth of each member in the frames of the TCA surfaces c1, c2."""
    setups = {k: types.SimpleNamespace(flank=f) for k, f in flanks.items()}
    pts = {k: f.grid(*FE_GRID, curvature=False).points for k, f in flanks.items()}
    return (_tooth_grids(pts, Member.PINION, s1, c1.rotation, tooth_rotation(blank, setups, Member.PINION)),
            _tooth_grids(pts, Member.GEAR, s2, c2.rotation, tooth_rotation(blank, setups, Member.GEAR)))


@pytest.fixture(scope="module")
def fe_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("fe")


def _sample2(fe_dir, hand="LH"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        blank = compute_blank(BlankInput(**SAMPLE2, hand1=hand))
    basic = hypoid_basic_flanks(blank)
    c, s, _, _ = basic[(Member.PINION, Side.CONCAVE)]
    syn = synthesize_hypoid_pinion(basic[(Member.GEAR, Side.CONVEX)][2], c, s, blank, eta=math.radians(40.0),
                                   semi_major_axis=4.5, te_magnitude=8.0 * math.pi / 648000.0)
    c1, c2, start = tca_surfaces(syn)
    tca = solve_tca(c1, c2, syn.kinematics, n_positions=11, start=start)
    flanks = {k: v[2] for k, v in basic.items()}
    flanks[(Member.PINION, Side.CONCAVE)] = syn.pinion_flank
    pin, gear = _grids(blank, flanks, c1, c2)
    kw = dict(pinion_grids=pin, gear_grids=gear, sides=("concave", "convex"), cache_dir=fe_dir)
    return dict(syn=syn, c1=c1, c2=c2, tca=tca, kw=kw,
                model=ltca_model(c1, c2, syn.kinematics, tca, grid=(15, 5), **kw))


@pytest.fixture(scope="module")
def hypoid(fe_dir):
    return _sample2(fe_dir)


def test_zero_offset_through_the_hypoid_path_is_the_spiral_bevel_fe_ltca(fe_dir):
    """The bundled face-milled design (E = 0) assembled by the offset kinematics and phased at the hypoid pitch point
    against the intersecting-axes assembly, both with their own FE segments built from their own phased grids."""
    from spiralbevel.io.design_file import load_design
    from spiralbevel.job.blank import blank_from_design

    blank = blank_from_design(load_design(str(DATA / "aviation_23x65_facemilled.toml")))
    flanks = {k: v[2] for k, v in hypoid_basic_flanks(blank).items()}
    f1, f2 = flanks[(Member.PINION, Side.CONCAVE)], flanks[(Member.GEAR, Side.CONVEX)]
    ref = meshing_pair(f1, f2, blank)
    kin = HypoidPairKinematics.from_blank(blank)
    assert kin.offset == 0.0
    out = []
    for c1, c2, k in ((ref.pinion, ref.gear, ref.kinematics), (*phased_for_hypoid_pair(kin, blank, f1, f2), kin)):
        tca = solve_tca(c1, c2, k, n_positions=11, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        pin, gear = _grids(blank, flanks, c1, c2)
        m = ltca_model(c1, c2, k, tca, pinion_grids=pin, gear_grids=gear, cache_dir=fe_dir, grid=(15, 5))
        out.append((m.run(1e5, approach_target=None), m.approach_torque()))
    (a, Ta), (b, Tb) = out
    # round-off: the two phasings turn the flanks by angles equal to ~1e-16 rad (arctan of the same numbers; the
    # TCAs agree to 1e-7 arcsec at worst); measured here: identical to the last bit
    np.testing.assert_allclose(b.te_loaded, a.te_loaded, rtol=0, atol=1e-7)
    np.testing.assert_allclose(b.load_share, a.load_share, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.max_pressure, a.max_pressure, rtol=1e-12)
    assert Tb == pytest.approx(Ta, rel=1e-12)


def _levers(model, res, i, kin):
    """Lever arms ((q - o) x n) . a of the potential points of position i about the pinion and the wheel axes."""
    a1, o1, a2, o2, _ = kin.axes()
    n = np.array([model.positions[i].pairs[j].normal for j in res.pair_of_point[i]])
    q = res.points[i]
    return (np.einsum("ni,i->n", np.cross(q - o1, n), a1), np.einsum("ni,i->n", np.cross(q - o2, n), a2))


def test_forces_balance_both_torques_about_each_members_own_axis(hypoid):
    """Gear torque T = sum F h2 about the wheel axis (exact: the solve's equilibrium). The pinion torque
    sum F h1 about the offset pinion axis is T times a force-weighted mean of h1/h2 over the loaded cells, so it lies
    within their range; and h1/h2 at each unloaded contact point is the instantaneous velocity ratio dphi2/dphi1 of
    that pair in the TCA (frictionless power balance, n . v12 = 0), here against a central difference of the TCA's
    gear angles."""
    m, tca, kin = hypoid["model"], hypoid["tca"], hypoid["syn"].kinematics
    assert kin.offset != 0.0
    # N mm: at this torque one pair carries the load at 5 of the 11 positions (at 2e5 N mm the exiting pair's
    # trailing edge contact shares the load all through the cycle)
    T = 5e4
    res = m.run(T, approach_target=None)
    single = 0
    for i in range(len(res.force)):
        h1, h2 = _levers(m, res, i, kin)
        F = res.force[i]
        assert np.all(F >= 0)
        assert abs(F @ h2 - T) < 1e-9 * T
        loaded = F > 0
        ratio = h1 / h2
        assert ratio[loaded].min() <= (F @ h1) / T <= ratio[loaded].max()
        for j in np.unique(res.pair_of_point[i][loaded]):
            pc = m.positions[i].pairs[j]
            r = (np.cross(pc.point - kin.axes()[1], pc.normal) @ kin.axes()[0]) / (
                np.cross(pc.point - kin.axes()[3], pc.normal) @ kin.axes()[2])
            if res.load_share[i, j] > 1 - 1e-9 and 0 < i < len(tca.phi1) - 1:
                # one pair carries the load, inside the cycle: the TCA's gear angle of that pair is parabolic in
                # phi1 there, so the central difference is exact up to its deviation from a parabola (measured
                # 1.6e-6 relative on this 0.048 rad step)
                d = (tca.phi2_pairs[i + 1, j] - tca.phi2_pairs[i - 1, j]) / (tca.phi1[i + 1] - tca.phi1[i - 1])
                assert r == pytest.approx(d, rel=1e-5)
                single += 1
    assert single >= 3
    # the pair force is along the common normal: net force on the gear = sum F_i n_j, on the pinion its opposite;
    # its moment about the wheel axis through any point of the axis is T (the axis origin is not special)
    i = len(res.force) // 2
    a2, o2 = kin.axes()[2], kin.axes()[3]
    n = np.array([m.positions[i].pairs[j].normal for j in res.pair_of_point[i]])
    h2s = np.einsum("ni,i->n", np.cross(res.points[i] - (o2 + 37.0 * a2), n), a2)
    assert res.force[i] @ h2s == pytest.approx(T, rel=1e-12)


def test_small_torque_gives_the_unloaded_te(hypoid):
    m, tca = hypoid["model"], hypoid["tca"]
    res = m.run(1e-3, approach_target=None)
    # the grid's centre cell sits on each TCA contact point (w = 0 there): the same envelope; at 1e-3 N mm the
    # elastic closure is ~1e-6 arcsec (measured 1.2e-6)
    assert np.max(np.abs(res.te_unloaded - tca.te_arcsec)) < 1e-9
    assert np.max(np.abs(res.te_loaded - tca.te_arcsec)) < 1e-3
    a, b = m.run(1e4, approach_target=None), m.run(1e5, approach_target=None)
    assert np.all(np.abs(b.te_loaded - tca.te_arcsec) > np.abs(a.te_loaded - tca.te_arcsec))


def test_hertz_at_a_single_pair_position(hypoid):
    """As the spiral bevel test (tests/meshing/ltca/test_from_tca.py): one pair at the mean position, FE on, the
    peak pressure on a 41 x 15 contact grid against Hertz for that contact's curvatures and force within 5 %."""
    from spiralbevel.meshing.ellipse import hertz_peak_pressure
    from spiralbevel.meshing.ltca import contact_modulus

    tca = hypoid["tca"]
    i = len(tca.phi1) // 2
    j = int(tca.pair[i])
    model = ltca_model(hypoid["c1"], hypoid["c2"], hypoid["syn"].kinematics, tca, grid=(41, 15), **hypoid["kw"])
    pos = model.positions[i]
    one = dataclasses.replace(model, positions=[ContactPosition(pos.pinion_angle, [
        pc if q == j else None for q, pc in enumerate(pos.pairs)])])
    r = one.run(2e5, approach_target=None)
    p0, _ = hertz_peak_pressure(tca.relative_curvatures[i], r.pair_force[0, j], contact_modulus())
    assert abs(r.max_pressure[0] / p0 - 1.0) < 0.05


def test_mirror_of_hands(hypoid, fe_dir):
    """The right-hand pinion and left-hand wheel (E = +a): the mirror image, run backwards (positions phi1 -> -phi1,
    pairs -1 <-> +1). With rigid teeth the loaded cycle mirrors to round-off; with FE teeth to the FE discretization,
    since the mirrored tooth's tetrahedra are not the mirror images of the original's (each hexahedron is split along
    its main diagonal in lattice order). Measured: rigid 4e-11 arcsec, 9e-12 relative pressure, 4e-13 load share;
    FE 0.30 arcsec (1 %) in the loaded TE, 0.56 % in the peak pressure, 0.0034 in the load share."""
    rh = _sample2(fe_dir, "RH")
    lh = hypoid
    assert rh["syn"].kinematics.offset == -lh["syn"].kinematics.offset != 0.0
    T = 2e5
    for rigid, tol_te, tol_p, tol_share in ((True, 1e-9, 1e-10, 1e-11), (False, 0.5, 0.01, 0.005)):
        res = []
        for h in (lh, rh):
            m = (ltca_model(h["c1"], h["c2"], h["syn"].kinematics, h["tca"], rigid=True, grid=(15, 5)) if rigid
                 else h["model"])
            res.append(m.run(T, approach_target=None))
        a, b = res
        np.testing.assert_allclose(b.te_loaded[::-1], a.te_loaded, rtol=0, atol=tol_te)
        np.testing.assert_allclose(b.max_pressure[::-1], a.max_pressure, rtol=tol_p)
        np.testing.assert_allclose(b.load_share[::-1, ::-1], a.load_share, rtol=0, atol=tol_share)
