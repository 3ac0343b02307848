"""Parameter domains of tooth flanks.

The log-spiral flank of seed 000 lives on a parallelogram in the (varphi, phi) plane, which is a rectangle in the
(psi, phi) coordinates: phi in [phi_min, phi_max] (toe and heel spheres) and psi in [psi_min, psi_max] (root and face
cones, docs/theory/logspiral.md, Eq. (S10)). psi is signed: psi > 0 on the branch with varphi > phi.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ParallelogramDomain:
    """Rectangle in (psi, phi), a parallelogram in (varphi, phi).

    Attributes
    ----------
    phi_min, phi_max : float, rad
        Spiral-parameter range: the toe and heel spheres |r| = rho0 exp(phi sin(delta) cot(beta)).
    psi_min, psi_max : float, rad
        Signed range of psi = (varphi - phi) sin(delta): root and face cones. It never contains 0 (singular edge).
    base_cone_angle : float, rad
        delta of the flank, needed to map psi back to varphi.
    """

    phi_min: float
    phi_max: float
    psi_min: float
    psi_max: float
    base_cone_angle: float

    def to_varphi(self, psi, phi):
        """varphi = phi + psi / sin(delta)."""
        return np.asarray(phi, float) + np.asarray(psi, float) / np.sin(self.base_cone_angle)

    def grid(self, n_phi: int, n_psi: int):
        """Parameter grid, shape (n_phi, n_psi): returns ``(varphi, phi)`` arrays in rad.

        Rows run from phi_min to phi_max (toe to heel when beta > 0, heel to toe when beta < 0;
        ``DesignedFlank.grid`` always orders toe to heel); columns run from psi_min to psi_max.
        """
        phi = np.linspace(self.phi_min, self.phi_max, n_phi)[:, None]
        psi = np.linspace(self.psi_min, self.psi_max, n_psi)[None, :]
        phi, psi = np.broadcast_arrays(phi, psi)
        return self.to_varphi(psi, phi), phi.copy()

    def vertices(self):
        """The four corners in (varphi, phi), counterclockwise from (psi_min, phi_min), shape (4, 2)."""
        pts = [(self.psi_min, self.phi_min), (self.psi_max, self.phi_min),
               (self.psi_max, self.phi_max), (self.psi_min, self.phi_max)]
        return np.array([(self.to_varphi(ps, ph), ph) for ps, ph in pts])
