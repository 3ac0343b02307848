"""The batched contact system of multi-point control (seed 001 Eqs. (16)-(17), docs/theory/tca.md, Eqs. (T5), (T8)), one
per control point, solved by the compiled Newton of :mod:`spiralbevel._core.multipoint_newton`.

Unknowns z = (phi_1, psi_c1, phi_2, psi_c2, phi2, E_m1): the absolute cutter angles and cradle angles of the contact
point on the pinion and on the gear (the (phi, psi_c) chart of ``GeneratedSurface``), the gear rotation and the pinion's
instantaneous blank offset (mm, user sign of ``MachineSettings.blank_offset``). The blade parameters u_1, u_2 are
eliminated by the equations of meshing of generation f_1 = f_2 = 0 (solved inside the compiled jet, which returns them),
so the 8 x 8 system of docs/theory/tca.md, Eqs. (T5), (T8) becomes 6 x 6 here:

    o1 + R(a1, phi1) r1(phi_1, psi_c1; E_m1, E_m1') - o2 - R(a2, phi2) R_y(S) r2(phi_2, psi_c2) = 0   (3, mm)
    L (n1 + n2) . t_a = 0,  L (n1 + n2) . t_b = 0                                        (2, mm)
    L [TE(phi2) - target] = 0                                                            (1, mm; Eq. (17))

with o1, o2 the pitch apexes (member-frame origins) of the pair: zero for intersecting axes, those of
``HypoidPairKinematics.axes()`` (pinion axis through (0, E, 0), apexes t1, t2 along the axes) for a hypoid pair,
TE = D [-(phi2 - phi20) - (z1/z2)(phi1 - phi10)] (docs/conventions.md), t_a, t_b two fixed unit vectors across the
mean normal and L a length (|M|) that turns the normal and TE equations into mm. The pinion point at psi_c1 depends on
the blank offset only through its value E_m1 and its rate E_m1' = dE_m1/dpsi_c at that instant (the rate enters the
relative velocity of generation, docs/theory/generation.md, Eqs. (G5)-(G6)); the rate is given per system (frozen during
one solve). For
the mean contact point the last equation is L (E_m1 - E_m10) = 0 instead: it fixes the offset and defines phi20.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...conventions import Hand

#: Newton step caps: phi_1 rad, psi_c1 rad, phi_2 rad, psi_c2 rad, phi2 rad, E_m1 mm
MAX_STEP = np.array([0.02, 0.02, 0.02, 0.02, 0.01, 0.5])


@dataclass
class SystemResult:
    """Outcome of :meth:`MultiPointSystem.solve` (per system, like ``NewtonResult``).

    Attributes
    ----------
    x : (m, 6) float
        z = (phi_1 rad, psi_c1 rad, phi_2 rad, psi_c2 rad, phi2 rad, E_m1 mm).
    u : (m, 2) float, mm
        Blade parameters u_1, u_2 of the two contact points at ``x``.
    converged : (m,) bool
    residual : (m,) float, mm
    iterations : int
    """

    x: np.ndarray
    u: np.ndarray
    converged: np.ndarray
    residual: np.ndarray
    iterations: int

    @property
    def params(self):
        """(u mm, psi_c rad) of the contact points on the pinion and on the gear, (m, 2) each."""
        return np.stack([self.u[:, 0], self.x[:, 1]], -1), np.stack([self.u[:, 1], self.x[:, 3]], -1)


def _kernel_params(gen, **mp):
    """Parameter vector of the compiled generated-flank jet of ``gen`` (member frame, no phasing turn)."""
    from ..._core import generation_blade_jet as _gbj  # numba stays off the import path of the CLI

    return _gbj.parameters(gen.cp, dict(gen.mp, **mp), gen.hand is Hand.RIGHT, 0.0)


def _origins(kin):
    """Pitch apexes o1, o2 ((3,) mm each, fixed frame) of the aligned pair: zero for intersecting axes
    (``BevelPairKinematics``), ``kin.axes()`` for a pair with crossed axes (``HypoidPairKinematics``), whose axes must
    be the kernel's a1 = +z and a2 = (sin S, 0, cos S)."""
    place = getattr(kin, "axes", None)
    if not callable(place):
        return np.zeros(3), np.zeros(3)
    a1, o1, a2, o2, _ = place()
    S = float(kin.shaft_angle)
    if not (np.allclose(a1, [0.0, 0.0, 1.0], rtol=0, atol=1e-15)
            and np.allclose(a2, [np.sin(S), 0.0, np.cos(S)], rtol=0, atol=1e-15)):
        raise ValueError("multi-point control: the pair's axes are not the aligned a1 = +z, a2 = (sin S, 0, cos S)")
    return np.asarray(o1, float), np.asarray(o2, float)


class MultiPointSystem:
    """Compiled control-point systems of one synthesized pair.

    Parameters
    ----------
    synthesis : SynthesisResult
        Pinion flank (generator and machine settings), gear flank, mean contact M, phi10, phi20.
    pinion_flank, gear_flank : ToothFlank, optional
        Replace the synthesis flanks (same settings, e.g. generated with straight blades down to the tip plane).
    """

    def __init__(self, synthesis, pinion_flank=None, gear_flank=None):
        self.synthesis = synthesis
        self.gen = (pinion_flank or synthesis.pinion_flank).generator
        self.gear = gear_flank or synthesis.gear_flank
        mc = synthesis.mean
        self.kin = mc.kinematics
        self.ratio = self.kin.z1 / self.kin.z2
        self.drive = int(mc.drive_sign)
        self.phi1_mean = float(synthesis.phi1_mean)
        self.offset0 = float(synthesis.pinion_settings.blank_offset)
        self.length = float(np.linalg.norm(mc.point))
        n = np.asarray(mc.normal, float)
        a = np.cross(n, [1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.cross(n, [0.0, 1.0, 0.0])
        a /= np.linalg.norm(a)
        self.t_a, self.t_b = a, np.cross(n, a)
        self.o1, self.o2 = _origins(self.kin)
        # the pinion's offset law is set per system inside the kernel (E and E_rate of the vector)
        self.prm1 = _kernel_params(self.gen, E=0.0, E_rate=0.0, E_poly=(), E_table=None)
        self.prm2 = _kernel_params(self.gear.generator)
        self._jets = (self.prm1, self.prm2)

    def te(self, x, phi2, phi2_ref):
        """TE (rad) of a contact at pinion rotation phi10 + x and gear rotation phi2 (docs/conventions.md)."""
        return self.drive * (-(np.asarray(phi2) - phi2_ref) - self.ratio * np.asarray(x))

    def _constants(self, phi2_ref):
        return np.array([self.phi1_mean, self.kin.shaft_angle, self.ratio, float(self.drive), float(phi2_ref),
                         self.length, self.offset0, *self.t_a, *self.t_b, *self.o1, *self.o2])

    def solve(self, y0, x, target, rate, phi2_ref, mean, tol=1e-11, max_iter=40) -> SystemResult:
        """Newton on every system from ``y0 (m, 6)`` (z, see module) for offsets ``x (m,)`` rad, TE targets ``(m,)``
        rad, offset rates ``(m,)`` mm/rad and the mean mask ``(m,)``; tolerance on max|F| in mm."""
        from ..._core.multipoint_newton import solve_systems

        m = len(np.atleast_1d(x))
        def vec(v, dt=float):   # a writable copy: a read-only view would compile the kernel a second time
            return np.array(np.broadcast_to(np.asarray(v, dt), (m,)))

        z, u, conv, res, its = solve_systems(
            *self._jets, np.ascontiguousarray(np.asarray(y0, float).reshape(m, 6)), vec(x), vec(target),
            vec(rate), vec(mean, bool), self._constants(phi2_ref), MAX_STEP, float(tol), int(max_iter))
        return SystemResult(z, u, conv, res, int(its))

    def march(self, stations, tol=1e-11, max_iter=40):
        """Contact traced from M (TE free, constant offset E_m10) through ``stations (n_sides, n)`` rad in order on
        each side; returns z (n_sides, n, 6), u (n_sides, n, 2) mm and the count of converged stations per side."""
        from ..._core.multipoint_newton import march

        return march(*self._jets, self.start(), np.ascontiguousarray(stations, float),
                     self._constants(self.synthesis.phi2_mean), MAX_STEP, float(tol), int(max_iter))

    def start(self):
        """z at the mean contact point M of the synthesis (E_m1 = E_m10)."""
        s = self.synthesis
        u1, psi1 = (float(v) for v in s.pinion_params[:2])
        u2, psi2 = (float(v) for v in s.mean.gear_params)
        phi1 = float(self.gen.contact(np.array(u1), np.array(psi1))["phi"])
        phi2 = float(self.gear.generator.contact(np.array(u2), np.array(psi2))["phi"])
        return np.array([phi1, psi1, phi2, psi2, s.phi2_mean, self.offset0])
