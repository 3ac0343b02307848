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
        rho, z, chi, dchi = _g.profile(u, self.cp)
        sol = dict(phi=phi, psi=psi, rho=rho, z=z, chi=chi, dchi=dchi, u=u, theta=phi - (np.pi - self.mp["q"] + psi))
        return self._evaluate(sol, curvature)

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
        return self._evaluate(sol, curvature)

    def _evaluate(self, sol, curvature):
        mp, psi = self.mp, sol["psi"]
        r, n_h, t_h, _ = _g.machine_state(sol, self.cp, mp)
        n_in = self.s * n_h
        pts = self._mirror(_g.to_member(r, psi, mp))
        nrm = self._mirror(_g.to_member(-n_in, psi, mp, point=False))
        if curvature:
            kI = -sol["dchi"]
            kII = -self.s * np.sin(sol["chi"]) / sol["rho"]
            eII = np.cross(n_in, t_h)
            vel = _g.relative_velocity(r, psi, mp)
            k_a, k_b, d_a, d_b, _ = _g.transfer_curvature(n_in, t_h, eII, kI, kII, vel)
            d_a = self._mirror(_g.to_member(d_a, psi, mp, point=False))
            d_b = self._mirror(_g.to_member(d_b, psi, mp, point=False))
            k1, k2, e1, e2 = _order(pts, nrm, k_a, k_b, d_a, d_b)
        else:
            nan = np.full(sol["u"].shape, np.nan)
            k1 = k2 = nan
            e1 = e2 = np.full(pts.shape, np.nan)
        return FlankPoints(points=pts, normals=nrm, k1=k1, k2=k2, e1=e1, e2=e2, u=sol["u"], theta=sol["theta"],
                           psi_c=psi, fillet=sol["u"] < self.cp["u_j"])

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


def _order(pts, nrm, k_a, k_b, d_a, d_b):
    """Order principal data: k1 along the profile (direction most perpendicular to r), e1 root->top, e1 x e2 = n."""
    rhat = pts / np.linalg.norm(pts, axis=-1, keepdims=True)
    a_is_profile = np.abs(np.einsum("...i,...i", d_a, rhat)) <= np.abs(np.einsum("...i,...i", d_b, rhat))
    k1 = np.where(a_is_profile, k_a, k_b)
    k2 = np.where(a_is_profile, k_b, k_a)
    e1 = np.where(a_is_profile[..., None], d_a, d_b)
    # root -> top: away from the axis in the axial plane, perpendicular to r
    radial = pts.copy()
    radial[..., 2] = 0.0
    radial /= np.linalg.norm(radial, axis=-1, keepdims=True)
    up = radial - np.einsum("...i,...i", radial, rhat)[..., None] * rhat
    sgn = np.where(np.einsum("...i,...i", e1, up) < 0.0, -1.0, 1.0)
    e1 = e1 * sgn[..., None]
    e2 = np.cross(nrm, e1)
    return k1, k2, e1, e2
