"""STL export (spiralbevel.io.stl): binary and ASCII round trips, layout checked with struct, atomic writes."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from spiralbevel._core import logspiral as ls
from spiralbevel._core.rotations import apply, rot_z
from spiralbevel.errors import DesignError
from spiralbevel.geometry.solid import tooth_mesh
from spiralbevel.geometry.surface_mesh import TriangleMesh
from spiralbevel.io.stl import read_stl, write_stl

RHO0, DELTA, BETA = 100.0, np.radians(20.0), np.radians(35.0)


def flank(sign, n=11, m=6, rot=0.0):
    psi = sign * np.linspace(0.05, 0.3, m)
    phi, psi = np.meshgrid(np.linspace(0.0, 0.3, n), psi, indexing="ij")
    g = ls.geometry(phi + psi / np.sin(DELTA), phi, RHO0, DELTA, BETA)
    return apply(rot_z(rot), g["r"]), sign * apply(rot_z(rot), g["n"])


@pytest.fixture(scope="module")
def mesh():
    return tooth_mesh(flank(1), flank(-1, rot=0.35))


def test_binary_round_trip(tmp_path, mesh):
    path = write_stl(tmp_path / "tooth.stl", mesh, binary=True, name="tooth")
    assert path.stat().st_size == 84 + 50 * len(mesh.faces)
    back = read_stl(path)
    expected = mesh.triangles.reshape(-1, 3)
    assert np.array_equal(back.vertices, expected.astype(np.float32).astype(float))
    assert np.max(np.abs(back.vertices - expected)) <= 1e-5 * np.abs(expected).max()
    assert back.volume() == pytest.approx(mesh.volume(), rel=1e-5)
    assert back.area() == pytest.approx(mesh.area(), rel=1e-5)


def test_binary_layout_read_with_struct(tmp_path, mesh):
    """Header, count and the first facet decoded independently with struct (little-endian float32 records)."""
    data = write_stl(tmp_path / "t.stl", mesh, name="solid-looking name").read_bytes()
    assert not data[:80].startswith(b"solid")  # would make readers take the file for ASCII
    assert struct.unpack("<I", data[80:84])[0] == len(mesh.faces)
    record = struct.unpack("<12fH", data[84:134])
    tri = mesh.triangles[0]
    normal = np.cross(tri[1] - tri[0], tri[2] - tri[0])
    normal /= np.linalg.norm(normal)
    assert np.allclose(record[:3], normal, atol=1e-6)
    assert np.allclose(np.reshape(record[3:12], (3, 3)), tri, rtol=1e-6)
    assert record[12] == 0


def test_ascii_round_trip(tmp_path, mesh):
    path = write_stl(tmp_path / "tooth.stl", mesh, binary=False, name="tooth")
    text = path.read_text()
    assert text.startswith("solid tooth\n") and text.rstrip().endswith("endsolid tooth")
    assert text.count("facet normal") == len(mesh.faces)
    back = read_stl(path)
    expected = mesh.triangles.reshape(-1, 3)
    assert np.max(np.abs(back.vertices - expected)) <= 1e-8 * np.abs(expected).max()
    assert back.volume() == pytest.approx(mesh.volume(), rel=1e-8)


def test_facet_normals_point_outward(tmp_path, mesh):
    """For a closed outward mesh the written normals agree with the face orientation (divergence of x: 3 V)."""
    data = write_stl(tmp_path / "t.stl", mesh).read_bytes()
    rec = np.frombuffer(data, dtype=[("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")], offset=84)
    centroid = rec["c"].astype(float).mean(axis=1)
    areas = 0.5 * np.linalg.norm(np.cross(rec["c"][:, 1] - rec["c"][:, 0], rec["c"][:, 2] - rec["c"][:, 0]), axis=1)
    flux = np.sum(np.einsum("ij,ij->i", rec["n"].astype(float), centroid) * areas) / 3.0
    assert flux == pytest.approx(mesh.volume(), rel=1e-5)


def test_failed_write_leaves_the_old_file(tmp_path, mesh):
    path = write_stl(tmp_path / "t.stl", mesh)
    before = path.read_bytes()
    with pytest.raises(DesignError, match="mesh.vertices"):
        write_stl(path, TriangleMesh(np.full((3, 3), np.nan), [[0, 1, 2]]))
    with pytest.raises(DesignError, match="name"):
        write_stl(path, mesh, name="bad\nname")
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.stl"]  # no temporary left behind


def test_read_refuses_garbage(tmp_path):
    bad = tmp_path / "x.stl"
    bad.write_bytes(b"hello world")
    with pytest.raises(DesignError, match="path"):
        read_stl(bad)
