"""STEP export of face-milled generated flanks: exact B-spline surfaces read back against the generator, and whole
teeth (fillets, root, top land, toe and heel) as one valid closed solid."""

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
    assert len(surfaces) == 2
    # independent points: the flank located by Newton midway between the grid nodes (not used by the fit)
    mid = 0.25 * (gx.points[:-1, :-1] + gx.points[1:, :-1] + gx.points[:-1, 1:] + gx.points[1:, 1:])
    exact = convex.locate(mid[..., 2], np.hypot(mid[..., 0], mid[..., 1]), curvature=False).points
    dist = np.min([s.distance(exact.reshape(-1, 3)) for s in surfaces], axis=0)
    assert dist.max() <= 1e-3
    nodes = np.min([s.distance(gx.points.reshape(-1, 3)) for s in surfaces], axis=0)
    assert nodes.max() <= 1e-6


# --- whole teeth of the ISO 23509 sample 1 gear set with its derived cutters ------------------------------------
N_FACE, N_PROFILE = 9, 7


@pytest.fixture(scope="module")
def iso_sample():
    from spiralbevel.io.design_file import default_design_text, parse_design
    from spiralbevel.job import facemilled as fm
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.outputs import cad_teeth

    spec = parse_design(default_design_text("iso23509_sample1.toml"))
    blank = blank_from_design(spec)
    setups = fm._basic_setups(spec, blank)
    cad, warnings = cad_teeth(spec, blank, setups, N_FACE, N_PROFILE)
    return spec, blank, setups, cad, warnings


@pytest.fixture(scope="module")
def whole_tooth(iso_sample, tmp_path_factory):
    _, _, _, cad, _ = iso_sample
    c = cad[Member.PINION]
    (pa, _), (pb, _) = c["tooth"]
    path = tmp_path_factory.mktemp("whole") / "pinion_tooth.step"
    return write_step(path, pa, pb, solid=True, fillet_rows=c["fillet_rows"]), c


def _read_shape(path):
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    return reader.OneShape()


def _shapes(shape, kind):
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer

    ex, out = TopExp_Explorer(shape, getattr(TopAbs.TopAbs_ShapeEnum, f"TopAbs_{kind}")), []
    while ex.More():
        out.append(ex.Current())
        ex.Next()
    return out


def _edge_face_counts(shape):
    """Number of faces at each edge of the shape (2 everywhere on a closed manifold shell)."""
    from OCP import TopAbs
    from OCP.TopExp import TopExp
    try:  # OCP >= 8 moved the NCollection instantiations
        from OCP.collections import IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as Map
    except ImportError:  # pragma: no cover - OCP 7.x
        from OCP.TopTools import TopTools_IndexedDataMapOfShapeListOfShape as Map

    m = Map()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs.TopAbs_EDGE, TopAbs.TopAbs_FACE, m)
    return np.array([m.FindFromIndex(i).Size() for i in range(1, m.Extent() + 1)])


def test_derived_cutters_fit_the_tooth_space(iso_sample):
    """The derived cutters' point width is the slot width at the root: neighbouring teeth do not overlap there, and
    the whole gears keep their fillets."""
    from spiralbevel.geometry.solid import root_slot_width

    _, blank, setups, cad, warnings = iso_sample
    assert warnings == []
    for m, z in ((Member.PINION, blank.z1), (Member.GEAR, blank.z2)):
        assert cad[m]["gear_fillet_rows"] == cad[m]["fillet_rows"] > 0
        (pa, _), (pb, _) = cad[m]["tooth"]
        width = root_slot_width(pa, pb, z)
        # the slot bottom is the cutter's tip flat: positive, narrower than the point width
        assert np.all(width > 0) and np.all(width < setups[(m, Side.CONVEX)].cutter.point_width)


def test_whole_tooth_is_one_valid_closed_solid(whole_tooth):
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    res, _ = whole_tooth
    shape = _read_shape(res.path)
    assert BRepCheck_Analyzer(shape).IsValid()
    assert len(_shapes(shape, "SOLID")) == 1 and len(_shapes(shape, "SHELL")) == 1
    # two faces per flank (fillet, blade), root, top land, and toe and heel faces per flank segment: no loose copies
    faces = _shapes(shape, "FACE")
    assert len(faces) == res.n_faces == 10
    assert np.all(_edge_face_counts(shape) == 2)  # closed: no free edge, no edge shared by three faces
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    # the file holds the solid written (decimal text and the reader's tolerances: measured 4e-8 relative)
    assert props.Mass() == pytest.approx(res.solid_volume, rel=1e-6) and res.solid_volume > 0


def test_whole_tooth_flanks_and_fillets_read_back(whole_tooth, iso_sample):
    """Generated points between the fitted nodes (a grid twice as fine: every other row and column is new, on the
    fillet and on the blade) lie on the faces read back within 1e-3 mm (measured 1.9e-4 mm)."""
    _, blank, setups, _, _ = iso_sample
    res, c = whole_tooth
    surfaces = read_step_surfaces(res.path)
    from spiralbevel.job import facemilled as fm
    from spiralbevel.job.outputs import CAD_FILLET_ROWS

    rot = fm.tooth_rotation(blank, setups, Member.PINION)
    for side in (Side.CONVEX, Side.CONCAVE):
        fine = setups[(Member.PINION, side)].flank.grid(2 * N_FACE - 1, 2 * N_PROFILE - 1,
                                                        n_fillet=2 * CAD_FILLET_ROWS - 1, curvature=False)
        pts = fine.points if side is Side.CONVEX else fm.rotate_grid(fine.points, fine.normals, rot)[0]
        assert fine.fillet.sum() >= 2 * N_FACE * (CAD_FILLET_ROWS - 1)  # the check covers fillet points
        dist = np.min([s.distance(pts.reshape(-1, 3)) for s in surfaces], axis=0)
        assert dist.max() <= 1e-3, (side, dist.max())


def test_whole_tooth_volume_against_the_stl_mesh(whole_tooth):
    """The STL mesh of the same grids (planar triangles between the same nodes, the same bridging rungs) against the
    STEP solid: the mesh's chordal error is O(h^2) and makes it differ by 0.35 % (measured) on this coarse 9 x 15
    grid, whose cells along the face are ~4 mm long on a flank curved with a ~20 mm radius; 5e-3 bounds it."""
    from spiralbevel.geometry.solid import tooth_mesh

    res, c = whole_tooth
    mesh = tooth_mesh(*c["tooth"])
    assert mesh.is_watertight() and mesh.euler_characteristic() == 2
    rel = abs(mesh.volume() / res.solid_volume - 1.0)
    assert rel < 5e-3, rel


def test_cutter_wider_than_the_tooth_space_is_named():
    """Seed 001's given 2.29 mm point width is wider than the tooth space at the root of the ISO blank: the
    warning names the design-file key, and the whole gear falls back to the flanks above the fillets."""
    from spiralbevel.geometry.solid import root_slot_width
    from spiralbevel.io.design_file import default_design_text, parse_design
    from spiralbevel.job import facemilled as fm
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.outputs import cad_teeth

    spec = parse_design(default_design_text("aviation_23x65_facemilled.toml"))
    blank = blank_from_design(spec)
    cad, warnings = cad_teeth(spec, blank, fm._basic_setups(spec, blank), 7, 5)
    assert any("pinion" in w and "face_milling.pinion_concave.cutter.point_width" in w for w in warnings)
    c = cad[Member.PINION]
    assert c["gear_fillet_rows"] == 0 and c["fillet_rows"] > 0
    (pa, _), (pb, _) = c["tooth"]
    assert root_slot_width(pa, pb, blank.z1).min() < 0
    (ga, _), (gb, _) = c["gear"]
    assert np.array_equal(ga, pa[:, c["fillet_rows"]:]) and root_slot_width(ga, gb, blank.z1).min() > 0
