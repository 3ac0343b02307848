"""Equation of meshing of generation and the generated surface as a function of (u, psi_c).

seed 001 Eqs. (11)-(15) (docs/theory/generation.md, Eqs. (G5)-(G8)); seed 003 (docs/theory/generation.md, Eqs.
(G9)-(G11)). The cutter angle theta is found in closed form
for every (u, psi_c) (see ``_core.generation.solve_contact``), so the generated surface is the explicit map
(u, psi_c) -> r_i. Hand: the kernel is written for a left-hand member; a right-hand member is its mirror image
y -> -y in the member frame (and the machine is mirrored, docs/conventions.md "Machine settings").
"""

from __future__ import annotations

import numpy as np

from spiralbevel._core import generation as _g
from spiralbevel._core import generation_blade as _gb
from spiralbevel.conventions import Hand
from spiralbevel.errors import GeometryError
from spiralbevel.generation.results import FlankPoints

__all__ = ["Generator", "meshing_residual"]

_MIRROR = np.array([1.0, -1.0, 1.0])


class Generator:
    """Generation kinematics of one cutter blade with one set of machine settings, for one hand."""

    def __init__(self, cutter, settings, hand: Hand):
        self.cutter = cutter
        self.settings = settings
        self.hand = Hand(hand)
        self.cp = cutter._params()
        self.mp = settings.kernel_params()
        self.s = cutter.sign

    def _mirror(self, v):
        return v * _MIRROR if self.hand is Hand.RIGHT else v

    def contact(self, u, psi, dphi=0.0):
        """Closed-form contact (cutter angle) at blade parameter u and cradle angle psi_c.

        Of the two roots of the equation of meshing, the one nearer the reference angle (``reference_angle``) plus
        ``dphi`` (rad, broadcast with u and psi_c) is taken.
        """
        psi = np.asarray(psi, float)
        ref = _g.reference_angle(psi, self.mp, self.cutter.nominal_radius) + dphi
        return _g.solve_contact(u, psi, self.cp, self.mp, ref)

    def reference_angle(self, psi):
        """Absolute cutter angle (rad) toward the contact zone at cradle angle psi_c (``_core.generation``)."""
        return _g.reference_angle(np.asarray(psi, float), self.mp, self.cutter.nominal_radius)

    def blade_axial_radial(self, phi, psi):
        """(axial z, radius) of the blade point at cutter angle phi and cradle angle psi_c (the (phi, psi_c) chart,
        ``_core.generation_blade``), with its blade parameter u (mm) and d f / d u of the equation of meshing."""
        psi = np.asarray(psi, float)
        r, u = _gb.blade_points(phi, psi, self.cp, self.mp)
        ax, rad = _g.axial_radial(r, np.broadcast_to(psi, u.shape), self.mp)
        return ax, rad, u

    def point_at(self, u, phi, psi):
        """(axial z, radius) about the member axis of the cutter point (u, phi) at cradle angle psi_c, and the
        equation of meshing's value f there (``_core.generation_blade.meshing_function``; zero on the flank)."""
        u, phi, psi = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, phi, psi)))
        rho, z, chi, dchi = _g.profile(u, self.cp)
        r = _g.contact_point(dict(phi=phi, psi=psi, rho=rho, z=z), self.mp)
        ax, rad = _g.axial_radial(r, psi, self.mp)
        return ax, rad, _gb.meshing_function(u, phi, psi, self.cp, self.mp)

    def evaluate_blade(self, phi, psi, curvature=True) -> FlankPoints:
        """Flank points of the blade at cutter angle phi and cradle angle psi_c (rad), u from the equation of
        meshing (the (phi, psi_c) chart, regular across the fold of the (u, psi_c) chart)."""
        phi, psi = np.broadcast_arrays(np.asarray(phi, float), np.asarray(psi, float))
        u, _ = _gb.blade_u(phi, psi, self.cp, self.mp)
        return self.evaluate_at(u, phi, psi, curvature)

    def evaluate_at(self, u, phi, psi, curvature=True) -> FlankPoints:
        """Flank points at (u, phi, psi_c) that satisfy the equation of meshing (the caller's root)."""
        u, phi, psi = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, phi, psi)))
        return self._evaluate(u, phi, psi, curvature)

    def axial_radial(self, u, psi, dphi=0.0):
        """(axial z, radius) of the generated point in the member frame, and the meshing discriminant (root choice
        as :meth:`contact`)."""
        sol = self.contact(u, psi, dphi)
        r = _g.contact_point(sol, self.mp)
        ax, rad = _g.axial_radial(r, sol["psi"], self.mp)
        return ax, rad, sol["disc"]

    def points(self, u, psi):
        """Member-frame points only, (..., 3) mm."""
        sol = self.contact(u, psi)
        r, _, _, _ = _g.machine_state(sol, self.cp, self.mp)
        return self._mirror(_g.to_member(r, sol["psi"], self.mp))

    def evaluate(self, u, psi, curvature=True) -> FlankPoints:
        """Points, outward normals and (optionally) principal curvatures by the transfer formula
        (docs/theory/generation.md, Eqs. (G13)-(G15), #curvature-transfer)."""
        sol = self.contact(u, psi)
        if np.any(np.abs(sol["disc"]) > 1.0):
            raise GeometryError.single("settings", "-", "settings for which the cutter generates the flank", "-",
                                       "the equation of meshing has no solution: the cutter does not reach the blank")
        return self._evaluate(sol["u"], sol["phi"], sol["psi"], curvature)

    def _kernel_params(self):
        """(prm, fil) of the compiled flank points (``_core.generation_points``) in the member frame of this hand,
        built again whenever ``hand``, ``cp`` or ``mp`` has been replaced (callers set another hand, or a copy with
        another offset law)."""
        key = (self.hand, self.cp, self.mp)
        cached = self.__dict__.get("_prm_cache")
        if cached is None or any(a is not b for a, b in zip(cached[0], key)):
            from spiralbevel._core import generation_blade_jet, generation_points  # numba off the CLI's import path

            cached = (key, (generation_blade_jet.parameters(self.cp, self.mp, self.hand is Hand.RIGHT, 0.0),
                            generation_points.fillet_parameters(self.cp)))
            self.__dict__["_prm_cache"] = cached
        return cached[1]

    def _evaluate(self, u, phi, psi, curvature):
        """Points, outward normals and (if ``curvature``) principal curvatures and directions at (u, phi, psi_c)
        (broadcast arrays), compiled per point (``_core.generation_points``: the curvature transfer,
        docs/theory/generation.md, Eqs. (G13)-(G15), #curvature-transfer)."""
        from spiralbevel._core.generation_points import flank_points

        prm, fil = self._kernel_params()
        shape = u.shape
        flat = [np.ascontiguousarray(x, float).reshape(-1) for x in (u, phi, psi)]
        P, N, E1, E2, k1, k2 = flank_points(prm, fil, *flat, bool(curvature))
        v3 = shape + (3,)
        return FlankPoints(points=P.reshape(v3), normals=N.reshape(v3), k1=k1.reshape(shape), k2=k2.reshape(shape),
                           e1=E1.reshape(v3), e2=E2.reshape(v3), u=u, theta=phi - (np.pi - self.mp["q"] + psi),
                           psi_c=psi, fillet=u < self.cp["u_j"])

    def meshing_residual(self, u, theta, psi):
        """Relative residual n.v / max(|v|, 1e-4 |omega_12| |r|) of seed 001 Eq. (13) at (u, theta, psi_c).

        The floor on the denominator only matters on and near the instantaneous axis, where v = 0 (the cutter tip line
        when the cradle plane rolls purely on the root cone; the mean pitch point of basic settings whose
        instantaneous axis passes through it): there n.v is rounding noise of order 1e-16 |omega_12| |r| and the plain
        ratio would magnify it without bound.
        """
        u, theta, psi = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, theta, psi)))
        rho, z, chi, dchi = _g.profile(u, self.cp)
        phi = np.pi - self.mp["q"] + psi + theta
        sol = dict(phi=phi, psi=psi, rho=rho, z=z, chi=chi, dchi=dchi, u=u)
        r, n_h, _, _ = _g.machine_state(sol, self.cp, self.mp)
        vel = _g.relative_velocity(r, psi, self.mp)
        v = vel["v12"]
        scale = np.linalg.norm(vel["w1"] - vel["w2"], axis=-1) * np.linalg.norm(r, axis=-1)
        return np.einsum("...i,...i", n_h, v) / np.maximum(np.linalg.norm(v, axis=-1), 1e-4 * scale)


def meshing_residual(cutter, settings, u, theta, psi_c):
    """Relative residual |n . v| / |v| of the equation of meshing of generation (seed 001 Eqs. (13)-(15)).

    Parameters
    ----------
    cutter : HeadCutter
    settings : MachineSettings
    u : array_like, mm
    theta, psi_c : array_like, rad
    """
    return Generator(cutter, settings, Hand.LEFT).meshing_residual(u, theta, psi_c)
