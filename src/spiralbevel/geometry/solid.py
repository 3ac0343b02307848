"""Closed triangle meshes of one tooth and of a whole gear, built from two flank point grids.

Input grids are plain: ``points (n_face, n_profile, 3)`` in mm in the member frame (axis +z, apex at the origin, body
toward +z; docs/conventions.md), toe -> heel along axis 0 and root -> top along axis 1, with optional outward unit
normals of the same shape. Any object with ``points`` and ``normals`` attributes, a ``(points, normals)`` tuple, a
mapping with those keys or a bare points array is accepted, so both log-spiral and generated flanks can be closed.

A tooth is a topological box: the two flanks, the top land (ruled strip between the flanks' top edges), the root
strip (between their root edges) and the toe and heel end faces (ruled between the two toe, resp. heel, profiles).
Edges that coincide (a pointed top, flanks meeting at the root) are welded, so their strip vanishes.

A gear is z teeth turned by 2 pi k / z about +z, root lands (ruled strips between the root edges of neighbouring
teeth) and a body: a front face from the toe root loop to a bore circle at ``front_z``, a bore cylinder and a back face
from the heel root loop to the bore circle at ``back_z``. The body alone (:func:`gear_body_mesh`) closes the root
loops with the root strips under the teeth instead of the teeth, so gear = body + z x tooth exactly (same strips).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spiralbevel._core.rotations import apply, rot_z
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.geometry.surface_mesh import (
    MeshBuilder,
    OrientationError,
    TriangleMesh,
    chord_param,
    grid_faces,
    open_edges,
    orientation_sign,
    strip_faces,
    weld,
    zip_rungs,
)

__all__ = ["GearBody", "TriangleMesh", "tooth_mesh", "gear_mesh", "gear_body_mesh", "flank_grid", "root_slot_width",
           "spherical_lerp"]

_WELD_REL = 1e-9  # vertices closer than this fraction of the model size are the same vertex


@dataclass(frozen=True)
class GearBody:
    """Simple gear body under the root cone.

    Attributes
    ----------
    bore_radius : float, mm
        Radius of the bore (0 < bore_radius < smallest radius of the root loops). ``None``: half the smallest
        radius of the toe root loop.
    front_z : float, mm
        Axial position of the front (toe-side) bore circle, at most the smallest z of the toe root loop. ``None``:
        that smallest z.
    back_z : float, mm
        Axial position of the back (heel-side) bore circle, at least the largest z of the heel root loop. ``None``:
        that largest z.
    n_bore : int
        Number of vertices on each bore circle (>= 3). ``None``: max(48, 4 z).
    """

    bore_radius: float | None = None
    front_z: float | None = None
    back_z: float | None = None
    n_bore: int | None = None


def flank_grid(grid, name: str = "grid") -> tuple[np.ndarray, np.ndarray | None]:
    """Points (n, m, 3) and normals (n, m, 3) or None from any accepted grid form; validated (DesignError)."""
    normals = None
    if isinstance(grid, dict):
        points, normals = grid["points"], grid.get("normals")
    elif hasattr(grid, "points"):
        points, normals = grid.points, getattr(grid, "normals", None)
    elif isinstance(grid, tuple) and len(grid) == 2:
        points, normals = grid
    else:
        points = grid
    try:
        points = np.asarray(points, dtype=float)
    except (TypeError, ValueError) as err:
        raise DesignError.single(f"{name}.points", type(points).__name__, "an (n, m, 3) float array", "mm") from err
    if points.ndim != 3 or points.shape[2] != 3 or points.shape[0] < 2 or points.shape[1] < 2:
        raise DesignError.single(f"{name}.points", f"shape {points.shape}", "shape (n, m, 3) with n, m >= 2", "mm")
    if not np.all(np.isfinite(points)):
        raise DesignError.single(f"{name}.points", "non-finite values", "finite coordinates", "mm")
    if normals is not None:
        normals = np.asarray(normals, dtype=float)
        if normals.shape != points.shape or not np.all(np.isfinite(normals)):
            raise DesignError.single(f"{name}.normals", f"shape {normals.shape}", f"finite, shape {points.shape}", "-")
    return points, normals


def _scale(*grids) -> float:
    pts = np.concatenate([g.reshape(-1, 3) for g in grids])
    return float(np.ptp(pts, axis=0).max() + np.abs(pts).max())


def _spherical(p):
    """(rho, theta, alpha) of points (..., 3): distance from the apex, polar angle from +z, azimuth."""
    rho = np.linalg.norm(p, axis=-1)
    return rho, np.arccos(np.clip(p[..., 2] / np.where(rho > 0, rho, 1.0), -1.0, 1.0)), np.arctan2(p[..., 1], p[..., 0])


def spherical_lerp(p, q, t):
    """Points at fractions t (k,) between p and q (3,), linear in (rho, theta, alpha) about the apex.

    A rung between two points of one sphere stays on that sphere and one between two points of one cone about +z
    stays on that cone, so end faces stay on the toe/heel spheres and root strips on the root cone.
    """
    (r0, t0, a0), (r1, t1, a1) = _spherical(p), _spherical(q)
    da = (a1 - a0 + np.pi) % (2.0 * np.pi) - np.pi
    rho, th, al = r0 + t * (r1 - r0), t0 + t * (t1 - t0), a0 + t * da
    return np.stack([rho * np.sin(th) * np.cos(al), rho * np.sin(th) * np.sin(al), rho * np.cos(th)], -1)


class _Bridger:
    """Strips between two vertex polylines, subdivided across into rungs of length about ``h`` (mm).

    Rungs are cached by their end vertices so that a rung shared by two strips (a tooth's toe face and the root strip
    under it, say) has the same interior vertices in both.
    """

    def __init__(self, builder: MeshBuilder, h: float):
        self.builder, self.h = builder, h
        self._cache: dict = {}

    def rung(self, u: int, v: int, pu, pv) -> np.ndarray:
        key = (u, v) if u < v else (v, u)
        if key not in self._cache:
            p, q = (pu, pv) if u < v else (pv, pu)
            k = max(1, int(np.ceil(np.linalg.norm(q - p) / self.h)))
            mid = self.builder.add_vertices(spherical_lerp(p, q, np.linspace(0.0, 1.0, k + 1)[1:-1]))
            self._cache[key] = np.concatenate([[key[0]], mid, [key[1]]]).astype(np.int64)
        r = self._cache[key]
        return r if u == key[0] else r[::-1]

    def strip(self, a, b, pa, pb) -> np.ndarray:
        """Faces between polylines a (na,) and b (nb,) with coordinates pa (na, 3), pb (nb, 3)."""
        i, j = zip_rungs(chord_param(pa), chord_param(pb))
        rungs = [self.rung(a[ii], b[jj], pa[ii], pb[jj]) for ii, jj in zip(i, j)]
        faces = np.concatenate([strip_faces(r0, r1, np.linspace(0, 1, len(r0)), np.linspace(0, 1, len(r1)))
                                for r0, r1 in zip(rungs[:-1], rungs[1:])])
        keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])
        return faces[keep]


class _ToothIdx:
    """Vertex indices and coordinates of the two flanks of one tooth placed in a MeshBuilder."""

    def __init__(self, builder: MeshBuilder, pa, pb, R=None):
        if R is not None:
            pa, pb = apply(R, pa), apply(R, pb)
        self.pa, self.pb = pa, pb
        self.a = builder.add_vertices(pa)
        self.b = builder.add_vertices(pb)


def _spacing(*grids) -> float:
    """Median edge length of the flank grids, mm: the target rung spacing of the bridging strips."""
    lengths = [np.linalg.norm(np.diff(g, axis=ax), axis=-1).ravel() for g in grids for ax in (0, 1)]
    h = float(np.median(np.concatenate(lengths)))
    return h if h > 0 else 1.0


def _add_flanks(builder, idx, na, nb):
    """Flank patches oriented by their outward normals."""
    verts = builder.vertices()
    for ids, normals, name in ((idx.a, na, "convex flank"), (idx.b, nb, "concave flank")):
        faces = grid_faces(ids)
        vn = np.zeros_like(verts)
        vn[ids.ravel()] = normals.reshape(-1, 3)
        sign = orientation_sign(TriangleMesh(verts, faces), vn)
        builder.add_patch(faces if sign > 0 else faces[:, ::-1], fixed=True, name=name)


def _add_tooth(builder, br: _Bridger, idx, na, nb, root: bool):
    if na is not None and nb is not None:
        _add_flanks(builder, idx, na, nb)
        pending = []
    else:  # orientation propagates: convex flank, strips, then concave flank
        builder.add_patch(grid_faces(idx.a), name="convex flank")
        pending = [grid_faces(idx.b)]
    a, b, pa, pb = idx.a, idx.b, idx.pa, idx.pb
    builder.add_patch(br.strip(a[:, -1], b[:, -1], pa[:, -1], pb[:, -1]), name="top land")
    builder.add_patch(br.strip(a[0, :], b[0, :], pa[0, :], pb[0, :]), name="toe face")
    builder.add_patch(br.strip(a[-1, :], b[-1, :], pa[-1, :], pb[-1, :]), name="heel face")
    if root:
        builder.add_patch(br.strip(a[:, 0], b[:, 0], pa[:, 0], pb[:, 0]), name="root strip")
    for faces in pending:
        builder.add_patch(faces, name="concave flank")


def _finish(builder, scale, normals_known: bool) -> TriangleMesh:
    mesh = weld(builder.mesh(), _WELD_REL * scale)
    if not normals_known and mesh.volume() < 0:
        mesh = TriangleMesh(mesh.vertices, mesh.faces[:, ::-1])
    return mesh


def tooth_mesh(convex, concave) -> TriangleMesh:
    """Closed, consistently oriented triangle mesh of one tooth.

    Parameters
    ----------
    convex, concave : grid
        Flank grids ``points (n, m, 3)``, mm, toe -> heel along axis 0 and root -> top along axis 1, with outward
        ``normals`` (optional; without them the orientation is chosen so that the volume is positive). The two grids
        may have different sizes.

    Returns
    -------
    TriangleMesh
        Watertight genus-0 mesh with outward face normals: flanks, top land, root strip, toe and heel faces.

    Raises
    ------
    DesignError
        Malformed grids, or normals that are not outward on both flanks (inconsistent orientation).
    """
    pa, na = flank_grid(convex, "convex")
    pb, nb = flank_grid(concave, "concave")
    builder = MeshBuilder()
    idx = _ToothIdx(builder, pa, pb)
    try:
        _add_tooth(builder, _Bridger(builder, _spacing(pa, pb)), idx, na, nb, root=True)
    except OrientationError as err:
        raise GeometryError.single("concave.normals", "inconsistent", "outward normals on both flanks", "-",
                                   str(err)) from err
    return _finish(builder, _scale(pa, pb), na is not None and nb is not None)


def _azimuth(p):
    return np.arctan2(p[..., 1], p[..., 0])


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2.0 * np.pi) - np.pi


def _rotated_sectors(builder, br: _Bridger, pa, pb, na, nb, rots, b_leads) -> list:
    """Add z teeth and the root lands between them to ``builder`` by rotation of one sector.

    The sector (one tooth: flanks, top land, toe and heel faces; and the root land from its leading root edge to the
    trailing root edge of the next tooth) is built once; sector k is that mesh turned by ``rots[k]``, its next-tooth
    vertices being those of sector k + 1 (mod z). Sectors share only the root edges, whose orientation the builder
    checks. The sector's bridging rungs enter ``br``'s cache under each sector's vertex numbers, so that the end faces
    built afterwards reuse them. Returns the teeth's flank indices and coordinates (as ``_ToothIdx``).
    """
    z = len(rots)
    tb = MeshBuilder()
    tbr = _Bridger(tb, br.h)
    t0 = _ToothIdx(tb, pa, pb)
    _add_tooth(tb, tbr, t0, na, nb, root=False)
    n_tooth_faces = len(tb.mesh().faces)
    (lead, lead_p), (trail, trail_p) = ((t0.b[:, 0], pb[:, 0]), (t0.a[:, 0], pa[:, 0])) if b_leads else \
        ((t0.a[:, 0], pa[:, 0]), (t0.b[:, 0], pb[:, 0]))
    next_p = apply(rots[1 % z] if z > 1 else rots[0], trail_p)
    ghost = tb.add_vertices(next_p)  # the next tooth's trailing root edge
    tb.add_patch(tbr.strip(lead, ghost, lead_p, next_p), name="root land")
    sector = tb.mesh()
    own = np.ones(len(sector.vertices), bool)
    own[ghost] = False
    own_idx = np.flatnonzero(own)
    pos = np.cumsum(own) - 1  # position of an own vertex in the sector block
    block, base0 = len(own_idx), builder.n_vertices
    for R in rots:
        builder.add_vertices(apply(R, sector.vertices[own_idx]))
    maps = []
    for k in range(z):
        m = np.empty(len(sector.vertices), np.int64)
        m[own_idx] = base0 + k * block + np.arange(block)
        m[ghost] = base0 + ((k + 1) % z) * block + pos[trail]
        maps.append(m)
    # sector k's vertices are new except its ghosts (the next sector's trailing root edge, an open edge of both), so
    # only the open edges of the sector's tooth and root land can meet the other sectors and the end faces: checking
    # and recording those is the full orientation check (MeshBuilder.add_patch, open_edges)
    tooth_faces, land_faces = sector.faces[:n_tooth_faces], sector.faces[n_tooth_faces:]
    tooth_open, land_open = open_edges(tooth_faces), open_edges(land_faces)
    for m in maps:
        builder.add_patch(m[tooth_faces], fixed=True, name="tooth", open_edges=m[tooth_open])
    for m in maps:
        builder.add_patch(m[land_faces], fixed=True, name="root land", open_edges=m[land_open])
        for (u, v), r in tbr._cache.items():
            U, V, r = m[u], m[v], m[r]
            br._cache[(U, V) if U < V else (V, U)] = r if U < V else r[::-1]
    teeth = []
    for k, R in enumerate(rots):
        t = _ToothIdx.__new__(_ToothIdx)
        t.a, t.b, t.pa, t.pb = maps[k][t0.a], maps[k][t0.b], apply(R, pa), apply(R, pb)
        teeth.append(t)
    return teeth


def _leading(pa, pb) -> bool:
    """True when the concave flank (b) leads, i.e. lies at the larger azimuth (counterclockwise about +z)."""
    mid_a, mid_b = pa[pa.shape[0] // 2, pa.shape[1] // 2], pb[pb.shape[0] // 2, pb.shape[1] // 2]
    return bool(_wrap(_azimuth(mid_b) - _azimuth(mid_a)) > 0)


def root_slot_width(convex, concave, z: int) -> np.ndarray:
    """Width of the tooth space at the root of a gear of z teeth, at each face station, mm.

    The arc, on the circle about the axis through the leading root edge point of tooth 0, from that point to the
    azimuth of the trailing root edge point of tooth 1 (same face station); negative where the root edges of
    neighbouring teeth cross, i.e. where the teeth overlap at the root (a cutter wider than the tooth space).

    Parameters
    ----------
    convex, concave : grid
        Flank grids of one tooth (see :func:`tooth_mesh`), row 0 along axis 1 being the root edge.
    z : int
        Number of teeth (>= 1).

    Returns
    -------
    (n_face,) float, mm
    """
    pa, _ = flank_grid(convex, "convex")
    pb, _ = flank_grid(concave, "concave")
    if isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 1:
        raise DesignError.single("z", z, "integer >= 1", "-")
    if pa.shape[0] != pb.shape[0]:
        raise DesignError.single("concave.points", f"{pb.shape[0]} face stations", f"{pa.shape[0]} (as convex)", "-")
    lead, trail = (pb[:, 0], pa[:, 0]) if _leading(pa, pb) else (pa[:, 0], pb[:, 0])
    gap = _wrap(_azimuth(trail) + 2.0 * np.pi / z - _azimuth(lead))
    return gap * np.hypot(lead[:, 0], lead[:, 1])


def _gear(convex, concave, z, body: GearBody | None, teeth: bool) -> TriangleMesh:
    if isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 3:
        raise DesignError.single("z", z, "integer >= 3", "-")
    z = int(z)
    pa, na = flank_grid(convex, "convex")
    pb, nb = flank_grid(concave, "concave")
    body = body or GearBody()
    # the leading flank lies at the larger azimuth (counterclockwise about +z); the root land runs from the leading
    # flank of tooth k to the trailing flank of tooth k+1
    b_leads = _leading(pa, pb)
    pitch = 2.0 * np.pi / z
    root_lead, root_trail = (pb[:, 0], pa[:, 0]) if b_leads else (pa[:, 0], pb[:, 0])
    root_width = max(_wrap(_azimuth(root_lead[[0, -1]]) - _azimuth(root_trail[[0, -1]])).max(), 0.0)
    if root_width >= pitch:
        raise GeometryError.single("z", z, f"< {2 * np.pi / root_width:.4g} (teeth overlap at the root)", "-")

    toe_loop = np.stack([root_trail[0], root_lead[0]])
    heel_loop = np.stack([root_trail[-1], root_lead[-1]])
    r_min = float(min(np.hypot(*toe_loop[:, :2].T).min(), np.hypot(*heel_loop[:, :2].T).min()))
    z_toe, z_heel = float(toe_loop[:, 2].min()), float(heel_loop[:, 2].max())
    bore = body.bore_radius if body.bore_radius is not None else 0.5 * float(np.hypot(*toe_loop[:, :2].T).min())
    front = body.front_z if body.front_z is not None else z_toe
    back = body.back_z if body.back_z is not None else z_heel
    n_bore = body.n_bore if body.n_bore is not None else max(48, 4 * z)
    if not (0.0 < bore < r_min):
        raise DesignError.single("body.bore_radius", bore, f"0 < value < {r_min:.6g} (root radius)", "mm")
    if not front <= z_toe:
        raise DesignError.single("body.front_z", front, f"<= {z_toe:.6g} (toe root)", "mm")
    if not back >= z_heel:
        raise DesignError.single("body.back_z", back, f">= {z_heel:.6g} (heel root)", "mm")
    if isinstance(n_bore, bool) or not isinstance(n_bore, (int, np.integer)) or n_bore < 3:
        raise DesignError.single("body.n_bore", n_bore, "integer >= 3", "-")

    builder = MeshBuilder()
    br = _Bridger(builder, _spacing(pa, pb))
    rots = rot_z(np.arange(z) * pitch)
    known = na is not None and nb is not None
    try:
        if teeth:
            tooth = _rotated_sectors(builder, br, pa, pb, na, nb, rots, b_leads)
        else:
            tooth = [_ToothIdx(builder, pa, pb, R) for R in rots]
            for t in tooth:
                builder.add_patch(br.strip(t.a[:, 0], t.b[:, 0], t.pa[:, 0], t.pb[:, 0]), name="root strip")
        # (indices, coordinates) of the leading and trailing root edges of every tooth
        lead = [(t.b[:, 0], t.pb[:, 0]) if b_leads else (t.a[:, 0], t.pa[:, 0]) for t in tooth]
        trail = [(t.a[:, 0], t.pa[:, 0]) if b_leads else (t.b[:, 0], t.pb[:, 0]) for t in tooth]
        if not teeth:
            for k in range(z):
                (ia, qa), (ib, qb) = lead[k], trail[(k + 1) % z]
                builder.add_patch(br.strip(ia, ib, qa, qb), name="root land")
        for end, zc in ((0, front), (-1, back)):
            parts = []
            for k in range(z):
                (it, qt), (il, ql), (in_, qn) = trail[k], lead[k], trail[(k + 1) % z]
                parts += [br.rung(it[end], il[end], qt[end], ql[end])[:-1],
                          br.rung(il[end], in_[end], ql[end], qn[end])[:-1]]
            loop = np.concatenate(parts)
            az = np.unwrap(_azimuth(builder.vertices()[loop]))
            if np.any(np.diff(az) < -1e-12):
                raise GeometryError.single("z", z, "teeth ordered around the axis", "-", "root loop folds back")
            if end == 0:  # one set of bore azimuths for both circles, so the bore is a straight prism
                theta = az[0] + np.linspace(0.0, 2.0 * np.pi, n_bore + 1)[:-1]
                circle_xy = bore * np.stack([np.cos(theta), np.sin(theta)], -1)
            # start the circle at the bore vertex nearest in azimuth to the loop's first vertex
            s0 = int(np.round(_wrap(az[0] - theta[0]) / (2.0 * np.pi / n_bore))) % n_bore
            ring = builder.add_vertices(np.column_stack([circle_xy, np.full(n_bore, zc)]))
            ring_from = np.roll(ring, -s0)
            th = az[0] + _wrap(theta[s0] - az[0]) + 2.0 * np.pi * np.arange(n_bore + 1) / n_bore
            builder.add_patch(strip_faces(np.append(loop, loop[0]), np.append(ring_from, ring_from[0]),
                                          np.append(az, az[0] + 2 * np.pi), th),
                              name="front face" if end == 0 else "back face")
            if end == 0:
                front_ring = ring
            else:
                builder.add_patch(grid_faces(np.stack([np.append(front_ring, front_ring[0]),
                                                       np.append(ring, ring[0])], 1)), name="bore")
    except OrientationError as err:
        raise GeometryError.single("concave.normals", "inconsistent", "outward normals on both flanks", "-",
                                   str(err)) from err
    scale = _scale(pa, pb) + abs(front) + abs(back)
    return _finish(builder, scale, known and teeth)


def gear_mesh(convex, concave, z: int, body: GearBody | None = None) -> TriangleMesh:
    """Closed triangle mesh of a whole gear: z teeth, root lands and a bored body.

    Parameters
    ----------
    convex, concave : grid
        Flank grids of one tooth (see :func:`tooth_mesh`).
    z : int
        Number of teeth; tooth k is the given tooth turned by 2 pi k / z about +z.
    body : GearBody, optional
        Bore radius and axial extent of the body; defaults described in :class:`GearBody`.

    Returns
    -------
    TriangleMesh
        Watertight, outward-oriented mesh of genus 1 (Euler characteristic 0).

    Raises
    ------
    DesignError
        Bad z or body values (named with their allowed range).
    GeometryError
        Teeth that overlap at the root, or flanks whose normals are not both outward.
    """
    return _gear(convex, concave, z, body, teeth=True)


def gear_body_mesh(convex, concave, z: int, body: GearBody | None = None) -> TriangleMesh:
    """The body of :func:`gear_mesh` alone: root strips under the teeth instead of the teeth (same arguments)."""
    return _gear(convex, concave, z, body, teeth=False)
