"""Closed solids for STEP export: one tooth sewn from its faces, the body of revolution of a whole gear, and the
gear fused from the body and z placements of one tooth (OpenCascade; used by :func:`spiralbevel.io.step.write_step`).
"""

from __future__ import annotations

import numpy as np

from spiralbevel.errors import DesignError
from spiralbevel.geometry.solid import GearBody, spherical_lerp
from spiralbevel.io.step import _count, _face, _valid, _volume, flank_surface


def _bridge(ea, eb, n_across: int):
    """B-spline face grid between two node polylines ea, eb (k, 3): rungs linear in (rho, theta, azimuth) about the
    apex, as the triangle meshes bridge them (``geometry.solid``), so that a face between two points of one sphere
    (toe, heel) or one cone about the axis (root) stays on it."""
    t = np.linspace(0.0, 1.0, n_across)
    return np.stack([spherical_lerp(p, q, t) for p, q in zip(ea, eb)])


def _tooth_solid(occ, ga: list, gb: list, sa: list, sb: list, tol: float, n_across: int = 7):
    """Sew the flank surfaces ``sa``, ``sb`` (root -> top lists, the same number per flank, fitted to the node grids
    ``ga``, ``gb``) and the root, top land, toe and heel faces bridged between their edges into one closed solid;
    (solid, volume), or (None, reason)."""
    B = occ["BRepBuilderAPI"]
    faces = [_face(occ, s) for s in sa + sb]
    bridges = [(ga[0][:, 0], gb[0][:, 0]), (ga[-1][:, -1], gb[-1][:, -1])]  # root (cutter-tip lines), top land
    for pa, pb in zip(ga, gb):  # toe and heel, one face per flank segment
        bridges += [(pa[0], pb[0]), (pa[-1], pb[-1])]
    for ea, eb in bridges:
        faces.append(_face(occ, flank_surface(_bridge(ea, eb, n_across))))
    sew = B.BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sew.Add(f)
    sew.Perform()
    shell = sew.SewedShape()
    if shell.ShapeType() != occ["TopAbs"].TopAbs_ShapeEnum.TopAbs_SHELL:
        return None, "the faces do not sew into one shell"
    if sew.NbFreeEdges() or sew.NbMultipleEdges():
        return None, f"{sew.NbFreeEdges()} free and {sew.NbMultipleEdges()} multiple edges after sewing"
    # the same shell with its faces in construction order (flanks first, root -> top, convex then concave), so that
    # a reader finds the flank faces first
    ordered = occ["TopoDS"].TopoDS_Shell()
    builder = occ["BRep"].BRep_Builder()
    builder.MakeShell(ordered)
    sewn = [sew.Modified(f) for f in faces]
    explorer = occ["TopExp"].TopExp_Explorer(shell, occ["TopAbs"].TopAbs_ShapeEnum.TopAbs_FACE)
    in_shell = []  # (construction index, face as oriented in the sewn shell)
    while explorer.More():
        face = explorer.Current()
        in_shell.append((next((k for k, f in enumerate(sewn) if f.IsSame(face)), len(sewn)), face))
        explorer.Next()
    for _, face in sorted(in_shell, key=lambda t: t[0]):
        builder.Add(ordered, face)
    ordered.Closed(True)
    maker = B.BRepBuilderAPI_MakeSolid(ordered)
    if not maker.IsDone():
        return None, "no solid from the sewn shell"
    solid = maker.Solid()
    volume = _volume(occ, solid)
    if volume < 0:  # shell oriented inward: reverse it
        solid.Reverse()
        volume = -volume
    if not _valid(occ, solid):
        return None, "BRepCheck_Analyzer finds the solid invalid"
    return solid, volume


def _body_solid(occ, pa, pb, body: GearBody):
    """Solid of revolution under the teeth: the cone fitted to the root edges of both flanks (the least-squares line
    r = r0 + k z through their (z, r) in the axial plane: a cone through the apex for a spiral bevel member, whose
    root edges lie on it, r0 = 0 to round-off; a root apex off the member origin for a hypoid member), between planes
    through the lowest toe and highest heel root points, down to the bore. (solid, volume, dict of the chosen
    values)."""
    gp = occ["gp"]
    root = np.concatenate([pa[:, 0], pb[:, 0]])
    r0, k = np.linalg.lstsq(np.column_stack([np.ones(len(root)), root[:, 2]]), np.hypot(root[:, 0], root[:, 1]),
                            rcond=None)[0]
    toe = np.stack([pa[0, 0], pb[0, 0]])
    heel = np.stack([pa[-1, 0], pb[-1, 0]])
    z_front, z_back = float(toe[:, 2].min()), float(heel[:, 2].max())
    front = body.front_z if body.front_z is not None else z_front
    back = body.back_z if body.back_z is not None else z_back
    r_toe = float(np.hypot(toe[:, 0], toe[:, 1]).min())
    bore = body.bore_radius if body.bore_radius is not None else 0.5 * r_toe
    r_front, r_back = float(r0 + k * z_front), float(r0 + k * z_back)
    if not 0.0 < bore < min(r_front, r_back):
        raise DesignError.single("body.bore_radius", bore, f"0 < value < {min(r_front, r_back):.6g} (root radius)",
                                 "mm")
    if not front <= z_front:
        raise DesignError.single("body.front_z", front, f"<= {z_front:.6g} (toe root)", "mm")
    if not back >= z_back:
        raise DesignError.single("body.back_z", back, f">= {z_back:.6g} (heel root)", "mm")
    # profile in the xz half plane: bore front, cone toe (on the front plane), cone heel, bore back
    prof = [(bore, front), (r_front, front), (r_front, z_front), (r_back, z_back), (r_back, back), (bore, back)]
    prof = [p for k, p in enumerate(prof) if k == 0 or np.hypot(p[0] - prof[k - 1][0], p[1] - prof[k - 1][1]) > 0]
    poly = occ["BRepBuilderAPI"].BRepBuilderAPI_MakePolygon()
    for r, zz in prof:
        poly.Add(gp.gp_Pnt(float(r), 0.0, float(zz)))
    poly.Close()
    face = occ["BRepBuilderAPI"].BRepBuilderAPI_MakeFace(poly.Wire(), True).Face()
    axis = gp.gp_Ax1(gp.gp_Pnt(0, 0, 0), gp.gp_Dir(0, 0, 1))
    solid = occ["BRepPrimAPI"].BRepPrimAPI_MakeRevol(face, axis, 2.0 * np.pi).Shape()
    volume = _volume(occ, solid)
    if volume < 0:
        solid.Reverse()
        volume = -volume
    return solid, volume


def _rotation(occ, k: int, z: int):
    gp = occ["gp"]
    trsf = gp.gp_Trsf()
    trsf.SetRotation(gp.gp_Ax1(gp.gp_Pnt(0, 0, 0), gp.gp_Dir(0, 0, 1)), 2.0 * np.pi * k / z)
    return trsf


def _gear_solid(occ, tooth, body_solid, z: int, fuzzy: float):
    """Fuse the body with z located copies of one tooth solid (TopLoc locations: one tooth geometry, z placements)."""
    args, tools = occ["ListOfShape"](), occ["ListOfShape"]()
    args.Append(body_solid)
    for k in range(z):
        tools.Append(tooth.Moved(occ["TopLoc"].TopLoc_Location(_rotation(occ, k, z))))
    fuse = occ["BRepAlgoAPI"].BRepAlgoAPI_Fuse()
    fuse.SetArguments(args)
    fuse.SetTools(tools)
    fuse.SetFuzzyValue(fuzzy)
    fuse.SetUseOBB(True)  # oriented bounding boxes: fewer candidate face pairs (measured about 2x faster)
    fuse.Build()
    if not fuse.IsDone():
        return None, "the Boolean fuse of body and teeth failed"
    fuse.SimplifyResult()
    shape = fuse.Shape()
    if _count(occ, shape, "SOLID") != 1:
        return None, f"{_count(occ, shape, 'SOLID')} solids after the fuse (teeth not joined to the body)"
    if not _valid(occ, shape):
        return None, "BRepCheck_Analyzer finds the fused gear invalid"
    return shape, _volume(occ, shape)
