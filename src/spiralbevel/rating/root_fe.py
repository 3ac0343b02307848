"""Plane-stress finite elements for tooth root stresses (scikit-fem, extra ``fem``).

A tooth section (or any plate) is meshed with triangles, clamped on part of its boundary, loaded by tractions on
another part, and solved for the displacement; the stress is projected onto the displacement's scalar space so that
the maximum principal stress can be read anywhere, in particular along the root fillet. The check against a known
answer (the exact elasticity solution of an end-loaded cantilever) and its convergence rate is in
``tests/rating/test_root_fe.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from ..errors import DesignError, MissingDependencyError

__all__ = ["PlaneStressResult", "solve_plane_stress"]


@dataclass(frozen=True)
class PlaneStressResult:
    """Displacement and stress of a plane-stress FE solve.

    Attributes
    ----------
    u : (N,) float, mm
        Displacement degrees of freedom (scikit-fem ordering).
    stress : (3, M) float, N/mm^2
        sigma_xx, sigma_yy, tau_xy at the degrees of freedom of the scalar space ``scalar_basis``.
    basis, scalar_basis : skfem.CellBasis
    """

    u: np.ndarray
    stress: np.ndarray
    basis: Any
    scalar_basis: Any

    def stress_at(self, points: np.ndarray) -> np.ndarray:
        """Stress components at points.

        Parameters
        ----------
        points : (2, n) float, mm

        Returns
        -------
        (3, n) float, N/mm^2
            sigma_xx, sigma_yy, tau_xy.
        """
        P = self.scalar_basis.probes(np.asarray(points, float))
        return np.stack([P @ s for s in self.stress])

    def max_principal(self, points: np.ndarray) -> np.ndarray:
        """Maximum principal stress sigma_1 = (sxx + syy)/2 + sqrt(((sxx - syy)/2)^2 + txy^2), (n,) N/mm^2."""
        sxx, syy, txy = self.stress_at(points)
        return 0.5 * (sxx + syy) + np.hypot(0.5 * (sxx - syy), txy)


def solve_plane_stress(mesh, E: float, nu: float, clamped: Callable, traction: Callable,
                       loaded: Callable, clamp_displacement: Optional[Callable] = None,
                       order: int = 2) -> PlaneStressResult:
    """Linear elastic plane stress on a triangle mesh (unit thickness).

    Parameters
    ----------
    mesh : skfem.MeshTri
        Triangles, mm.
    E : float, N/mm^2
    nu : float
    clamped : callable
        ``clamped(x) -> (n,) bool`` on facet midpoints ``x`` (2, n): the facets whose displacement is prescribed.
    traction : callable
        ``traction(x, n) -> (2, ...)`` N/mm^2 (force per unit area of the unit-thickness edge) at facet quadrature
        points ``x`` with outward normals ``n``.
    loaded : callable
        ``loaded(x) -> (n,) bool`` on facet midpoints: the facets carrying ``traction``.
    clamp_displacement : callable, optional
        ``clamp_displacement(x) -> (2, n)`` mm at the clamped degrees of freedom's locations; default zero.
    order : {1, 2}
        Polynomial order of the triangles.

    Returns
    -------
    PlaneStressResult

    Notes
    -----
    Plane-stress Lame constants mu = E/(2(1 + nu)), lambda* = E nu/(1 - nu^2); the stress of the displacement
    gradient (piecewise polynomial of order ``order - 1``) is L2-projected onto the continuous scalar space of order
    ``order``.
    """
    try:
        import skfem
        from skfem.helpers import dot
        from skfem.models.elasticity import linear_elasticity
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise MissingDependencyError("scikit-fem", "fem", "FE tooth root stress") from err
    if not (E > 0 and 0 < nu < 0.5):
        raise DesignError.single("E, nu", (E, nu), "E > 0, 0 < nu < 0.5", "N/mm^2, -")
    elem = skfem.ElementTriP2() if order == 2 else skfem.ElementTriP1()
    basis = skfem.Basis(mesh, skfem.ElementVector(elem))
    mu = E / (2.0 * (1.0 + nu))
    lam = E * nu / (1.0 - nu * nu)
    K = skfem.asm(linear_elasticity(lam, mu), basis)

    mid = mesh.p[:, mesh.facets].mean(axis=1)
    b = mesh.boundary_facets()
    cf = b[np.asarray(clamped(mid[:, b]), bool)]
    lf = b[np.asarray(loaded(mid[:, b]), bool)]
    if len(cf) == 0:
        raise DesignError.single("clamped", 0, "at least one clamped boundary facet", "-")
    fb = skfem.FacetBasis(mesh, skfem.ElementVector(elem), facets=lf)

    @skfem.LinearForm
    def load(v, w):
        return dot(traction(w.x, w.n), v)

    f = skfem.asm(load, fb)
    D = basis.get_dofs(facets=cf).all()
    u = np.zeros(basis.N)
    if clamp_displacement is not None:
        xd = basis.doflocs[:, D]
        val = np.asarray(clamp_displacement(xd))
        comp = np.arange(basis.N)[D] % 2  # ElementVector interleaves x, y components
        u[D] = np.where(comp == 0, val[0], val[1])
    u = skfem.solve(*skfem.condense(K, f, x=u, D=D))

    sb = basis.with_element(elem)
    grad = basis.interpolate(u).grad  # (2, 2, nel, nqp)
    exx, eyy = grad[0, 0], grad[1, 1]
    gxy = grad[0, 1] + grad[1, 0]
    tr = exx + eyy
    stress = np.stack([sb.project(2 * mu * exx + lam * tr), sb.project(2 * mu * eyy + lam * tr),
                       sb.project(mu * gxy)])
    return PlaneStressResult(u=u, stress=stress, basis=basis, scalar_basis=sb)
