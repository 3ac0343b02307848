"""STEP export with exact B-spline flank surfaces (spiralbevel.io.step, optional extra ``cad``).

The reference points are evaluated exactly from the closed-form log-spiral kernel (seed 000 Eq. (16),
docs/theory/logspiral.md, Eq. (S2) (#surface))
at the grid nodes AND midway between them (in phi, in psi and at cell centres), then projected onto the surfaces read
back from the file with OpenCascade's GeomAPI_ProjectPointOnSurf: the distance must stay <= 1e-3 mm.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from spiralbevel._core import logspiral as ls
from spiralbevel._core.rotations import apply, rot_z
from spiralbevel.errors import DesignError, MissingDependencyError
from spiralbevel.geometry.surface_mesh import MeshBuilder, TriangleMesh, grid_faces, weld

RHO0, DELTA, BETA, ROT = 100.0, np.radians(20.0), np.radians(35.0), 0.35
N, M = 25, 13


def kernel(sign, phi, psi, rot=0.0):
    phi, psi = np.meshgrid(phi, sign * np.asarray(psi), indexing="ij")
    return apply(rot_z(rot), ls.point(phi + psi / np.sin(DELTA), phi, RHO0, DELTA, BETA))


def params(n=N, m=M):
    return np.linspace(0.0, 0.3, n), np.linspace(0.05, 0.3, m)


def grids(n=N, m=M):
    phi, psi = params(n, m)
    return kernel(1, phi, psi), kernel(-1, phi, psi, ROT)


def midway_points(sign, rot):
    phi, psi = params()
    phi_m, psi_m = 0.5 * (phi[1:] + phi[:-1]), 0.5 * (psi[1:] + psi[:-1])
    return [kernel(sign, a, b, rot) for a, b in ((phi, psi), (phi_m, psi), (phi, psi_m), (phi_m, psi_m))]


def test_missing_ocp_names_the_cad_extra(monkeypatch, tmp_path):
    from spiralbevel.io import step

    monkeypatch.setitem(sys.modules, "OCP", None)  # makes "import OCP" raise ImportError
    pa, pb = grids(5, 4)
    with pytest.raises(MissingDependencyError) as info:
        step.write_step(tmp_path / "t.step", pa, pb)
    assert "spiralbevel[cad]" in str(info.value) and info.value.extra == "cad"
    assert "cadquery-ocp-novtk" in str(info.value)
    assert not (tmp_path / "t.step").exists()


ocp = pytest.importorskip("OCP")
from spiralbevel.io.step import flank_surface, read_step_surfaces, write_step  # noqa: E402


@pytest.fixture(scope="module")
def tooth_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("step") / "tooth.step"
    pa, pb = grids()
    return write_step(path, pa, pb, solid=True)


def test_read_back_surfaces_match_the_kernel(tooth_file):
    surfaces = read_step_surfaces(tooth_file.path)
    assert len(surfaces) == 2 + 6  # two flank faces + the faces of the sewn solid
    worst = 0.0
    for surface, (sign, rot) in zip(surfaces[:2], ((1, 0.0), (-1, ROT))):
        for pts in midway_points(sign, rot):
            worst = max(worst, float(surface.distance(pts).max()))
    assert worst <= 1e-3  # measured 1.5e-4 mm for this 25 x 13 grid
    assert tooth_file.node_deviation < 1e-9  # interpolation passes through the nodes


def test_file_is_in_millimetres(tooth_file):
    text = tooth_file.path.read_text()
    assert "ISO-10303-21" in text and ".MILLI." in text and "B_SPLINE_SURFACE" in text


def test_surface_sampler_lies_on_the_flank(tooth_file):
    """Points sampled from the read surface have orthogonal distance ~0 to the exact flank: project them back onto
    a finely interpolated surface of a dense kernel grid (independent of the written file)."""
    surfaces = read_step_surfaces(tooth_file.path)
    u0, u1, v0, v1 = surfaces[0].bounds
    assert (u0, v0) == (0.0, 0.0) and (u1, v1) == (1.0, 1.0)
    corners = surfaces[0](np.array([0.0, 1.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0, 1.0]))
    pa, _ = grids()
    assert np.allclose(corners, pa[[0, -1, 0, -1], [0, 0, -1, -1]], atol=1e-9)
    from spiralbevel.io.step import StepSurface

    dense = StepSurface(flank_surface(kernel(1, *params(61, 41))))
    assert float(dense.distance(surfaces[0].sample(9, 7)).max()) <= 1e-3


def ruled_tooth_volume(n, m):
    """Triangulated volume of the same solid as the STEP one: the kernel flanks and straight rulings (node i of one
    flank edge to node i of the other), each ruled strip subdivided along its rulings as finely as the flanks."""
    pa, pb = grids(n, m)
    t = np.linspace(0.0, 1.0, m)[None, :, None]
    patches = [pa, pb[:, ::-1]]
    for ea, eb in ((pa[:, -1], pb[:, -1]), (pa[0], pb[0]), (pa[-1], pb[-1]), (pa[:, 0], pb[:, 0])):
        patches.append((1.0 - t) * ea[:, None] + t * eb[:, None])
    meshes = []
    for grid in patches:
        idx = np.arange(grid.shape[0] * grid.shape[1]).reshape(grid.shape[:2])
        meshes.append(TriangleMesh(grid.reshape(-1, 3), grid_faces(idx)))
    raw = TriangleMesh.concatenate(meshes)
    mesh = weld(raw, 1e-9)
    faces = mesh.faces.copy()
    # orient patch by patch through a MeshBuilder so the closed mesh is consistent
    b = MeshBuilder()
    b.add_vertices(mesh.vertices)
    start = 0
    for m_ in meshes:
        b.add_patch(faces[start:start + len(m_.faces)])
        start += len(m_.faces)
    closed = b.mesh()
    assert closed.is_watertight() and closed.euler_characteristic() == 2
    return abs(closed.volume())


def test_sewn_solid_volume_matches_the_ruled_mesh(tooth_file):
    """OpenCascade's volume integral of the sewn B-spline solid vs the triangulated volume of the same ruled solid
    built from the kernel, which converges at O(h^2) (measured 2.2e-3, 5.6e-4, 1.4e-4, 3.4e-5 for m = 11..81)."""
    v = tooth_file.solid_volume
    assert v is not None and v > 0
    errors = np.array([abs(ruled_tooth_volume(2 * m - 1, m) / v - 1.0) for m in (11, 21, 41)])
    ratios = errors[:-1] / errors[1:]
    assert np.all((ratios > 3.5) & (ratios < 4.5)) and errors[-1] < 2e-4, errors  # O(h^2) towards OCC's volume


def test_whole_gear_compound(tmp_path):
    z = 5
    pa, pb = grids(13, 7)
    res = write_step(tmp_path / "gear.step", pa, pb, z=z)
    surfaces = read_step_surfaces(res.path)
    assert res.n_faces == len(surfaces) == 2 * z
    for k in range(z):  # the convex flank of tooth k holds the nodes turned by 2 pi k / z
        assert float(surfaces[2 * k].distance(apply(rot_z(2 * np.pi * k / z), pa)).max()) < 1e-6


def test_approximation_within_tolerance(tmp_path):
    pa, pb = grids()
    res = write_step(tmp_path / "a.step", pa, pb, tolerance=1e-4)
    assert res.node_deviation <= 1e-4
    surfaces = read_step_surfaces(res.path)
    assert float(surfaces[0].distance(midway_points(1, 0.0)[3]).max()) <= 1e-3


def test_bad_requests_leave_no_file(tmp_path):
    pa, pb = grids(5, 4)
    with pytest.raises(DesignError, match="z"):
        write_step(tmp_path / "t.step", pa, pb, z=0)
    with pytest.raises(DesignError, match="parametrization"):
        write_step(tmp_path / "t.step", pa, pb, parametrization="spline")
    with pytest.raises(DesignError, match="path"):
        read_step_surfaces(tmp_path / "missing.step")
    assert list(tmp_path.iterdir()) == []
