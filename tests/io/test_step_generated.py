"""STEP export of face-milled generated flanks: exact B-spline surfaces read back against the generator."""

import numpy as np
import pytest

pytest.importorskip("OCP")

from spiralbevel.conventions import Member, Side  # noqa: E402
from spiralbevel.generation import generate_flank  # noqa: E402
from spiralbevel.io.step import read_step_surfaces, write_step  # noqa: E402
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings  # noqa: E402
from spiralbevel.machine import HeadCutter, MachineSettings  # noqa: E402


def test_generated_gear_tooth_step_round_trip(tmp_path):
    blank = seed001_blank()
    cutter, settings = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    convex = generate_flank(cutter, settings, blank, Member.GEAR, Side.CONVEX)
    outer = HeadCutter(point_radius=cutter.point_radius + cutter.point_width, blade_angle=cutter.blade_angle,
                       point_width=cutter.point_width, edge_radius=cutter.edge_radius, blade="outer")
    concave = generate_flank(outer, MachineSettings.from_blank(blank, Member.GEAR, Side.CONCAVE, outer), blank,
                             Member.GEAR, Side.CONCAVE)
    n_face, n_prof = 25, 13
    gx, gc = convex.grid(n_face, n_prof), concave.grid(n_face, n_prof)
    path = tmp_path / "gear_tooth.step"
    write_step(path, (gx.points, gx.normals), (gc.points, gc.normals))
    surfaces = read_step_surfaces(path)
    assert len(surfaces) >= 2
    # independent points: the flank located by Newton midway between the grid nodes (not used by the fit)
    mid = 0.25 * (gx.points[:-1, :-1] + gx.points[1:, :-1] + gx.points[:-1, 1:] + gx.points[1:, 1:])
    exact = convex.locate(mid[..., 2], np.hypot(mid[..., 0], mid[..., 1]), curvature=False).points
    dist = np.min([s.distance(exact.reshape(-1, 3)) for s in surfaces], axis=0)
    assert dist.max() <= 1e-3
    nodes = np.min([s.distance(gx.points.reshape(-1, 3)) for s in surfaces], axis=0)
    assert nodes.max() <= 1e-6
