"""TCA of a hypoid pair with a Formate wheel (ISO 23509 Sample 2; the wheel's concave flank is the cutter surface,
spiralbevel.meshing.formate_surface) against the brute-force oracle (tests/meshing/_contact_oracle.py).

The pinion is the hypoid local synthesis against the Formate wheel with the ellipse of a generated gear (path
direction -20 deg, 8 arcsec design TE). The pair interferes: away from the mean point the next tooth pair touches
hundreds of arcsec ahead, first on the pinion's fillet junction, then at the corner where that boundary crosses the
wheel's heel edge, then on the wheel's heel edge. TCA finds the surface contacts, the fillet-junction edge contact,
the corner contact (two boundary curves meeting) and the heel-edge contact past it; the oracle agrees at every
sampled position (without corner contacts TCA lost the contact at the corner and reported the trailing pair, 350-709
arcsec short of the oracle).
"""

import math

import numpy as np
import pytest

from _contact_oracle import Oracle, grid_box, lead_deviation

from spiralbevel.conventions import Member, Side
from spiralbevel.meshing.formate import solve_formate_settings
from spiralbevel.meshing.formate_surface import FormateSurface
from spiralbevel.meshing.generated_surface import GeneratedSurface
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from spiralbevel.meshing.synthesis.hypoid_local import synthesize_hypoid_pinion
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC
from _hypoid_sample2 import sample2_blank

#: arcsec: the oracle's own accuracy on a contact it samples is ~1e-3 arcsec (zooming grids, Newton to 1e-11 mm)
TOL_ARCSEC = 0.01


@pytest.fixture(scope="module")
def formate_pair():
    blank = sample2_blank()
    side = Side.CONVEX                       # pinion convex against the Formate wheel's concave flank
    _, _, gear = solve_formate_settings(blank, Member.GEAR, side.mate)
    pc, ps, _, _ = hypoid_basic_flanks(blank)[(Member.PINION, side)]
    res = synthesize_hypoid_pinion(gear, pc, ps, blank, side=side, eta=math.radians(-20.0), semi_major_axis=6.0,
                                   te_magnitude=8.0 * ARCSEC)
    c1 = GeneratedSurface(res.pinion_flank, res.phi1_mean)
    c2 = FormateSurface(gear, res.phi2_mean)
    tca = solve_tca(c1, c2, res.kinematics, n_positions=21, start=np.r_[c1.reference_params, c2.reference_params, 0])
    return c1, c2, res.kinematics, tca


def _box_formate(surface):
    """(u, theta) box of the Formate flank: flank points located over face width and depth, widened by 2 %."""
    ol = surface.flank.outline
    q = np.array([surface.flank.locate_params(*ol.axial_radius(R, h))
                  for R in np.linspace(ol.Ri, ol.Re, 5)
                  for h in np.linspace(0.8 * float(ol.h_root(R)), float(ol.h_face(R)), 5)])
    lo, hi = q.min(0), q.max(0)
    d = 0.02 * (hi - lo)
    return np.stack([lo - d, hi + d], 1)


def test_formate_surface_is_the_formate_flank(formate_pair):
    """The TCA surface is the Formate flank: the mean point at the reference parameters, margins 0 on the outline."""
    _, c2, _, _ = formate_pair
    fl = c2.flank
    mp = fl.mean_point()
    r, n = c2.evaluate(c2.reference_params)
    R = np.array([[math.cos(c2.rotation), -math.sin(c2.rotation), 0], [math.sin(c2.rotation), math.cos(c2.rotation), 0],
                  [0, 0, 1]])
    assert np.allclose(r, R @ mp.point, atol=1e-12) and np.allclose(n, R @ mp.normal, atol=1e-14)
    ol = fl.outline
    heel = fl.locate_params(*ol.axial_radius(ol.Re, 0.0))
    top = fl.locate_params(*ol.axial_radius(ol.Rm, float(ol.h_face(ol.Rm))))
    assert abs(c2.boundary_margins(heel)[1]) < 1e-9 and abs(c2.boundary_margins(top)[2]) < 1e-9
    assert c2.contains(c2.reference_params)


def _deviation(formate_pair, idx):
    """TCA lead minus oracle lead (arcsec) at positions ``idx``, and the oracle."""
    c1, c2, kin, res = formate_pair
    # a coarse grid of 48 x 24 (not the default 24 x 12): at position 10 the pinion's fillet-junction edge leads the
    # surface contact of the same pair by 1.0 arcsec, and the default grid zooms in on the surface contact only
    o = Oracle(c1, c2, grid_box(c1), _box_formate(c2), kin.z1, kin.z2, kin.axes(), n=(48, 24))
    return lead_deviation(o, res, idx) / ARCSEC, o


def test_formate_pair_tca_matches_brute_force_up_to_the_corner(formate_pair):
    """Up to the corner (the first 13 of 21 positions: surface contacts, then the pinion's fillet-junction edge) the
    leading contact agrees with the oracle; the pair interferes (hundreds of arcsec of TE)."""
    _, _, _, res = formate_pair
    dev, _ = _deviation(formate_pair, np.arange(0, 14, 2))
    assert np.all(np.isfinite(dev)) and np.max(np.abs(dev)) <= TOL_ARCSEC, np.round(dev, 4)
    assert np.nanmax(res.te_arcsec) - np.nanmin(res.te_arcsec) > 200.0
    assert any(e[2:] == ("pinion", "fillet") for e in res.edges)


def test_formate_pair_tca_matches_brute_force_past_the_corner(formate_pair):
    """Past the fillet junction: the corner where the pinion's fillet junction meets the wheel's heel edge, then
    the heel edge against the pinion flank (both reported as edge contacts)."""
    c1, c2, kin, res = formate_pair
    idx = np.arange(14, len(res.phi1), 2)
    dev, o = _deviation(formate_pair, idx)
    P = np.asarray(res.pairs)
    # TCA never trails the oracle (it found every leading contact the oracle samples) ...
    assert np.all(np.isfinite(dev)) and np.min(dev) >= -TOL_ARCSEC, np.round(dev, 4)
    # ... and where it leads the oracle (a boundary maximum between the oracle's samples), the oracle's own meeting
    # of TCA's pinion contact point with the wheel flank confirms that contact (same gear rotation, on the flank)
    for a in np.flatnonzero(dev > TOL_ARCSEC):
        i = idx[a]
        j = int(res.pair[i])
        k = int(P[j])
        r1, _ = c1.evaluate(res.params1[i, j])
        phi_eff = np.array([res.phi1[i] + 2 * np.pi * k / kin.z1])
        p2_eff = res.phi2[i] - 2 * np.pi * k / kin.z2
        q, p2m, ok = o._meet(0, r1[None], phi_eff, np.array([p2_eff]), res.params2[i, j][None])
        assert ok[0] and abs(p2m[0] - p2_eff) / ARCSEC < 1e-6
    kinds = {e[2:] for e in res.edges}
    assert ("pinion/gear", "fillet/heel corner") in kinds and ("gear", "heel") in kinds, kinds
