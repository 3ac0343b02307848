"""The pinion conjugate to a wheel flank in a hypoid pair, and the hypoid ease-off
(spiralbevel.meshing.hypoid_conjugate): envelope property by finite differences, the synthesized pinion touches its
conjugate at the mean contact, E = 0 equals the intersecting-axes envelope solver and ease-off."""

import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.meshing.easeoff import conjugate_pinion, easeoff
from spiralbevel.meshing.generated_surface import phased_for_pair
from spiralbevel.meshing.hypoid_conjugate import conjugate_pinion_points, hypoid_easeoff
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from spiralbevel.meshing.synthesis import synthesize_pinion
from spiralbevel.meshing.synthesis.hypoid_local import tca_surfaces
from _hypoid_sample2 import sample2_blank, sample2_concave_pinion

R = math.radians
ARCSEC = math.pi / 648000.0


@pytest.fixture(scope="module")
def hypoid():
    blank = sample2_blank()
    flanks = hypoid_basic_flanks(blank)
    syn = sample2_concave_pinion(blank, flanks, R(6.0), 3.7, 6.0 * ARCSEC)
    return syn, tca_surfaces(syn)


@pytest.fixture(scope="module")
def seed001():
    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    r = synthesize_pinion(gc, gs, blank, side=Side.CONCAVE, eta=R(6.0), semi_major_axis=3.7,
                          te_magnitude=3.0 * ARCSEC)
    return r, HypoidPairKinematics(blank.Sigma, blank.z1, blank.z2)


def test_conjugate_touches_the_synthesized_pinion_at_the_mean_contact(hypoid):
    syn, (c1, c2, _) = hypoid
    r, n, phi2 = conjugate_pinion_points(*c2.evaluate(c2.reference_params), syn.kinematics)
    p, m = c1.evaluate(c1.reference_params)
    assert abs(phi2) < 1e-10                   # the phased mean contact is at zero roll
    np.testing.assert_allclose(r, p, atol=1e-9)
    np.testing.assert_allclose(n, m, atol=1e-10)


def test_conjugate_is_an_envelope(hypoid):
    """The conjugate surface, parametrized by the wheel's (phi, psi_c), has the mapped normal as its own normal."""
    syn, (_, c2, _) = hypoid

    def conj(q):
        return conjugate_pinion_points(*c2.evaluate(q), syn.kinematics)[:2]

    h = np.array([1e-5, 1e-6])                  # rad, rad: truncation ~1e-10 relative, round-off ~1e-11
    mp = c2.mean_point
    for du, dpsi in ((0.0, 0.0), (1.0, 0.02), (-1.5, -0.03)):   # mm of blade, rad of cradle from the mean point
        u, psi = mp.u + du, mp.psi_c + dpsi
        q = np.array([c2.flank.generator.contact(u, psi)["phi"], psi])    # the same point in the (phi, psi_c) chart
        assert c2.contains(q)
        _, n = conj(q)
        for k in range(2):
            e = np.zeros(2)
            e[k] = h[k]
            d = (conj(q + e)[0] - conj(q - e)[0]) / (2 * h[k])
            assert abs(d @ n) / np.linalg.norm(d) < 1e-8


def test_zero_offset_is_the_envelope_solver(seed001):
    r, kin = seed001
    access, _ = conjugate_pinion(r.gear_flank, kin)
    g = r.gear_flank.grid(5, 4, curvature=False)
    ref_p, ref_n = access.surface(g.u, g.psi_c)
    mp = r.gear_flank.mean_point()
    got_p, got_n, _ = conjugate_pinion_points(g.points, g.normals, kin,
                                              phi2_ref=math.pi - math.atan2(mp.point[1], mp.point[0]))
    np.testing.assert_allclose(got_p, ref_p, atol=1e-11)
    np.testing.assert_allclose(got_n, ref_n, atol=1e-13)


def test_zero_offset_easeoff_is_the_spiral_bevel_easeoff(seed001):
    r, kin = seed001
    _, gear = phased_for_pair(r.pinion_flank, r.gear_flank)
    a = easeoff(r.pinion_flank, r.gear_flank, kin, n_face=5, n_profile=4)
    b = hypoid_easeoff(r.pinion_flank, gear, kin, n_face=5, n_profile=4)
    assert np.max(np.abs(a.values)) > 0.01
    np.testing.assert_allclose(b.values, a.values, atol=1e-10)


def test_hypoid_easeoff_of_the_synthesized_pinion(hypoid):
    """A crowned point contact: zero at the mean contact, clearance (positive) everywhere else."""
    syn, (_, c2, _) = hypoid
    eo = hypoid_easeoff(syn.pinion_flank, c2, syn.kinematics, n_face=7, n_profile=5)
    assert np.min(eo.values) > -1e-6
    i, j = np.unravel_index(np.argmin(eo.values), eo.values.shape)
    assert eo.values[i, j] < 1e-3 and abs(eo.R[i, j] - eo.mean_R) < 0.2 * (eo.R.max() - eo.R.min())
    assert np.max(eo.values) > 0.05                         # tens of micrometres at toe and heel
