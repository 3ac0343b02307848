"""Face-milled generated flanks as TCA contact surfaces (the ``ContactSurface`` protocol of ``contact_surface.py``).

:class:`GeneratedSurface`: parameters (phi, psi_c), the absolute cutter angle and the cradle angle of generation (rad);
the blade parameter u that satisfies the equation of meshing of generation is solved in closed form (straight blade;
Newton for an arc blade), compiled with its derivatives in ``_core.generation_blade_jet`` (the jet TCA runs in its
compiled Newton; ``_core.generation_blade`` is its numpy reference form). This chart is regular where the (u, psi_c)
chart of :class:`GeneratedSurfaceUPsi` folds (the two cutter angles of the equation of meshing merge inside the face at
low spiral angles). The flank may be turned about the member axis by ``rotation`` (rad) to phase it in its member frame.
The domain is the blade (u >= u_j); the fillet below it is the "fillet" boundary of edge contact.
"""

from __future__ import annotations

import math

import numpy as np

from .._core.generation import axial_radial, contact_point
from .._core.generation_blade import blade_jet
from .._core.generation_jet import generated_jet
from .._core.rotations import rot_z
from ..conventions import Hand

__all__ = ["GeneratedSurface", "GeneratedSurfaceUPsi", "phased_for_pair"]

#: mm: margin below which a point counts as on a flank boundary (round-off of points solved onto an edge)
EDGE_TOL = 1e-9


class GeneratedSurface:
    """A :class:`~spiralbevel.generation.flank.ToothFlank` seen by TCA, parameters (phi, psi_c) in rad.

    Parameters
    ----------
    flank : ToothFlank
    rotation : float, rad
        Turn about +z applied to points and normals (member frame).
    """

    fd_step = (1e-6, 1e-6)
    boundary_names = ("toe", "heel", "top", "fillet")

    def __init__(self, flank, rotation: float = 0.0):
        self.flank = flank
        self.rotation = float(rotation)
        self._R = rot_z(self.rotation)
        mp = flank.mean_point()
        self.reference_params = np.array([self.cutter_angle(mp.theta, mp.psi_c), mp.psi_c])
        self.mean_point = mp

    def cutter_angle(self, theta, psi_c):
        """Absolute cutter angle phi = theta + pi - q + psi_c (rad) of a cutter angle theta measured from the ray
        cradle axis -> cutter centre (``FlankPoints.theta``)."""
        return np.asarray(theta, float) + math.pi - self.flank.generator.mp["q"] + np.asarray(psi_c, float)

    @property
    def _Rm(self):
        """The phasing turn after the mirror image y -> -y of a right-hand member (``Generator._mirror``)."""
        return self._R * np.array([1.0, -1.0, 1.0]) if self.flank.generator.hand is Hand.RIGHT else self._R

    @property
    def jet(self):
        """``(kind, prm)`` of the compiled jet (:mod:`spiralbevel._core.jets`, kind ``GENERATED``) that compiled TCA
        evaluates, or None for a per-system offset law (arrays in the machine parameters)."""
        prm = self._prm()
        return None if prm is None else (1, prm)

    @property
    def contains_margin_tol(self):
        """``EDGE_TOL``: the margin part of :meth:`contains` is "every compiled margin (``boundary_jet``) >= -EDGE_TOL";
        None for a per-system offset law (no compiled margins). (:meth:`contains` also tests :meth:`on_sheet`, which
        the compiled edge screen applies from the same jet with the sign :meth:`_sheet_sign`.)"""
        return None if self._prm() is None else EDGE_TOL

    @property
    def boundary_jet(self):
        """``(kind, prm)`` of the compiled boundary margins with their gradients
        (:func:`spiralbevel._core.tca_edge.margins`, kind ``MARGIN_GENERATED``; the same margins as
        :meth:`boundary_margins`), or None without a compiled jet."""
        prm = self._prm()
        if prm is None:
            return None
        if getattr(self, "_bprm_src", None) is not prm:
            ol, gen = self.flank.outline, self.flank.generator
            head = [math.sin(ol.delta), math.cos(ol.delta), ol.Ri, ol.Re, ol.ham, ol.Rm,
                    math.tan(ol.delta_a - ol.delta), gen.cp["u_j"]]
            self._bprm = np.concatenate([np.array(head, float), prm])
            self._bprm_src = prm
        return 1, self._bprm

    def _prm(self):
        """Parameter vector of :mod:`spiralbevel._core.generation_blade_jet`, rebuilt when the generator's parameter
        dicts are replaced (solvers that vary a setting swap ``generator.mp``)."""
        gen = self.flank.generator
        src = getattr(self, "_prm_src", None)
        if src is None or src[0] is not gen.cp or src[1] is not gen.mp:
            from .._core import generation_blade_jet as _gbj  # numba stays off the import path of the CLI

            self._prm_cache = _gbj.parameters(gen.cp, gen.mp, gen.hand is Hand.RIGHT, self.rotation)
            self._prm_src = (gen.cp, gen.mp)  # held, so that a replaced dict is never mistaken for this one
        return self._prm_cache

    def _jet(self, params):
        """Stacked jet (..., 3, 6) in the member's own frame (mirror and phasing turn applied), blade parameter u
        (...) mm and the mask of the chart's singular set (u not finite, jet NaN there).

        Compiled (:func:`spiralbevel._core.generation_blade_jet.jet_batch`, the kernel TCA runs); a per-system offset
        law (no compiled jet) goes through the numpy form :func:`spiralbevel._core.generation_blade.blade_jet`."""
        params = np.asarray(params, float)
        prm = self._prm()
        if prm is None:
            gen = self.flank.generator
            with np.errstate(invalid="ignore", divide="ignore"):
                S, u, _ = blade_jet(params[..., 0], params[..., 1], gen.cp, gen.mp)
            off = ~np.isfinite(u)
            S = self._Rm @ S
            return np.where(off[..., None, None], np.nan, S), u, off
        from .._core import generation_blade_jet as _gbj

        q = np.ascontiguousarray(params.reshape(-1, 2))
        out, u = np.empty((q.shape[0], 3, 6)), np.empty(q.shape[0])
        _gbj.jet_batch(prm, q, out, u)
        shape = params.shape[:-1]
        u = u.reshape(shape)
        return out.reshape(shape + (3, 6)), u, ~np.isfinite(u)

    def evaluate(self, params):
        """Points (..., 3) mm and outward normals (..., 3) at ``params (..., 2) = (phi, psi_c)``; NaN where the chart
        is singular, so that solvers see "no surface there" and step back."""
        S, _, _ = self._jet(params)
        return S[..., 0], S[..., 1]

    def derivatives(self, params):
        """Points, outward normals and their derivatives w.r.t. (phi, psi_c) in closed form (the compiled jet,
        :mod:`spiralbevel._core.generation_blade_jet`), NaN where the chart is singular.

        Returns
        -------
        r : (..., 3) float, mm
        n : (..., 3) float
        dr : (..., 3, 2) float
            Columns dr/dphi and dr/dpsi_c (mm/rad).
        dn : (..., 3, 2) float
            Columns dn/dphi and dn/dpsi_c (1/rad).
        """
        S, _, _ = self._jet(params)
        return S[..., 0], S[..., 1], S[..., 2:4], S[..., 4:6]

    def boundary_margins(self, params):
        """Signed margins (..., 4) of (phi, psi_c) to the flank boundaries ``boundary_names`` (>= 0 on the flank):
        R - R_i and R_e - R (mm, toe and heel), h_face(R) - h (mm, top edge) and u - u_j (mm, fillet junction).
        Compiled (:func:`spiralbevel._core.tca_edge.margins`, the margins of edge contact); numpy for a per-system
        offset law."""
        params = np.asarray(params, float)
        b = self.boundary_jet
        if b is not None:
            from .._core import tca_edge as _ke

            g = _ke.margins_batch(b[0], b[1], np.ascontiguousarray(params.reshape(-1, 2)))[0]
            return g.reshape(params.shape[:-1] + (4,))
        S, u, _ = self._jet(params)
        r = S[..., 0]
        ol = self.flank.outline
        with np.errstate(invalid="ignore"):
            R, h = ol.Rh(r[..., 2], np.hypot(r[..., 0], r[..., 1]))
            return np.stack([R - ol.Ri, ol.Re - R, ol.h_face(R) - h, u - self.flank.generator.cp["u_j"]], -1)

    def contains(self, params):
        """True where (phi, psi_c) lies on the flank: between toe and heel, above the fillet junction, below the top,
        and not past a limit line of generation (:meth:`on_sheet`).

        A point on a boundary counts as on the flank within ``EDGE_TOL`` (a point that a solver put on an edge has
        margins of round-off size, of either sign)."""
        g = self.boundary_margins(params)
        with np.errstate(invalid="ignore"):
            return np.all(g >= -EDGE_TOL, axis=-1) & self.on_sheet(params)

    def on_sheet(self, params):
        """True where (phi, psi_c) lies on the sheet of the envelope that bounds the tooth: the orientation of the
        chart's tangents, sign((r_phi x r_psi) . n), is that at the mean point.

        Past a limit line of generation (where r_phi x r_psi vanishes: the generated surface has a cuspidal edge, the
        first sign of undercut, Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Sec. 6.3) the envelope
        folds back over itself: its points there lie on the air side of the sheet before the fold, inside the blade
        at the cradle angles that generate that sheet, i.e. cut away (tests/meshing/test_tca_limit_line.py shows it
        by sweeping the blade). Such points are no part of the real flank."""
        params = np.asarray(params, float)
        S, _, _ = self._jet(params.reshape(-1, 2))
        with np.errstate(invalid="ignore"):
            return (_orientation(S) * self._sheet_sign() > 0).reshape(params.shape[:-1])

    def _sheet_sign(self):
        """sign((r_phi x r_psi) . n) at the mean point, kept with the jet parameters it was computed for."""
        prm = self._prm()
        if getattr(self, "_sheet_src", None) is not prm or prm is None:
            self._sheet = float(np.sign(_orientation(self._jet(self.reference_params[None])[0])[0]))
            self._sheet_src = prm
        return self._sheet


def _orientation(S):
    """(r_phi x r_psi) . n (k,) of stacked jets S (k, 3, 6) (columns r, n, r_phi, r_psi, ...)."""
    a, b, n = S[:, :, 2], S[:, :, 3], S[:, :, 1]
    return ((a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]) * n[:, 0] + (a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]) * n[:, 1]
            + (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) * n[:, 2])


class GeneratedSurfaceUPsi:
    """A :class:`~spiralbevel.generation.flank.ToothFlank` seen by TCA in the (u, psi_c) chart (the cutter angle
    the root of the equation of meshing nearer the reference angle). It folds where the two roots merge (low spiral
    angles, docs/conventions.md "Fold of generation"): :class:`GeneratedSurface` is the chart TCA uses; this one
    serves the seed 001 multi-point control, whose system is written in (u, psi_c).

    Parameters
    ----------
    flank : ToothFlank
    rotation : float, rad
        Turn about +z applied to points and normals (member frame).
    """

    fd_step = (1e-4, 1e-6)

    def __init__(self, flank, rotation: float = 0.0):
        self.flank = flank
        self.rotation = float(rotation)
        self._R = rot_z(self.rotation)
        mp = flank.mean_point()
        self.reference_params = np.array([mp.u, mp.psi_c])
        self.mean_point = mp

    def _evaluate(self, params):
        """FlankPoints at (u, psi_c), and the mask of parameters off the generated surface (no root of the
        equation of meshing, |disc| > 1), which are evaluated at the reference parameters instead."""
        params = np.asarray(params, float)
        u, psi = np.broadcast_arrays(params[..., 0], params[..., 1])
        off = ~(np.abs(self.flank.generator.contact(u, psi)["disc"]) <= 1.0)
        if np.any(off):
            u, psi = np.where(off, self.reference_params[0], u), np.where(off, self.reference_params[1], psi)
        return self.flank.evaluate(u, psi, curvature=False), off

    def evaluate(self, params):
        """Points (..., 3) mm and outward normals (..., 3) at ``params (..., 2) = (u, psi_c)``; NaN off the surface,
        so that solvers see "no surface there" and step back."""
        fp, off = self._evaluate(params)
        r, n = fp.points @ self._R.T, fp.normals @ self._R.T
        if np.any(off):
            r, n = np.where(off[..., None], np.nan, r), np.where(off[..., None], np.nan, n)
        return r, n

    @property
    def _Rm(self):
        """The phasing turn after the mirror image y -> -y of a right-hand member (``Generator._mirror``)."""
        return self._R * np.array([1.0, -1.0, 1.0]) if self.flank.generator.hand is Hand.RIGHT else self._R

    def derivatives(self, params):
        """Points, outward normals and their derivatives w.r.t. (u, psi_c) in closed form
        (:func:`spiralbevel._core.generation_jet.generated_jet`), NaN off the surface.

        Returns
        -------
        r : (..., 3) float, mm
        n : (..., 3) float
        dr : (..., 3, 2) float
            Columns dr/du (-) and dr/dpsi_c (mm/rad).
        dn : (..., 3, 2) float
            Columns dn/du (1/mm) and dn/dpsi_c (1/rad).
        """
        params = np.asarray(params, float)
        gen = self.flank.generator
        with np.errstate(invalid="ignore"):
            S, disc = generated_jet(params[..., 0], params[..., 1], gen.cp, gen.mp, gen.cutter.nominal_radius)
            S = self._Rm @ S
        off = ~(np.abs(disc) <= 1.0)
        if np.any(off):
            S = np.where(off[..., None, None], np.nan, S)
        return S[..., 0], S[..., 1], S[..., 2:4], S[..., 4:6]

    def contains(self, params):
        """True where (u, psi_c) lies on the flank: between toe and heel, above the fillet junction, below the top."""
        params = np.asarray(params, float)
        gen = self.flank.generator
        u, psi = np.broadcast_arrays(params[..., 0], params[..., 1])
        sol = gen.contact(u, psi)
        off = ~(np.abs(sol["disc"]) <= 1.0)
        ax, rad = axial_radial(contact_point(sol, gen.mp), sol["psi"], gen.mp)
        ol = self.flank.outline
        with np.errstate(invalid="ignore"):
            R, h = ol.Rh(ax, rad)
            return ~off & (R >= ol.Ri) & (R <= ol.Re) & (h <= ol.h_face(R)) & (u >= gen.cp["u_j"])


    boundary_names = ("toe", "heel", "top", "fillet", "generated")

    def boundary_margins(self, params):
        """Signed margins (..., 5) of (u, psi_c) to the flank boundaries ``boundary_names`` (>= 0 on the flank):
        R - R_i and R_e - R (mm, toe and heel), h_face(R) - h (mm, top edge), u - u_j (mm, fillet junction) and
        1 - |disc| (root of the equation of meshing of generation)."""
        params = np.asarray(params, float)
        gen = self.flank.generator
        u, psi = np.broadcast_arrays(params[..., 0], params[..., 1])
        sol = gen.contact(u, psi)
        disc = 1.0 - np.abs(sol["disc"])
        ax, rad = axial_radial(contact_point(sol, gen.mp), sol["psi"], gen.mp)
        ol = self.flank.outline
        with np.errstate(invalid="ignore"):
            R, h = ol.Rh(ax, rad)
            return np.stack([R - ol.Ri, ol.Re - R, ol.h_face(R) - h, u - gen.cp["u_j"], disc], -1)


def phased_for_pair(pinion_flank, gear_flank):
    """Contact surfaces of a pinion and a gear flank turned so that their mean points meet at zero roll.

    The pinion mean point goes to azimuth 0 of the pinion frame and the gear mean point to azimuth pi of the gear
    frame: in the pair frame (docs/conventions.md) both then lie on the pitch line at phi1 = phi2 = 0.
    """
    mp1, mp2 = pinion_flank.mean_point(), gear_flank.mean_point()
    a1 = -math.atan2(mp1.point[1], mp1.point[0])
    a2 = math.pi - math.atan2(mp2.point[1], mp2.point[0])
    return GeneratedSurface(pinion_flank, a1), GeneratedSurface(gear_flank, a2)
