"""Log-spiral flanks as :class:`~spiralbevel.meshing.contact_surface.ContactSurface`, and an exactly conjugate
log-spiral pair (seed 000 Eq. (16); seed 002 conjugacy theorem, docs/theory/gearing.md, Eq. (M8) (#conjugacy)).

These are the reference surfaces of the TCA tests and benchmark: a consistent pair (sin d1 : sin d2 = z1 : z2, gear
spiral parameter -beta) is in line contact with zero transmission error; a crowned pinion
(:class:`~spiralbevel.meshing.contact_surface.NormalDeviation`) gives point contact and a parabolic TE.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._core import jets as _jets
from .._core import logspiral as _ls
from .._core import logspiral_jet as _lsj
from .._core.rotations import rot_z, rot_y
from ..design.logspiral_pair import pair_recipe
from ..errors import DesignError, GeometryError
from ..geometry.curves import psi_of_cone_angle

__all__ = ["LogSpiralSurface", "LogSpiralPair", "conjugate_logspiral_pair"]


@dataclass(frozen=True)
class LogSpiralSurface:
    """Seed-000 log-spiral flank with parameters (varphi, phi), turned by ``azimuth`` about the member axis.

    Parameters
    ----------
    rho0 : float, mm
    delta : float, rad
        Base-cone half-angle.
    beta : float, rad
        Spiral parameter in the base-cone tangent plane (> 0 right hand).
    azimuth : float, rad
        Rotation of the flank about +z (phasing).
    psi_range, phi_range : (2,) float, rad, optional
        Flank domain: signed psi = (varphi - phi) sin(delta) between root and face cones, phi between toe and heel
        spheres (docs/theory/logspiral.md, Eq. (S10)). ``contains`` is all True when omitted.
    reference_params : (2,) float, optional
        (varphi, phi) near the mean contact point.

    Notes
    -----
    Outward normal n_out = sign(psi) n with n of docs/theory/logspiral.md, Eq. (S4); derivatives analytic (Eqs.
    (S3)-(S8)):
    n_varphi = cos(delta) cos(psi - beta) m, n_phi = sin(delta) [cos(psi - beta) t + sin(psi - beta) w].
    """

    rho0: float
    delta: float
    beta: float
    azimuth: float = 0.0
    psi_range: tuple | None = None
    phi_range: tuple | None = None
    reference_params: tuple | None = None
    _prm: np.ndarray = field(init=False, repr=False, compare=False)
    _bprm: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not (self.rho0 > 0 and 0 < self.delta < np.pi / 2 and 0 < abs(self.beta) < np.pi / 2):
            raise DesignError.single("log-spiral flank", (self.rho0, self.delta, self.beta),
                                     "rho0 > 0, 0 < delta < pi/2, 0 < |beta| < pi/2", "mm, rad, rad")
        if self.psi_range is not None and self.psi_range[0] * self.psi_range[1] <= 0:
            raise GeometryError.single("psi_range", self.psi_range, "an interval not containing 0", "rad",
                                       "psi = 0 is the singular (cuspidal) edge, "
                                       "docs/theory/logspiral.md#singular-edge")
        object.__setattr__(self, "_prm", _lsj.parameters(self.rho0, self.delta, self.beta, self.azimuth))
        psi_lo, psi_hi = sorted(self.psi_range) if self.psi_range is not None else (0.0, 0.0)
        phi_lo, phi_hi = sorted(self.phi_range) if self.phi_range is not None else (0.0, 0.0)
        b = [np.sin(self.delta), psi_lo, psi_hi, float(psi_lo > 0), phi_lo, phi_hi,
             float(np.sin(self.delta) / np.tan(self.beta) > 0), float(self.psi_range is not None),
             float(self.phi_range is not None)]
        object.__setattr__(self, "_bprm", np.array(b, float))

    def _kernel(self, params, deriv):
        """Compiled jet (:mod:`spiralbevel._core.logspiral_jet`) at ``params (..., 2)``: r, n_out and optionally
        dr, dn (..., 3, 2). Wild solver iterates give inf/NaN, never warnings."""
        p = np.asarray(params, float)
        q = np.ascontiguousarray(p.reshape(-1, 2))
        out = np.empty((q.shape[0], 3, 6))
        _lsj.jet_batch(self._prm, q, out)
        out = out.reshape(p.shape[:-1] + (3, 6))
        if deriv:
            return out[..., 0], out[..., 1], out[..., 2:4], out[..., 4:6]
        return out[..., 0], out[..., 1]

    @property
    def jet(self):
        """``(kind, prm)`` of the compiled jet (:mod:`spiralbevel._core.jets`) that compiled TCA evaluates."""
        return _jets.LOGSPIRAL, self._prm

    @property
    def boundary_jet(self):
        """``(kind, prm)`` of the compiled boundary margins with their gradients
        (:func:`spiralbevel._core.tca_edge.margins`, kind ``MARGIN_LOGSPIRAL``; the margins of
        :meth:`boundary_margins`)."""
        return 0, self._bprm

    def evaluate(self, params):
        """Points (..., 3) mm and outward normals (..., 3) at ``params = (varphi, phi)``."""
        return self._kernel(params, False)

    def derivatives(self, params):
        """(r, n, dr, dn) with dr, dn (..., 3, 2) w.r.t. (varphi, phi), analytic."""
        return self._kernel(params, True)

    def contains(self, params, tol=1e-12):
        """True where (varphi, phi) lies on the flank domain (closed, with a tolerance ``tol`` rad)."""
        p = np.asarray(params, float)
        ok = np.ones(p.shape[:-1], bool)
        if self.psi_range is not None:
            psi = (p[..., 0] - p[..., 1]) * np.sin(self.delta)
            lo, hi = sorted(self.psi_range)
            ok &= (psi >= lo - tol) & (psi <= hi + tol)
        if self.phi_range is not None:
            lo, hi = sorted(self.phi_range)
            ok &= (p[..., 1] >= lo - tol) & (p[..., 1] <= hi + tol)
        return ok

    def boundary_margins(self, params):
        """Signed margins (..., 4) rad of ``params`` to the domain boundaries ``boundary_names`` (>= 0 inside; a
        missing range gives +inf): the psi bounds are the root and face cones, the phi bounds the toe and heel."""
        p = np.asarray(params, float)
        inf = np.full(p.shape[:-1], np.inf)
        out = [inf, inf, inf, inf]
        if self.psi_range is not None:
            psi = (p[..., 0] - p[..., 1]) * np.sin(self.delta)
            lo, hi = sorted(self.psi_range)
            # |psi| grows from the root cone to the face cone (psi = 0 is the base-cone edge)
            m_lo, m_hi = psi - lo, hi - psi
            out[0], out[1] = (m_lo, m_hi) if lo > 0 else (m_hi, m_lo)
        if self.phi_range is not None:
            lo, hi = sorted(self.phi_range)
            a, b = p[..., 1] - lo, hi - p[..., 1]
            # phi grows toward the heel when the spiral radius rho0 exp(phi sin(delta)/tan(beta)) grows
            out[2], out[3] = (a, b) if np.sin(self.delta) / np.tan(self.beta) > 0 else (b, a)
        return np.stack(out, -1)

    boundary_names = ("root", "top", "toe", "heel")

    def params_of(self, psi, phi):
        """(varphi, phi) stacked (..., 2) from psi and phi (rad)."""
        psi, phi = np.broadcast_arrays(np.asarray(psi, float), np.asarray(phi, float))
        return np.stack([phi + psi / np.sin(self.delta), phi], -1)

    def grid(self, n_phi=21, n_psi=11):
        """Points (n_phi, n_psi, 3) mm of the flank domain: rows toe -> heel, columns psi_range[0] -> [1]."""
        if self.psi_range is None or self.phi_range is None:
            raise DesignError.single("domain", None, "psi_range and phi_range set", "rad")
        phi = np.linspace(*self.phi_range, n_phi)[:, None]
        psi = np.linspace(*self.psi_range, n_psi)[None, :]
        return self.evaluate(self.params_of(psi, phi))[0]

    def with_changes(self, **kw) -> "LogSpiralSurface":
        d: dict[str, Any] = dict(rho0=self.rho0, delta=self.delta, beta=self.beta, azimuth=self.azimuth,
                                 psi_range=self.psi_range, phi_range=self.phi_range,
                                 reference_params=self.reference_params)
        d.update(kw)
        return LogSpiralSurface(**d)


@dataclass(frozen=True)
class LogSpiralPair:
    """A conjugate log-spiral pair in the assembly of docs/conventions.md, touching at the mean point at phi = 0.

    Attributes
    ----------
    pinion, gear : LogSpiralSurface
    z1, z2 : int
    shaft_angle : float, rad
    mean_point : (3,) float, mm
        Contact point at phi1 = phi2 = 0 (fixed frame = pinion frame at phi1 = 0), on the pitch line.
    pitch_angles : (2,) float, rad
    base_cone_angles : (2,) float, rad
    spiral_parameter : float, rad
        beta of the pinion; the gear has -beta.
    """

    pinion: LogSpiralSurface
    gear: LogSpiralSurface
    z1: int
    z2: int
    shaft_angle: float
    mean_point: np.ndarray
    pitch_angles: tuple
    base_cone_angles: tuple
    spiral_parameter: float


def conjugate_logspiral_pair(z1=23, z2=65, shaft_angle=np.pi / 2, normal_pressure_angle=np.radians(20.0),
                             spiral_angle=np.radians(35.0), mean_cone_distance=115.9511, face_width=37.0,
                             addendum=(5.10, 1.54), dedendum=(2.24, 5.80)) -> LogSpiralPair:
    """Exactly conjugate log-spiral pair: pinion convex (right hand, psi > 0), gear concave (left hand).

    Parameters
    ----------
    z1, z2 : int
    shaft_angle, normal_pressure_angle, spiral_angle : float, rad
        Sigma, alpha_n and the mean spiral angle on the pitch cone (docs/theory/logspiral.md, Eq. (S12)).
    mean_cone_distance, face_width : float, mm
    addendum, dedendum : (2,) float, mm
        Pinion and gear; they set the root and face cones of the flank domains (angles atan(h / A_m)).

    Notes
    -----
    Recipe (docs/theory/logspiral.md, Eq. (S12)): tan g1 = sin S / (z2/z1 + cos S), tan a_t = tan a_n / cos b_m, sin d_i
    = sin g_i cos a_t,
    sin beta = cos a_n sin b_m. The gear flank has base cone d2, spiral parameter -beta and is phased (azimuth) so
    that both flanks pass through the pitch point A_m p with opposite outward normals (docs/theory/gearing.md, Eq. (M8),
    #conjugacy).
    """
    S = float(shaft_angle)
    g1, g2, _, d1, d2, beta = pair_recipe(z1, z2, S, normal_pressure_angle, spiral_angle)
    Am, b = float(mean_cone_distance), float(face_width)
    p = np.array([np.sin(g1), 0.0, np.cos(g1)])
    target = Am * p
    # pinion: contact plane varphi* = +-acos(tan d1 / tan g1) at phi1 = 0; psi = +psi_pitch (convex branch)
    psi1 = psi_of_cone_angle(g1, d1)
    best = None
    for sgn in (1.0, -1.0):
        vphi = sgn * np.arccos(np.tan(d1) / np.tan(g1))
        phi = vphi - psi1 / np.sin(d1)
        rho0 = Am * np.exp(-phi * np.sin(d1) / np.tan(beta))
        r = _ls.point(vphi, phi, rho0, d1, beta)
        err = np.linalg.norm(r - target)
        if best is None or err < best[0]:
            best = (err, vphi, phi, rho0)
    assert best is not None  # the scan above evaluates at least one candidate
    err, vphi1, phi1m, rho01 = best
    if err > 1e-9 * Am:
        raise GeometryError.single("pitch point", err, "< 1e-9 A_m", "mm", "pinion flank misses the pitch point")

    def ranges(rho0, delta, bt, gamma, ha, hf, sign):
        phis = [np.log(R / rho0) / (np.sin(delta) / np.tan(bt)) for R in (Am - b / 2, Am + b / 2)]
        root = gamma - np.arctan(hf / Am)
        face = gamma + np.arctan(ha / Am)
        if root <= delta:
            raise GeometryError.single("root cone", np.degrees(root), f"> base cone {np.degrees(delta):.4f}", "deg",
                                       "the flank would cross the singular edge psi = 0")
        psis = sorted(sign * psi_of_cone_angle(c, delta) for c in (root, face))
        return tuple(psis), tuple(sorted(phis))

    psr1, phr1 = ranges(rho01, d1, beta, g1, addendum[0], dedendum[0], 1.0)
    pinion = LogSpiralSurface(rho01, d1, beta, 0.0, psr1, phr1, (float(vphi1), float(phi1m)))
    # gear: the pitch point in the gear member frame at phi2 = 0, and the pinion's outward normal there
    _, n1 = pinion.evaluate(np.array([vphi1, phi1m]))
    B2 = rot_y(S)
    r2 = B2.T @ target
    n2_target = -(B2.T @ n1)
    psi2m = psi_of_cone_angle(g2, d2)
    best = None
    for sgn in (1.0, -1.0):
        psi2 = sgn * psi2m
        q = np.array([psi2 / np.sin(d2), 0.0])  # rho0 = A_m -> phi = 0 at the pitch point
        g0 = LogSpiralSurface(Am, d2, -beta)
        r0, n0 = g0.evaluate(q)
        tau = np.arctan2(r2[1], r2[0]) - np.arctan2(r0[1], r0[0])
        Rz = rot_z(tau)
        miss = np.linalg.norm(Rz @ r0 - r2) + np.linalg.norm(Rz @ n0 - n2_target)
        if best is None or miss < best[0]:
            best = (miss, psi2, q, tau)
    assert best is not None  # the scan above evaluates at least one candidate
    miss, psi2, q2, tau = best
    if miss > 1e-9:
        raise GeometryError.single("gear phasing", miss, "< 1e-9", "mm", "no conjugate gear flank through the "
                                   "pitch point: base cones inconsistent")
    psr2, phr2 = ranges(Am, d2, -beta, g2, addendum[1], dedendum[1], np.sign(psi2))
    gear = LogSpiralSurface(Am, d2, -beta, float(tau), psr2, phr2, (float(q2[0]), float(q2[1])))
    return LogSpiralPair(pinion, gear, int(z1), int(z2), S, target, (float(g1), float(g2)), (float(d1), float(d2)),
                         float(beta))
