"""The contact system of TCA for one assembled pair: seed 001 Eq. (16) (docs/theory/tca.md, Eq. (T5)) in the pair frame
of
docs/conventions.md, batched over pinion rotations and tooth pairs.

Tooth pair k is pinion tooth k (the reference flank turned by +2 pi k / z1 about the pinion axis) against gear tooth
k (turned by -2 pi k / z2 about the gear axis). Since R_z(phi1) R_z(2 pi k/z1) = R_z(phi1 + 2 pi k/z1), and likewise on
the gear, pair k at pinion angle phi1 is the reference system at the *effective* angles
phi1 + 2 pi k / z1 and phi2 - 2 pi k / z2 (exact for a rigid, perfectly indexed assembly, misaligned or not).
"""

from __future__ import annotations

import numbers

import numpy as np

from .._core import tca as _k
from .._core import tca_batch as _b
from ..errors import DesignError, Problem
from .contact_surface import surface_derivatives
from .misalignment import Misalignment

__all__ = ["ContactProblem"]


class ContactProblem:
    """Batched contact equations of a pinion flank and a gear flank in an (optionally misaligned) assembly.

    Parameters
    ----------
    pinion, gear : ContactSurface
        Flanks in their member frames (outward normals).
    kinematics : object
        Anything with ``z1``, ``z2`` (int) and ``shaft_angle`` (rad), e.g.
        :class:`~spiralbevel.meshing.kinematics.BevelPairKinematics`; with an ``axes(misalignment)`` method
        (:class:`~spiralbevel.meshing.hypoid_kinematics.HypoidPairKinematics`) the pair is placed by it (crossed axes,
        pitch apexes off the crossing point) and the misalignment acts on top.
    misalignment : Misalignment, optional
    scale : float, mm, optional
        Length scale of the normal equations (default: |pinion point| at its reference parameters, else 100).

    Notes
    -----
    Unknowns x = (q1, q2, phi2_eff), equations F (5,) in mm (see ``spiralbevel._core.tca``).
    """

    def __init__(self, pinion, gear, kinematics, misalignment: Misalignment | None = None, scale: float | None = None):
        problems = []
        for name in ("z1", "z2"):
            z = getattr(kinematics, name, None)
            if isinstance(z, bool) or not isinstance(z, numbers.Integral) or z < 1:
                problems.append(Problem(f"kinematics.{name}", z, "integer >= 1", "-"))
        s = getattr(kinematics, "shaft_angle", None)
        if not isinstance(s, numbers.Real) or not 0.0 < float(s) < np.pi:
            problems.append(Problem("kinematics.shaft_angle", s, "0 < value < pi", "rad"))
        for name, surf in (("pinion", pinion), ("gear", gear)):
            if not hasattr(surf, "evaluate"):
                problems.append(Problem(name, type(surf).__name__, "an object with evaluate(params)", "-"))
        if problems:
            raise DesignError(problems)
        self.pinion, self.gear = pinion, gear
        self.z1, self.z2, self.shaft_angle = int(kinematics.z1), int(kinematics.z2), float(s)  # type: ignore[arg-type]
        self.misalignment = misalignment if misalignment is not None else Misalignment()
        # crossed axes (HypoidPairKinematics): the pair's own placement with the misalignments on top
        place = getattr(kinematics, "axes", None)
        self.axes = place(self.misalignment) if callable(place) else self.misalignment.axes(self.shaft_angle)
        if scale is None:
            ref = getattr(pinion, "reference_params", None)
            scale = float(np.linalg.norm(pinion.evaluate(np.asarray(ref, float))[0])) if ref is not None else 100.0
        self.scale = float(scale)
        self._const = _b.assembly_constants(self.axes, self.scale)

    # ------------------------------------------------------------------ angles of tooth pairs
    @property
    def ratio(self) -> float:
        """z1 / z2."""
        return self.z1 / self.z2

    def effective_phi1(self, phi1, pair):
        """phi1 + 2 pi k / z1, rad."""
        return np.asarray(phi1, float) + 2 * np.pi * np.asarray(pair) / self.z1

    def gear_angle(self, phi2_eff, pair):
        """Actual gear rotation phi2 = phi2_eff + 2 pi k / z2, rad."""
        return np.asarray(phi2_eff, float) + 2 * np.pi * np.asarray(pair) / self.z2

    # ------------------------------------------------------------------ evaluation
    def state(self, x):
        """Surface data at x (..., 5): ``(r1, n1, dr1, dn1, r2, n2, dr2, dn2)`` in member frames."""
        x = np.asarray(x, float)
        return surface_derivatives(self.pinion, x[..., 0:2]) + surface_derivatives(self.gear, x[..., 2:4])

    def pose(self, phi1_eff, phi2_eff):
        """Member -> fixed rotations (R1, R2) and apexes (o1, o2)."""
        R1, R2 = _k._pose(np.asarray(phi1_eff, float), np.asarray(phi2_eff, float), self.axes)
        return R1, R2, self.axes[1], self.axes[3]

    def basis(self, x, phi1_eff):
        """Basis (e1, e2) of the normal equations: orthogonal to the gear's fixed-frame normal at x."""
        x = np.asarray(x, float)
        _, n2 = self.gear.evaluate(x[..., 2:4])
        _, R2, _, _ = self.pose(phi1_eff, x[..., 4])
        return _k.tangent_basis(np.einsum("...ij,...j->...i", R2, n2))

    def system(self, x, phi1_eff, basis, jac=True):
        """(F (..., 5) mm, J (..., 5, 5)) at x (..., 5)."""
        st = self.state(x)
        return _k.contact_system(*st, phi1_eff, np.asarray(x, float)[..., 4], self.axes, basis, self.scale, jac)

    def residual(self, x, phi1_eff, basis):
        """F (..., 5) mm only (for plain per-point solvers such as scipy.optimize.fsolve)."""
        x = np.asarray(x, float)
        r1, n1 = self.pinion.evaluate(x[..., 0:2])
        r2, n2 = self.gear.evaluate(x[..., 2:4])
        z = np.zeros(x.shape[:-1] + (3, 2))
        return _k.contact_system(r1, n1, z, z, r2, n2, z, z, phi1_eff, x[..., 4], self.axes, basis, self.scale,
                                 jac=False)[0]

    def tangent(self, x, phi1_eff, basis):
        """dx/dphi1 (..., 5) along the solution path (minimum norm on a contact line)."""
        st = self.state(x)
        _, J = _k.contact_system(*st, phi1_eff, np.asarray(x, float)[..., 4], self.axes, basis, self.scale)
        Fp = _k.dF_dphi1(st[0], st[1], phi1_eff, self.axes, basis, self.scale)
        with np.errstate(all="ignore"):
            return _k.minnorm_step(J, Fp)[0]

    # ------------------------------------------------------------------ batched solve
    def newton(self, phi1_eff, x0, tol=1e-10, max_iter=30, basis=None, anchor=None, patience=None):
        """Batched Newton on flat batches, keeping the Jacobian and the surface data of the final iterate.

        Parameters
        ----------
        phi1_eff : (m,) float, rad
        x0 : (m, 5) float
        tol : float, mm
            On max|F|.
        basis : (m, 2, 3) float, optional
            Rows e_1, e_2 of the normal equations; default: orthogonal to the gear's fixed-frame normal at x0.
        anchor : (int, (m,) float), optional
            See :meth:`solve`.
        patience : int, optional
            Iterations without halving the best residual after which a system is given up
            (:func:`spiralbevel._core.tca_batch.newton_batched`); default: never (up to ``max_iter``).

        Returns
        -------
        x (m, 5), converged (m,), residual (m,) mm, J (m, 5 or 6, 5), data, iterations int, basis (m, 2, 3)
            ``data = (S1, S2, S1f, Q)``: stacked member-frame surface data of pinion and gear (m, 3, 6) (columns r, n,
            r_q0, r_q1, n_q0, n_q1) and their fixed-frame images (:func:`~spiralbevel._core.tca_batch.system_stacked`).
        """
        phi1_eff = np.asarray(phi1_eff, float).reshape(-1)
        x0 = np.asarray(x0, float).reshape(-1, 5)
        c1, s1 = np.cos(phi1_eff)[:, None], np.sin(phi1_eff)[:, None]
        E = None if basis is None else np.asarray(basis, float)
        const = self._const

        def fun(x, idx):
            nonlocal E
            S1 = _b.stack_state(*surface_derivatives(self.pinion, x[:, 0:2]))
            S2 = _b.stack_state(*surface_derivatives(self.gear, x[:, 2:4]))
            c2, s2 = np.cos(x[:, 4])[:, None], np.sin(x[:, 4])[:, None]
            if E is None:  # first call, all systems: basis from the gear normal at the start
                n2f = const[1][:3] @ _b.rotate_z(S2[:, :, 1:2], c2, s2)
                E = _b.basis_matrix(n2f[:, :, 0])
            F, J, S1f, Q = _b.system_stacked(S1, S2, c1[idx], s1[idx], c2, s2, const, E[idx])
            if anchor is not None:
                j, val = anchor
                F = np.concatenate([F, self.scale * (x[:, j] - np.asarray(val, float)[idx])[:, None]], -1)
                row = np.zeros((len(idx), 1, 5))
                row[:, 0, j] = self.scale
                J = np.concatenate([J, row], -2)
            return F, J, (S1, S2, S1f, Q)

        x, conv, res, J, data, it = _b.newton_batched(fun, x0, tol, max_iter=max_iter,
                                                      patience=max_iter if patience is None else patience)
        return x, conv, res, J, data, it, E

    def path_tangent(self, J, S1f, basis):
        """dx/dphi1 (m, 5) from the Jacobian and fixed-frame pinion data of :meth:`newton` (minimum norm on a
        contact line)."""
        with np.errstate(all="ignore"):
            return _b.newton_step(J, _b.dF_dphi1_stacked(S1f, basis, self.scale))

    def solve(self, phi1_eff, x0, tol=1e-10, max_iter=30, basis=None, anchor=None):
        """Batched Newton (minimum-norm steps) on flat batches.

        Parameters
        ----------
        phi1_eff : (m,) float, rad
        x0 : (m, 5) float
        tol : float, mm
            On max|F|.
        basis : tuple of (m, 3), optional
            Defaults to :meth:`basis` at x0.
        anchor : (int, (m,) float), optional
            ``(j, values)``: adds the equation x_j = value (scaled by ``scale``). On a contact line (exact conjugate
            surfaces) the 5 x 5 system is singular; the anchor fixes one surface parameter and picks one point of
            the line.

        Returns
        -------
        x (m, 5), converged (m,), residual (m,) mm, sratio (m,), iterations int
            ``sratio``: s_min / s_max of the column-equilibrated Jacobian at the final iterate (near 0 on a line).
        """
        E = None if basis is None else np.stack([np.asarray(basis[0], float), np.asarray(basis[1], float)], -2)
        x, conv, res, J, _, it, _ = self.newton(phi1_eff, x0, tol, max_iter, E, anchor)
        sratio = np.full(len(x), np.nan)
        good = np.isfinite(J).all(axis=(-1, -2))
        if good.any():
            cn = np.linalg.norm(J[good], axis=-2)
            cn = np.where(cn > 0, cn, 1.0)
            s = np.linalg.svd(J[good] / cn[..., None, :], compute_uv=False)
            sratio[good] = s[..., -1] / s[..., 0]
        return x, conv, res, sratio, it
