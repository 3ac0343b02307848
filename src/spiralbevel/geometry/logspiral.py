"""The logarithmic-spiral bevel tooth flank of seed 000 as a user-facing object.

The surface is seed 000 Eq. (16) as corrected in docs/theory/logspiral.md, Eq. (S2): a planar log spiral (pole at the
apex O, angle
``spiral_angle`` between tangent and radius) lying in a plane that rolls on the base cone of half-angle
``base_cone_angle``. Frame: member frame of docs/conventions.md (axis +z, apex at the origin, body toward +z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spiralbevel._core import logspiral_flank as _kernel
from spiralbevel._core.rotations import rot_z
from spiralbevel.conventions import Hand, Side
from spiralbevel.errors import DesignError, GeometryError

__all__ = ["LogSpiralFlank", "FlankGeometry"]


@dataclass(frozen=True, eq=False)
class FlankGeometry:
    """Points, outward normals, fundamental forms and principal curvatures of a flank (read-only arrays).

    Attributes
    ----------
    point : (..., 3) float, mm
        Surface points.
    normal : (..., 3) float
        Outward unit normals (out of the tooth material into the tooth space), n_out = sign(psi) n with n the
        corrected seed 000 Eq. (21) (docs/theory/logspiral.md, Eq. (S4)). n_out . r/|r| = sign(psi) sin(beta), i.e.
        +sin|beta| on the
        convex flank and -sin|beta| on the concave flank.
    E, F, G : (...) float, mm^2
        First fundamental form in (varphi, phi): E = |r_varphi|^2, F = r_varphi . r_phi (= 0), G = |r_phi|^2.
    L, M, N : (...) float, mm
        Second fundamental form **w.r.t. the outward normal with the convex-positive sign**:
        L = -r_varphivarphi . n_out = r_varphi . d(n_out)/dvarphi, etc. Hence L = -sign(psi) L_L of
        docs/theory/logspiral.md Eq. (S7) (the papers'
        L = r_uu . n) and the eigenvalues of I^-1 II are ``k1, k2``. M = 0.
    k1, k2 : (...) float, 1/mm
        Principal curvatures, convex = positive (docs/conventions.md): ``k1`` along the spherical involute (the
        varphi-curve, profile), ``k2`` along the planar log spiral (the phi-curve, lengthwise).
        k1 = cos(psi - beta)/(rho |sin psi|), k2 = sign(psi) sin(beta)/rho.
    e1, e2 : (..., 3) float
        Unit principal directions: e1 = r_varphi/|r_varphi| (profile), e2 along the lengthwise spiral pointing from
        toe to heel (e2 . r > 0); e1 x e2 = normal.
    psi : (...) float, rad
        psi = (varphi - phi) sin(delta); its sign selects the branch (sign(psi) = sign(beta): convex).
    rho : (...) float, mm
        Distance from the apex, rho = rho0 exp(phi sin(delta) cot(beta)).
    """

    point: np.ndarray
    normal: np.ndarray
    E: np.ndarray
    F: np.ndarray
    G: np.ndarray
    L: np.ndarray
    M: np.ndarray
    N: np.ndarray
    k1: np.ndarray
    k2: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    psi: np.ndarray
    rho: np.ndarray

    def __post_init__(self):
        for value in self.__dict__.values():
            if isinstance(value, np.ndarray):
                value.flags.writeable = False

    @property
    def gaussian_curvature(self):
        """K = k1 k2, 1/mm^2 (> 0 on the convex flank, < 0 on the concave flank)."""
        return self.k1 * self.k2

    @property
    def mean_curvature(self):
        """H = (k1 + k2)/2, 1/mm, convex = positive."""
        return 0.5 * (self.k1 + self.k2)

    def rotated(self, angle: float) -> "FlankGeometry":
        """The same geometry turned by ``angle`` (rad) about +z (vectors rotated, scalars unchanged)."""
        R = rot_z(float(angle))
        vec = {k: getattr(self, k) @ R.T for k in _kernel.FIELDS_VEC}
        sca = {k: getattr(self, k).copy() for k in _kernel.FIELDS_SCALAR}
        return FlankGeometry(**vec, **sca)


def _check_float(field, value, lo, hi, unit, allowed):
    try:
        x = float(value)
    except (TypeError, ValueError) as err:
        raise DesignError.single(field, value, allowed, unit, "not a number") from err
    if not np.isfinite(x) or not (lo < x < hi):
        raise DesignError.single(field, value, allowed, unit)
    return x


@dataclass(frozen=True)
class LogSpiralFlank:
    """Logarithmic-spiral bevel tooth surface, seed 000 Eq. (16) corrected in docs/theory/logspiral.md, Eq. (S2)

    Parameters
    ----------
    rho0 : float, mm
        Apex distance of the point with phi = 0 (rho = rho0 exp(phi sin(delta) cot(beta))). Changing rho0 only turns
        the surface about +z.
    base_cone_angle : float, rad
        Base-cone half-angle delta, 0 < delta < pi/2.
    spiral_angle : float, rad
        Spiral parameter beta of the planar log spiral in the rolling plane, 0 < |beta| < pi/2. beta > 0 is a right-hand
        flank, beta < 0 the left-hand (mirror) flank. This is *not* the pitch-cone spiral angle
        (docs/theory/logspiral.md, Eq. (S12), "design
        recipe"): on a coaxial cone gamma the trace angle is tan(beta_gamma) = tan(beta) sin(gamma)/sin(delta).

    Notes
    -----
    r(varphi, phi) = rho (cos psi t(varphi) + sin psi w(varphi)), psi = (varphi - phi) sin(delta), with
    t = (sin d cos varphi, sin d sin varphi, cos d), w = (sin varphi, -cos varphi, 0). The branch sign(psi) = sign(beta)
    is the convex flank, the other one the concave flank (docs/theory/logspiral.md, Eq. (S9) (#flank-types)). psi = 0 is
    a cuspidal edge (the c-curve,
    seed 000 Eq. (17)) where the surface is singular; :meth:`evaluate` raises :class:`GeometryError` there.
    """

    rho0: float
    base_cone_angle: float
    spiral_angle: float

    def __post_init__(self):
        rho0 = _check_float("rho0", self.rho0, 0.0, np.inf, "mm", "0 < rho0 < inf")
        delta = _check_float("base_cone_angle", self.base_cone_angle, 0.0, np.pi / 2, "rad", "0 < value < pi/2")
        beta = _check_float("spiral_angle", self.spiral_angle, -np.pi / 2, np.pi / 2, "rad",
                            "0 < |value| < pi/2")
        if beta == 0.0:
            raise DesignError.single("spiral_angle", self.spiral_angle, "0 < |value| < pi/2", "rad",
                                     "a log spiral needs a nonzero spiral angle")
        object.__setattr__(self, "rho0", rho0)
        object.__setattr__(self, "base_cone_angle", delta)
        object.__setattr__(self, "spiral_angle", beta)

    # ---------------------------------------------------------------- parameters
    @property
    def hand(self) -> Hand:
        """Hand of spiral: right for beta > 0 (docs/conventions.md)."""
        return Hand.RIGHT if self.spiral_angle > 0 else Hand.LEFT

    def psi_sign(self, side: Side) -> int:
        """Sign of psi on ``side``: sign(beta) on the convex flank, -sign(beta) on the concave flank."""
        s = 1 if self.spiral_angle > 0 else -1
        return s if Side(side) is Side.CONVEX else -s

    def psi(self, varphi, phi):
        """psi = (varphi - phi) sin(delta), rad."""
        return (np.asarray(varphi, float) - np.asarray(phi, float)) * np.sin(self.base_cone_angle)

    def rho(self, phi):
        """rho = rho0 exp(phi sin(delta) cot(beta)), mm (seed 000 Eq. (9))."""
        d, b = self.base_cone_angle, self.spiral_angle
        return self.rho0 * np.exp(np.asarray(phi, float) * np.sin(d) / np.tan(b))

    def phi_of_rho(self, rho):
        """Inverse of :meth:`rho`: phi = ln(rho/rho0) / (sin(delta) cot(beta)), rad."""
        d, b = self.base_cone_angle, self.spiral_angle
        return np.log(np.asarray(rho, float) / self.rho0) * np.tan(b) / np.sin(d)

    def varphi_of(self, psi, phi):
        """varphi = phi + psi / sin(delta), rad."""
        return np.asarray(phi, float) + np.asarray(psi, float) / np.sin(self.base_cone_angle)

    def side_of(self, varphi, phi) -> Side:
        """Flank (convex/concave) of the parameter point(s); all points must lie on the same branch."""
        s = np.sign(self.psi(varphi, phi))
        if not np.all(np.abs(s) > 0):
            raise GeometryError(self._edge_message())
        if np.all(s == s.flat[0]):
            convex = s.flat[0] == (1 if self.spiral_angle > 0 else -1)
            return Side.CONVEX if convex else Side.CONCAVE
        raise GeometryError("side_of: the points lie on both branches (psi changes sign); evaluate each side apart")

    # ---------------------------------------------------------------- evaluation
    def point(self, varphi, phi):
        """Surface points r(varphi, phi), (..., 3) mm (defined on the singular edge too)."""
        varphi, phi = np.broadcast_arrays(np.asarray(varphi, float), np.asarray(phi, float))
        d = self.base_cone_angle
        psi = self.psi(varphi, phi)
        rho = self.rho(phi)
        cf, sf, cp, sp = np.cos(varphi), np.sin(varphi), np.cos(psi), np.sin(psi)
        return np.stack([rho * (cp * np.sin(d) * cf + sp * sf), rho * (cp * np.sin(d) * sf - sp * cf),
                         rho * cp * np.cos(d)], axis=-1)

    def evaluate(self, varphi, phi) -> FlankGeometry:
        """Closed-form geometry at broadcastable parameter arrays (rad).

        Parameters
        ----------
        varphi, phi : array_like float, rad
            Rolling angle and spiral parameter (seed 000 Eq. (16)); broadcast together to the result shape.

        Returns
        -------
        FlankGeometry
            See its attributes; vectors have xyz on the trailing axis.

        Raises
        ------
        GeometryError
            If a point lies on the singular edge psi = 0 (the c-curve, seed 000 Eq. (17)) or a parameter is not finite.
        """
        varphi, phi = np.broadcast_arrays(np.asarray(varphi, float), np.asarray(phi, float))
        shape = varphi.shape
        psi = self.psi(varphi, phi)
        ok = np.abs(psi) > 0.0
        if not ok.all():
            raise GeometryError(self._edge_message(psi, ok))
        res = _kernel.flank_flat(varphi, phi, self.rho0, self.base_cone_angle, self.spiral_angle)
        vec = {k: res[k].reshape(shape + (3,)) for k in _kernel.FIELDS_VEC}
        sca = {k: res[k].reshape(shape) for k in _kernel.FIELDS_SCALAR}
        if not np.isfinite(sca["rho"]).all():
            raise GeometryError("LogSpiralFlank.evaluate: phi too large, rho = rho0 exp(phi sin(delta) cot(beta)) "
                                "overflows")
        return FlankGeometry(**vec, **sca)

    def _edge_message(self, psi=None, ok=None):
        if psi is not None and not np.isfinite(psi[~ok]).all():
            return "LogSpiralFlank.evaluate: varphi and phi must be finite numbers (got NaN or inf)"
        return ("LogSpiralFlank.evaluate: psi = (varphi - phi) sin(delta) = 0 lies on the singular (cuspidal) edge of "
                "the log-spiral flank, the c-curve on the base cone "
                "(seed 000 Eq. (17), docs/theory/logspiral.md#singular-edge); "
                "a flank domain must keep psi != 0 (varphi != phi)")

    def c_curve(self, phi):
        """The cuspidal edge c(phi) = r(phi, phi) = rho(phi) t(phi) on the base cone, (..., 3) mm (seed 000 Eq.
        (17))."""
        return self.point(phi, phi)

    def mirrored(self) -> "LogSpiralFlank":
        """The mirror image in the xz-plane (y -> -y): the flank with spiral angle -beta.

        The point (varphi, phi) maps to (-varphi, -phi) of the mirrored flank; convex maps to convex.
        """
        return LogSpiralFlank(self.rho0, self.base_cone_angle, -self.spiral_angle)
