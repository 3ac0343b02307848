"""Basic settings solved on the generation kernel hit the design (issue: from basic data to a developed pair).

The achieved angles are measured here by a second method, independent of ``ToothFlank.mean_point``: the normal from
finite differences of generated points, the tooth trace from two located points on the pitch cone, and the root from
the fillet rows of the flank grid against the root cone through the ISO heel root point (Re, -hfe).
"""

import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.generation.basic_settings_solve import solve_basic_settings
from spiralbevel.machine.default_cutter import default_cutter, largest_edge_radius, slot_width_at_root

DESIGNS = [  # (z1, z2, Sigma deg, beta_m deg, pinion hand, module mm, face width mm)
    (12, 41, 90.0, 35.0, "RH", 5.0, 30.0),
    (12, 41, 75.0, 35.0, "LH", 5.0, 30.0),
    (25, 60, 110.0, 25.0, "LH", 3.0, 25.0),
]


def _blank(z1, z2, sigma, beta, hand, m, b):
    return compute_blank(BlankInput(z1=z1, z2=z2, shaft_angle=math.radians(sigma), met=m, b=b,
                                    beta_m=math.radians(beta),
                                    alpha_dD=math.radians(20.0), alpha_dC=math.radians(20.0), hand1=hand,
                                    rc0=114.3))


@pytest.fixture(scope="module", params=DESIGNS, ids=lambda d: f"{d[0]}x{d[1]}-S{d[2]:g}-b{d[3]:g}-{d[4]}")
def solved(request):
    blank = _blank(*request.param)
    out = {}
    for m in (Member.PINION, Member.GEAR):
        for s in (Side.CONVEX, Side.CONCAVE):
            out[(m, s)] = solve_basic_settings(blank, m, s, default_cutter(blank, m, s))
    return blank, out


def _fd_normal(flank, u, psi, h=1e-5):
    """Unit normal from central differences of generated points in (u, psi_c) (the kernel's normal not used)."""
    def p(du, dp):
        return flank.evaluate(u + du, psi + dp, curvature=False).points
    t1 = (p(h, 0) - p(-h, 0)) / (2 * h)
    t2 = (p(0, h) - p(0, -h)) / (2 * h)
    n = np.cross(t1, t2)
    return n / np.linalg.norm(n)


def test_mean_point_angles_hit_the_design(solved):
    blank, out = solved
    for (m, s), (_cutter, _settings, flank, fit) in out.items():
        i = m.index
        delta = getattr(blank, f"delta{i}")
        design_alpha = blank.alpha_nD if (m is Member.PINION) == (s is Side.CONCAVE) else blank.alpha_nC
        # mean pitch point, located on the circle (axial, radius) of R = Rm, h = 0
        ax, rad = blank.Rm * math.cos(delta), blank.Rm * math.sin(delta)
        fp = flank.locate(np.array([ax]), np.array([rad]), curvature=False)
        p = fp.points[0]
        n = _fd_normal(flank, fp.u[0], fp.psi_c[0])
        rho = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
        z = np.array([0.0, 0.0, 1.0])
        N = math.cos(delta) * rho - math.sin(delta) * z          # pitch-cone normal
        g = math.sin(delta) * rho + math.cos(delta) * z          # pitch-cone generatrix
        alpha = math.asin(abs(n @ N))
        # tooth trace on the pitch cone: two located points at R = Rm -+ 0.01 mm, h = 0
        eps = 0.01
        R = blank.Rm + np.array([-eps, eps])
        q = flank.locate(R * math.cos(delta), R * math.sin(delta), curvature=False).points
        t = (q[1] - q[0]) / np.linalg.norm(q[1] - q[0])
        beta = math.acos(abs(t @ g))
        # 0.05 deg acceptance; the method errors are ~1e-9 rad (differences) and ~eps/Rm * curvature terms (trace)
        assert math.degrees(abs(alpha - design_alpha)) < 1e-4
        assert math.degrees(abs(beta - abs(blank.beta_m1))) < 1e-3
        assert fit.pressure_angle == pytest.approx(alpha, abs=1e-7)


def test_root_on_root_cone(solved):
    blank, out = solved
    for (m, s), (_cutter, _settings, flank, _fit) in out.items():
        i = m.index
        delta, delta_f = getattr(blank, f"delta{i}"), getattr(blank, f"delta_f{i}")
        # root cone through the ISO heel root point (R = Re, h = -hfe), at the root angle
        Re, hfe = getattr(blank, f"Re{i}"), getattr(blank, f"hfe{i}")
        P0 = np.array([Re * math.cos(delta) + hfe * math.sin(delta), Re * math.sin(delta) - hfe * math.cos(delta)])
        d = np.array([math.cos(delta_f), math.sin(delta_f)])
        root = flank.grid(7, 3, n_fillet=3, curvature=False).points[:, 0]
        pts = np.stack([root[:, 2], np.hypot(root[:, 0], root[:, 1])], -1) - P0
        dist = pts[:, 0] * d[1] - pts[:, 1] * d[0]               # signed distance from the root-cone line
        # 0.01 mm acceptance; hfe is printed by the blank from the same cone (exact to rounding)
        assert np.max(np.abs(dist)) < 1e-6, (m, s, dist)


def test_pitch_roll_puts_instantaneous_axis_through_mean_point(solved):
    """The relative velocity of cradle and work vanishes at the mean pitch point (second check of the roll)."""
    blank, out = solved
    for (_m, _s), (_cutter, _settings, flank, _fit) in out.items():
        mp = flank.mean_point()
        assert abs(flank.meshing_residual(mp.u, mp.theta, mp.psi_c)) < 1e-6


def test_default_cutter_fits_the_slot():
    blank = _blank(*DESIGNS[0])
    for m in (Member.PINION, Member.GEAR):
        W = slot_width_at_root(blank, m)
        i = m.index
        # slot width at the root, again: space width at the root line in the normal section by the flank run-outs
        space = math.pi * blank.mmn - getattr(blank, f"smn{i}")
        h = getattr(blank, f"hfm{i}")
        assert W == pytest.approx(space - h * math.tan(blank.alpha_nD) - h * math.tan(blank.alpha_nC), rel=1e-12)
        rho = largest_edge_radius(W, (blank.alpha_nD, blank.alpha_nC), blank.c)
        for s in (Side.CONVEX, Side.CONCAVE):
            c = default_cutter(blank, m, s)
            a = c.blade_angle
            # fillet reach within half the point width and its junction height within the tip clearance
            assert c.edge_radius * (1 - math.sin(a)) / math.cos(a) <= 0.5 * W + 1e-12
            assert c.edge_radius * (1 - math.sin(a)) <= blank.c + 1e-12
            assert c.edge_radius == pytest.approx(rho)


def test_mean_point_generated_at_zero_cradle_angle(solved):
    """Gauge of the solved settings: the mean point is generated at psi_c = 0 (the start of local synthesis)."""
    blank, out = solved
    for (_m, _s), (_cutter, _settings, flank, _fit) in out.items():
        assert abs(flank.mean_point().psi_c) < 1e-8
