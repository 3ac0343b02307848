"""Tooth compliance by finite elements (scikit-fem, optional extra ``fem``).

A linear-elastic model of a tooth segment (:func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment`, quadratic
tetrahedra by default) clamped at the bore/web is assembled in one vectorized pass (:func:`stiffness_matrix`),
factorized once (:func:`factorize`: ``scipy.sparse.linalg.splu`` in symmetric mode) and solved for unit normal loads
at every flank-grid node of the loaded flanks of all teeth (many right-hand sides). The result is the nodal
flexibility G_ab = n_a . u_a(unit load n_b at b) in mm/N (symmetric by reciprocity).

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
from ..._progress import report
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
        """Weights (n, m) of member-frame points on the given teeth (one tooth index per point) and the on-flank
        mask."""
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


def stiffness_matrix(basis_scalar, element_dofs, n_dofs, lam, mu):
    """Linear-elastic stiffness matrix of a vector Lagrange basis, assembled element by element in one pass.

    Parameters
    ----------
    basis_scalar : skfem.Basis
        Scalar basis of the element (P1 or P2 tetrahedra) with a quadrature that integrates the stiffness exactly
        (order 2 (p - 1) on affine elements).
    element_dofs : (3 n_s, n_elem) int
        Global dofs of the vector basis, local dof 3 s + i = component i of scalar shape function s (the numbering
        of ``skfem.ElementVector``).
    n_dofs : int
    lam, mu : float, N/mm^2
        Lame parameters.

    Returns
    -------
    (n_dofs, n_dofs) scipy.sparse.csc_matrix, N/mm

    Notes
    -----
    For the vector shape functions phi_s e_i the bilinear form lam div u div v + 2 mu eps(u) : eps(v) gives the
    element matrix K[si, tj] = lam S[si, tj] + mu (delta_ij sum_k S[sk, tk] + S[sj, ti]) with
    S[si, tj] = int d_i phi_s d_j phi_t dV, one batched matrix product over the quadrature points. It is the matrix of
    ``skfem.models.elasticity.linear_elasticity`` (checked to 1e-12 in the tests) without its per-dof-pair loop.
    """
    import scipy.sparse as sp

    g = np.stack([b[0].grad for b in basis_scalar.basis])  # (n_s, 3, n_elem, n_q)
    n_s = g.shape[0]
    dx = basis_scalar.dx  # (n_elem, n_q): quadrature weights times |det J|
    n_e = dx.shape[0]
    g = g.transpose(2, 0, 1, 3).reshape(n_e, 3 * n_s, -1)
    S = ((g * dx[:, None, :]) @ g.transpose(0, 2, 1)).reshape(n_e, n_s, 3, n_s, 3)
    K = lam * S + mu * S.transpose(0, 1, 4, 3, 2)
    trace = np.einsum("esktk->est", S)
    for i in range(3):
        K[:, :, i, :, i] += mu * trace
    n = 3 * n_s
    ed = np.asarray(element_dofs).T  # (n_elem, n)
    rows, cols = np.repeat(ed, n, axis=1).ravel(), np.tile(ed, (1, n)).ravel()
    return sp.coo_matrix((K.reshape(-1), (rows, cols)), shape=(n_dofs, n_dofs)).tocsc()


def factorize(K):
    """Sparse LU of a symmetric positive definite matrix (csc): minimum-degree ordering of A^T + A, diagonal pivots
    (SuperLU's symmetric mode). Same solution as the default ``splu`` to rounding, about a third less fill."""
    from scipy.sparse.linalg import splu

    return splu(K, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def _solve_fe(mesh: SegmentMesh, loads_nodes, loads_normals, material, order):
    try:
        import skfem
        from skfem.models.elasticity import lame_parameters
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise MissingDependencyError("scikit-fem", "fem", "LTCA tooth compliance") from err

    m = skfem.MeshTet(mesh.vertices.T.copy(), mesh.tets.T.copy())
    elem = skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1()
    # exact quadrature of the (affine-element) stiffness: gradients of degree order - 1
    basis = skfem.Basis(m, skfem.ElementVector(elem), intorder=max(1, 2 * (order - 1)))
    K = stiffness_matrix(skfem.Basis(m, elem, intorder=max(1, 2 * (order - 1))), basis.element_dofs, basis.N,
                         *lame_parameters(material.youngs_modulus, material.poisson_ratio))
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
    stage = f"FE compliance, {len(free)} dofs"
    nl = len(loads_nodes)
    report(f"{stage}: factorizing", 0, nl)
    lu = factorize(K[free][:, free].tocsc())
    G = np.empty((nl, nl))
    for start in range(0, nl, 64):
        sl = slice(start, min(nl, start + 64))
        B = np.zeros((len(free), sl.stop - sl.start))
        cols = np.arange(sl.stop - sl.start)
        for c in range(3):
            B[rows[c, sl], cols] += nrm[sl, c]
        U = lu.solve(B)
        G[:, sl] = sum(nrm[:, c, None] * U[rows[c]] for c in range(3))
        report(f"{stage}: unit loads", sl.stop, nl)
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
