"""Batched location of generated flank points by Newton's method (seed 003 with docs/theory/generation.md, Eqs.
(G10)-(G11) (#mean-point)).

A point is located by two conditions on the generated surface (u, psi_c) -> r_i, with the cutter angle theta in
closed form at every iterate. For a target (axial, radius) in the member frame the conditions are the corrected
seed 003 equations F1 = |r x k| - R = 0 and F2 = r . k - L = 0 with k = (0, 0, 1) in the member frame.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.spatial import cKDTree

from spiralbevel._core.newton import solve_batched
from spiralbevel.conventions import TOL, Member
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.generation.locate_blade import BladeLocator

__all__ = ["BlankOutline", "locate_params"]


@dataclass(frozen=True)
class BlankOutline:
    """Axial section of one member's blank in the coordinates used to clip flanks.

    R = rho sin(delta) + z cos(delta) is the distance along the pitch generatrix (toe R_i, heel R_e: front and back
    cones perpendicular to the pitch cone); h = rho cos(delta) - z sin(delta) is the height above the pitch line
    (face cone through (R_m, h_am) at angle delta_a, root cone through (R_m, -h_fm) at angle delta_f).
    """

    delta: float
    delta_a: float
    delta_f: float
    Rm: float
    Ri: float
    Re: float
    ham: float
    hfm: float

    @classmethod
    def from_blank(cls, blank, member) -> "BlankOutline":
        i = Member(member).index
        try:
            g = lambda name: float(getattr(blank, f"{name}{i}"))  # noqa: E731
            Re = float(getattr(blank, f"Re{i}", blank.Re2))
            Ri = float(getattr(blank, f"Ri{i}", blank.Ri2))
            out = cls(delta=g("delta"), delta_a=g("delta_a"), delta_f=g("delta_f"), Rm=float(blank.Rm), Ri=Ri,
                      Re=Re, ham=g("ham"), hfm=g("hfm"))
        except AttributeError as err:
            raise DesignError.single("blank", type(blank).__name__, "an ISO 23509 BevelBlank", "-", str(err)) from err
        if not (0 < out.Ri < out.Rm < out.Re):
            raise DesignError.single("blank.Ri/Rm/Re", (out.Ri, out.Rm, out.Re), "0 < Ri < Rm < Re", "mm")
        return out

    def Rh(self, axial, radius):
        sd, cd = np.sin(self.delta), np.cos(self.delta)
        return radius * sd + axial * cd, radius * cd - axial * sd

    def axial_radius(self, R, h):
        sd, cd = np.sin(self.delta), np.cos(self.delta)
        return R * cd - h * sd, R * sd + h * cd

    def h_face(self, R):
        return self.ham + (np.asarray(R, float) - self.Rm) * np.tan(self.delta_a - self.delta)

    def h_root(self, R):
        return -self.hfm - (np.asarray(R, float) - self.Rm) * np.tan(self.delta - self.delta_f)


class Locator:
    """Newton solves on the generated surface of one ``Generator`` with a coarse start table."""

    def __init__(self, gen, outline: BlankOutline, psi_span=1.2, n_psi=97, n_u=13):
        self.gen, self.outline, self.psi_span = gen, outline, psi_span
        u0, uj = gen.cp["u_min"], gen.cp["u_j"]
        depth = outline.ham + outline.hfm
        u_top = uj + 1.6 * depth / np.cos(gen.cutter.blade_angle)
        self.u_range = (u0, u_top)
        U, P = np.meshgrid(np.linspace(u0, u_top, n_u), np.linspace(-psi_span, psi_span, n_psi), indexing="ij")
        ax, rad, disc = gen.axial_radial(U, P)
        R, h = outline.Rh(ax, rad)
        mR = 0.3 * (outline.Re - outline.Ri)
        ok = (np.abs(disc) <= 1.0) & (R > outline.Ri - mR) & (R < outline.Re + mR)
        ok &= (h > outline.h_root(R) - depth) & (h < outline.h_face(R) + depth)
        if not np.any(ok):
            raise GeometryError.single("settings.radial_setting", gen.settings.radial_setting,
                                       "a setting for which the cutter reaches the blank", "mm",
                                       "the equation of meshing has no solution")
        self._tab = np.stack([ax[ok], rad[ok]], -1)
        self._par = np.stack([U[ok], P[ok]], -1)
        self._tree = cKDTree(self._tab)
        blade = self._par[:, 0] >= uj
        self._blade = (cKDTree(self._tab[blade]), self._par[blade]) if np.any(blade) else (self._tree, self._par)

    def start(self, axial, radius):
        """Nearest table entry to each target (axial, radius)."""
        tgt = np.stack([axial, radius], -1).reshape(-1, 2)
        _, idx = self._tree.query(tgt)
        return self._par[idx].reshape(np.shape(axial) + (2,))

    def starts(self, axial, radius, k):
        """Alternative starts: k = 1 the nearest table entry on the blade (not the fillet, whose points crowd near the
        tip), k >= 2 the k-th nearest entry of the whole table."""
        tgt = np.stack([axial, radius], -1).reshape(-1, 2)
        if k == 5:
            return self._fine_start(tgt).reshape(np.shape(axial) + (2,))
        tree, par = (self._blade if k == 1 else (self._tree, self._par))
        kk = 0 if k == 1 else k
        _, idx = tree.query(tgt, k=kk + 1)
        idx = np.minimum(np.reshape(idx, (len(tgt), -1))[:, kk], len(par) - 1)
        return par[idx].reshape(np.shape(axial) + (2,))

    def _fine_start(self, tgt):
        """Nearest reached point of a fine (u, psi_c) table (61 x 481), for targets the coarse table misleads."""
        if not hasattr(self, "_fine"):
            U, P = np.meshgrid(np.linspace(*self.u_range, 61), np.linspace(-self.psi_span, self.psi_span, 481),
                               indexing="ij")
            ax, rad, disc = self.gen.axial_radial(U, P)
            ok = np.abs(disc) <= 1.0
            self._fine = (cKDTree(np.stack([ax[ok], rad[ok]], -1)), np.stack([U[ok], P[ok]], -1))
        tree, par = self._fine
        _, idx = tree.query(tgt)
        return par[idx]

    def fold_in_blank(self):
        """Face position R (mm) where the edge of the contact region of generation lies inside the blank, else None.

        The equation of meshing ``P cos(phi) + Q sin(phi) + R = 0`` has two roots per (u, psi_c) where
        ``|disc| < 1``; they merge on ``|disc| = 1``, the edge of the region the cutter generates in the (u, psi_c)
        parameters, where the contact line of generation touches the blade circle u = const. The (u, psi_c) chart
        follows one root (the branch toward the root line's crossing, ``reference_angle``), so where that edge maps
        inside the blank (between toe and heel, root and face cone) the flank continues on the other root, which only
        the (phi, psi_c) chart of the blade (:attr:`blade`) reaches. Found on the fine (u, psi_c) table: neighbours
        in psi_c on both sides of the edge.
        """
        U, P = np.meshgrid(np.linspace(*self.u_range, 61), np.linspace(-self.psi_span, self.psi_span, 481),
                           indexing="ij")
        ax, rad, disc = self.gen.axial_radial(U, P)
        ok = np.abs(disc) <= 1.0
        edge = ok[:, 1:] != ok[:, :-1]
        inside = np.where(ok[:, 1:], 1, 0)   # the reached neighbour of each edge pair
        i, j = np.nonzero(edge)
        if i.size == 0:
            return None
        j = j + inside[i, j]
        ol = self.outline
        R, h = ol.Rh(ax[i, j], rad[i, j])
        # on the blade only: the blade tip generates the root line by a grazing contact, itself on |disc| = 1
        hit = (U[i, j] >= self.gen.cp["u_j"]) & (R > ol.Ri) & (R < ol.Re) & (h > ol.h_root(R)) & (h < ol.h_face(R))
        return float(np.median(R[hit])) if np.any(hit) else None

    def fold_error(self, what, fold):
        """The error for a flank whose generation edge (see :meth:`fold_in_blank`) lies inside the blank."""
        gen, ol = self.gen, self.outline
        return GeometryError.single(
            "gear_set.mean_spiral_angle", "-", "a spiral angle away from the fold of generation", "deg",
            f"{what}: the contact line of generation folds inside the face width (at R = {fold:.1f} mm, toe "
            f"{ol.Ri:.1f} mm, heel {ol.Re:.1f} mm): there the two cutter angles that solve the equation of meshing "
            "merge, and the fillet points asked for here are located in the (u, psi_c) chart, which follows one of "
            "them (the blade is located in the (phi, psi_c) chart, regular through the fold). It "
            "happens where the cutter's radial direction at the mean point is nearly square to the tooth's root line "
            "(low spiral angles, up to about 20 deg with a cutter radius near Rm): change gear_set.mean_spiral_angle "
            f"(a larger spiral angle) or gear_set.cutter_radius (now {gen.cutter.nominal_radius:.1f} mm at this blade)")

    def solve(self, fun, x0, what, retry=None, dphi=0.0):
        """Batched Newton from ``x0``; ``retry(k)`` gives the k-th alternative starts for points that do not converge
        (the coarse table's nearest entry can sit on the degenerate fillet tip, where the map (u, psi_c) -> point
        folds)."""
        def reached(r):
            # a converged point is valid only where the cutter reaches it (|disc| <= 1 in the contact solve)
            _, _, disc = self.gen.axial_radial(r.x[..., 0], r.x[..., 1], dphi)
            r.converged = r.converged & (np.abs(disc) <= 1.0)
            return r

        res = solve_batched(fun, x0, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter,
                            max_step=np.array([2.0, 0.05]))
        if retry is not None:
            res = reached(res)
        for k in range(1, 6 if retry is not None else 1):
            bad = ~res.converged
            if not np.any(bad):
                break
            x1 = np.where(bad[..., None], retry(k), res.x)
            again = reached(solve_batched(fun, x1, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter,
                                          max_step=np.array([2.0, 0.05])))
            keep = bad & again.converged
            res.x = np.where(keep[..., None], again.x, res.x)
            res.residual = np.where(keep, again.residual, res.residual)
            res.converged = res.converged | keep
        if not np.all(res.converged):
            bad = ~res.converged
            fold = self.fold_in_blank()
            if fold is not None:
                raise self.fold_error(what, fold)
            raise GeometryError.single(
                what, f"{int(bad.sum())} of {bad.size} points", "points on the generated flank", "mm",
                f"the generated flank does not reach them (largest residual {np.max(res.residual):.3g} mm): "
                "cutter/settings miss the blank or the face width")
        _, _, disc = self.gen.axial_radial(res.x[..., 0], res.x[..., 1], dphi)
        if np.any(np.abs(disc) > 1.0):
            raise GeometryError.single(what, "-", "points reached by the cutter", "-", "no contact")
        return res.x

    @cached_property
    def blade(self) -> BladeLocator:
        """Locator of blade points in the (phi, psi_c) chart, regular across the fold of the (u, psi_c) chart."""
        return BladeLocator(self.gen, self.outline, (self.gen.cp["u_j"] - 0.25 * (self.outline.ham + self.outline.hfm),
                                                     self.u_range[1]), self.psi_span)

    def _blade_or_fail(self, x, ok, u, what):
        """(u, phi, psi_c) of blade solves (u mm of each), or the error naming the points the blade chart did not
        reach."""
        with np.errstate(invalid="ignore"):
            ok = ok & (u >= self.gen.cp["u_j"] - 1e-9)
        if not np.all(ok):
            raise GeometryError.single(
                what, f"{int((~ok).sum())} of {ok.size} points", "points on the generated flank", "mm",
                "the generated blade flank does not reach them: cutter/settings miss the blank or the face width")
        return np.stack([u, x[..., 0], x[..., 1]], -1)

    def at_axial_radius(self, axial, radius):
        """(u, phi, psi_c) (..., 3) of the flank point on the circle (axial, radius) about the member axis: on the
        blade in the (phi, psi_c) chart, on the fillet (points the blade chart places below the junction) in the
        (u, psi_c) chart."""
        axial, radius = np.broadcast_arrays(np.asarray(axial, float), np.asarray(radius, float))
        x = np.empty(axial.shape + (3,))
        todo = np.ones(axial.shape, bool)
        if not self.blade.empty:
            xb, ok, ub = self.blade.at_axial_radius(axial, radius)
            with np.errstate(invalid="ignore"):
                ok &= ub >= self.gen.cp["u_j"] - 1e-9
            x[ok] = np.stack([ub[ok], xb[ok][..., 0], xb[ok][..., 1]], -1)
            todo = ~ok
        if np.any(todo):
            xu = self._at_axial_radius_u(axial[todo], radius[todo])
            phi = self.gen.contact(xu[..., 0], xu[..., 1])["phi"]
            x[todo] = np.stack([xu[..., 0], phi, xu[..., 1]], -1)
        return x

    def at_R_h(self, R, h, x0=None):
        """(u, phi, psi_c) of the blade points at (R, h) (mm); ``x0`` (..., 2) optional starts in (phi, psi_c)."""
        ax, rad = self.outline.axial_radius(np.asarray(R, float), np.asarray(h, float))
        if self.blade.empty:
            raise self._no_reach("grid(blade)")
        x, ok, u = self.blade.at_axial_radius(ax, rad, x0)
        return self._blade_or_fail(x, ok, u, "grid(blade)")

    def profile_rows(self, R, h, xj):
        """(u, phi, psi_c) (n, m, 3) of the blade points at cone-distance coordinates R (n,) mm and heights h (n, m) mm,
        row 0 the junction points ``xj`` (n, 3), each further row located from the row below (compiled, rows
        :meth:`BladeLocator.rows`; a row with a point that start does not reach, and every row after it, by
        :meth:`at_R_h` with its further starts)."""
        R, h = np.asarray(R, float), np.asarray(h, float)
        ax, rad = self.outline.axial_radius(R[:, None], h)
        out = np.empty(h.shape + (3,))
        out[:, 0] = xj
        x, u = self.blade.rows(ax[:, 1:], rad[:, 1:], xj[:, 1:])
        k = 1 + u.shape[1]
        out[:, 1:k, 0] = u
        out[:, 1:k, 1:] = x
        for j in range(k, h.shape[1]):
            out[:, j] = self.at_R_h(R, h[:, j], out[:, j - 1, 1:])
        return out

    def junction(self, R, anchor=None):
        """(u, phi, psi_c) of the fillet/blade junction line (u = u_j) at cone-distance coordinates R (mm); ``anchor``
        (2,) optional (phi, psi_c) of the mean point, the first start of every station."""
        if self.blade.empty:
            raise self._no_reach("grid(face station)")
        R = np.asarray(R, float)
        x, ok, u = self.blade.at_R_u(R, np.full_like(R, self.gen.cp["u_j"]), anchor)
        return self._blade_or_fail(x, ok, u, "grid(face station)")

    def fillet_rows(self, R, u, xj):
        """(u, phi, psi_c) of the fillet points at cone-distance coordinates R (n,) mm and blade parameters u (k,) mm
        (descending from the junction), continued row by row from the junction points ``xj`` (n, 3).

        Unknowns (phi, psi_c) at fixed u, equations f(u, phi, psi_c) = 0 (the equation of meshing itself, no choice
        of root) and R(u, phi, psi_c) = R: regular across the fold of the (u, psi_c) chart, where only f_phi vanishes.
        """
        gen, ol = self.gen, self.outline
        out = np.empty((len(R), len(u), 3))
        x = xj[:, 1:].copy()
        for k, uk in enumerate(u):
            def fun(y, uk=uk):
                ax, rad, f = gen.point_at(uk, y[..., 0], y[..., 1])
                return np.stack([f, ol.Rh(ax, rad)[0] - R], -1)
            res = solve_batched(fun, x, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter,
                                max_step=np.array([0.05, 0.05]))
            if not np.all(res.converged):
                raise GeometryError.single(
                    "grid(fillet)", f"{int((~res.converged).sum())} of {len(R)} points at u = {uk:.4g} mm",
                    "points on the generated fillet", "mm", "the edge radius does not generate them")
            x = res.x
            out[:, k] = np.concatenate([np.full((len(R), 1), uk), x], -1)
        return out

    def _no_reach(self, what):
        return GeometryError.single(what, "-", "points on the generated flank", "mm",
                                    "the generated blade flank does not reach the blank")

    def _at_axial_radius_u(self, axial, radius, x0=None):
        """(u, psi_c) of the flank point on the circle (axial, radius) about the member axis ((u, psi_c) chart)."""
        axial, radius = np.broadcast_arrays(np.asarray(axial, float), np.asarray(radius, float))
        gen = self.gen

        def fun(x):
            ax, rad, _ = gen.axial_radial(x[..., 0], x[..., 1])
            return np.stack([rad - radius, ax - axial], -1)

        return self.solve(fun, self.start(axial, radius) if x0 is None else x0, "locate(axial, radius)",
                          retry=lambda k: self.starts(axial, radius, k))

    def at_R_u(self, R, u, dphi=0.0, psi0=None):
        """psi_c (with u) of the flank point at blade parameter u and cone-distance coordinate R ((u, psi_c) chart,
        for the fillet; the root of the equation of meshing nearest the reference angle plus ``dphi``, rad;
        ``psi0`` optional starting cradle angles)."""
        R, u = np.broadcast_arrays(np.asarray(R, float), np.asarray(u, float))
        gen, ol = self.gen, self.outline

        def fun(x):
            ax, rad, _ = gen.axial_radial(x[..., 0], x[..., 1], dphi)
            Rx, _ = ol.Rh(ax, rad)
            return np.stack([Rx - R, x[..., 0] - u], -1)

        ax0, rad0 = ol.axial_radius(R, np.zeros_like(R) - ol.hfm)
        x0 = self.start(ax0, rad0)
        x0[..., 0] = u
        if psi0 is not None:
            x0[..., 1] = psi0

        def retry(k):
            x = self.starts(ax0, rad0, k)
            x[..., 0] = u
            return x

        return self.solve(fun, x0, "grid(face station)", retry=retry, dphi=dphi)


def locate_params(gen, outline, axial, radius):
    """(u, psi_c) arrays of the flank points at the given member-frame axial positions and radii."""
    x = Locator(gen, outline).at_axial_radius(axial, radius)
    return x[..., 0], x[..., 2]
