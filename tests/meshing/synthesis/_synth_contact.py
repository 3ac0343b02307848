"""Independent point-contact check of two generated flanks (test helper; no synthesis code is used).

For a pinion rotation phi1, unknowns x = (u1, psi1, u2, psi2, phi2): the pinion point R_z(phi1) r1(u1, psi1) and the
gear point R(a2, phi2) R_y(Sigma) r2(u2, psi2) coincide (3 equations) and the outward normals are opposite (2
equations: n1 + n2 projected on two fixed vectors across the mean normal). Seed 001 Eq. (16), docs/theory/tca.md, Eq.
(T5), in the
pair frame of docs/conventions.md. Solved by the batched Newton with forward-difference Jacobians, by continuation
from the mean point in steps of ``step`` rad.
"""

import numpy as np

from spiralbevel._core.newton import solve_batched


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


class PairContact:
    def __init__(self, pinion, gear, kin, n_ref):
        self.p, self.g, self.kin = pinion, gear, kin
        n_ref = np.asarray(n_ref, float)
        a = np.cross(n_ref, [1.0, 0.0, 0.0])
        a /= np.linalg.norm(a)
        self.ta, self.tb = a, np.cross(n_ref, a)

    def state(self, x, phi1):
        f1 = self.p.evaluate(x[..., 0], x[..., 1], curvature=False)
        f2 = self.g.evaluate(x[..., 2], x[..., 3], curvature=False)
        R1 = _rz(np.asarray(phi1, float))
        R2 = self.kin.gear_to_fixed(x[..., 4])
        r1 = np.einsum("...ij,...j", R1, f1.points)
        n1 = np.einsum("...ij,...j", R1, f1.normals)
        r2 = np.einsum("...ij,...j", R2, f2.points)
        n2 = np.einsum("...ij,...j", R2, f2.normals)
        return r1, n1, r2, n2

    def residual(self, x, phi1):
        r1, n1, r2, n2 = self.state(x, phi1)
        s = n1 + n2
        return np.concatenate([r1 - r2, 100.0 * np.stack([s @ self.ta, s @ self.tb], -1)], -1)

    def solve(self, phi1, x0):
        phi1 = np.asarray(phi1, float)
        res = solve_batched(lambda x: self.residual(x, phi1), x0, tol=1e-10, max_iter=40,
                            max_step=np.array([1.0, 0.02, 1.0, 0.02, 0.02]))
        assert np.all(res.converged), res.residual
        return res.x

    def path(self, x_mean, phi1_mean, offsets, step=0.01):
        """Solutions at phi1_mean + offsets (sorted ascending, may include 0), by continuation from the mean."""
        offsets = np.asarray(offsets, float)
        out = np.empty(offsets.shape + (5,))
        for sign in (1.0, -1.0):
            sel = np.nonzero(sign * offsets >= 0)[0]
            o = offsets[sel]
            order = np.argsort(np.abs(o))
            x, cur = np.array(x_mean, float), 0.0
            for i in order:
                target = o[i]
                n = max(1, int(np.ceil(abs(target - cur) / step)))
                for t in np.linspace(cur, target, n + 1)[1:]:
                    x = self.solve(phi1_mean + t, x)
                cur = target
                out[sel[i]] = x
        return out
