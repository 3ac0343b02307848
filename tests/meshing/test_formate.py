"""Formate (non-generated) wheel flanks of a hypoid pair (spiralbevel.meshing.formate): the design mean-point angles
reached by the settings solve, the flank's curvatures against numerical differential geometry of the surface, and the
Formate flank as the cutter surface (the universal generator with the cradle locked)."""

import math
import warnings

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.errors import DesignError
from spiralbevel.machine.default_cutter import design_pressure_angle
from spiralbevel.meshing.formate import FormateFlank, solve_formate_settings
from _hypoid_sample2 import SAMPLE2

R = math.radians


@pytest.fixture(scope="module")
def formate():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        blank = compute_blank(BlankInput(**SAMPLE2))
    return blank, {side: solve_formate_settings(blank, Member.GEAR, side) for side in Side}


def _normal_curvature(flank, x, t):
    """t . dn/ds along the unit tangent t at parameters x, by central differences of points and normals."""
    h = np.array([1e-5, 1e-7])                   # mm, rad: truncation ~1e-10, round-off ~1e-9 relative
    d = []
    for k in range(2):
        e = np.zeros(2)
        e[k] = h[k]
        a, m = flank.evaluate(*(x + e)), flank.evaluate(*(x - e))
        d.append(((a.points - m.points) / (2 * h[k]), (a.normals - m.normals) / (2 * h[k])))
    A = np.stack([d[0][0], d[1][0]], 1)
    c = np.linalg.lstsq(A, t, rcond=None)[0]
    return float(t @ (c[0] * d[0][1] + c[1] * d[1][1]))


@pytest.mark.parametrize("side", list(Side))
def test_formate_wheel_has_the_design_angles(formate, side):
    blank, flanks = formate
    cutter, settings, flank = flanks[side]
    assert not settings.generated
    mp = flank.mean_point()
    assert mp.spiral_angle == pytest.approx(blank.beta_m2, abs=1e-8)
    assert mp.pressure_angle == pytest.approx(design_pressure_angle(blank, Member.GEAR, side), abs=1e-8)
    assert mp.hand_sign == blank.hand2.sign
    assert math.hypot(*mp.point[:2]) == pytest.approx(blank.Rm2 * math.sin(blank.delta2), abs=1e-9)
    # a straight-blade Formate flank is a cone: no curvature along the blade
    assert mp.k1 == 0.0


@pytest.mark.parametrize("side", list(Side))
def test_formate_curvature_by_numerical_geometry(formate, side):
    _, flanks = formate
    flank = flanks[side][2]
    mp = flank.mean_point()
    x = np.array([mp.u, mp.theta])
    for k, e in ((mp.k1, mp.e1), (mp.k2, mp.e2)):
        assert _normal_curvature(flank, x, e) == pytest.approx(k, abs=1e-8)
    np.testing.assert_allclose(np.cross(mp.e1, mp.e2), mp.normal, atol=1e-12)
    # e1 runs from root to top: the height above the pitch cone grows along it
    p = mp.point
    rho = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
    d = flank.outline.delta
    assert mp.e1 @ (math.cos(d) * rho - math.sin(d) * np.array([0.0, 0.0, 1.0])) > 0


def test_formate_flank_needs_formate_settings(formate):
    blank, flanks = formate
    cutter, settings, _ = flanks[Side.CONVEX]
    with pytest.raises(DesignError, match="settings.generated"):
        FormateFlank(cutter, settings.replace(generated=True), blank, Member.GEAR, Side.CONVEX)
