"""The contact system of TCA for one assembled pair: seed 001 Eq. (16) (docs/theory/tca.md, Eq. (T5)) in the pair frame
of
docs/conventions.md, batched over pinion rotations and tooth pairs.

Tooth pair k is pinion tooth k (the reference flank turned by +2 pi k / z1 about the pinion axis) against gear tooth
k (turned by -2 pi k / z2 about the gear axis). Since R_z(phi1) R_z(2 pi k/z1) = R_z(phi1 + 2 pi k/z1), and likewise on
the gear, pair k at pinion angle phi1 is the reference system at the *effective* angles
phi1 + 2 pi k / z1 and phi2 - 2 pi k / z2 (exact for a rigid, perfectly indexed assembly, misaligned or not).
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from .._core import tca as _k
from .._core import tca_batch as _b
from .._core import tca_solve as _n
from ..errors import DesignError, Problem
from .contact_surface import surface_derivatives
from .misalignment import Misalignment

__all__ = ["ContactProblem"]

#: rank threshold of the minimum-norm step and trial halvings of the Newton (:mod:`spiralbevel._core.tca_newton`)
_RCOND = 1e-10
_HALVINGS = 8
#: the aligned assembly (a frozen dataclass, shared: building one validates its fields)
_ALIGNED = Misalignment()


def _jet(surface):
    """``(kind, prm)`` of a surface's compiled jet (:mod:`spiralbevel._core.jets`), or None."""
    jet = getattr(surface, "jet", None)
    if jet is None:
        return None
    kind, prm = jet
    return int(kind), np.ascontiguousarray(prm, float)


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
        self.misalignment = misalignment if misalignment is not None else _ALIGNED
        # crossed axes (HypoidPairKinematics): the pair's own placement with the misalignments on top
        place = getattr(kinematics, "axes", None)
        self.axes = place(self.misalignment) if callable(place) else self.misalignment.axes(self.shaft_angle)
        if scale is None:
            ref = getattr(pinion, "reference_params", None)
            scale = 100.0
            if ref is not None:  # |r| (as np.linalg.norm computes it, without its checks)
                r = np.asarray(pinion.evaluate(np.asarray(ref, float))[0], float).ravel()
                scale = math.sqrt(r.dot(r))
        self.scale = float(scale)
        d, M2, L = _b.assembly_constants(self.axes, self.scale)
        self._const = (np.ascontiguousarray(d), np.ascontiguousarray(M2), L)
        jets = (_jet(pinion), _jet(gear))
        self._jets = jets if jets[0] is not None and jets[1] is not None else None

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
    def _stacked(self, x):
        """Member-frame surface data ``(S1, S2)`` (m, 3, 6) of pinion and gear at x (m, 5), by numpy."""
        S1 = _b.stack_state(*surface_derivatives(self.pinion, x[:, 0:2]))
        S2 = _b.stack_state(*surface_derivatives(self.gear, x[:, 2:4]))
        return np.ascontiguousarray(S1, float), np.ascontiguousarray(S2, float)

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
            (:mod:`spiralbevel._core.tca_newton`); default: never (up to ``max_iter``).

        Returns
        -------
        x (m, 5), converged (m,), residual (m,) mm, J (m, 5 or 6, 5), data, iterations int, basis (m, 2, 3)
            ``data = (S1, S2, S1f, Q)``: stacked member-frame surface data of pinion and gear (m, 3, 6) (columns r, n,
            r_q0, r_q1, n_q0, n_q1) and their fixed-frame images (:func:`~spiralbevel._core.tca_newton.assemble`).

        Notes
        -----
        The iteration is compiled (:mod:`spiralbevel._core.tca_newton`). When both flanks expose a compiled jet
        (``jet = (kind, prm)``, :mod:`spiralbevel._core.jets`) it runs entirely in compiled code; otherwise numpy
        evaluates the flanks between the compiled steps (same rules, same arithmetic of the system and the step).
        """
        phi1_eff = np.ascontiguousarray(np.asarray(phi1_eff, float).reshape(-1))
        x0 = np.ascontiguousarray(np.asarray(x0, float).reshape(-1, 5))
        m = x0.shape[0]
        c1, s1 = np.cos(phi1_eff), np.sin(phi1_eff)
        have_E = basis is not None
        E = np.array(basis, float, order="C") if have_E else np.empty((m, 2, 3))
        if anchor is None:
            aj, aval = -1, np.zeros(m)
        else:
            aj, aval = int(anchor[0]), np.ascontiguousarray(np.broadcast_to(np.asarray(anchor[1], float), (m,)))
        d, M2, L = self._const
        patience = max_iter if patience is None else int(patience)
        if self._jets is not None:
            (k1, p1), (k2, p2) = self._jets
            x, _, J, res, S1, S2, S1f, Q, it = _n.newton_jets(k1, p1, k2, p2, c1, s1, x0, E, have_E, d, M2, L, aj,
                                                              aval, tol, max_iter, _RCOND, patience, _HALVINGS)
            return x, res < tol, res, J, (S1, S2, S1f, Q), it, E
        k = 6 if aj >= 0 else 5
        with np.errstate(all="ignore"):
            S1, S2 = self._stacked(x0)
        run = _n.Iteration(m, k, c1, s1, E, d, M2, L, aj, aval, tol, max_iter, _RCOND, patience, _HALVINGS)
        c = run.begin(x0, S1, S2, have_E)
        while c:
            with np.errstate(all="ignore"):  # wild iterates give inf/NaN, handled by the halving rule
                T1, T2 = self._stacked(run.xn[:c])
            c = run.advance(T1, T2)   # the accepted trials' data copied into S1, S2
        x, res = run.x, run.res
        return x, res < tol, res, run.J, (S1, S2, run.S1f, run.Q), run.iterations, run.E

    def path_tangent(self, J, S1f, basis):
        """dx/dphi1 (m, 5) from the Jacobian and fixed-frame pinion data of :meth:`newton` (minimum norm on a
        contact line)."""
        return _n.tangent_batch(np.ascontiguousarray(J, float), np.ascontiguousarray(S1f, float),
                                np.ascontiguousarray(basis, float), self.scale, _RCOND)

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
