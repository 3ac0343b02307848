"""Location of blade points of a generated flank in the (phi, psi_c) chart (``_core.generation_blade``).

The (u, psi_c) chart of the generated flank folds where the two cutter angles that solve the equation of meshing of
generation merge (at low spiral angles that fold runs through the face width); the (phi, psi_c) chart, with the blade
parameter u solved from the equation of meshing, is regular there (docs/conventions.md, "Fold of generation").
Points on the blade (u >= u_j) are located here by compiled Newton solves in (phi, psi_c)
(:mod:`spiralbevel._core.blade_locate`); the fillet keeps the (u, psi_c) chart (``locate.Locator``).
"""

from __future__ import annotations

import itertools
from functools import cached_property

import numpy as np
from scipy.spatial import cKDTree

from spiralbevel.conventions import TOL

__all__ = ["BladeLocator"]

_MAX_STEP = np.array([0.05, 0.05])      # rad: Newton steps in phi and psi_c


class BladeLocator:
    """Newton solves for blade points of one ``Generator`` in the (phi, psi_c) chart, with a start table.

    Parameters
    ----------
    gen : Generator
    outline : BlankOutline
    u_range : (2,) float, mm
        Blade parameters of the table (from below the fillet junction to above the face cone).
    psi_span : float, rad
        Cradle angles of the table, -psi_span..psi_span.
    phi_span : float, rad
        Cutter angles around the reference angle toward the contact zone (``reference_angle``: where the cutter
        circle crosses the member's root line, displaced by the blank offset) that belong to the flank; the start
        table covers +-0.5 rad. The face spans less than about 0.35 rad of cutter angle (face width up to 0.3 R_e,
        cutter radius from 0.8 R_m), and the mean point lies up to about 0.25 rad from the reference angle (small
        cutters); farther parts of the
        envelope are where the cutter circle would cross the blank again, away from the design contact zone.
    """

    def __init__(self, gen, outline, u_range, psi_span=1.2, phi_span=0.75, n_psi=97, n_phi=51):
        self.gen, self.outline, self.phi_span = gen, outline, phi_span
        self.u_j = gen.cp["u_j"]
        # starts from the inner part of the window (the contact zone itself); solutions anywhere in it
        P, D = np.meshgrid(np.linspace(-psi_span, psi_span, n_psi), np.linspace(-0.5, 0.5, n_phi), indexing="ij")
        Phi = gen.reference_angle(P) + D
        from spiralbevel._core import blade_locate  # numba off the CLI's import path

        ax, rad, u = (a.reshape(P.shape) for a in blade_locate.axial_radius(self._prm, np.stack([Phi, P], -1)
                                                                             .reshape(-1, 2)))
        R, h = outline.Rh(ax, rad)
        depth = outline.ham + outline.hfm
        mR = 0.3 * (outline.Re - outline.Ri)
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(u) & (u >= u_range[0]) & (u <= u_range[1])
            ok &= (R > outline.Ri - mR) & (R < outline.Re + mR)
            ok &= (h > outline.h_root(R) - depth) & (h < outline.h_face(R) + depth)
        self.empty = not np.any(ok)
        if self.empty:
            return
        self._par = np.stack([Phi[ok], P[ok]], -1)
        self._tab = cKDTree(np.stack([ax[ok], rad[ok]], -1))
        self._Ru = cKDTree(np.stack([R[ok], u[ok]], -1))

    @cached_property
    def _prm(self):
        """Parameter vector of the compiled jet (axial position and radius only: no mirror, no phasing turn)."""
        from spiralbevel._core import generation_blade_jet  # numba off the CLI's import path

        return generation_blade_jet.parameters(self.gen.cp, self.gen.mp, False, 0.0)

    # ------------------------------------------------------------------------------------------------------------
    def on_branch(self, x, u):
        """True where (phi, psi_c) ``x (..., 2)`` rad with blade parameter ``u (...)`` mm is a regular point of the
        chart (u finite) within the table's cutter-angle window (compiled, ``_core.blade_locate.on_branch``)."""
        from spiralbevel._core import blade_locate  # numba off the CLI's import path

        ok = blade_locate.on_branch(self._prm, float(self.gen.cutter.nominal_radius), float(self.phi_span),
                                    np.ascontiguousarray(x, float).reshape(-1, 2),
                                    np.ascontiguousarray(u, float).reshape(-1))
        return ok.reshape(np.shape(u))

    def _solve(self, solver, starts, accept=None):
        """Compiled Newton ``solver(x0) -> (x, converged, u)`` (:mod:`spiralbevel._core.blade_locate`) from the first
        start; the following starts for the systems not yet converged (or whose solution ``accept(x, u)`` rejects).
        Returns (x (..., 2), converged (...), u (...) mm)."""
        x, conv, u = None, None, None
        for x0 in starts:
            xr, cv, ur = solver(x0)
            ok = self.on_branch(xr, ur) & cv
            if accept is not None:
                ok &= accept(xr, ur)
            if x is None:
                x, conv, u = xr, ok, ur
            else:
                keep = ~conv & ok
                x = np.where(keep[..., None], xr, x)
                u = np.where(keep, ur, u)
                conv = conv | keep
            if np.all(conv):
                break
        return x, conv, u

    def _nearest(self, tree, tgt, shape, k=0):
        _, idx = tree.query(tgt.reshape(-1, 2), k=k + 1)
        idx = np.minimum(np.reshape(idx, (len(tgt.reshape(-1, 2)), -1))[:, k], len(self._par) - 1)
        return self._par[idx].reshape(shape + (2,))

    def at_axial_radius(self, axial, radius, x0=None):
        """(phi, psi_c) (..., 2), converged mask (...) and blade parameter u (...) mm of the blade points on the
        circles (axial, radius)."""
        axial, radius = np.broadcast_arrays(np.asarray(axial, float), np.asarray(radius, float))
        from spiralbevel._core import blade_locate  # numba off the CLI's import path

        prm = self._prm
        a, r = np.ascontiguousarray(axial.ravel()), np.ascontiguousarray(radius.ravel())

        def solver(x0):     # compiled Newton, analytic Jacobian of the jet (_core/blade_locate.py)
            x, u, conv, _ = blade_locate.locate_axial_radius(
                prm, np.ascontiguousarray(np.broadcast_to(x0, axial.shape + (2,)).reshape(-1, 2), float), a, r,
                TOL.newton_abs * 10, TOL.max_iter, _MAX_STEP)
            return x.reshape(axial.shape + (2,)), conv.reshape(axial.shape), u.reshape(axial.shape)

        tgt = np.stack([axial, radius], -1)
        starts = itertools.chain([] if x0 is None else [np.broadcast_to(x0, axial.shape + (2,))],
                                 (self._nearest(self._tab, tgt, axial.shape, k) for k in range(4)))   # when needed

        def accept(x, u):   # on the blade: the extended blade cone below the junction generates another surface
            with np.errstate(invalid="ignore"):
                return u >= self.u_j - 1e-9

        return self._solve(solver, starts, accept)

    def rows(self, axial, radius, x0):
        """Rows of blade points on the circles ``axial, radius (n, m)`` mm, each row located from the row before, the
        first from ``x0 (n, 2)`` (phi, psi_c), in one compiled call (:func:`spiralbevel._core.blade_locate.locate_rows`:
        the first start of :meth:`at_axial_radius` and the acceptance rule of :meth:`_solve`). Returns (phi, psi_c)
        (n, k, 2), u (n, k) mm of the first k rows accepted in full (k <= m)."""
        from spiralbevel._core import blade_locate  # numba off the CLI's import path

        x, u, k = blade_locate.locate_rows(
            self._prm, np.ascontiguousarray(x0, float), np.ascontiguousarray(axial, float),
            np.ascontiguousarray(radius, float), TOL.newton_abs * 10, TOL.max_iter, _MAX_STEP,
            float(self.gen.cutter.nominal_radius), float(self.phi_span), self.u_j - 1e-9)
        return x[:, :k], u[:, :k]

    def at_R_u(self, R, u, anchor=None):
        """(phi, psi_c), converged mask and u (mm) of the blade points with cone-distance coordinate R (mm) and blade
        parameter u (mm, >= u_j); ``anchor`` (2,) (phi, psi_c) of a flank point (the mean point) is the first start,
        so that the line u = const is the one through the flank's own contact zone."""
        R, u = np.broadcast_arrays(np.asarray(R, float), np.asarray(u, float))
        ol = self.outline
        from spiralbevel._core import blade_locate  # numba off the CLI's import path

        prm = self._prm
        Rf, uf = np.ascontiguousarray(R.ravel()), np.ascontiguousarray(u.ravel())

        def solver(x0):     # compiled Newton (_core/blade_locate.py)
            x, uu, conv, _ = blade_locate.locate_R_u(
                prm, np.ascontiguousarray(np.broadcast_to(x0, R.shape + (2,)).reshape(-1, 2), float), Rf, uf,
                float(np.sin(ol.delta)), float(np.cos(ol.delta)), TOL.newton_abs * 10, TOL.max_iter, _MAX_STEP)
            return x.reshape(R.shape + (2,)), conv.reshape(R.shape), uu.reshape(R.shape)

        # starts: table points nearest the root-cone point at R (the junction runs close to the root), then those
        # nearest in (R, u)
        ax0, rad0 = ol.axial_radius(R, ol.h_root(R))
        near_root = np.stack([ax0, rad0], -1)
        starts = itertools.chain(
            [] if anchor is None else [np.broadcast_to(np.asarray(anchor, float), R.shape + (2,))],
            (self._nearest(self._tab, near_root, R.shape, k) for k in range(3)),
            (self._nearest(self._Ru, np.stack([R, u], -1), R.shape, k) for k in range(3)))   # when needed
        depth = ol.ham + ol.hfm

        def accept(x, u):   # the junction line's point of this face station, not one of its continuation
            ax, rad, _ = blade_locate.axial_radius(prm, np.ascontiguousarray(x, float).reshape(-1, 2))
            ax, rad = ax.reshape(R.shape), rad.reshape(R.shape)
            with np.errstate(invalid="ignore"):
                return np.abs(ol.Rh(ax, rad)[1] - ol.h_root(R)) < depth

        return self._solve(solver, starts, accept)
