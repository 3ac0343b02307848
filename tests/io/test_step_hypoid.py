"""CAD of hypoid teeth (ISO 23509 Sample 2, pinion flanks by hypoid local synthesis): the derived pinion edge radius
refitted to the generated root slot (gearset/hypoid_fillet.py), the slot holding the cutter, whole teeth as one valid
closed STEP solid read back against the generated flank and fillet points, the whole pinion as STEP (the tooth
patterned z times on the body) and STL, and the mirror of hands."""

import math
import warnings

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from _hypoid_sample2 import SAMPLE2_TOML, SEED001_SYNTHESIS

N_FACE, N_PROFILE = 9, 7
#: a given synthesis (path 40 deg on both sides) instead of the default's search over path directions: same chain,
#: a second instead of twenty
SYNTHESIS = "\n[synthesis]\nsides = ['drive', 'coast']\npath_direction = 40.0\n" + SEED001_SYNTHESIS


def _design(hand="LH"):
    from spiralbevel.gearset import hypoid as hy
    from spiralbevel.gearset.blank import blank_from_design
    from spiralbevel.io.design_file import parse_design

    spec = parse_design(SAMPLE2_TOML.replace('pinion_hand = "LH"', f'pinion_hand = "{hand}"') + SYNTHESIS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        blank = blank_from_design(spec)
        setups, synth = hy.setup_hypoid_flanks(spec, blank, with_synthesis=True)
    return spec, blank, setups, synth


@pytest.fixture(scope="module")
def sample2():
    from spiralbevel.gearset.outputs import cad_teeth

    spec, blank, setups, synth = _design()
    cad, warns = cad_teeth(spec, blank, setups, N_FACE, N_PROFILE)
    return spec, blank, setups, synth, cad, warns


def test_derived_pinion_edge_radius_is_refitted_to_the_generated_slot(sample2):
    """The derived cutter's edge radius fits a straight-sided slot in the mean normal section; the generated slot of
    the fixed-setting pinion (two cutter radii, curved generated profile) is narrower at the root, so the fillets of
    neighbouring teeth cross with it. The refit takes EDGE_RADIUS_FILL x the radius at which they just meet, and
    changes nothing on the blades."""
    from spiralbevel.design.hypoid_member import member_blank
    from spiralbevel.gearset.hypoid_fillet import generated_root_slot
    from spiralbevel.machine.default_cutter import EDGE_RADIUS_FILL, default_cutter

    _, blank, setups, synth, _, _ = sample2
    derived = default_cutter(member_blank(blank, Member.PINION), Member.PINION, Side.CONCAVE).edge_radius
    rho = setups[(Member.PINION, Side.CONCAVE)].cutter.edge_radius
    assert setups[(Member.PINION, Side.CONVEX)].cutter.edge_radius == rho < derived
    assert generated_root_slot(blank, setups, Member.PINION, derived).min() < -0.1       # crossed: 0.5 mm here
    # at the limit the fillets touch: the root find's tolerance (1e-4 rho) times the slope (~1.6 mm per mm) bounds
    # the width left there
    assert abs(generated_root_slot(blank, setups, Member.PINION, rho / EDGE_RADIUS_FILL).min()) < 2e-4
    assert generated_root_slot(blank, setups, Member.PINION).min() > 0.0
    # the wheel's slot holds its derived edge radius: kept
    assert setups[(Member.GEAR, Side.CONVEX)].cutter.edge_radius == pytest.approx(
        default_cutter(member_blank(blank, Member.GEAR), Member.GEAR, Side.CONVEX).edge_radius, rel=1e-15)
    # the blade surface is that of the virtual sharp point: the synthesized mean point M is unchanged, and the
    # synthesized pair meshes with the refitted flanks
    import dataclasses

    from spiralbevel.generation import generate_flank

    u = np.linspace(2.0, 6.0, 5)[:, None]
    psi = np.linspace(-0.2, 0.2, 5)[None, :]
    for name, res in synth.items():
        s1 = Side.CONCAVE if name == "drive" else Side.CONVEX
        st = setups[(Member.PINION, s1)]
        assert res.pinion_flank is st.flank and res.pinion_cutter is st.cutter
        assert "fitted to the generated root slot" in st.source
        before = generate_flank(dataclasses.replace(st.cutter, edge_radius=derived), st.settings,
                                member_blank(blank, Member.PINION), Member.PINION, s1)
        np.testing.assert_array_equal(before.evaluate(u, psi, curvature=False).points,
                                      st.flank.evaluate(u, psi, curvature=False).points)


def test_generated_slot_holds_the_cutter(sample2):
    """As for the spiral bevel sample (tests/io/test_step_generated.py): neighbouring teeth do not overlap at the
    root, the slot bottom is narrower than the point width, and both whole members keep their fillets."""
    from spiralbevel.geometry.solid import root_slot_width

    _, blank, setups, _, cad, warns = sample2
    assert warns == []
    for m, z in ((Member.PINION, blank.z1), (Member.GEAR, blank.z2)):
        assert cad[m]["gear_fillet_rows"] == cad[m]["fillet_rows"] > 0
        (pa, _), (pb, _) = cad[m]["tooth"]
        width = root_slot_width(pa, pb, z)
        assert np.all(width > 0) and np.all(width < setups[(m, Side.CONVEX)].cutter.point_width), (m, width)


def _read_shape(path):
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    return reader.OneShape()


def _count(shape, kind):
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer

    ex, n = TopExp_Explorer(shape, getattr(TopAbs.TopAbs_ShapeEnum, f"TopAbs_{kind}")), 0
    while ex.More():
        n += 1
        ex.Next()
    return n


@pytest.fixture(scope="module")
def pinion_step(sample2, tmp_path_factory):
    pytest.importorskip("OCP")
    from spiralbevel.io.step import write_step

    c = sample2[4][Member.PINION]
    (pa, _), (pb, _) = c["tooth"]
    d = tmp_path_factory.mktemp("hyp_step")
    return (write_step(d / "pinion_tooth.step", pa, pb, solid=True, fillet_rows=c["fillet_rows"]),
            write_step(d / "pinion.step", pa, pb, solid=True, z=int(sample2[1].z1), fillet_rows=c["fillet_rows"]))


def test_whole_tooth_is_one_valid_closed_solid_and_reads_back_on_the_flanks(pinion_step, sample2):
    """Generated points between the fitted nodes (a grid twice as fine, on the fillet and on the blade) lie on the
    faces read back within 1e-3 mm, the bound of the spiral bevel test (measured 5.3e-4 mm)."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    from spiralbevel.gearset import facemilled as fm
    from spiralbevel.gearset.outputs import CAD_FILLET_ROWS
    from spiralbevel.io.step import read_step_surfaces

    _, blank, setups, _, _, _ = sample2
    res = pinion_step[0]
    shape = _read_shape(res.path)
    assert BRepCheck_Analyzer(shape).IsValid()
    assert _count(shape, "SOLID") == 1 and _count(shape, "SHELL") == 1 and res.n_faces == 10
    surfaces = read_step_surfaces(res.path)
    rot = fm.tooth_rotation(blank, setups, Member.PINION)
    for side in (Side.CONVEX, Side.CONCAVE):
        fine = setups[(Member.PINION, side)].flank.grid(2 * N_FACE - 1, 2 * N_PROFILE - 1,
                                                        n_fillet=2 * CAD_FILLET_ROWS - 1, curvature=False)
        pts = fine.points if side is Side.CONVEX else fm.rotate_grid(fine.points, fine.normals, rot)[0]
        dist = np.min([s.distance(pts.reshape(-1, 3)) for s in surfaces], axis=0)
        assert dist.max() <= 1e-3, (side, dist.max())


def test_whole_pinion_step_is_the_tooth_patterned_on_the_body(pinion_step):
    """One valid solid; its volume is the body's plus z teeth less what they share with the body (the root strip of
    each tooth lies on the body's cone, fitted to the root edges with the hypoid pinion's root apex off the member
    origin: nothing shared)."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    tooth, gear = pinion_step
    shape = _read_shape(gear.path)
    assert BRepCheck_Analyzer(shape).IsValid()
    assert _count(shape, "SOLID") == 1
    # measured 1.2e-6: the fused faces' volume integrated numerically by OpenCascade
    assert gear.solid_volume == pytest.approx(gear.body_volume + 13 * tooth.solid_volume, rel=1e-5)


def test_whole_pinion_stl_is_closed(sample2):
    from spiralbevel.geometry.solid import gear_mesh, tooth_mesh

    c = sample2[4][Member.PINION]
    tooth = tooth_mesh(*c["tooth"])
    gear = gear_mesh(*c["gear"], int(sample2[1].z1))
    # closed; a tooth is a sphere (chi = 2), the whole pinion with its bore a torus (chi = 0)
    assert tooth.is_watertight() and tooth.euler_characteristic() == 2
    assert gear.is_watertight() and gear.euler_characteristic() == 0
    assert gear.volume() > 13 * tooth.volume() > 0


def test_mirror_of_hands(sample2):
    """The right-hand pinion and left-hand wheel: every CAD tooth grid is the mirror image (y -> -y) of the
    left-hand design's, with the same refitted edge radius (measured: equal to 2e-12 mm, round-off of the mirrored
    machine settings)."""
    from spiralbevel.gearset.outputs import cad_teeth

    spec, blank, setups, _, cad, _ = sample2
    spec_r, blank_r, setups_r, _ = _design("RH")
    cad_r, warns = cad_teeth(spec_r, blank_r, setups_r, N_FACE, N_PROFILE)
    assert warns == []
    for m in (Member.PINION, Member.GEAR):
        assert setups_r[(m, Side.CONCAVE)].cutter.edge_radius == pytest.approx(
            setups[(m, Side.CONCAVE)].cutter.edge_radius, rel=1e-8)
        # the mirror turns the tooth about the axis the other way: compare up to one rotation about z
        p0, q0 = cad[m]["tooth"][0][0][4, 4] * [1.0, -1.0, 1.0], cad_r[m]["tooth"][0][0][4, 4]
        a = math.atan2(p0[1], p0[0]) - math.atan2(q0[1], q0[0])
        back = np.array([[math.cos(a), math.sin(a), 0.0], [-math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]])
        for k in (0, 1):
            p, p_r = cad[m]["tooth"][k][0], cad_r[m]["tooth"][k][0]
            err = np.abs((p * [1.0, -1.0, 1.0]) @ back - p_r).max()
            assert err < 1e-9, (m, k, err)


def test_gearset_writes_the_hypoid_teeth(sample2, tmp_path):
    """GearSet.to_stl / to_step on a hypoid design: the files of the main job, the same whole teeth and pinion as the
    CAD grids above (the volumes of the STL read back equal the meshes of those grids to the binary STL's float32
    rounding, ~1e-7 relative)."""
    import tomllib

    pytest.importorskip("OCP")
    import spiralbevel as sb
    from spiralbevel.geometry.solid import gear_mesh, tooth_mesh
    from spiralbevel.io.stl import read_stl

    data = tomllib.loads(SAMPLE2_TOML + SYNTHESIS)
    data["output"] = {"grid": [N_FACE, N_PROFILE]}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gs = sb.GearSet.from_dict(data)
        stl = gs.to_stl(tmp_path / "stl")
        step = gs.to_step(tmp_path / "step", whole_gear=False)
    assert sorted(p.name for p in stl) == ["gear.stl", "gear_tooth.stl", "pinion.stl", "pinion_tooth.stl"]
    assert sorted(p.name for p in step) == ["gear_tooth.step", "pinion_tooth.step"]
    c = sample2[4][Member.PINION]
    for name, mesh in (("pinion_tooth.stl", tooth_mesh(*c["tooth"])), ("pinion.stl", gear_mesh(*c["gear"], 13))):
        assert read_stl(tmp_path / "stl" / name).volume() == pytest.approx(mesh.volume(), rel=1e-6), name
