"""STEP export of tooth flanks as exact B-spline surfaces (OpenCascade through the optional ``OCP`` package).

Each flank grid ``points (n_face, n_profile, 3)`` (mm, member frame, toe -> heel along axis 0, root -> top along axis
1) is interpolated by a bicubic C2 B-spline surface (``GeomAPI_PointsToBSplineSurface``) that passes through every
node; u runs toe -> heel and v root -> top. The file holds the flank faces of one tooth, optionally the flanks of all
z teeth (turned by 2 pi k / z about +z) and optionally a closed solid of one tooth sewn from the two flanks and ruled
top land, root, toe and heel faces. Units: mm (``write.step.unit``). The file is written atomically.

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

from spiralbevel.errors import DesignError, MissingDependencyError
from spiralbevel.geometry.solid import flank_grid
from spiralbevel.io.atomic import atomic_write_bytes

__all__ = ["StepExport", "StepSurface", "flank_surface", "write_step", "read_step_surfaces"]

_PARAM = {"iso": "Approx_IsoParametric", "chord": "Approx_ChordLength", "centripetal": "Approx_Centripetal"}


def _occ(purpose: str = "STEP export"):
    """Import the OCP modules used here, or raise MissingDependencyError naming the ``cad`` extra."""
    try:
        import OCP  # noqa: F401
        from OCP import (
            Approx, BRep, BRepBuilderAPI, BRepFill, BRepGProp, GeomAbs, GeomAPI, GProp, IFSelect, Interface,
            STEPControl, TopAbs, TopExp, TopoDS, gp,
        )
    except ImportError as err:
        raise MissingDependencyError("cadquery-ocp-novtk", "cad", purpose) from err
    try:  # OCP >= 8 moved the NCollection instantiations
        from OCP.collections import Array2_gp_Pnt as Array2OfPnt
    except ImportError:  # pragma: no cover - OCP 7.x
        from OCP.TColgp import TColgp_Array2OfPnt as Array2OfPnt
    return dict(Approx=Approx, BRep=BRep, BRepBuilderAPI=BRepBuilderAPI, BRepFill=BRepFill, BRepGProp=BRepGProp,
                GeomAbs=GeomAbs, GeomAPI=GeomAPI, GProp=GProp, IFSelect=IFSelect, Interface=Interface,
                STEPControl=STEPControl, TopAbs=TopAbs, TopExp=TopExp, TopoDS=TopoDS, gp=gp, Array2OfPnt=Array2OfPnt)


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
        Volume of the sewn tooth solid, ``None`` when no solid was requested or sewing failed.
    node_deviation : float, mm
        Largest distance of a grid node from its fitted surface (~1e-12 for interpolation).
    """

    path: Path
    n_faces: int
    solid_volume: float | None
    node_deviation: float


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


def _tooth_solid(occ, sa, sb, tol: float):
    """Sew the two flank surfaces and ruled top land, root, toe and heel faces into a solid; (solid, volume)."""
    B = occ["BRepBuilderAPI"]
    faces = [_face(occ, sa), _face(occ, sb)]
    ua0, ua1, va0, va1 = sa.Bounds()
    ub0, ub1, vb0, vb1 = sb.Bounds()
    pairs = [(sa.VIso(va1), sb.VIso(vb1)), (sa.VIso(va0), sb.VIso(vb0)),  # top land, root
             (sa.UIso(ua0), sb.UIso(ub0)), (sa.UIso(ua1), sb.UIso(ub1))]  # toe, heel
    for ca, cb in pairs:
        ea, eb = B.BRepBuilderAPI_MakeEdge(ca).Edge(), B.BRepBuilderAPI_MakeEdge(cb).Edge()
        faces.append(occ["BRepFill"].BRepFill.Face_s(ea, eb))
    sew = B.BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sew.Add(f)
    sew.Perform()
    shell = sew.SewedShape()
    if shell.ShapeType() != occ["TopAbs"].TopAbs_ShapeEnum.TopAbs_SHELL:
        return None, None
    maker = B.BRepBuilderAPI_MakeSolid(_downcast(occ, "Shell", shell))
    if not maker.IsDone():
        return None, None
    solid = maker.Solid()
    props = occ["GProp"].GProp_GProps()
    occ["BRepGProp"].BRepGProp.VolumeProperties_s(solid, props)
    volume = props.Mass()
    if volume < 0:  # shell oriented inward: reverse it
        solid.Reverse()
        volume = -volume
    return solid, volume


def write_step(path: "str | os.PathLike[str]", convex, concave, *, z: int | None = None, solid: bool = False,
               parametrization: str = "iso", tolerance: float | None = None) -> StepExport:
    """Write the flanks of a tooth (or of a whole gear) as exact B-spline faces to a STEP file (AP214, mm).

    Parameters
    ----------
    path : str or PathLike
        Target ``.step`` file; its directory must exist. Written to a temporary file, then moved into place.
    convex, concave : grid
        Flank grids ``points (n, m, 3)``, mm (see :func:`spiralbevel.geometry.solid.tooth_mesh`); normals unused.
    z : int, optional
        Number of teeth: write the flanks of all z teeth (a compound of 2 z faces) instead of one tooth.
    solid : bool
        Also write a closed solid of one tooth (flanks sewn to ruled top land, root, toe and heel faces).
    parametrization, tolerance
        Passed to :func:`flank_surface`.

    Returns
    -------
    StepExport
        Path, number of faces, solid volume and the node deviation of the fits.

    Raises
    ------
    MissingDependencyError
        The optional package ``cadquery-ocp-novtk`` (extra ``cad``) is not installed.
    """
    occ = _occ()
    pa, _ = flank_grid(convex, "convex")
    pb, _ = flank_grid(concave, "concave")
    if z is not None and (isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 1):
        raise DesignError.single("z", z, "integer >= 1 (or None for one tooth)", "-")
    surfaces = [flank_surface(p, parametrization, tolerance) for p in (pa, pb)]
    deviation = max(float(StepSurface(s).distance(p).max()) for s, p in zip(surfaces, (pa, pb)))
    gp = occ["gp"]
    builder = occ["BRep"].BRep_Builder()
    compound = occ["TopoDS"].TopoDS_Compound()
    builder.MakeCompound(compound)
    n_faces = 0
    for k in range(1 if z is None else int(z)):
        trsf = gp.gp_Trsf()
        trsf.SetRotation(gp.gp_Ax1(gp.gp_Pnt(0, 0, 0), gp.gp_Dir(0, 0, 1)), 2.0 * np.pi * k / (z or 1))
        for s in surfaces:
            face = _face(occ, s)
            if k:
                face = occ["BRepBuilderAPI"].BRepBuilderAPI_Transform(face, trsf, True).Shape()
            builder.Add(compound, face)
            n_faces += 1
    volume = None
    if solid:
        scale = float(np.ptp(np.concatenate([pa, pb]).reshape(-1, 3), axis=0).max())
        shape, volume = _tooth_solid(occ, *surfaces, tol=max(1e-6, 1e-7 * scale))  # type: ignore[misc]  # two flanks
        if shape is not None:
            builder.Add(compound, shape)
            n_faces += 6
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
    return StepExport(path=target, n_faces=n_faces, solid_volume=volume, node_deviation=deviation)


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
