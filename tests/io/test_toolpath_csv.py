"""Tool-path CSV: exact round trip, header with units, atomic write, malformed files."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

from spiralbevel.errors import DesignError
from spiralbevel.geometry.domain import ParallelogramDomain
from spiralbevel.io.toolpath_csv import COLUMNS, read_toolpath_csv, write_toolpath_csv
from spiralbevel.manufacturing.toolpath import plan_toolpath


class _Flank:
    rho0 = 100.0
    base_cone_angle = math.radians(20.0)
    spiral_angle = math.radians(32.6)


@pytest.fixture(scope="module")
def toolpath():
    dom = ParallelogramDomain(0.0, 0.3, 0.35, 0.5, _Flank.base_cone_angle)
    return plan_toolpath(_Flank(), dom, 4.0, 0.05, lead=math.radians(8), max_segment=5.0)


@pytest.mark.parametrize("reference", ["center", "tip"])
def test_round_trip_is_exact(tmp_path, toolpath, reference):
    f = tmp_path / "tp.csv"
    write_toolpath_csv(f, toolpath, reference=reference)
    t = read_toolpath_csv(f)
    assert t.tool_radius == 4.0 and t.scallop_height == 0.05 and t.reference == reference
    np.testing.assert_array_equal(t.points, toolpath.stacked(reference))
    np.testing.assert_array_equal(t.axis, toolpath.stacked("axis"))
    np.testing.assert_array_equal(t.path, toolpath.path_index)
    np.testing.assert_array_equal(t.index, toolpath.point_index)
    assert len(np.unique(t.path)) == len(toolpath)


def test_header_names_units(tmp_path, toolpath):
    f = tmp_path / "tp.csv"
    write_toolpath_csv(f, toolpath)
    lines = f.read_text().splitlines()
    assert "# tool_radius_mm = 4.0" in lines
    assert any(line.startswith("# reference = center") for line in lines)
    assert lines[lines.index(",".join(COLUMNS))] == "path,index,x_mm,y_mm,z_mm,i,j,k"
    first = lines[lines.index(",".join(COLUMNS)) + 1].split(",")
    assert first[:2] == ["0", "0"] and len(first) == 8
    # csv module reads it too (comments aside)
    import csv
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    assert tuple(rows[0]) == COLUMNS and len(rows) - 1 == len(toolpath.path_index)


def test_write_is_atomic(tmp_path, toolpath, monkeypatch):
    f = tmp_path / "tp.csv"
    f.write_text("previous")

    def boom(src, dst):
        raise OSError("no space")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        write_toolpath_csv(f, toolpath)
    monkeypatch.undo()
    assert f.read_text() == "previous" and sorted(p.name for p in tmp_path.iterdir()) == ["tp.csv"]


def test_bad_reference_and_malformed_files(tmp_path, toolpath):
    with pytest.raises(DesignError, match="reference"):
        write_toolpath_csv(tmp_path / "x.csv", toolpath, reference="centre")
    bad = tmp_path / "bad.csv"
    bad.write_text("# tool_radius_mm = 3\npath,index,x_mm,y_mm,z_mm,i,j,k\n0,0,1,2,3,0,0\n")
    with pytest.raises(DesignError, match="bad.csv:3"):
        read_toolpath_csv(bad)
    bad.write_text("# tool_radius_mm = 3\np,i,x,y,z,i,j,k\n")
    with pytest.raises(DesignError, match="header"):
        read_toolpath_csv(bad)
    bad.write_text("path,index,x_mm,y_mm,z_mm,i,j,k\n")
    with pytest.raises(DesignError, match="tool_radius_mm"):
        read_toolpath_csv(bad)
