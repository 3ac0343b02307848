"""STEP export of teeth and gears with exact B-spline flank surfaces (OpenCascade through the optional ``OCP`` package).

Each flank grid ``points (n_face, n_profile, 3)`` (mm, member frame, toe -> heel along axis 0, root -> top along axis
1) is interpolated by bicubic C2 B-spline surfaces (``GeomAPI_PointsToBSplineSurface``) that pass through every node;
u runs toe -> heel and v root -> top. A flank whose first rows lie on the generated root fillet gets two faces, fillet
and blade, meeting at the fillet/blade junction (one bicubic across the junction, where the curvature jumps, would
wander by ~0.1 mm between the nodes). The file holds the flank faces of one tooth or of all z teeth, one closed tooth
solid (flanks, root, top land, toe and heel; the last four bridged between the flank edges along arcs about the apex,
as the STL meshes are, so that they lie on the toe and heel spheres and on the root and face cones where the edges
do), or a whole gear: that solid placed z times about the axis (one shape, z locations) and fused with a body of
revolution. Units: mm (``write.step.unit``). The file is written atomically.

Install with ``pip install 'spiralbevel[cad]'`` (package ``cadquery-ocp-novtk``); OCP is imported inside the
functions, so the rest of spiralbevel works without it.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spiralbevel.errors import DesignError, GeometryError, MissingDependencyError
from spiralbevel.geometry.solid import GearBody, flank_grid
from spiralbevel.io.atomic import atomic_write_bytes

__all__ = ["StepExport", "StepSurface", "flank_surface", "write_step", "read_step_surfaces"]

#: mm: faces whose edges lie closer than this are sewn together (the fillet faces use chord-length parameters along
#: the face width, the faces bridged to them index-uniform ones: their shared edges interpolate the same nodes and
#: differ between them by about 1e-5 mm on the designs tested)
SEWING_TOLERANCE = 1e-3

_PARAM = {"iso": "Approx_IsoParametric", "chord": "Approx_ChordLength", "centripetal": "Approx_Centripetal"}


def _occ(purpose: str = "STEP export"):
    """Import the OCP modules used here, or raise MissingDependencyError naming the ``cad`` extra."""
    try:
        import OCP  # noqa: F401
        from OCP import (
            Approx, BRep, BRepAlgoAPI, BRepBuilderAPI, BRepCheck, BRepFill, BRepGProp, BRepPrimAPI, GeomAbs, GeomAPI,
            GProp, IFSelect, Interface, STEPControl, TopAbs, TopExp, TopLoc, TopoDS, gp,
        )
    except ImportError as err:
        raise MissingDependencyError("cadquery-ocp-novtk", "cad", purpose) from err
    try:  # OCP >= 8 moved the NCollection instantiations
        from OCP.collections import Array2_gp_Pnt as Array2OfPnt
    except ImportError:  # pragma: no cover - OCP 7.x
        from OCP.TColgp import TColgp_Array2OfPnt as Array2OfPnt
    try:
        from OCP.collections import List_TopoDS_Shape as ListOfShape
    except ImportError:  # pragma: no cover - OCP 7.x
        from OCP.TopTools import TopTools_ListOfShape as ListOfShape
    return dict(Approx=Approx, BRep=BRep, BRepAlgoAPI=BRepAlgoAPI, BRepBuilderAPI=BRepBuilderAPI, BRepCheck=BRepCheck,
                BRepFill=BRepFill, BRepGProp=BRepGProp, BRepPrimAPI=BRepPrimAPI, GeomAbs=GeomAbs, GeomAPI=GeomAPI,
                GProp=GProp, IFSelect=IFSelect, Interface=Interface, STEPControl=STEPControl, TopAbs=TopAbs,
                TopExp=TopExp, TopLoc=TopLoc, TopoDS=TopoDS, gp=gp, Array2OfPnt=Array2OfPnt, ListOfShape=ListOfShape)


def _downcast(occ, kind: str, shape):
    """TopoDS::Face/Shell(shape) in either OCP spelling (``TopoDS.Face_s`` in 7.x, module functions in 8.x)."""
    ns = occ["TopoDS"].TopoDS
    fn = getattr(ns, kind + "_s", None) or getattr(ns, kind)
    return fn(shape)


@contextlib.contextmanager
def _quiet():
    """Raise OpenCascade's default printers to warnings only (the STEP translators print statistics to stdout)."""
    try:
        from OCP.Message import Message, Message_Gravity

        printers = list(Message.DefaultMessenger_s().Printers())
    except Exception:  # pragma: no cover - messenger API differs between OCP versions
        yield
        return
    levels = [p.GetTraceLevel() for p in printers]
    for p in printers:
        p.SetTraceLevel(Message_Gravity.Message_Warning)
    try:
        yield
    finally:
        for p, level in zip(printers, levels):
            p.SetTraceLevel(level)


def flank_surface(points, parametrization: str = "iso", tolerance: float | None = None):
    """Bicubic C2 B-spline surface through a flank grid (an OCP ``Geom_BSplineSurface``).

    Parameters
    ----------
    points : (n, m, 3) float, mm
        Grid nodes, n, m >= 4 is advisable (>= 2 required).
    parametrization : {"iso", "chord", "centripetal"}
        Parameters given to the nodes: uniform in the grid indices (best when the grid is uniform in the flank's own
        parameters, as grids from :class:`~spiralbevel.geometry.domain.ParallelogramDomain` are), chord length, or
        centripetal.
    tolerance : float, mm, optional
        ``None`` interpolates (the surface passes through every node). A value approximates with degree 3, C2, and
        that largest distance at the nodes.

    Returns
    -------
    OCP.Geom.Geom_BSplineSurface
        u along axis 0 (toe -> heel), v along axis 1 (root -> top), parameters in [0, 1].
    """
    occ = _occ()
    pts, _ = flank_grid(points, "points")
    if parametrization not in _PARAM:
        raise DesignError.single("parametrization", parametrization, "one of " + ", ".join(_PARAM), "-")
    if tolerance is not None and not (np.isfinite(tolerance) and tolerance > 0):
        raise DesignError.single("tolerance", tolerance, "> 0 (or None to interpolate)", "mm")
    n, m = pts.shape[:2]
    arr = occ["Array2OfPnt"](1, n, 1, m)
    gp_Pnt = occ["gp"].gp_Pnt
    for i in range(n):
        for j in range(m):
            x, y, z = pts[i, j]
            arr.SetValue(i + 1, j + 1, gp_Pnt(float(x), float(y), float(z)))
    par = getattr(occ["Approx"].Approx_ParametrizationType, _PARAM[parametrization])
    fit = occ["GeomAPI"].GeomAPI_PointsToBSplineSurface()
    if tolerance is None:
        fit.Interpolate(arr, par, False)
    else:
        fit.Init(arr, par, 3, 3, occ["GeomAbs"].GeomAbs_Shape.GeomAbs_C2, float(tolerance), False)
    if not fit.IsDone():
        raise DesignError.single("points", f"grid {n}x{m}", "a regular grid without repeated nodes", "mm",
                                 "B-spline fit failed")
    return fit.Surface()


@dataclass(frozen=True)
class StepExport:
    """What :func:`write_step` wrote.

    Attributes
    ----------
    path : pathlib.Path
        The STEP file.
    n_faces : int
        Faces written (flanks of every tooth, plus the faces of the solid).
    solid_volume : float or None, mm^3
        Volume of the written solid (the tooth, or the whole gear), ``None`` when no solid was requested.
    node_deviation : float, mm
        Largest distance of a grid node from its fitted surface (~1e-12 for interpolation).
    tooth_volume : float or None, mm^3
        Volume of the one tooth solid (also for a whole gear).
    body_volume : float or None, mm^3
        Volume of the body of revolution of a whole gear, before the teeth are fused to it.
    """

    path: Path
    n_faces: int
    solid_volume: float | None
    node_deviation: float
    tooth_volume: float | None = None
    body_volume: float | None = None


class StepSurface:
    """A surface read from a STEP file: evaluation and point projection (wraps an OCP ``Geom_Surface``)."""

    def __init__(self, surface):
        self.surface = surface

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(u_min, u_max, v_min, v_max)."""
        return tuple(self.surface.Bounds())

    def __call__(self, u, v) -> np.ndarray:
        """Points at parameters (u, v) (broadcast), shape (..., 3), mm."""
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        out = np.empty(u.shape + (3,))
        for k, (uu, vv) in enumerate(zip(u.ravel(), v.ravel())):
            p = self.surface.Value(float(uu), float(vv))
            out.reshape(-1, 3)[k] = (p.X(), p.Y(), p.Z())
        return out

    def sample(self, nu: int, nv: int) -> np.ndarray:
        """Grid of nu x nv points uniform in (u, v) over the bounds, shape (nu, nv, 3), mm."""
        u0, u1, v0, v1 = self.bounds
        u, v = np.meshgrid(np.linspace(u0, u1, nu), np.linspace(v0, v1, nv), indexing="ij")
        return self(u, v)

    def distance(self, points) -> np.ndarray:
        """Distance of each point to the (untrimmed) surface by orthogonal projection, shape (...), mm; inf when
        no orthogonal projection exists."""
        occ = _occ("STEP import")
        pts = np.asarray(points, dtype=float)
        out = np.empty(pts.shape[:-1])
        gp_Pnt, Project = occ["gp"].gp_Pnt, occ["GeomAPI"].GeomAPI_ProjectPointOnSurf
        for k, p in enumerate(pts.reshape(-1, 3)):
            proj = Project(gp_Pnt(*map(float, p)), self.surface)
            out.reshape(-1)[k] = proj.LowerDistance() if proj.NbPoints() > 0 else np.inf
        return out


def _face(occ, surface):
    u0, u1, v0, v1 = surface.Bounds()
    return occ["BRepBuilderAPI"].BRepBuilderAPI_MakeFace(surface, u0, u1, v0, v1, 1e-7).Face()


def _volume(occ, shape) -> float:
    props = occ["GProp"].GProp_GProps()
    occ["BRepGProp"].BRepGProp.VolumeProperties_s(shape, props)
    return float(props.Mass())


def _count(occ, shape, kind: str) -> int:
    explorer = occ["TopExp"].TopExp_Explorer(shape, getattr(occ["TopAbs"].TopAbs_ShapeEnum, f"TopAbs_{kind}"))
    n = 0
    while explorer.More():
        n += 1
        explorer.Next()
    return n


def _valid(occ, shape) -> bool:
    return bool(occ["BRepCheck"].BRepCheck_Analyzer(shape).IsValid())


def _flank_surfaces(points, fillet_rows: int, parametrization: str, tolerance):
    """Surfaces of one flank from root to top: the fillet (rows 0..k, chord-length parameters: its rows crowd toward
    the cutter tip) and the blade part (rows k..m-1), or one surface when ``fillet_rows`` k is 0."""
    if not fillet_rows:
        return [flank_surface(points, parametrization, tolerance)]
    return [flank_surface(points[:, :fillet_rows + 1], "chord", tolerance),
            flank_surface(points[:, fillet_rows:], parametrization, tolerance)]


def write_step(path: "str | os.PathLike[str]", convex, concave, *, z: int | None = None, solid: bool = False,
               parametrization: str = "iso", tolerance: float | None = None, fillet_rows=0,
               body: GearBody | None = None) -> StepExport:
    """Write one tooth or a whole gear to a STEP file (AP214, mm) with exact B-spline flank faces.

    Four kinds of file:

    - ``solid=False``: the flank faces of one tooth (``z=None``) or of all z teeth, turned by 2 pi k / z about +z;
    - ``solid=True, z=None``: one closed tooth solid and nothing else: flank faces (each split at the fillet/blade
      junction when ``fillet_rows`` is given), a ruled root face between the two cutter-tip lines, a ruled top land
      and ruled toe and heel faces;
    - ``solid=True, z``: a whole gear, one solid: that tooth placed z times (the same shape under z rotations, TopLoc
      locations) fused with a body of revolution (the cone through the root edges, front and back planes, bore).

    Parameters
    ----------
    path : str or PathLike
        Target ``.step`` file; its directory must exist. Written to a temporary file, then moved into place.
    convex, concave : grid
        Flank grids ``points (n, m, 3)``, mm (see :func:`spiralbevel.geometry.solid.tooth_mesh`); normals unused.
    z : int, optional
        Number of teeth.
    solid : bool
        Write closed solids (see above) instead of loose flank faces.
    parametrization, tolerance
        Passed to :func:`flank_surface` (the fillet faces always use chord-length parameters).
    fillet_rows : int or (int, int)
        Rows 0..k of each grid lie on the root fillet, row k being the fillet/blade junction (also the first blade
        row: the grids hold it once). 0: no fillet. One value for both flanks or (convex, concave); both zero or both
        positive for a solid.
    body : GearBody, optional
        Bore radius and axial extent of the whole gear's body (``n_bore`` unused); defaults as in
        :class:`~spiralbevel.geometry.solid.GearBody`.

    Returns
    -------
    StepExport
        Path, number of faces, volumes and the node deviation of the fits.

    Raises
    ------
    MissingDependencyError
        The optional package ``cadquery-ocp-novtk`` (extra ``cad``) is not installed.
    GeometryError
        The solid does not close (sewing leaves free edges, or BRepCheck finds it invalid) or the fused gear is not
        one valid solid.
    """
    from spiralbevel.io.step_solid import _body_solid, _gear_solid, _rotation, _tooth_solid

    occ = _occ()
    pa, _ = flank_grid(convex, "convex")
    pb, _ = flank_grid(concave, "concave")
    if z is not None and (isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 1):
        raise DesignError.single("z", z, "integer >= 1 (or None for one tooth)", "-")
    ka, kb = (fillet_rows, fillet_rows) if np.isscalar(fillet_rows) else tuple(fillet_rows)
    for name, k, p in (("fillet_rows", ka, pa), ("fillet_rows", kb, pb)):
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 0 <= k <= p.shape[1] - 2:
            raise DesignError.single(name, k, f"integer, 0 <= value <= {p.shape[1] - 2} (profile rows - 2)", "-")
    if solid and (ka == 0) != (kb == 0):
        raise DesignError.single("fillet_rows", (ka, kb), "both zero or both positive for a solid", "-")
    sa = _flank_surfaces(pa, ka, parametrization, tolerance)
    sb = _flank_surfaces(pb, kb, parametrization, tolerance)
    nodes = [p[:, :k + 1] for p, k in ((pa, ka), (pb, kb)) if k] + [pa[:, ka:], pb[:, kb:]]
    fits = [s for s in sa[:-1] + sb[:-1]] + [sa[-1], sb[-1]]
    deviation = max(float(StepSurface(s).distance(p).max()) for s, p in zip(fits, nodes))
    builder = occ["BRep"].BRep_Builder()
    compound = occ["TopoDS"].TopoDS_Compound()
    builder.MakeCompound(compound)
    n_faces, volume, tooth_volume, body_volume = 0, None, None, None
    if not solid:
        for k in range(1 if z is None else int(z)):
            for s in sa + sb:
                face = _face(occ, s)
                if k:
                    face = face.Moved(occ["TopLoc"].TopLoc_Location(_rotation(occ, k, int(z))))  # type: ignore[arg-type]  # k > 0: z set
                builder.Add(compound, face)
                n_faces += 1
    else:
        scale = float(np.ptp(np.concatenate([pa, pb]).reshape(-1, 3), axis=0).max())
        ga = [pa[:, :ka + 1], pa[:, ka:]] if ka else [pa]
        gb = [pb[:, :kb + 1], pb[:, kb:]] if kb else [pb]
        tooth, reason = _tooth_solid(occ, ga, gb, sa, sb, tol=SEWING_TOLERANCE)
        if tooth is None:
            raise GeometryError.single("flanks", "not closed", "flank grids bounding one tooth", "-", reason)
        tooth_volume = volume = reason
        shape = tooth
        if z is not None:
            body_shape, body_volume = _body_solid(occ, pa, pb, body or GearBody())
            shape, reason = _gear_solid(occ, tooth, body_shape, int(z), fuzzy=1e-5 * scale)
            if shape is None:
                raise GeometryError.single("z", z, "teeth that join the body into one solid", "-", reason)
            volume = reason
        builder.Add(compound, shape)
        n_faces = _count(occ, shape, "FACE")
    Interface_Static = occ["Interface"].Interface_Static
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    writer = occ["STEPControl"].STEPControl_Writer()
    with _quiet(), tempfile.TemporaryDirectory() as tmp:
        writer.Transfer(compound, occ["STEPControl"].STEPControl_StepModelType.STEPControl_AsIs)
        tmp_file = os.path.join(tmp, "export.step")
        status = writer.Write(tmp_file)
        if status != occ["IFSelect"].IFSelect_ReturnStatus.IFSelect_RetDone:
            raise OSError(f"STEP writer failed with status {status}")
        target = atomic_write_bytes(path, Path(tmp_file).read_bytes())
    return StepExport(path=target, n_faces=n_faces, solid_volume=volume, node_deviation=deviation,
                      tooth_volume=tooth_volume, body_volume=body_volume)


def read_step_surfaces(path: "str | os.PathLike[str]") -> list[StepSurface]:
    """Read every face of a STEP file and return its underlying surface, in file order.

    Parameters
    ----------
    path : str or PathLike
        STEP file (lengths converted to mm by the reader).

    Returns
    -------
    list of StepSurface
        One per face (flanks first for files written by :func:`write_step`).
    """
    occ = _occ("STEP import")
    if not Path(path).is_file():
        raise DesignError.single("path", str(path), "an existing STEP file", "-")
    reader = occ["STEPControl"].STEPControl_Reader()
    with _quiet():
        if reader.ReadFile(str(path)) != occ["IFSelect"].IFSelect_ReturnStatus.IFSelect_RetDone:
            raise DesignError.single("path", str(path), "a readable STEP file", "-")
        reader.TransferRoots()
    shape = reader.OneShape()
    explorer = occ["TopExp"].TopExp_Explorer(shape, occ["TopAbs"].TopAbs_ShapeEnum.TopAbs_FACE)
    out = []
    while explorer.More():
        face = _downcast(occ, "Face", explorer.Current())
        out.append(StepSurface(occ["BRep"].BRep_Tool.Surface_s(face)))
        explorer.Next()
    return out
