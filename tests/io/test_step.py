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
    assert len(surfaces) == 6  # the faces of the sewn solid only: no loose copies of the flanks
    worst = 0.0
    for sign, rot in ((1, 0.0), (-1, ROT)):
        probe = kernel(sign, [0.15], [0.2], rot).reshape(1, 3)  # a flank point: picks the flank's face
        face = min(surfaces, key=lambda s: float(s.distance(probe)[0]))
        for pts in midway_points(sign, rot):
            worst = max(worst, float(face.distance(pts).max()))
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


def analytic_tooth_volume(rot):
    """Volume of the kernel tooth: in spherical coordinates about the apex its toe and heel are spheres and its root
    and top cones (seed 000 Eq. (16): the azimuth of the convex branch is varphi - atan(tan(psi)/sin(delta)), psi
    constant along a cone of polar angle acos(cos(psi) cos(delta))), so V = (rho_heel^3 - rho0^3) / 3 cos(delta)
    * integral of sin(psi) (rot - 2 f(psi)) dpsi with f(psi) = psi / sin(delta) - atan(tan(psi) / sin(delta))."""
    from scipy.integrate import quad

    sd = np.sin(DELTA)
    phi, psi = params()
    rho_heel = RHO0 * np.exp(phi[-1] * sd / np.tan(BETA))
    f = lambda p: p / sd - np.arctan(np.tan(p) / sd)  # noqa: E731
    integral = quad(lambda p: np.sin(p) * (rot - 2.0 * f(p)), psi[0], psi[-1], epsabs=1e-13, epsrel=1e-13)[0]
    return (rho_heel**3 - RHO0**3) / 3.0 * np.cos(DELTA) * integral


def test_solid_volume_matches_the_quadrature(tooth_file):
    """OpenCascade's volume of the sewn solid (B-spline flanks through the 25 x 13 nodes, root/top/toe/heel faces
    bridged on their cones and spheres) against the closed-form volume: the fits deviate from the kernel by
    <= 1.5e-4 mm over ~4e3 mm^2 of surface, i.e. <~1e-4 of the volume; measured 1.4e-6, bounded by 1e-5."""
    v = tooth_file.solid_volume
    assert v is not None and v > 0 and tooth_file.tooth_volume == v and tooth_file.body_volume is None
    assert v == pytest.approx(analytic_tooth_volume(ROT), rel=1e-5)


def test_solid_volume_matches_the_stl_mesh(tooth_file):
    """The STL mesh of the same tooth (same nodes, same bridging rungs) converges to the STEP solid at O(h^2)."""
    from spiralbevel.geometry.solid import tooth_mesh

    errors = []
    for m in (7, 13, 25):
        pa, pb = grids(2 * m - 1, m)
        errors.append(abs(tooth_mesh(pa, pb).volume() / tooth_file.solid_volume - 1.0))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 3.0) & (ratios < 5.0)) and errors[-1] < 5e-4, errors  # O(h^2)


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


def _read_shape(path):
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    return reader.OneShape()


def _volume(shape):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


@pytest.fixture(scope="module")
def gear_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("gear")
    pa, pb = grids(13, 7)
    return (write_step(d / "gear.step", pa, pb, z=Z_GEAR, solid=True),
            write_step(d / "tooth.step", pa, pb, solid=True), pa, pb)


Z_GEAR = 12


def test_whole_gear_is_one_valid_solid(gear_file):
    from OCP import TopAbs
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopExp import TopExp_Explorer

    res, _, _, _ = gear_file
    shape = _read_shape(res.path)
    assert BRepCheck_Analyzer(shape).IsValid()
    counts = {}
    for kind in ("SOLID", "SHELL"):
        ex, counts[kind] = TopExp_Explorer(shape, getattr(TopAbs.TopAbs_ShapeEnum, f"TopAbs_{kind}")), 0
        while ex.More():
            counts[kind] += 1
            ex.Next()
    assert counts == {"SOLID": 1, "SHELL": 1}
    assert _volume(shape) == pytest.approx(res.solid_volume, rel=1e-9)  # decimal text: measured 2e-13


def test_whole_gear_volume_is_body_plus_teeth(gear_file):
    """Gear = body + z x tooth - z x (body and tooth in common), each term computed apart: the body in closed form
    (a frustum of the cone through the root edges, less the bore) and as an OpenCascade cone primitive less a
    cylinder, the tooth from its own file, their common part by a separate Boolean operation."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    res, tooth_res, pa, pb = gear_file
    root = np.concatenate([pa[:, 0], pb[:, 0]])
    theta = np.mean(np.arctan2(np.hypot(root[:, 0], root[:, 1]), root[:, 2]))
    z_f, z_b = min(pa[0, 0, 2], pb[0, 0, 2]), max(pa[-1, 0, 2], pb[-1, 0, 2])
    r_f, r_b, h = z_f * np.tan(theta), z_b * np.tan(theta), z_b - z_f
    bore = 0.5 * min(np.hypot(*pa[0, 0, :2]), np.hypot(*pb[0, 0, :2]))
    frustum = np.pi / 3.0 * h * (r_f**2 + r_f * r_b + r_b**2) - np.pi * bore**2 * h
    assert res.body_volume == pytest.approx(frustum, rel=1e-9)
    ax = gp_Ax2(gp_Pnt(0.0, 0.0, float(z_f)), gp_Dir(0.0, 0.0, 1.0))
    body = BRepAlgoAPI_Cut(BRepPrimAPI_MakeCone(ax, float(r_f), float(r_b), float(h)).Shape(),
                           BRepPrimAPI_MakeCylinder(ax, float(bore), float(h)).Shape()).Shape()
    assert _volume(body) == pytest.approx(frustum, rel=1e-9)
    tooth = _read_shape(tooth_res.path)
    assert res.tooth_volume == pytest.approx(_volume(tooth), rel=1e-6)
    common = _volume(BRepAlgoAPI_Common(body, tooth).Shape())
    expected = frustum + Z_GEAR * (res.tooth_volume - common)
    # measured 8e-8 (OpenCascade integrates the volume of the fused faces numerically); the common part is 0 here:
    # the kernel tooth stands on the cone through its root edges
    assert res.solid_volume == pytest.approx(expected, rel=1e-6), (res.solid_volume, expected, common)


def test_whole_gear_volume_against_the_stl_mesh(gear_file):
    """STL gears of the same kernel (root lands and end faces on the same cone and planes, a fine bore polygon) at
    two grid sizes converge to the STEP gear at O(h^2)."""
    from spiralbevel.geometry.solid import GearBody, gear_mesh

    res = gear_file[0]
    errors = []
    for m in (7, 13):
        mesh = gear_mesh(*grids(2 * m - 1, m), Z_GEAR, GearBody(n_bore=2000))
        assert mesh.is_watertight()
        errors.append(abs(mesh.volume() / res.solid_volume - 1.0))
    # measured 2.0e-3 and 5.0e-4: halving the cells divides the difference by 4
    assert 3.5 < errors[0] / errors[1] < 4.5 and errors[1] < 7e-4, errors
