"""The instantaneous blank offset E_m1(psi_c1) of multi-point control (seed 001 §4.3.1 step 3, Figure 6).

A law through nodes (psi_c1 at which each control-point contact is generated, blank-offset increment over the value
E_m10 at the mean contact point): piecewise linear between the nodes as in the paper, a natural cubic spline, or the
interpolating polynomial through all of them. Each passes exactly through the nodes.

Smoothness matters: the rate dE_m1/dpsi_c enters the equation of meshing of generation, so where the rate jumps (at
the nodes of the linear law) the generated point jumps along the cutter (by about 0.03 mm for the seed 001 example,
where the offset itself varies by less than 1 um). The flank generated with the linear law is therefore a patchwork
of smooth pieces, one per segment, exact between its nodes; the spline (C2, linear beyond the end nodes) and the
polynomial are smooth flanks. The polynomial is reliable only within the nodes (it is extrapolated as a polynomial).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._core.generation import table_offset
from ...errors import DesignError

__all__ = ["OffsetLaw", "INTERPOLATIONS"]

INTERPOLATIONS = ("linear", "spline", "polynomial")


@dataclass(frozen=True, eq=False)
class OffsetLaw:
    """Blank offset of the pinion as a function of the cradle angle.

    Attributes
    ----------
    kind : {"linear", "spline", "polynomial"}
    nodes : (m,) float, rad
        Cradle angles psi_c1 of the nodes, strictly increasing.
    increments : (m,) float, mm
        E_m1 - E_m10 at the nodes.
    base : float, mm
        E_m10, the blank offset at the mean contact point (the synthesis value).

    Notes
    -----
    ``linear``: ``spiralbevel._core.generation.table_offset`` (linear extrapolation beyond the end nodes; at a node the
    slope of the segment on the side of psi_c = 0). ``spline``: natural cubic spline (zero second derivative at the
    end nodes, linear beyond them). Both become ``MachineSettings.blank_offset_table``. ``polynomial``: degree m - 1
    in psi_c, computed in the scaled variable psi_c / max|psi_c| and converted to monomial coefficients
    (``MachineSettings.blank_offset_poly``).
    """

    kind: str
    nodes: np.ndarray
    increments: np.ndarray
    base: float

    def __post_init__(self):
        if self.kind not in INTERPOLATIONS:
            raise DesignError.single("interpolation", self.kind, " or ".join(INTERPOLATIONS), "-")
        x = np.asarray(self.nodes, float)
        if x.ndim != 1 or x.size < 2 or not np.all(np.diff(x) > 0):
            raise DesignError.single("nodes", x.tolist(), "at least 2 strictly increasing cradle angles", "rad",
                                     "control points must be generated at distinct cradle angles")
        object.__setattr__(self, "nodes", x)
        object.__setattr__(self, "increments", np.asarray(self.increments, float))

    @property
    def coefficients(self) -> np.ndarray:
        """Monomial coefficients (c0, c1, ...) of the polynomial law's increment, mm/rad^k (polynomial only)."""
        x, y = self.nodes, self.increments
        scale = float(np.max(np.abs(x)))
        t = x / scale
        a = np.linalg.solve(np.vander(t, increasing=True), y)
        return a / scale ** np.arange(a.size)

    def increment(self, psi):
        """E_m1(psi) - E_m10, mm."""
        return self._eval(psi)[0]

    def __call__(self, psi):
        """E_m1(psi), mm."""
        return self.base + self.increment(psi)

    def rate(self, psi):
        """dE_m1/dpsi_c, mm/rad (linear: node convention of ``table_offset``)."""
        return self._eval(psi)[1]

    def local(self, psi, base_settings):
        """``base_settings`` with the constant-rate law E_m1(psi) + rate(psi) (p - psi) that agrees with this law in
        value and rate at ``psi`` (rad): on a segment of the linear law, the law itself."""
        e, s = float(self(psi)), float(self.rate(psi))
        return base_settings.replace(blank_offset=e - s * float(psi), blank_offset_poly=(s,), blank_offset_table=())

    @property
    def moments(self):
        """Second derivatives of the spline at the nodes, mm/rad^2 (spline only, else None)."""
        if self.kind != "spline":
            return None
        from scipy.interpolate import CubicSpline

        return CubicSpline(self.nodes, self.increments, bc_type="natural")(self.nodes, 2)

    def _eval(self, psi):
        psi = np.asarray(psi, float)
        if self.kind != "polynomial":
            return table_offset(psi, self.nodes, self.increments, self.moments)[:2]
        P = np.polynomial.polynomial
        c = self.coefficients
        return P.polyval(psi, c), P.polyval(psi, P.polyder(c))

    def settings(self, base_settings):
        """``base_settings`` (MachineSettings) with this law as its blank offset (replacing the old constant)."""
        if self.kind != "polynomial":
            table = (tuple(self.nodes), tuple(self.increments))
            if self.kind == "spline":
                table += (tuple(self.moments),)
            return base_settings.replace(blank_offset=self.base, blank_offset_poly=(), blank_offset_table=table)
        c = self.coefficients
        return base_settings.replace(blank_offset=self.base + float(c[0]), blank_offset_poly=tuple(c[1:]),
                                     blank_offset_table=())
