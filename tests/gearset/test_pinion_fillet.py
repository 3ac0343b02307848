"""Refit of a pinion's edge radius below the gear's top (gearset/pinion_fillet.py).

On the 12/41, 35 deg, module 5 design the derived pinion edge radius (1.27 mm) puts the generated fillet/blade
junction 1.02-1.24 mm above the root cone, above the gear's top (the clearance, 0.88 mm): the refit must bring the
junction below it everywhere along the face while leaving the blade (mean point, angles) bit-identical. A pinion
whose settings lift its root is put back on the root cone with the same blade surface.
"""

import dataclasses
import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation.basic_settings_solve import root_deviation
from spiralbevel.generation.flank import generate_flank
from spiralbevel.gearset.pinion_fillet import (fit_pinion_edge_radius, gear_top_height, junction_height, lower_root,
                                             raise_root)
from spiralbevel.gearset.root_cone import root_heights
from spiralbevel.machine.default_cutter import EDGE_RADIUS_FILL
from _design_12x41 import design_12x41
from _designs import basic_setups
from _synthesis_stand_in import Result

DESIGN = design_12x41()


@pytest.fixture(scope="module")
def case():
    _, blank, setups = basic_setups(DESIGN)
    return blank, setups[(Member.PINION, Side.CONVEX)]


def test_gear_top_is_the_iso_clearance(case):
    blank, _ = case
    R = np.array([float(blank.Ri2), float(blank.Rm), float(blank.Re2)])
    # at the mean cone distance the gear's top lies the ISO clearance c = h_fm1 - h_am2 above the pinion's root
    assert gear_top_height(blank, R)[1] == pytest.approx(float(blank.c), abs=1e-12)
    # uniform clearance (ISO 23509: theta_f1 = theta_a2 for this taper): the same at toe and heel
    assert gear_top_height(blank, R) == pytest.approx(float(blank.c), abs=1e-9)


def test_refit_keeps_the_junction_below_the_gear_top_and_the_blade(case):
    blank, st = case
    ol = st.flank.outline
    top = gear_top_height(blank, np.linspace(ol.Ri, ol.Re, 7))
    assert np.any(junction_height(st.flank) > top)          # the case: the derived fillet reaches above the top
    new = fit_pinion_edge_radius(blank, Result(st.cutter, st.settings, st.flank))
    rho = new.pinion_cutter.edge_radius
    assert rho < st.cutter.edge_radius
    # below the top everywhere, and the bound is tight: at rho / fill the junction meets the top (Brent to 1e-4 rho)
    assert np.all(junction_height(new.pinion_flank) < top)
    at_limit = generate_flank(dataclasses.replace(st.cutter, edge_radius=rho / EDGE_RADIUS_FILL), st.settings, blank,
                              Member.PINION, Side.CONVEX)
    assert np.max(junction_height(at_limit) - top) == pytest.approx(0.0, abs=2e-3)
    # only the fillet changes: the cutter's blade (sharp point, angle, width) and the generated mean point are equal
    for name in ("point_radius", "blade_angle", "point_width", "blade"):
        assert getattr(new.pinion_cutter, name) == getattr(st.cutter, name)
    # generated blade points at the same (blade parameter u above the old junction, cradle angle psi_c): bit-identical
    u_j = st.cutter.fillet_range[1]
    u, psi = np.meshgrid(np.linspace(u_j, u_j + 6.0, 13), np.linspace(-0.15, 0.15, 7))
    assert np.array_equal(st.flank.generator.points(u, psi), new.pinion_flank.generator.points(u, psi))
    # the mean point is found again by Newton from starts that depend on the fillet: equal to round-off
    a, b = st.flank.mean_point(), new.pinion_flank.mean_point()
    assert np.allclose(a.point, b.point, rtol=0.0, atol=1e-12)
    assert a.pressure_angle == pytest.approx(b.pressure_angle, abs=1e-13)
    assert a.spiral_angle == pytest.approx(b.spiral_angle, abs=1e-13)
    assert math.isfinite(rho) and rho > 0.0


def test_lower_root_puts_the_root_on_the_cone_with_the_same_blade(case):
    """A pinion whose settings lift the root 0.3 mm (sliding base - 0.3 mm) is put back on the root cone; the
    blade surface is the same point set: the old blade parameter u is u + Delta / cos(alpha) of the extended blade."""
    blank, st = case
    lifted = dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base - 0.3)
    flank = generate_flank(st.cutter, lifted, blank, Member.PINION, Side.CONVEX)
    dev = np.array(root_deviation(flank), float)
    assert np.all(dev > 0.29)                               # the case: the root 0.3 mm above the cone
    new = lower_root(blank, Result(st.cutter, lifted, flank))
    delta = new.pinion_settings.sliding_base - lifted.sliding_base
    # moved by the root-cone check's own measure (11 stations, root_heights: one measure for the check and the
    # placement), which agrees with the second measure root_deviation to its 2e-4 rho sampling offset
    assert delta == pytest.approx(root_heights(flank)[1].min(), abs=1e-15)
    assert delta == pytest.approx(dev.min(), abs=1e-3)
    # on the root cone where it was lowest, nowhere below it (root_deviation samples 2e-4 rho above the tip; the
    # lift varies along the face by the 1e-5 mm of the basic root)
    after = np.array(root_deviation(new.pinion_flank), float)
    assert after.min() == pytest.approx(0.0, abs=1e-3) and np.all(after > -1e-3)
    # the same blade surface: independent evaluation of both generators at corresponding parameters
    c = st.cutter
    u_j = c.fillet_range[1]
    u, psi = np.meshgrid(np.linspace(u_j + 0.5, u_j + 6.0, 12), np.linspace(-0.15, 0.15, 7))
    old = flank.generator.points(u, psi)
    shifted = new.pinion_flank.generator.points(u + delta / math.cos(c.blade_angle), psi)
    assert np.max(np.abs(shifted - old)) < 1e-11            # round-off of the generation kernel at ~100 mm
    assert new.pinion_cutter.blade_angle == c.blade_angle
    assert new.pinion_cutter.point_width == pytest.approx(c.point_width - 2.0 * delta * math.tan(c.blade_angle))


def test_raise_root_puts_a_deep_root_on_the_cone_with_the_same_blade(case):
    """A pinion whose settings put the cutter's tip plane 0.8 mm below the root cone (sliding base + 0.8 mm, as the
    synthesis' settings do on 20/39 of bench_robustness.py 100 2) is put back on the root cone by a shorter blade:
    the cutting blade's surface is the same point set (the old blade parameter u is u + Delta / cos(alpha) of the new
    cutter, Delta < 0); the point width stays (the cutter-fit refit narrows it from the derived one)."""
    blank, st = case
    deep = dataclasses.replace(st.settings, sliding_base=st.settings.sliding_base + 0.8)
    flank = generate_flank(st.cutter, deep, blank, Member.PINION, Side.CONVEX)
    dev = np.array(root_deviation(flank), float)
    assert np.all(dev < -0.79)                              # the case: the root 0.8 mm below the cone
    assert raise_root(blank, Result(st.cutter, st.settings, st.flank)).pinion_flank is st.flank   # on it: kept
    new = raise_root(blank, Result(st.cutter, deep, flank))
    delta = new.pinion_settings.sliding_base - deep.sliding_base
    assert delta == pytest.approx(root_heights(flank)[1].max(), abs=1e-15)   # the check's measure, as above
    assert delta == pytest.approx(dev.max(), abs=1e-3)
    # on the root cone where it was highest, nowhere above it (tolerance as for lower_root above)
    after = np.array(root_deviation(new.pinion_flank), float)
    assert after.max() == pytest.approx(0.0, abs=1e-3) and np.all(after < 1e-3)
    c, n = st.cutter, new.pinion_cutter
    u_j = c.fillet_range[1]
    u, psi = np.meshgrid(np.linspace(u_j + 1.0, u_j + 6.0, 11), np.linspace(-0.15, 0.15, 7))
    old = flank.generator.points(u, psi)
    shifted = new.pinion_flank.generator.points(u + delta / math.cos(c.blade_angle), psi)
    assert np.max(np.abs(shifted - old)) < 1e-11            # round-off of the generation kernel at ~100 mm
    assert n.point_width == c.point_width and n.edge_radius <= c.edge_radius
    # the cutting blade's meridian (cutter frame S_h, HeadCutter.points, independent of the generation kernel): the
    # straight part is a line rho = a + b z, the same line k Delta along the axis (k = +-1) after the raise
    def line(cut):
        u0 = cut.fillet_range[1]
        p = cut.points(np.linspace(u0 + 1.0, u0 + 5.0, 5), np.zeros(5))
        b, a = np.polyfit(p[:, 2], p[:, 0], 1)
        return a, b

    (a0, b0), (a1, b1) = line(c), line(n)
    assert b1 == pytest.approx(b0, abs=1e-12)
    assert abs(abs((a0 - a1) / (b0 * delta)) - 1.0) < 1e-9
