"""Triangle surface meshes: the :class:`TriangleMesh` container and the triangulation primitives used to close tooth
and gear solids (structured grids, ruled strips between two polylines, welding, patch orientation).

Everything works on plain float64 arrays in mm with xyz on the trailing axis; faces are int64 index triples. A face
(i, j, k) is oriented counterclockwise seen from the side its normal (v_j - v_i) x (v_k - v_i) points to.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["TriangleMesh", "MeshBuilder", "grid_faces", "strip_faces", "zip_rungs", "chord_param", "triangulate_grid",
           "weld", "open_edges"]


@dataclass(frozen=True, eq=False)
class TriangleMesh:
    """Triangle mesh.

    Attributes
    ----------
    vertices : (n, 3) float, mm
        Vertex coordinates.
    faces : (m, 3) int
        Vertex indices of each triangle, counterclockwise seen from outside for a closed outward-oriented mesh.
    """

    vertices: np.ndarray
    faces: np.ndarray

    def __post_init__(self):
        v = np.ascontiguousarray(self.vertices, dtype=float).reshape(-1, 3)
        f = np.ascontiguousarray(self.faces, dtype=np.int64).reshape(-1, 3)
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)

    @property
    def triangles(self) -> np.ndarray:
        """Corner coordinates, shape (m, 3, 3), mm."""
        return self.vertices[self.faces]

    def face_normals(self, unit: bool = True) -> np.ndarray:
        """Face normals (v1 - v0) x (v2 - v0), shape (m, 3); unit length when ``unit`` (zero for degenerate faces)."""
        t = self.triangles
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        if unit:
            length = np.linalg.norm(n, axis=1, keepdims=True)
            n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
        return n

    def area(self) -> float:
        """Total surface area, mm^2."""
        return float(0.5 * np.linalg.norm(self.face_normals(unit=False), axis=1).sum())

    def volume(self) -> float:
        """Signed enclosed volume, mm^3: positive for a closed mesh with outward orientation.

        Notes
        -----
        Divergence theorem: V = (1/6) sum over faces of v0 . (v1 x v2); the vertex centroid is subtracted first to
        limit cancellation (the result of a closed mesh does not depend on the origin).
        """
        t = self.triangles - self.vertices.mean(axis=0) if len(self.vertices) else self.triangles
        return float(np.einsum("ij,ij->", t[:, 0], np.cross(t[:, 1], t[:, 2])) / 6.0)

    def directed_edges(self) -> np.ndarray:
        """Directed edges (v_i, v_j) of every face, shape (3m, 2)."""
        f = self.faces
        return np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])

    def edges(self) -> np.ndarray:
        """Unique undirected edges (sorted pairs), shape (e, 2)."""
        return np.unique(np.sort(self.directed_edges(), axis=1), axis=0)

    def is_watertight(self) -> bool:
        """True when every edge is shared by exactly two faces that traverse it in opposite directions.

        This also means the orientation is consistent over the whole mesh. No face may repeat a vertex.
        """
        if len(self.faces) == 0:
            return False
        f = self.faces
        if np.any((f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])):
            return False
        d = self.directed_edges()
        keys = _edge_keys(d)
        if len(np.unique(keys)) != len(keys):  # a directed edge used twice: inconsistent orientation or non-manifold
            return False
        return bool(np.all(np.isin(_edge_keys(d[:, ::-1]), keys)))

    def euler_characteristic(self) -> int:
        """V - E + F over the vertices used by faces; 2 for a closed genus-0 surface, 0 for genus 1 (a ring)."""
        used = len(np.unique(self.faces))
        return int(used - len(self.edges()) + len(self.faces))

    @staticmethod
    def concatenate(meshes) -> "TriangleMesh":
        """Put several meshes into one (no vertex merging)."""
        verts, faces, offset = [], [], 0
        for m in meshes:
            verts.append(m.vertices)
            faces.append(m.faces + offset)
            offset += len(m.vertices)
        return TriangleMesh(np.concatenate(verts), np.concatenate(faces))


def _edge_keys(edges: np.ndarray) -> np.ndarray:
    edges = np.asarray(edges, dtype=np.int64)
    return (edges[:, 0] << 32) | edges[:, 1]


def grid_faces(index: np.ndarray) -> np.ndarray:
    """Triangles of a structured grid of vertex indices.

    Parameters
    ----------
    index : (n, m) int
        Vertex index of grid node (i, j).

    Returns
    -------
    (2 (n-1)(m-1), 3) int
        Faces oriented like the parameter directions: the normal of every face points along P_i x P_j, where P_i
        and P_j are the differences along axis 0 and axis 1. Quads are split along the (i, j)-(i+1, j+1) diagonal.
    """
    idx = np.asarray(index, dtype=np.int64)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])


def chord_param(points: np.ndarray) -> np.ndarray:
    seg = np.linalg.norm(np.diff(points, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    return s / s[-1] if s[-1] > 0 else np.linspace(0.0, 1.0, len(points))


def zip_rungs(sa, sb) -> tuple[np.ndarray, np.ndarray]:
    """Rungs (i, j) that zip two polylines with increasing parameters ``sa`` (na,) and ``sb`` (nb,).

    Returns index pairs from (0, 0) to (na - 1, nb - 1). Between consecutive rungs the polyline whose next parameter
    is smaller advances by one; on a tie (parameters compared after rounding to 1e-9, so that rigidly moved or
    mirrored copies zip alike) both advance, which keeps rungs "straight" between equally sampled polylines.
    """
    sa, sb = np.round(np.asarray(sa, float), 9), np.round(np.asarray(sb, float), 9)
    events = np.concatenate([sa[1:], sb[1:]])
    kind = np.concatenate([np.zeros(len(sa) - 1, np.int64), np.ones(len(sb) - 1, np.int64)])
    order = np.lexsort((kind, events))
    ev, kd = events[order], kind[order]
    da, db = (kd == 0).astype(np.int64), (kd == 1).astype(np.int64)
    tie = np.flatnonzero((kd[:-1] == 0) & (kd[1:] == 1) & (ev[:-1] == ev[1:]))
    db[tie] = 1
    keep = np.ones(len(kd), bool)
    keep[tie + 1] = False
    da, db = da[keep], db[keep]
    return np.concatenate([[0], np.cumsum(da)]), np.concatenate([[0], np.cumsum(db)])


def strip_faces(a, b, sa=None, sb=None, points=None) -> np.ndarray:
    """Ruled strip of triangles between two polylines of vertex indices (any numbers of vertices).

    Parameters
    ----------
    a, b : (na,) int, (nb,) int
        Vertex indices of the two polylines, running the same way; the strip's first rung is (a[0], b[0]) and its
        last rung (a[-1], b[-1]).
    sa, sb : (na,) float, (nb,) float, optional
        Increasing parameters along each polyline used to zip them together (:func:`zip_rungs`), e.g. normalised
        arc length or azimuth; by default normalised chord length computed from ``points``.
    points : (n, 3) float, mm, optional
        Vertex coordinates, needed only for the default parameters.

    Returns
    -------
    (k, 3) int
        Faces oriented like the quad (a_0, a_1, b_1, b_0): advancing on ``a`` gives (a_i, a_i+1, b_j), advancing on
        ``b`` gives (a_i, b_j+1, b_j), advancing on both gives both (a_i, a_i+1, b_j+1) and (a_i, b_j+1, b_j).
    """
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    if sa is None:
        sa = chord_param(points[a])
    if sb is None:
        sb = chord_param(points[b])
    i, j = zip_rungs(sa, sb)
    i0, j0, i1, j1 = i[:-1], j[:-1], i[1:], j[1:]
    on_a = i1 > i0
    on_b = j1 > j0
    first = np.stack([a[i0], np.where(on_a, a[i1], b[j1]), np.where(on_a, b[j1], b[j0])], 1)
    both = on_a & on_b
    second = np.stack([a[i0[both]], b[j1[both]], b[j0[both]]], 1)
    return np.concatenate([first, second])


def triangulate_grid(points, normals=None) -> TriangleMesh:
    """Triangle mesh of one flank grid, oriented so that face normals agree with the given normals.

    Parameters
    ----------
    points : (n, m, 3) float, mm
        Grid of surface points.
    normals : (n, m, 3) float, optional
        Outward unit normals at the nodes. When given, the faces are flipped if their normals point against them
        (decided by the sum of n . (face normal) over the grid); otherwise the orientation follows P_i x P_j.
    """
    pts = np.asarray(points, dtype=float)
    n, m = pts.shape[:2]
    faces = grid_faces(np.arange(n * m).reshape(n, m))
    mesh = TriangleMesh(pts.reshape(-1, 3), faces)
    if normals is not None and orientation_sign(mesh, np.asarray(normals, float).reshape(-1, 3)) < 0:
        mesh = TriangleMesh(mesh.vertices, faces[:, ::-1])
    return mesh


def orientation_sign(mesh: TriangleMesh, vertex_normals: np.ndarray, faces=None) -> float:
    """+1 when the faces' normals agree with the mean of their vertices' normals (summed over faces), else -1."""
    f = mesh.faces if faces is None else faces
    t = mesh.vertices[f]
    fn = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    vn = vertex_normals[f].sum(axis=1)
    return 1.0 if np.einsum("ij,ij->", fn, vn) >= 0 else -1.0


def weld(mesh: TriangleMesh, tol: float) -> TriangleMesh:
    """Merge vertices closer than ``tol`` (mm), drop faces that repeat a vertex and unused vertices."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    v = mesh.vertices
    pairs = cKDTree(v).query_pairs(tol, output_type="ndarray") if tol > 0 else np.empty((0, 2), int)
    faces = mesh.faces
    if len(pairs):
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(v), len(v)))
        _, label = connected_components(graph, directed=False)
        # representative = smallest original index of each class, so the first-added vertex wins
        rep = np.full(label.max() + 1, len(v), dtype=np.int64)
        np.minimum.at(rep, label, np.arange(len(v)))
        faces = rep[label][faces]
    keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])
    faces = faces[keep]
    used, inverse = np.unique(faces, return_inverse=True)
    return TriangleMesh(v[used], inverse.reshape(-1, 3))


def open_edges(faces) -> np.ndarray:
    """Directed edges (k, 2) of ``faces`` (m, 3) that no other face of them traverses in either direction: the open
    boundary of a consistently oriented patch, directed as the patch traverses it."""
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    d = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    d = d[d[:, 0] != d[:, 1]]
    undirected = _edge_keys(np.sort(d, axis=1))
    _, inverse, count = np.unique(undirected, return_inverse=True, return_counts=True)
    return d[count[inverse.ravel()] == 1]


class OrientationError(ValueError):
    """A patch cannot be oriented consistently with the patches already present."""


class MeshBuilder:
    """Assembles a mesh patch by patch, orienting each new patch against the edges already present.

    A patch that shares edges with earlier patches is flipped when it traverses them in the same direction; a patch
    whose shared edges disagree among themselves raises :class:`OrientationError` (the surface is not orientable as
    built, which
    for tooth solids means the given normals were not all outward).
    """

    def __init__(self):
        self._verts: list[np.ndarray] = []
        self._n = 0
        self._faces: list[np.ndarray] = []
        self._keys: set[int] = set()

    @property
    def n_vertices(self) -> int:
        return self._n

    def add_vertices(self, points) -> np.ndarray:
        """Append points of shape (..., 3); returns their indices with shape (...)."""
        pts = np.asarray(points, dtype=float)
        idx = np.arange(self._n, self._n + pts[..., 0].size).reshape(pts.shape[:-1])
        self._verts.append(pts.reshape(-1, 3))
        self._n += pts[..., 0].size
        return idx

    def vertices(self) -> np.ndarray:
        return np.concatenate(self._verts) if self._verts else np.empty((0, 3))

    def add_patch(self, faces, fixed: bool = False, name: str = "patch", open_edges=None) -> np.ndarray:
        """Add a connected, consistently oriented patch; returns the faces as added (possibly flipped).

        ``fixed`` keeps the given orientation but still checks it against the edges present.

        ``open_edges`` ((k, 2) int, directed as the patch traverses them), when given, are the only edges of the patch
        that other patches may share: the edges of its open boundary. Only they are checked and recorded; the caller
        guarantees that every other edge is interior to the patch (traversed once each way within it) and joins
        vertices that no other patch uses. For a patch that is a copy of a checked one on new vertices (the teeth of
        a gear), this is the same check for a fraction of the work.
        """
        faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
        if open_edges is None:
            d = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
        else:
            d = np.asarray(open_edges, dtype=np.int64).reshape(-1, 2)
        d = d[d[:, 0] != d[:, 1]]
        same = not self._keys.isdisjoint(_edge_keys(d).tolist())
        opposite = not self._keys.isdisjoint(_edge_keys(d[:, ::-1]).tolist())
        if same and opposite:
            raise OrientationError(f"{name}: orientation disagrees with the patches already present")
        if same:
            if fixed:
                raise OrientationError(f"{name}: fixed orientation disagrees with the patches already present")
            faces = faces[:, ::-1]
            d = d[:, ::-1]
        self._faces.append(faces)
        self._keys.update(_edge_keys(d).tolist())
        return faces

    def mesh(self) -> TriangleMesh:
        faces = np.concatenate(self._faces) if self._faces else np.empty((0, 3), np.int64)
        return TriangleMesh(self.vertices(), faces)
