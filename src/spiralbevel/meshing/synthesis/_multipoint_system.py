"""The batched contact system of multi-point control (seed 001 Eqs. (16)-(17), docs/theory/tca.md, Eqs. (T5), (T8)), one
per control point.

Unknowns y = (u1, psi_c1, u2, psi_c2, phi2, E_m1): the blade parameters and cradle angles of the contact point on the
pinion and on the gear, the gear rotation and the pinion's instantaneous blank offset (mm, user sign of
``MachineSettings.blank_offset``). The cutter angles theta_1, theta_2 are eliminated in closed form by the equations of
meshing of generation f_1 = f_2 = 0 (``_core.generation.solve_contact``), so the 8 x 8 system of docs/theory/tca.md,
Eqs. (T5), (T8) becomes
6 x 6 here:

    R(a1, phi1) r1(u1, psi_c1; E_m1, E_m1') - R(a2, phi2) R_y(S) r2(u2, psi_c2) = 0      (3, mm)
    L (n1 + n2) . t_a = 0,  L (n1 + n2) . t_b = 0                                        (2, mm)
    L [TE(phi2) - target] = 0                                                            (1, mm; Eq. (17))

with TE = D [-(phi2 - phi20) - (z1/z2)(phi1 - phi10)] (docs/conventions.md), t_a, t_b two fixed unit vectors across the
mean normal and L a length (|M|) that turns the normal and TE equations into mm. The pinion point at psi_c1 depends on
the blank offset only through its value E_m1 and its rate E_m1' = dE_m1/dpsi_c at that instant (the rate enters the
relative velocity of generation, docs/theory/generation.md, Eqs. (G5)-(G6)); the rate is given per system (frozen during
one solve). For
the mean contact point the last equation is L (E_m1 - E_m10) = 0 instead: it fixes the offset and defines phi20.
"""

from __future__ import annotations

import copy

import numpy as np

from ..._core.newton import solve_batched
from ..._core.rotations import rot_z

#: Newton step caps: u1 mm, psi_c1 rad, u2 mm, psi_c2 rad, phi2 rad, E_m1 mm
MAX_STEP = np.array([1.0, 0.02, 1.0, 0.02, 0.01, 0.5])


class MultiPointSystem:
    """Batched residual of the control-point systems of one synthesized pair.

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

    # ------------------------------------------------------------------ pinion with a local offset law
    def pinion(self, u, psi, value, rate):
        """Pinion flank points and outward normals (member frame) at (u mm, psi_c rad), generated with the blank
        offset E_m1 = ``value`` (mm) and dE_m1/dpsi_c = ``rate`` (mm/rad) at that instant; all broadcast together."""
        gen = copy.copy(self.gen)
        u, psi, value, rate = np.broadcast_arrays(*(np.asarray(v, float) for v in (u, psi, value, rate)))
        # local law E(p) = value + rate (p - psi), kernel sign (MachineSettings.kernel_params): E enters negated
        gen.mp = dict(self.gen.mp, E=-(value - rate * psi), E_rate=-rate, E_poly=(), E_table=None)
        fp = gen.evaluate(u, psi, curvature=False)
        return fp.points, fp.normals

    def te(self, x, phi2, phi2_ref):
        """TE (rad) of a contact at pinion rotation phi10 + x and gear rotation phi2 (docs/conventions.md)."""
        return self.drive * (-(np.asarray(phi2) - phi2_ref) - self.ratio * np.asarray(x))

    def residual(self, y, x, target, rate, phi2_ref, mean):
        """F (m, 6) mm at y (m, 6) for offsets x (m,) rad, targets (m,) rad, rates (m,) mm/rad, mean mask (m,)."""
        r1, n1 = self.pinion(y[:, 0], y[:, 1], y[:, 5], rate)
        fp = self.gear.evaluate(y[:, 2], y[:, 3], curvature=False)
        R1 = rot_z(self.phi1_mean + x)
        R2 = self.kin.gear_to_fixed(y[:, 4])
        d = np.einsum("mij,mj->mi", R1, r1) - np.einsum("mij,mj->mi", R2, fp.points)
        s = np.einsum("mij,mj->mi", R1, n1) + np.einsum("mij,mj->mi", R2, fp.normals)
        L = self.length
        last = np.where(mean, y[:, 5] - self.offset0, self.te(x, y[:, 4], phi2_ref) - target)
        return np.concatenate([d, L * np.stack([s @ self.t_a, s @ self.t_b, last], -1)], -1)

    def solve(self, y0, x, target, rate, phi2_ref, mean, tol=1e-11, max_iter=40):
        """Batched Newton (forward-difference Jacobian) of all systems at once; returns a ``NewtonResult``."""
        x, target, rate, mean = (np.asarray(v) for v in (x, target, rate, mean))

        def fun(y):
            return self.residual(y, x, target, rate, phi2_ref, mean)

        return solve_batched(fun, y0, tol=tol, max_iter=max_iter, max_step=MAX_STEP)

    def start(self):
        """y at the mean contact point M of the synthesis (E_m1 = E_m10)."""
        s = self.synthesis
        return np.array([s.pinion_params[0], s.pinion_params[1], *s.mean.gear_params, s.phi2_mean, self.offset0])
