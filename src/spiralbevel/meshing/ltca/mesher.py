"""Structured tetrahedral mesh of a tooth segment (several teeth on a rim) built from flank grids.

Input: the two flank grids of one reference tooth in the member frame (axis +z), each (n_face, n_profile, 3) with
axis 0 toe -> heel and axis 1 root -> top. The segment holds ``n_teeth`` copies turned by multiples of the pitch
angle 2 pi / z about +z. The volume is a structured hexahedral lattice indexed (face station i, angular column a,
level v):

* tooth columns: straight interpolation across the tooth between its two flanks at the same (i, j);
* tooth-space columns (root level only): interpolation in cylindrical coordinates (R, angle, z) between the facing
  root points of neighbouring teeth, so the space bottom follows the root cone;
* rim levels below the root: the root lattice offset by up to ``rim_thickness`` along the inward normal of the
  root line in the axial plane (toward the axis for a pinion, behind the teeth for a gear); the deepest level is the
  bore/web and is clamped.

With ``rim_layers = 0`` there is no rim and the tooth roots are clamped (a cantilever; used by the tests).
Each hexahedron is split into 6 tetrahedra along its main diagonal (Kuhn split), which is conforming on a
structured lattice.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import permutations

import numpy as np

from ...errors import DesignError

__all__ = ["SegmentMesh", "mesh_tooth_segment", "grid_normals"]


@dataclass(frozen=True)
class SegmentMesh:
    """Tetrahedral mesh of a tooth segment.

    Attributes
    ----------
    vertices : (nv, 3) float, mm
        Member frame.
    tets : (nt, 4) int
        Positively oriented tetrahedra.
    fixed : (nv,) bool
        Clamped vertices (bore/web, or the tooth roots without a rim).
    flank_nodes : dict
        ``(tooth, side) -> (n_face, n_profile) int`` vertex indices of each flank grid; tooth in
        ``-(n_teeth-1)//2 .. n_teeth//2`` (0 = reference tooth), side ``"convex"`` or ``"concave"``.
    pitch_angle : float, rad
        Angle 2 pi / z between neighbouring teeth.
    """

    vertices: np.ndarray
    tets: np.ndarray
    fixed: np.ndarray
    flank_nodes: dict
    pitch_angle: float

    @property
    def teeth(self):
        return sorted({k for k, _ in self.flank_nodes})


def grid_normals(grid):
    """Unit normals (n_face, n_profile, 3) of a flank grid from central differences, d/d(face) x d/d(profile)."""
    gu = np.gradient(grid, axis=0)
    gv = np.gradient(grid, axis=1)
    n = np.cross(gu, gv)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def _rotz(p, a):
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]], -1)


def _cyl_interp(A, B, tau):
    """Points between A and B (..., 3) linear in radius, angle and z; tau (m,) -> (..., m, 3)."""
    ra, rb = np.hypot(A[..., 0], A[..., 1]), np.hypot(B[..., 0], B[..., 1])
    ta, tb = np.arctan2(A[..., 1], A[..., 0]), np.arctan2(B[..., 1], B[..., 0])
    tb = ta + np.angle(np.exp(1j * (tb - ta)))
    t = tau[None, :] if A.ndim == 2 else tau
    r = ra[..., None] * (1 - t) + rb[..., None] * t
    th = ta[..., None] * (1 - t) + tb[..., None] * t
    z = A[..., 2, None] * (1 - t) + B[..., 2, None] * t
    return np.stack([r * np.cos(th), r * np.sin(th), z], -1)


def mesh_tooth_segment(convex, concave, z, n_teeth=3, thickness_divisions=2, space_divisions=2, rim_layers=2,
                       rim_thickness=None) -> SegmentMesh:
    """Build the structured tetrahedral mesh of ``n_teeth`` teeth on a rim.

    Parameters
    ----------
    convex, concave : (n_face, n_profile, 3) float, mm
        Flank grids of the reference tooth (member frame; axis 0 toe -> heel, axis 1 root -> top). The grid lines
        are the mesh lines, so their spacing sets the element size along the flank.
    z : int
        Number of teeth of the member (pitch angle 2 pi / z).
    n_teeth : int
        Teeth in the segment (>= 1; >= 3 for load sharing with both neighbours).
    thickness_divisions, space_divisions : int
        Element layers across a tooth and across a tooth-space bottom.
    rim_layers : int
        Element layers in the rim (0: no rim, the roots are clamped).
    rim_thickness : float, mm, optional
        Rim depth below the root; default the tooth's whole depth.

    Returns
    -------
    SegmentMesh
    """
    cv, cc = np.asarray(convex, float), np.asarray(concave, float)
    if cv.ndim != 3 or cv.shape != cc.shape or cv.shape[-1] != 3 or min(cv.shape[:2]) < 2:
        raise DesignError.single("flank grids", f"{cv.shape} and {cc.shape}", "equal shapes (n_face >= 2, "
                                 "n_profile >= 2, 3)", "mm", "tooth segment mesh")
    for name, v, lo in (("n_teeth", n_teeth, 1), ("thickness_divisions", thickness_divisions, 1),
                        ("space_divisions", space_divisions, 1), ("rim_layers", rim_layers, 0), ("z", z, 1)):
        if int(v) != v or v < lo:
            raise DesignError.single(name, v, f"integer >= {lo}", "-", "tooth segment mesh")
    nf, npf = cv.shape[:2]
    pitch = 2 * np.pi / z
    def ang(g):
        return np.angle(np.mean(np.exp(1j * np.arctan2(g[..., 1], g[..., 0]))))
    turn = np.angle(np.exp(1j * (ang(cc) - ang(cv))))
    lo_side, hi_side = ("convex", "concave") if turn > 0 else ("concave", "convex")
    low, high = (cv, cc) if lo_side == "convex" else (cc, cv)
    ks = list(range(-((n_teeth - 1) // 2), n_teeth // 2 + 1))
    nt, ns, nr = thickness_divisions, space_divisions, rim_layers
    tau_t = np.linspace(0, 1, nt + 1)
    # angular columns: (tooth id or -1, column points at every profile level or root only)
    cols_root, tooth_of_col = [], []
    tooth_cols = {}
    for m, k in enumerate(ks):
        L, H = _rotz(low, k * pitch), _rotz(high, k * pitch)
        if m > 0:
            Hp = _rotz(high, ks[m - 1] * pitch)
            space = _cyl_interp(Hp[:, 0], L[:, 0], np.linspace(0, 1, ns + 1)[1:-1])  # (nf, ns-1, 3)
            for c in range(ns - 1):
                cols_root.append(space[:, c])
                tooth_of_col.append(-1)
        first = len(cols_root)
        for tau in tau_t:
            cols_root.append((1 - tau) * L[:, 0] + tau * H[:, 0])
            tooth_of_col.append(m)  # position of the tooth in the segment; -1 marks tooth-space columns
        tooth_cols[k] = (first, L, H)
    Na = len(cols_root)
    root = np.stack(cols_root, axis=1)  # (nf, Na, 3)
    col_tooth = np.array(tooth_of_col)
    nV = nr + npf
    X = np.full((nf, Na, nV, 3), np.nan)
    X[:, :, nr] = root
    for first, L, H in tooth_cols.values():
        for c, tau in enumerate(tau_t):
            X[:, first + c, nr:] = (1 - tau) * L + tau * H
    if nr > 0:
        depth = float(rim_thickness) if rim_thickness is not None else float(
            np.max(np.linalg.norm(cv[:, -1] - cv[:, 0], axis=-1)))
        if not depth > 0:
            raise DesignError.single("rim_thickness", rim_thickness, "> 0", "mm", "tooth segment mesh")
        R = np.hypot(root[..., 0], root[..., 1])
        g = np.stack([np.gradient(R, axis=0), np.gradient(root[..., 2], axis=0)], -1)
        g /= np.linalg.norm(g, axis=-1, keepdims=True)
        nRz = np.stack([-g[..., 1], g[..., 0]], -1)  # inward normal of the root line in the axial plane
        eR = root[..., :2] / R[..., None]
        inward = np.concatenate([nRz[..., :1] * eR, nRz[..., 1:]], -1)
        for m in range(1, nr + 1):
            X[:, :, nr - m] = root + (m / nr) * depth * inward
    exists = np.isfinite(X[..., 0])
    idx = np.full(exists.shape, -1, dtype=np.int64)
    idx[exists] = np.arange(exists.sum())
    verts = X[exists]
    fixed = np.zeros(len(verts), bool)
    fixed[idx[:, :, 0][exists[:, :, 0]]] = True
    if nr == 0:
        fixed[:] = False
        fixed[idx[:, :, 0][idx[:, :, 0] >= 0]] = True
    # hexahedra
    same_tooth = (col_tooth[:-1] == col_tooth[1:]) & (col_tooth[:-1] >= 0)
    corners: dict[tuple[int, ...], np.ndarray] = {}
    for di in (0, 1):
        for da in (0, 1):
            for dv in (0, 1):
                corners[(di, da, dv)] = idx[di:nf - 1 + di, da:Na - 1 + da, dv:nV - 1 + dv]
    ok = np.all([c >= 0 for c in corners.values()], axis=0)
    level = np.arange(nV - 1)[None, None, :]
    ok &= (level < nr) | same_tooth[None, :, None]
    blocks = []
    for perm in permutations(range(3)):
        path: list[tuple[int, ...]] = [(0, 0, 0)]
        for ax in perm:
            nxt = list(path[-1])
            nxt[ax] = 1
            path.append(tuple(nxt))
        blocks.append(np.stack([corners[c][ok] for c in path], axis=1))
    tets = np.concatenate(blocks, axis=0)
    P = verts[tets]
    vol = np.einsum("ij,ij->i", np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), P[:, 3] - P[:, 0])
    if np.any(np.abs(vol) < 1e-12 * np.abs(vol).max()):
        raise DesignError.single("flank grids", "degenerate", "non-crossing flanks", "mm",
                                 "tooth segment mesh has flat or inverted elements")
    neg = vol < 0
    tets[neg] = tets[neg][:, [0, 2, 1, 3]]
    flank_nodes = {}
    for k, (first, _, _) in tooth_cols.items():
        flank_nodes[(k, lo_side)] = idx[:, first, nr:]
        flank_nodes[(k, hi_side)] = idx[:, first + nt, nr:]
    return SegmentMesh(verts, tets, fixed, flank_nodes, pitch)
