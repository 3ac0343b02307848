"""Variable blank offset from a table of nodes (piecewise linear or cubic spline): the law itself, the sign and
validation in MachineSettings, and — the point of it — that dE_m/dt enters the relative velocity of generation
(docs/theory/generation.md, Eqs. (G5)-(G6)). The generation tests already cover the polynomial law
(tests/generation/test_flank.py)."""

import math
import os
import sys
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from spiralbevel._core import generation as _g
from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "generation"))
from _chain import chain  # noqa: E402  (independent kinematic chain, complex-step friendly)

NODES = (-0.2, -0.07, 0.05, 0.16)
VALUES = (0.02, -0.01, 0.03, 0.0)          # mm: rates of 0.2-0.3 mm/rad, far larger than multi-point control needs


def test_linear_table_values_and_slopes_against_numpy_interp():
    psi = np.linspace(-0.19, 0.15, 37)
    E, dE, ddE = _g.table_offset(psi, NODES, VALUES)
    np.testing.assert_allclose(E, np.interp(psi, NODES, VALUES), atol=1e-15)
    h = 1e-7
    fd = (np.interp(psi + h, NODES, VALUES) - np.interp(psi - h, NODES, VALUES)) / (2 * h)
    inner = np.min(np.abs(psi[:, None] - np.array(NODES)), axis=1) > 2 * h
    np.testing.assert_allclose(dE[inner], fd[inner], atol=1e-8)
    assert np.all(ddE == 0.0)


def test_linear_table_node_convention_and_extrapolation():
    # at a node the segment on the side of psi = 0 is used (docs of table_offset)
    x, y = np.array(NODES), np.array(VALUES)
    s = np.diff(y) / np.diff(x)
    _, d = _g.table_offset(np.array([x[1], x[2]]), x, y)[:2]
    assert d[0] == pytest.approx(s[1]) and d[1] == pytest.approx(s[1])
    E, d, _ = _g.table_offset(np.array([-0.5, 0.4]), x, y)
    assert E[0] == pytest.approx(y[0] + s[0] * (-0.5 - x[0])) and d[0] == pytest.approx(s[0])
    assert E[1] == pytest.approx(y[-1] + s[-1] * (0.4 - x[-1])) and d[1] == pytest.approx(s[-1])


def test_spline_table_against_scipy_cubic_spline():
    cs = CubicSpline(NODES, VALUES, bc_type="natural")
    M = cs(NODES, 2)
    psi = np.linspace(-0.3, 0.25, 101)
    E, dE, ddE = _g.table_offset(psi, NODES, VALUES, M)
    inside = (psi >= NODES[0]) & (psi <= NODES[-1])
    for k, val in enumerate((E, dE, ddE)):
        np.testing.assert_allclose(val[inside], cs(psi[inside], k), atol=1e-13)
    # natural spline: continued linearly with the end slope (C2, zero second derivative outside)
    lo = psi < NODES[0]
    np.testing.assert_allclose(E[lo], cs(NODES[0]) + cs(NODES[0], 1) * (psi[lo] - NODES[0]), atol=1e-13)
    assert np.all(ddE[~inside] == 0.0)


def test_settings_table_sign_validation_and_dict():
    _, s = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    t = s.replace(blank_offset=0.5, blank_offset_table=(NODES, VALUES))
    E, dE, _ = _g.offset(np.array(0.0), t.kernel_params())
    # kernel works on the mirrored machine: E enters negated (MachineSettings.kernel_params)
    assert E == pytest.approx(-(0.5 + np.interp(0.0, NODES, VALUES)))
    assert t.to_dict()["blank_offset_table"] == [list(NODES), list(VALUES)]
    assert s.kernel_params()["E_table"] is None
    for bad in [((0.1, 0.0), (1.0, 2.0)), ((0.0,), (1.0,)), ((0.0, 1.0), (1.0,)), ((0.0, math.nan), (0, 0)), (1, 2)]:
        with pytest.raises(DesignError, match="blank_offset_table"):
            s.replace(blank_offset_table=bad)


def _segment_settings(settings, i, x, y):
    """The constant-rate law of segment i as base offset + polynomial (for the independent chain)."""
    sl = (y[i + 1] - y[i]) / (x[i + 1] - x[i])
    return SimpleNamespace(**{**settings.to_dict(degrees=False),
                              "blank_offset": settings.blank_offset + y[i] - sl * x[i],
                              "blank_offset_poly": (sl,), "modified_roll": settings.modified_roll})


@pytest.mark.parametrize("member,side", [(Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)])
def test_generated_points_satisfy_meshing_with_variable_offset(member, side):
    """Points generated with a table lie on the cutter at (u, theta, psi_c) and n . dr/dpsi_c = 0 for the family of
    cutter positions moved by E_m(psi_c) (independent chain, complex step): the rate dE_m/dt is in the relative
    velocity. Without it (same offset value, zero rate) the meshing residual is far from zero."""
    blank = seed001_blank()
    cutter, settings = seed001_settings()[(member, side)]
    x, y = np.array(NODES), np.array(VALUES)
    t = settings.replace(blank_offset_table=(NODES, VALUES))
    fl = generate_flank(cutter, t, blank, member, side)
    uj = cutter.fillet_range[1]
    U, P = np.meshgrid(uj + np.linspace(0.5, 4.0, 4), [-0.15, -0.1, 0.0, 0.1], indexing="ij")   # away from nodes
    g = fl.evaluate(U, P, curvature=False)
    assert np.all(np.abs(fl.meshing_residual(g.u, g.theta, g.psi_c)) <= 1e-10)
    hs = fl.hand.sign
    worst_pos = worst_mesh = 0.0
    for u, th, ps, p in zip(g.u.ravel(), g.theta.ravel(), g.psi_c.ravel(), g.points.reshape(-1, 3)):
        i = int(np.clip(np.searchsorted(x, ps) - 1, 0, x.size - 2))
        seg = _segment_settings(settings, i, x, y)
        r, nh = chain(u, th, ps, cutter, seg, hs)
        worst_pos = max(worst_pos, np.abs(r - p).max())
        dr = chain(u, th, complex(ps, 1e-20), cutter, seg, hs)[0].imag / 1e-20
        worst_mesh = max(worst_mesh, abs(dr @ nh) / np.linalg.norm(dr))
    assert worst_pos < 1e-10 and worst_mesh < 1e-10
    # the same instantaneous offset without its rate: not an envelope point
    E = settings.blank_offset + np.interp(g.psi_c, x, y)
    frozen = [generate_flank(cutter, settings.replace(blank_offset=float(e)), blank, member, side)
              .meshing_residual(u, th, ps) for e, u, th, ps in zip(E.ravel()[:5], g.u.ravel(), g.theta.ravel(),
                                                                      g.psi_c.ravel())]
    assert np.max(np.abs(frozen)) > 1e-5
