"""TCA engine: vectorized solver vs per-position scipy fsolve, line contact of the conjugate log-spiral pair,
parabolic TE of a crowned pair, transfer points, edge contact, errors (seed 001 §4-5, Eq. (16); docs/theory/tca.md, Eq.
(T5))."""

import warnings

import numpy as np
import pytest
from scipy.optimize import fsolve

from spiralbevel.errors import DesignError, NoContactError
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair


def _fsolve(prob, phi, basis, x0):
    """Plain scipy fsolve of the same 5 equations. MINPACK's forward-difference step is sqrt(eps)|x_j|, which is
    useless for unknowns that are ~1e-17 instead of exactly 0 (phi2, gear phi at the mean point): solve for
    y = x + 1 instead."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # "xtol too small": converged to machine precision
        y = fsolve(lambda y: prob.residual(y - 1.0, phi, basis), np.asarray(x0, float) + 1.0, xtol=1e-14)
    return y - 1.0


@pytest.fixture(scope="module")
def pair():
    return conjugate_logspiral_pair()


@pytest.fixture(scope="module")
def kin(pair):
    return BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)


@pytest.fixture(scope="module")
def crowned(pair):
    # material removed away from the mean point: profile and lengthwise crowning (mm per rad^2 of (varphi, phi))
    return NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))


@pytest.fixture(scope="module")
def crowned_result(crowned, pair, kin):
    return solve_tca(crowned, pair.gear, kin)


def test_conjugate_pair_line_contact_zero_te(pair, kin):
    res = solve_tca(pair.pinion, pair.gear, kin)
    ok = res.status_pairs != ContactStatus.NO_CONTACT
    assert ok.all()
    # seed 002 conjugacy theorem (docs/theory/gearing.md, Eqs. (M1)-(M8)): exact conjugate flanks -> zero TE for every
    # pair
    assert np.max(np.abs(res.te_pairs)) < 1e-12
    assert np.all(res.status == ContactStatus.LINE)
    assert np.all(np.isinf(res.semi_axes[:, 0]))
    # every solution satisfies the contact equations
    assert np.max(res.residual) < 1e-10
    # the reported point of the line is the mid-face one (anchor: pinion phi = reference value); where that point
    # lies beyond the gear's top edge, the pair's contact is reported as the edge contact of that top edge, at the
    # same (zero) TE, on the edge
    line = res.status_pairs == ContactStatus.LINE
    np.testing.assert_allclose(res.params1[line][:, 1], pair.pinion.reference_params[1], atol=1e-12)
    edge = res.status_pairs == ContactStatus.EDGE
    assert np.all(line | edge)
    g1 = np.min(pair.pinion.boundary_margins(res.params1[edge]), axis=-1)
    g2 = np.min(pair.gear.boundary_margins(res.params2[edge]), axis=-1)
    assert np.max(np.minimum(np.abs(g1), np.abs(g2))) < 1e-11


def test_contact_points_coincide_and_normals_opposite(crowned_result):
    res = crowned_result
    from spiralbevel._core.rotations import rot_axis, rot_y, rot_z

    k = res.pairs[None, :]
    phi1 = res.phi1[:, None] + 2 * np.pi * k / res.z1
    phi2 = res.phi2_pairs - 2 * np.pi * k / res.z2
    a2 = np.array([np.sin(res.shaft_angle), 0, np.cos(res.shaft_angle)])
    p1 = np.einsum("...ij,...j->...i", rot_z(phi1), res.point1)
    p2 = np.einsum("...ij,...j->...i", rot_axis(a2, phi2) @ rot_y(res.shaft_angle), res.point2)
    n2 = np.einsum("...ij,...j->...i", rot_axis(a2, phi2) @ rot_y(res.shaft_angle), res.normal2)
    assert np.max(np.linalg.norm(p1 - p2, axis=-1)) < 1e-9
    # opposite normals at surface contacts (at an edge contact only the touched flank has a normal there)
    surf = res.status_pairs != ContactStatus.EDGE
    assert np.max(np.linalg.norm(res.normal_fixed + n2, axis=-1)[surf]) < 1e-11


def test_vectorized_matches_per_position_fsolve(crowned, pair, kin, crowned_result):
    """Same equations solved per position with scipy.optimize.fsolve, marching from the mean point."""
    res = crowned_result
    prob = ContactProblem(crowned, pair.gear, kin)
    x = np.concatenate([res.params1[20, 1], res.params2[20, 1], [res.phi2_pairs[20, 1]]])
    worst = 0.0
    # march pair 0 from the centre to both ends of the cycle
    for order in (range(20, 41), range(20, -1, -1)):
        xp = x.copy()
        for i in order:
            phi = res.phi1[i]
            basis = prob.basis(xp, phi)
            xp = _fsolve(prob, phi, basis, xp)
            assert np.max(np.abs(prob.residual(xp, phi, basis))) < 1e-9
            if res.status_pairs[i, 1] == ContactStatus.EDGE:
                continue  # the surface contact lies beyond a flank boundary: TCA reports the edge contact there
            p_ref = crowned.evaluate(xp[0:2])[0]
            worst = max(worst, np.linalg.norm(p_ref - res.point1[i, 1]),
                        np.linalg.norm(pair.gear.evaluate(xp[2:4])[0] - res.point2[i, 1]))
            assert abs(xp[4] - res.phi2_pairs[i, 1]) < 1e-12
    assert worst < 1e-9  # mm


def test_crowned_te_is_parabola_like_and_nonpositive(crowned_result):
    res = crowned_result
    te0 = res.te_pairs[:, 1]
    # the crowning removes material away from the mean point: the gear lags there, TE <= 0 with max 0 at phi10
    assert te0[20] == pytest.approx(0.0, abs=1e-15)
    assert np.all(te0 <= 1e-15)
    assert np.argmax(te0) == 20
    # envelope: the pair in contact has the largest TE
    assert np.all(res.te[np.isfinite(res.te)] >= np.nanmax(res.te_pairs, axis=1)[np.isfinite(res.te)] - 1e-18)


def test_te_second_derivative_matches_direct_finite_difference(crowned, pair, kin, crowned_result):
    """TE'' at the mean point: from the TCA arrays (central differences over neighbouring positions, Richardson)
    against three direct per-point fsolve solutions at phi10 +- h."""
    res = crowned_result
    prob = ContactProblem(crowned, pair.gear, kin)
    x0 = np.concatenate([res.params1[20, 1], res.params2[20, 1], [res.phi2_pairs[20, 1]]])
    h = 1e-3

    def te(phi):
        basis = prob.basis(x0, phi)
        x = _fsolve(prob, phi, basis, x0)
        return res.drive_sign * (-(x[4] - res.phi2_mean) - prob.ratio * (phi - res.phi1_mean))

    direct = (te(h) + te(-h) - 2 * te(0.0)) / h**2
    t = res.te_pairs[:, 1]
    dphi = res.phi1[1] - res.phi1[0]
    d1 = (t[21] + t[19] - 2 * t[20]) / dphi**2
    d2 = (t[22] + t[18] - 2 * t[20]) / (2 * dphi) ** 2
    tca = (4 * d1 - d2) / 3  # Richardson: O(dphi^4)
    assert direct < 0
    assert tca == pytest.approx(direct, rel=1e-4)  # FD truncation of `direct`: O(h^2) ~ 1e-6 relative


def test_transfer_points_and_path_continuity(crowned, pair, kin):
    # on the real flanks this crowned pair leaves the pinion flank before the TE curves cross (edge contact, see
    # test_edge_positions_report_no_te): the crossing of the surface contacts is that of the extended surfaces
    res = solve_tca(crowned, pair.gear, kin, flank_bounds=False)
    assert len(res.transfer_phi1) >= 1
    for pt in res.transfer_phi1:
        i = np.searchsorted(res.phi1, pt) - 1
        a, b = res.pair[i], res.pair[i + 1]
        # the two pairs' TE curves cross between the two positions (continuous envelope)
        d0 = res.te_pairs[i, b] - res.te_pairs[i, a]
        d1 = res.te_pairs[i + 1, b] - res.te_pairs[i + 1, a]
        assert d0 <= 0 <= d1
    # the contact path of each pair is smooth (no branch jump): second differences well below first differences,
    # third differences well below second differences
    for k in range(len(res.pairs)):
        p = res.point1[:, k]
        d1 = np.linalg.norm(np.diff(p, axis=0), axis=-1)
        d2 = np.linalg.norm(np.diff(p, 2, axis=0), axis=-1)
        d3 = np.linalg.norm(np.diff(p, 3, axis=0), axis=-1)
        assert d2.max() < 0.2 * d1.min()
        assert d3.max() < 0.2 * d2.min()


def test_edge_contact_detected(crowned, pair, kin):
    """A pinion narrowed face-wise: the surface contact runs off its toe and heel; there TCA reports the edge
    contact: a point on one member's boundary, on the other member's real flank."""
    base = pair.pinion
    narrow = base.with_changes(phi_range=(base.reference_params[1] - 0.02, base.reference_params[1] + 0.02))
    crowned_narrow = NormalDeviation(narrow, crowned.deviation)
    res = solve_tca(crowned_narrow, pair.gear, kin)
    edge = res.status_pairs == ContactStatus.EDGE
    assert edge.any()
    g1 = np.min(narrow.boundary_margins(res.params1[edge]), axis=-1)
    g2 = np.min(pair.gear.boundary_margins(res.params2[edge]), axis=-1)
    # on one member's boundary (1e-11: the edge solve's tolerance), on the other's flank
    assert np.all(np.minimum(np.abs(g1), np.abs(g2)) < 1e-11)
    assert np.all((g1 > -1e-11) & (g2 > -1e-11))
    ok = res.status_pairs == ContactStatus.OK
    assert np.all(narrow.contains(res.params1[ok]) & pair.gear.contains(res.params2[ok]))
    assert np.any(res.status == ContactStatus.EDGE)


def test_no_contact_raises(pair, kin):
    # the pinion flank against itself: normals cannot be opposite -> no contact at the mean position
    with pytest.raises(NoContactError, match="mean position"):
        solve_tca(pair.pinion, pair.pinion, kin, start=np.r_[pair.pinion.reference_params,
                                                               pair.pinion.reference_params, 0.0])


@pytest.mark.parametrize("kw, field", [({"n_positions": 1}, "n_positions"), ({"pairs": (0, 0)}, "pairs"),
                                       ({"approach": -1.0}, "approach"), ({"tol": 1.0}, "tol")])
def test_bad_input_design_error(pair, kin, kw, field):
    with pytest.raises(DesignError, match=field):
        solve_tca(pair.pinion, pair.gear, kin, **kw)


def test_te_units(crowned_result):
    np.testing.assert_allclose(crowned_result.te_arcsec * ARCSEC, crowned_result.te)
    assert ARCSEC == pytest.approx(np.radians(1 / 3600))


def test_edge_positions_report_the_edge_contact(crowned_result, crowned, pair, kin):
    """Only contacts on the real flanks count: where the extended surfaces of a pair would touch beyond a flank
    boundary, the pair's contact is the edge contact of that boundary against the other flank. Its TE trails the
    extended surfaces' contact (a subset of the same flank touches later) and leads every other pair's contact where
    it is reported; elsewhere the TE is that of a contact inside both flank domains."""
    res = crowned_result
    edge = res.status == ContactStatus.EDGE
    assert edge.any() and len(res.edges) == edge.sum()
    assert np.all(np.isfinite(res.te[edge]))
    ok = ~edge & (res.pair >= 0)
    j = res.pair[ok]
    i = np.flatnonzero(ok)
    assert np.all(crowned.contains(res.params1[i, j])) and np.all(pair.gear.contains(res.params2[i, j]))
    ext = solve_tca(crowned, pair.gear, kin, flank_bounds=False)
    assert np.all(np.isfinite(ext.te)) and not np.any(ext.status == ContactStatus.EDGE)
    for idx, k, member, name in res.edges:
        jj = list(res.pairs).index(k)
        surf, q = (crowned, res.params1) if member == "pinion" else (pair.gear, res.params2)
        g = surf.boundary_margins(q[idx, jj])
        assert abs(g[list(surf.boundary_names).index(name)]) < 1e-11  # on the named edge
        assert res.te_pairs[idx, jj] <= ext.te_pairs[idx, jj] + 1e-15
        assert res.te_pairs[idx, jj] >= np.nanmax(np.delete(res.te_pairs[idx], jj), initial=-np.inf)


@pytest.mark.parametrize("crown", [(0.5, 0.0, 5.0), (2.0, 0.0, 1.0), (0.2, 0.0, 20.0)])
def test_no_te_from_points_off_the_real_flanks(pair, kin, crown):
    """Scan of crownings and the four misalignments: every reported TE comes from a contact whose two points lie on
    the real flanks (the domains' contains), and every EDGE position names a crossed boundary."""
    from spiralbevel.meshing.misalignment import Misalignment

    surf = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, crown))
    for mis in (None, Misalignment(pinion_axial=0.1), Misalignment(gear_axial=0.1), Misalignment(offset=0.1),
                Misalignment(shaft_angle=np.radians(0.05))):
        try:
            res = solve_tca(surf, pair.gear, kin, misalignment=mis)
        except NoContactError:
            continue
        fin = np.isfinite(res.te)
        i, j = np.flatnonzero(fin), res.pair[fin]
        assert np.all(surf.contains(res.params1[i, j])) and np.all(pair.gear.contains(res.params2[i, j]))
        assert np.all(res.status[~fin] != ContactStatus.OK)
        assert all(name in pair.gear.boundary_names for _, _, _, name in res.edges)
