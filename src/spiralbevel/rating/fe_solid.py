"""Stresses in a solid FE tooth model (scikit-fem, extra ``fem``): many load cases on one factorisation.

The tetrahedral tooth segment of :func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment` is assembled with the
stiffness of :func:`~spiralbevel.meshing.ltca.compliance.stiffness_matrix` and factorised once with
:func:`~spiralbevel.meshing.ltca.compliance.factorize` (the functions of the LTCA compliance, so both models are the
same linear-elastic solid); nodal loads of any number of load cases are then solved as right-hand sides. The stress of
a load case is recovered from the displacement gradients at the vertices of every element (for quadratic tetrahedra
the gradient is linear in the element, evaluated exactly at its corners) and averaged over the elements that share a
vertex (nodal averaging), which gives a continuous field whose surface values are read along the root.

Checks: ``tests/rating/test_fe_solid.py`` (a clamped block under an end load against the Saint-Venant flexure stress
6 F a / (b h^2), with its convergence rate; equilibrium of reactions and loads; mirror symmetry).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import DesignError, MissingDependencyError

__all__ = ["SolidModel", "solid_model", "max_principal"]


@dataclass(frozen=True)
class SolidModel:
    """Factorised linear-elastic model of a tetrahedral mesh clamped at its fixed vertices.

    Attributes
    ----------
    vertices : (nv, 3) float, mm
    tets : (nt, 4) int
    basis : skfem.Basis
        Vector basis (P1 or P2 tetrahedra).
    K : (N, N) scipy.sparse.csc_matrix, N/mm
        Full stiffness (clamped dofs included, for the reactions).
    free : (n_free,) int
        Unconstrained dofs.
    lu : scipy.sparse.linalg.SuperLU
        Factorisation of K[free][:, free].
    lam, mu : float, N/mm^2
        Lame parameters.
    """

    vertices: np.ndarray
    tets: np.ndarray
    basis: Any
    K: Any
    free: np.ndarray
    lu: Any
    lam: float
    mu: float

    def nodal_load_vector(self, forces) -> np.ndarray:
        """Global load vectors of vertex forces.

        Parameters
        ----------
        forces : (n_cases, nv, 3) or (nv, 3) float, N
            Force on every vertex (member frame).

        Returns
        -------
        (N, n_cases) float, N
        """
        F = np.asarray(forces, float)
        F = F[None] if F.ndim == 2 else F
        if F.shape[1:] != (len(self.vertices), 3):
            raise DesignError.single("forces", F.shape, f"(n_cases, {len(self.vertices)}, 3)", "N", "FE tooth loads")
        B = np.zeros((self.basis.N, F.shape[0]))
        for c in range(3):
            B[self.basis.nodal_dofs[c]] = F[:, :, c].T
        return B

    def solve(self, forces) -> np.ndarray:
        """Displacements (N, n_cases) in mm of vertex forces (n_cases, nv, 3) N (one back-substitution per case)."""
        B = self.nodal_load_vector(forces)
        U = np.zeros_like(B)
        U[self.free] = self.lu.solve(np.ascontiguousarray(B[self.free]))
        return U

    def reactions(self, U) -> np.ndarray:
        """Forces (n_cases, 3) in N that the clamp exerts on the solid: the sum of K u over the clamped dofs by
        component (equal and opposite to the applied loads when the solve is in equilibrium)."""
        R = self.K @ np.asarray(U, float)
        R[self.free] = 0.0
        return np.stack([R[self.basis.nodal_dofs[c]].sum(axis=0) + _edge_sum(self.basis, R, c)
                         for c in range(3)], axis=-1)

    def vertex_stress(self, U) -> np.ndarray:
        """Nodal-averaged Cauchy stress at the vertices.

        Parameters
        ----------
        U : (N,) or (N, n_cases) float, mm

        Returns
        -------
        (n_cases, nv, 3, 3) float, N/mm^2
            Symmetric stress tensors (member frame).
        """
        import skfem

        U = np.asarray(U, float)
        U = U[:, None] if U.ndim == 1 else U
        # quadrature points at the reference vertices (the element's own vertex order)
        Xref = np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
        vb = skfem.Basis(self.basis.mesh, self.basis.elem, quadrature=(Xref, np.full(4, 1.0 / 24.0)))
        t = self.tets.T  # (4, nt): vertex a of element e is t[a, e]
        count = np.bincount(t.ravel(), minlength=len(self.vertices)).astype(float)
        out = np.empty((U.shape[1], len(self.vertices), 3, 3))
        eye = np.eye(3)
        for c in range(U.shape[1]):
            G = vb.interpolate(U[:, c]).grad  # (3, 3, nt, 4): d u_i / d x_j
            eps = 0.5 * (G + G.transpose(1, 0, 2, 3))
            tr = np.einsum("iiea->ea", eps)
            sig = 2.0 * self.mu * eps + self.lam * tr[None, None] * eye[:, :, None, None]
            acc = np.zeros((len(self.vertices), 3, 3))
            np.add.at(acc, t.T.ravel(), sig.transpose(2, 3, 0, 1).reshape(-1, 3, 3))
            out[c] = acc / count[:, None, None]
        return out


def _edge_sum(basis, R, c):
    """Sum of component ``c`` of R over the edge (mid-side) dofs of a P2 basis (0 for P1)."""
    ed = getattr(basis, "edge_dofs", None)
    if ed is None or ed.size == 0:
        return 0.0
    return R[ed[c]].sum(axis=0)


def max_principal(stress) -> np.ndarray:
    """Largest eigenvalue of symmetric stress tensors (..., 3, 3) -> (...), N/mm^2."""
    return np.linalg.eigvalsh(np.asarray(stress, float))[..., -1]


def solid_model(mesh, youngs_modulus: float = 206000.0, poisson_ratio: float = 0.3, order: int = 2) -> SolidModel:
    """Assemble and factorise the linear-elastic model of a tooth segment mesh.

    Parameters
    ----------
    mesh : SegmentMesh
        From :func:`~spiralbevel.meshing.ltca.mesher.mesh_tooth_segment` (``vertices``, ``tets``, ``fixed``).
    youngs_modulus : float, N/mm^2
    poisson_ratio : float, -
    order : {1, 2}
        Tetrahedron order (2: quadratic, free of the bending locking of linear tetrahedra).

    Returns
    -------
    SolidModel

    Raises
    ------
    DesignError
        Bad order or material, or no clamped vertex.
    MissingDependencyError
        scikit-fem is not installed (extra ``fem``).
    """
    try:
        import skfem
        from skfem.models.elasticity import lame_parameters
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise MissingDependencyError("scikit-fem", "fem", "FE tooth root stress") from err
    from ..meshing.ltca.compliance import factorize, stiffness_matrix

    if order not in (1, 2):
        raise DesignError.single("order", order, "1 or 2", "-", "FE tooth root stress")
    if not (np.isfinite(youngs_modulus) and youngs_modulus > 0):
        raise DesignError.single("youngs_modulus", youngs_modulus, "> 0", "N/mm^2", "FE tooth root stress")
    if not (np.isfinite(poisson_ratio) and 0.0 <= poisson_ratio < 0.5):
        raise DesignError.single("poisson_ratio", poisson_ratio, "[0, 0.5)", "-", "FE tooth root stress")
    fixed_v = np.asarray(mesh.fixed, bool)
    if fixed_v.sum() < 3:
        raise DesignError.single("fixed", int(fixed_v.sum()), ">= 3 non-collinear clamped vertices", "-",
                                 "FE tooth root stress")
    m = skfem.MeshTet(np.asarray(mesh.vertices, float).T.copy(), np.asarray(mesh.tets).T.copy())
    elem = skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1()
    intorder = max(1, 2 * (order - 1))  # exact on affine elements: gradients of degree order - 1
    basis = skfem.Basis(m, skfem.ElementVector(elem), intorder=intorder)
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    K = stiffness_matrix(skfem.Basis(m, elem, intorder=intorder), basis.element_dofs, basis.N, lam, mu)
    # clamp as the LTCA compliance does: every dof of the facets with all vertices fixed, and the fixed vertices
    facets = np.flatnonzero(np.all(fixed_v[m.facets], axis=0))
    clamped = basis.get_dofs(facets=facets).all() if len(facets) else np.array([], int)
    clamped = np.union1d(clamped, basis.nodal_dofs[:, fixed_v].ravel())
    free = np.setdiff1d(np.arange(basis.N), clamped)
    lu = factorize(K[free][:, free].tocsc())
    return SolidModel(np.asarray(mesh.vertices, float), np.asarray(mesh.tets), basis, K.tocsr(), free, lu,
                      float(lam), float(mu))
