"""Tooth compliance by finite elements (scikit-fem, optional extra ``fem``).

A linear-elastic model of a tooth segment (:func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment`, quadratic
tetrahedra by default) clamped at the bore/web is factorized once (``scipy.sparse.linalg.splu``) and solved for unit
normal loads at every flank-grid node of the loaded flanks of all teeth (many right-hand sides). The result is the
nodal flexibility G_ab = n_a . u_a(unit load n_b at b) in mm/N (symmetric by reciprocity).

A point load F n at a flank point x is distributed to the four nodes of the flank-grid cell containing x with the
bilinear weights N_a(x); the flexibility between two points is then c(x, y) = sum_ab N_a(x) G_ab N_b(y), which keeps
reciprocity exactly. The nodal normals n_a are the flank-grid normals.

Contact flattening: the FE mesh is far coarser than a Hertzian contact, so its local (near-field) response is a
mesh-dependent smear of the point-load singularity; nothing is subtracted from it. The local flattening is added as the
half-space term of :mod:`~spiralbevel.meshing.ltca.halfspace` for points of the same tooth pair (the FE near field
then over-counts a little: a conservative, stiffness-lowering choice, documented as such).

The FE result is cached on disk (:mod:`~spiralbevel.meshing.ltca.fe_cache`: keyed by mesh, loaded flanks, material,
element order and the code version, checked on load), so a second run (another torque, other mesh positions) skips the
factorization.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from ...errors import DesignError, MissingDependencyError
from .fe_cache import cache_key, default_cache_dir, load_matrix, store_matrix
from .halfspace import STEEL, Material
from .mesher import SegmentMesh, grid_normals

__all__ = ["ToothCompliance", "tooth_compliance", "default_cache_dir"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ToothCompliance:
    """Nodal normal flexibility of the loaded flanks of a tooth segment.

    Attributes
    ----------
    grids : dict
        ``tooth -> (n_face, n_profile, 3)`` loaded-flank grid (member frame), tooth 0 = reference tooth.
    normals : dict
        ``tooth -> (n_face, n_profile, 3)`` unit normals used for the loads.
    G : (m, m) float, mm/N
        Flexibility between all loaded-flank nodes, tooth by tooth in ``teeth`` order, each grid flattened (C order).
    teeth : tuple of int
    side : str
        Loaded flank, ``"convex"`` or ``"concave"``.
    key : str
        Cache key.
    asymmetry : float, -
        max |G - G^T| / max |G| before symmetrization (reciprocity check of the FE solve).
    """

    grids: dict
    normals: dict
    G: np.ndarray
    teeth: tuple
    side: str
    key: str
    asymmetry: float = 0.0

    @property
    def grid_shape(self):
        return self.grids[self.teeth[0]].shape[:2]

    def weights(self, tooth, points, return_inside=False):
        """Bilinear load-distribution weights (n_points, m) of member-frame points on the flank of ``tooth``
        (and, with ``return_inside``, a mask of the points whose foot lies on the flank grid)."""
        from .locate import locate_on_grid

        pts = np.asarray(points, float).reshape(-1, 3)
        grid = self.grids[tooth]
        nf, npf = grid.shape[:2]
        i, j, xi, eta, inside = locate_on_grid(grid, pts)
        off = self.teeth.index(tooth) * nf * npf
        W = np.zeros((len(pts), self.G.shape[0]))
        rows = np.arange(len(pts))
        for di, dj, wgt in ((0, 0, (1 - xi) * (1 - eta)), (1, 0, xi * (1 - eta)), (0, 1, (1 - xi) * eta),
                            (1, 1, xi * eta)):
            W[rows, off + (i + di) * npf + (j + dj)] += wgt
        return (W, inside) if return_inside else W

    def weight_matrix(self, teeth, points):
        """Weights (n, m) of member-frame points on the given teeth (one tooth index per point) and the on-flank mask."""
        teeth = np.asarray(teeth).ravel()
        pts = np.asarray(points, float).reshape(-1, 3)
        W = np.zeros((len(pts), self.G.shape[0]))
        inside = np.zeros(len(pts), bool)
        for k in np.unique(teeth):
            if int(k) not in self.teeth:
                raise DesignError.single("tooth", int(k), f"one of {self.teeth}", "-", "FE tooth compliance")
            sel = teeth == k
            W[sel], inside[sel] = self.weights(int(k), pts[sel], return_inside=True)
        return W, inside

    def flexibility(self, teeth, points) -> np.ndarray:
        """FE flexibility matrix (n, n) in mm/N of member-frame points on the given teeth (one tooth per point)."""
        W, _ = self.weight_matrix(teeth, points)
        return W @ self.G @ W.T


def _cache_key(mesh: SegmentMesh, side, material, order):
    arrays = [mesh.vertices, mesh.tets, mesh.fixed] + [mesh.flank_nodes[(k, side)] for k in mesh.teeth]
    return cache_key(arrays, f"{side}|{material.youngs_modulus!r}|{material.poisson_ratio!r}|{order}")


def _solve_fe(mesh: SegmentMesh, loads_nodes, loads_normals, material, order):
    try:
        import skfem
        from skfem.models.elasticity import lame_parameters, linear_elasticity
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise MissingDependencyError("scikit-fem", "fem", "LTCA tooth compliance") from err
    from scipy.sparse.linalg import splu

    m = skfem.MeshTet(mesh.vertices.T.copy(), mesh.tets.T.copy())
    elem = skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1()
    basis = skfem.Basis(m, skfem.ElementVector(elem))
    K = skfem.asm(linear_elasticity(*lame_parameters(material.youngs_modulus, material.poisson_ratio)), basis)
    fixed_v = mesh.fixed
    facets = np.flatnonzero(np.all(fixed_v[m.facets], axis=0))
    clamped = basis.get_dofs(facets=facets).all() if len(facets) else np.array([], int)
    clamped = np.union1d(clamped, basis.nodal_dofs[:, fixed_v].ravel())
    free = np.setdiff1d(np.arange(basis.N), clamped)
    if len(clamped) == 0:
        raise DesignError.single("fixed", 0, ">= 3 non-collinear clamped vertices", "-", "FE tooth compliance")
    pos = np.full(basis.N, -1)
    pos[free] = np.arange(len(free))
    dofs = basis.nodal_dofs[:, loads_nodes]  # (3, m)
    rows = pos[dofs]  # -1 at clamped load nodes: they neither load nor move (zero rows and columns of G)
    live = rows >= 0
    nrm = np.where(live.T, loads_normals, 0.0)
    rows = np.where(live, rows, 0)
    lu = splu(K[free][:, free].tocsc())
    nl = len(loads_nodes)
    G = np.empty((nl, nl))
    for start in range(0, nl, 64):
        sl = slice(start, min(nl, start + 64))
        B = np.zeros((len(free), sl.stop - sl.start))
        cols = np.arange(sl.stop - sl.start)
        for c in range(3):
            B[rows[c, sl], cols] += nrm[sl, c]
        U = lu.solve(B)
        G[:, sl] = sum(nrm[:, c, None] * U[rows[c]] for c in range(3))
    return G, len(free)


def tooth_compliance(mesh: SegmentMesh, side: str, material: Material = STEEL, order: int = 2, cache_dir=None,
                     use_cache: bool = True) -> ToothCompliance:
    """FE flexibility of the ``side`` flanks of every tooth of a segment mesh (cached on disk).

    Parameters
    ----------
    mesh : SegmentMesh
        From :func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment`.
    side : {"convex", "concave"}
        Loaded flank (pinion concave / gear convex on the drive side).
    material : Material
        Default steel, E = 206000 N/mm^2, nu = 0.3.
    order : {1, 2}
        Tetrahedron order (2 = quadratic, free of the bending locking of linear tetrahedra).
    cache_dir : path, optional
        Default :func:`default_cache_dir`.
    use_cache : bool
        Read and write the cache.

    Returns
    -------
    ToothCompliance

    Raises
    ------
    MissingDependencyError
        scikit-fem is not installed (extra ``fem``).
    """
    if side not in ("convex", "concave"):
        raise DesignError.single("side", side, "'convex' or 'concave'", "-", "FE tooth compliance")
    if order not in (1, 2):
        raise DesignError.single("order", order, "1 or 2", "-", "FE tooth compliance")
    teeth = tuple(mesh.teeth)
    grids = {k: mesh.vertices[mesh.flank_nodes[(k, side)]] for k in teeth}
    normals = {k: grid_normals(g) for k, g in grids.items()}
    key = _cache_key(mesh, side, material, order)
    nodes = np.concatenate([mesh.flank_nodes[(k, side)].ravel() for k in teeth])
    cached = load_matrix(cache_dir, key, len(nodes)) if use_cache else None
    if cached is not None:
        return ToothCompliance(grids, normals, cached[0], teeth, side, key, cached[1])
    nrm = np.concatenate([normals[k].reshape(-1, 3) for k in teeth])
    G, ndof = _solve_fe(mesh, nodes, nrm, material, order)
    asym = float(np.max(np.abs(G - G.T)) / np.max(np.abs(G)))
    G = 0.5 * (G + G.T)
    log.info("FE tooth compliance: %d free dofs, %d load nodes", ndof, len(nodes))
    if use_cache:
        store_matrix(cache_dir, key, G, asym)
    return ToothCompliance(grids, normals, G, teeth, side, key, asym)
