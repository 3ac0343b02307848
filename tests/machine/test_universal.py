"""Universal generator (spiralbevel.machine.universal): a second parametrization of face-milling generation, checked
against the cradle generator of spiralbevel.generation, the envelope condition by finite differences, and the sign of
every setting it adds (docs/conventions.md "Universal generator")."""

import math

import numpy as np
import pytest

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.machine.universal import UniversalGenerator, UniversalSettings

CASES = [(Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)]


def _case(member, side, **changes):
    cutter, settings = seed001_settings()[(member, side)]
    settings = settings.replace(**changes)
    flank = generate_flank(cutter, settings, seed001_blank(), member, side)
    return cutter, settings, flank


@pytest.mark.parametrize("member, side", CASES)
@pytest.mark.parametrize("hand", [Hand.LEFT, Hand.RIGHT])
def test_zero_tilt_reproduces_cradle_generator(member, side, hand):
    # modified roll and a variable blank offset on top of seed 001 Tables 4-5 (which carry E_m, X_B, X_D)
    cutter, settings, flank = _case(member, side, modified_roll=(0.05, -0.1), blank_offset_poly=(0.7, -2.0))
    grid = flank.grid(7, 5, n_fillet=3, curvature=False)
    flank.generator.hand = hand
    ref = flank.generator.evaluate(grid.u, grid.psi_c, curvature=False)
    got = UniversalGenerator(cutter, UniversalSettings.from_machine_settings(settings), hand).evaluate(
        grid.u, grid.psi_c)
    # round-off: coordinates of ~100 mm carry ~1e-14 relative error through two different matrix chains
    np.testing.assert_allclose(got.points, ref.points, rtol=0, atol=1e-10)
    np.testing.assert_allclose(got.normals, ref.normals, rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.angle(np.exp(1j * (got.theta - ref.theta))), 0.0, atol=1e-12)


def test_swivel_without_tilt_changes_nothing():
    cutter, settings, flank = _case(*CASES[0])
    grid = flank.grid(5, 4, curvature=False)
    base = UniversalSettings.from_machine_settings(settings)
    a = UniversalGenerator(cutter, base, Hand.LEFT).evaluate(grid.u, grid.psi_c)
    b = UniversalGenerator(cutter, base.replace(swivel=1.1), Hand.LEFT).evaluate(grid.u, grid.psi_c)
    np.testing.assert_allclose(b.points, a.points, rtol=0, atol=1e-10)


def _tilted(member=Member.PINION, side=Side.CONCAVE, tilt=-3.0):
    cutter, settings, flank = _case(member, side)
    us = UniversalSettings.from_machine_settings(settings).replace(
        tilt=math.radians(tilt), swivel=math.radians(40.0), modified_roll=(0.03,), helical_motion=(1.5, -0.8),
        vertical_motion=(0.6,), radial_motion=(-2.0, 1.0))
    return cutter, us, flank


@pytest.mark.parametrize("member, side, tilt", [(Member.GEAR, Side.CONVEX, 3.0), (Member.PINION, Side.CONCAVE, -3.0)])
def test_envelope_with_tilt_and_motions(member, side, tilt):
    """The normal of the kernel is the normal of the generated surface r(u, psi_c): central differences."""
    cutter, us, flank = _tilted(member, side, tilt)
    gen = UniversalGenerator(cutter, us, flank.hand)
    grid = flank.grid(5, 4, curvature=False)
    u, psi = grid.u[1:-1, 1:-1], grid.psi_c[1:-1, 1:-1]
    p = gen.evaluate(u, psi)
    h = 1e-4                     # mm and rad; truncation ~h^2 |r'''| ~ 1e-8 relative, round-off ~1e-16/h
    for du, dpsi in ((h, 0.0), (0.0, h)):
        d = (gen.evaluate(u + du, psi + dpsi).points - gen.evaluate(u - du, psi - dpsi).points) / (2 * h)
        cos = np.einsum("...i,...i", d, p.normals) / np.linalg.norm(d, axis=-1)
        assert np.max(np.abs(cos)) < 1e-7
    assert np.max(np.abs(gen.meshing_residual(p.u, p.theta, p.psi_c))) < 1e-12
    np.testing.assert_allclose(np.linalg.norm(p.normals, axis=-1), 1.0, atol=1e-14)


def test_tilt_moves_the_flank():
    cutter, us, flank = _tilted()
    grid = flank.grid(3, 3, curvature=False)
    a = UniversalGenerator(cutter, us.replace(tilt=0.0), flank.hand).evaluate(grid.u, grid.psi_c)
    b = UniversalGenerator(cutter, us, flank.hand).evaluate(grid.u, grid.psi_c)
    assert np.max(np.linalg.norm(a.points - b.points, axis=-1)) > 0.1


# ---------------------------------------------------------------------------------------------------- signs
def _positions(**changes):
    cutter, settings, _ = _case(*CASES[0])
    us = UniversalSettings.from_machine_settings(settings).replace(**changes)
    return lambda psi: UniversalGenerator(cutter, us, Hand.LEFT).machine_positions(psi), us


def test_sign_tilt_and_swivel():
    """Positive tilt about the swivel line d: the cutter axis leans toward d x Z_m. With j = +90 deg that is the ray
    machine centre -> cutter centre: the top of the cutter axis leans away from the cradle axis."""
    i = math.radians(5.0)
    pos, us = _positions(tilt=i, swivel=0.5 * math.pi)
    p = pos(0.0)
    ray = p["cutter_centre"] / np.linalg.norm(p["cutter_centre"])
    assert p["cutter_axis"] @ ray == pytest.approx(math.sin(i), abs=1e-15)
    assert p["cutter_axis"][2] == pytest.approx(math.cos(i), abs=1e-15)
    pos, _ = _positions(tilt=i, swivel=0.0)            # d along the ray: the axis leans clockwise of the ray
    p = pos(0.0)
    side = np.cross([0.0, 0.0, 1.0], p["cutter_centre"])
    assert p["cutter_axis"] @ side < 0.0 and abs(p["cutter_axis"] @ p["cutter_centre"]) < 1e-12


def test_sign_helical_vertical_radial_motions():
    psi = 0.2
    pos0, _ = _positions()
    pos, us = _positions(helical_motion=(2.0,), vertical_motion=(3.0,), radial_motion=(4.0,))
    a, b = pos0(psi), pos(psi)
    # helical: the sliding base grows with psi_c, the work moves along -Z_m (deeper)
    assert b["work_apex"][2] - a["work_apex"][2] == pytest.approx(-2.0 * psi, abs=1e-12)
    # vertical: the blank offset grows, away from the cutter-centre side (-Y_m on the left-hand machine)
    assert b["work_apex"][1] - a["work_apex"][1] == pytest.approx(-3.0 * psi, abs=1e-12)
    # radial: the cutter centre moves away from the cradle axis
    assert np.linalg.norm(b["cutter_centre"]) - np.linalg.norm(a["cutter_centre"]) == pytest.approx(4.0 * psi,
                                                                                                    abs=1e-12)
    # every motion is zero at psi_c = 0
    for key in ("work_apex", "cutter_centre"):
        np.testing.assert_allclose(pos(0.0)[key], pos0(0.0)[key], atol=1e-14)


# ---------------------------------------------------------------------------------------------------- Formate
def test_formate_flank_is_the_cutter_surface():
    """Formate: at each blade parameter the flank points over a full turn of theta lie on a circle of the blade
    radius (the cutter surface of revolution, untouched by any roll)."""
    cutter, us, flank = _tilted(Member.GEAR, Side.CONVEX, 3.0)
    gen = UniversalGenerator(cutter, us.replace(generated=False), Hand.LEFT)
    th = np.linspace(0.0, 2 * math.pi, 12, endpoint=False)
    for u in (0.5, 4.0, 9.0):
        p = gen.formate(u, th)
        centre = p.points.mean(axis=0)
        rho = cutter.points(u, 0.0)[0]
        np.testing.assert_allclose(np.linalg.norm(p.points - centre, axis=-1), rho, rtol=1e-13)
        assert np.ptp((p.points - centre) @ np.cross(p.points[1] - centre, p.points[4] - centre)) < 1e-9
    # the generated flank at psi_c = 0 is the line of the cutter surface it touches: same point as Formate
    g = UniversalGenerator(cutter, us, Hand.LEFT).evaluate(np.array([2.0, 5.0]), 0.0)
    f = gen.formate(g.u, g.theta)
    np.testing.assert_allclose(f.points, g.points, atol=1e-12)
    np.testing.assert_allclose(f.normals, g.normals, atol=1e-14)
    with pytest.raises(GeometryError, match="settings.generated"):
        gen.evaluate(1.0, 0.0)


def test_bad_settings_name_the_key():
    with pytest.raises(DesignError, match="settings.tilt"):
        UniversalSettings(radial_setting=100.0, cradle_angle=1.0, machine_root_angle=0.5, tilt=2.0)
    with pytest.raises(DesignError, match="settings.helical_motion"):
        UniversalSettings(radial_setting=100.0, cradle_angle=1.0, machine_root_angle=0.5, helical_motion=(1, "x"))
    with pytest.raises(DesignError, match="settings.radial_setting"):
        UniversalSettings(radial_setting=float("nan"), cradle_angle=1.0, machine_root_angle=0.5)
