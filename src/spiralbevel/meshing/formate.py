"""Formate (non-generated) flanks: the flank is the cutter surface placed on the universal generator with the cradle
locked (docs/theory/universal.md#formate-non-generated-members), and its basic settings from the blank.

:class:`FormateFlank` offers what local synthesis and the reports read from a generated ``ToothFlank`` (``member``,
``side``, ``hand``, ``outline``, ``mean_point``, ``evaluate``, ``locate``, ``grid``, ``meshing_residual``; parameters
(u, theta): blade parameter mm, cutter angle rad; ``locate_params`` gives the parameters of one point).
:func:`solve_formate_settings` solves the blade angle and the machine spiral angle so that the mean point has the
design spiral and pressure angles. TCA reads the flank through ``meshing.formate_surface.FormateSurface``; the pair
developed against a Formate gear: docs/theory/hypoid.md#formate-gear.
"""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member, Side
from ..design.hypoid_member import member_blank
from ..errors import ConvergenceError, DesignError, GeometryError
from ..generation.flank import _hand
from ..generation.locate import BlankOutline
from ..generation.results import FlankPoints, MeanPoint
from ..machine.basic_settings import basic_settings
from ..machine.cutter import HeadCutter
from ..machine.default_cutter import default_cutter, design_pressure_angle
from ..machine.universal import UniversalGenerator, UniversalSettings

__all__ = ["FormateFlank", "solve_formate_settings"]

_ANGLE_TOL = 1e-9      # rad, on the design angles
_MAX_ITER = 20


class FormateFlank:
    """One Formate flank of a member: the cutter surface at the cradle angle 0, clipped to the blank.

    Parameters
    ----------
    cutter : HeadCutter
    settings : UniversalSettings
        With ``generated=False``.
    blank : BevelBlank
        The member's view of the blank (``member_blank``) for a hypoid.
    member : Member
    side : Side
    """

    def __init__(self, cutter, settings: UniversalSettings, blank, member, side):
        self.member, self.side = Member(member), Side(side)
        if cutter.side is not self.side:
            raise DesignError.single("cutter.blade", cutter.blade.value, f"the blade for the {self.side.value} side",
                                     "-")
        if settings.generated:
            raise DesignError.single("settings.generated", True, "false for a Formate flank", "-")
        self.cutter, self.settings = cutter, settings
        self.hand = _hand(getattr(blank, f"hand{self.member.index}"))
        self.outline = BlankOutline.from_blank(blank, self.member)
        self.generator = UniversalGenerator(cutter, settings, self.hand)
        self._mean: dict = {}

    def evaluate(self, u, theta):
        """``UniversalPoints`` at blade parameter ``u`` (mm) and cutter angle ``theta`` (rad)."""
        return self.generator.formate(u, theta)

    def start(self):
        """(u, theta) near the mean point: mid-blade, toward the root line far from the machine centre."""
        from .._core.universal_generator import reference_theta

        th = float(reference_theta(0.0, self.generator.up, self.cutter.nominal_radius))
        return np.array([self.outline.hfm / math.cos(self.cutter.blade_angle), th])

    def locate(self, axial, radius, curvature: bool = True):
        """Flank points (``FlankPoints``) on the circles of given axial positions and radii (mm, broadcast), as
        ``ToothFlank.locate``: each by :meth:`locate_params`, from the previous point (the first from the mean
        point); ``psi_c`` = 0; NaN curvatures without ``curvature``."""
        ax, rad = np.broadcast_arrays(np.asarray(axial, float), np.asarray(radius, float))
        q = np.empty(ax.shape + (2,))
        x = None
        for idx in np.ndindex(ax.shape):
            x = q[idx] = self.locate_params(float(ax[idx]), float(rad[idx]), x0=x)
        fp = self.evaluate(q[..., 0], q[..., 1])
        if curvature:
            k1, k2, e1, e2 = self._curvatures(q[..., 0], q[..., 1], fp.normals)
        else:
            k1 = k2 = np.full(ax.shape, np.nan)
            e1 = e2 = np.full(ax.shape + (3,), np.nan)
        return FlankPoints(points=fp.points, normals=fp.normals, k1=k1, k2=k2, e1=e1, e2=e2, u=q[..., 0],
                           theta=q[..., 1], psi_c=np.zeros(ax.shape), fillet=q[..., 0] < self.cutter.fillet_range[1])

    def locate_params(self, axial: float, radius: float, x0=None) -> np.ndarray:
        """(u mm, theta rad) of the flank point at ``axial`` (mm, along the member axis) and ``radius`` (mm), by Newton
        with a finite-difference Jacobian."""
        x = self.start() if x0 is None else np.asarray(x0, float)
        goal = np.array([axial, radius])

        def f(x):
            p = self.evaluate(x[0], x[1]).points
            return np.array([p[2], math.hypot(p[0], p[1])]) - goal

        r = f(x)
        for _ in range(30):
            if np.max(np.abs(r)) < 1e-11:
                return x
            J = np.empty((2, 2))
            for k, h in enumerate((1e-6, 1e-8)):
                e = np.zeros(2)
                e[k] = h
                J[:, k] = (f(x + e) - f(x - e)) / (2 * h)
            x = x - np.linalg.solve(J, r)
            r = f(x)
        if np.max(np.abs(r)) < 1e-9:
            return x
        raise GeometryError.single("settings", "-", "a Formate cutter that reaches the point", "-",
                                   f"no flank point at axial {axial:.4f} mm, radius {radius:.4f} mm")

    def meshing_residual(self, u, theta, psi_c=0.0):
        """Zeros of the shape of ``u``: a Formate flank is the cutter surface itself, no equation of meshing of
        generation applies (the report's ``meshing_residual`` of a generated flank)."""
        return np.zeros(np.broadcast(np.asarray(u, float), np.asarray(theta, float)).shape)

    def _theta_at(self, R, u, th0):
        """Cutter angle (rad) at which the blade line of parameter ``u`` (mm) reaches the distance ``R`` (mm) along
        the pitch generatrix, by Newton from ``th0`` (central-difference derivative)."""
        ol = self.outline

        def f(th):
            p = self.evaluate(u, th).points
            return ol.Rh(p[2], math.hypot(p[0], p[1]))[0] - R

        th = float(th0)
        for _ in range(40):
            r = f(th)
            if abs(r) < 1e-11:
                return th
            th -= r / ((f(th + 1e-7) - f(th - 1e-7)) / 2e-7)
        raise GeometryError.single("settings", "-", "a Formate cutter that reaches the point", "-",
                                   f"the blade at u = {u:.4f} mm does not reach R = {R:.4f} mm")

    def root_deviation(self) -> tuple:
        """Height (mm) of the cut root above the blank's root cone at toe, mean cone distance and heel, as
        ``generation.basic_settings_solve.root_deviation`` for a generated flank: the cutter's edge radius sampled
        0.02 rad of arc from its tip (2e-4 of the edge radius above the tip plane)."""
        ol = self.outline
        u = self.cutter.fillet_range[0] + 0.02 * self.cutter.edge_radius
        out: list = []
        th = self.mean_point().theta
        for R in (ol.Ri, ol.Rm, ol.Re):
            try:
                th = self._theta_at(R, u, th)
            except GeometryError:
                out.append(None)
                continue
            p = self.evaluate(u, th).points
            Rx, h = ol.Rh(p[2], math.hypot(p[0], p[1]))
            out.append(float(h - ol.h_root(Rx)))
        return tuple(out)

    def grid(self, n_face: int = 31, n_profile: int = 15, n_fillet: int = 0, curvature: bool = True):
        """Flank grid clipped to the blank, shape (n_face, n_fillet + n_profile), as ``ToothFlank.grid``: axis 0 from
        toe (R_i) to heel (R_e), axis 1 from root to top (``n_fillet`` rows on the cutter's edge radius from its tip
        to the junction with the blade, then ``n_profile`` rows evenly in height from the junction to the face cone).

        Returns
        -------
        FlankPoints
            With ``psi_c`` = 0 and, with ``curvature``, the cutter's principal curvatures (k1 along the blade
            meridian, 0 on a straight blade; e1 root -> top, e1 x e2 = outward normal); NaN without.
        """
        for name, n, lo in (("n_face", n_face, 2), ("n_profile", n_profile, 2)):
            if not (isinstance(n, (int, np.integer)) and n >= lo):
                raise DesignError.single(name, n, f"integer >= {lo}", "-")
        if not (isinstance(n_fillet, (int, np.integer)) and (n_fillet == 0 or n_fillet >= 2)):
            raise DesignError.single("n_fillet", n_fillet, "0 or an integer >= 2", "-")
        ol = self.outline
        u_min, u_j = self.cutter.fillet_range
        mp = self.mean_point()
        R = np.linspace(ol.Ri, ol.Re, n_face)
        U = np.empty((n_face, n_fillet + n_profile))
        TH = np.empty_like(U)
        th = mp.theta
        for i, Ri in enumerate(R):
            th = self._theta_at(Ri, u_j, th)
            p = self.evaluate(u_j, th).points
            hj = ol.Rh(p[2], math.hypot(p[0], p[1]))[1]
            if n_fillet:
                U[i, :n_fillet] = np.linspace(u_min, u_j, n_fillet)
                TH[i, :n_fillet] = th          # the edge radius at the junction's cutter angle
            x = np.array([u_j, th])
            for k, h in enumerate(np.linspace(hj, float(ol.h_face(Ri)), n_profile)):
                ax, rad = ol.axial_radius(Ri, h)
                x = self.locate_params(ax, rad, x0=x)
                U[i, n_fillet + k], TH[i, n_fillet + k] = x
        fp = self.evaluate(U, TH)
        fillet = U < u_j - 1e-12
        if curvature:
            k1, k2, e1, e2 = self._curvatures(U, TH, fp.normals)
        else:
            k1 = k2 = np.full(U.shape, np.nan)
            e1 = e2 = np.full(U.shape + (3,), np.nan)
        return FlankPoints(points=fp.points, normals=fp.normals, k1=k1, k2=k2, e1=e1, e2=e2, u=U, theta=TH,
                           psi_c=np.zeros(U.shape), fillet=fillet)

    def _curvatures(self, u, theta, normals):
        """Principal curvatures (convex = positive) and directions of the cutter surface in the member frame."""
        k_mer, k_circ, e_mer, _ = self.cutter.principal_curvatures(u, theta)
        M = _chain0(self.generator)
        mirror = np.array([1.0, -1.0, 1.0]) if self.generator.hand.sign > 0 else np.ones(3)
        e1 = mirror * (np.asarray(e_mer, float) @ M.T)
        p = self.evaluate(u, theta).points
        rho = np.stack([p[..., 0], p[..., 1], np.zeros(p.shape[:-1])], -1)
        rho /= np.linalg.norm(rho, axis=-1, keepdims=True)
        d = self.outline.delta
        N = math.cos(d) * rho - math.sin(d) * np.array([0.0, 0.0, 1.0])
        e1 = np.where((np.einsum("...i,...i->...", e1, N) < 0)[..., None], -e1, e1)   # root -> top
        return np.asarray(k_mer, float), np.asarray(k_circ, float), e1, np.cross(normals, e1)

    def mean_point(self, depth: float = 0.0) -> MeanPoint:
        """Mean point (as ``ToothFlank.mean_point``): spiral and pressure angles on the pitch cone through it, and
        the principal curvatures of the cutter surface (convex = positive, k1 along the blade meridian, e1 root ->
        top, e1 x e2 = outward normal)."""
        key = float(depth)
        if key not in self._mean:
            self._mean[key] = self._mean_point(key)
        return self._mean[key]

    def _mean_point(self, depth):
        ol = self.outline
        ax, rad = ol.axial_radius(ol.Rm, -depth)
        u, th = self.locate_params(ax, rad)
        fp = self.evaluate(u, th)
        p, n = fp.points, fp.normals
        rho_hat = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
        z = np.array([0.0, 0.0, 1.0])

        def cone(a):
            return math.sin(a) * rho_hat + math.cos(a) * z, math.cos(a) * rho_hat - math.sin(a) * z

        g, N = cone(ol.delta)
        trace = np.cross(N, n)
        trace /= np.linalg.norm(trace)
        if trace @ g < 0:
            trace = -trace
        hand_sign = int(np.sign(np.cross(p, trace)[2]))
        _, Nr = cone(ol.delta_f)
        k_mer, k_circ, e_mer, e_circ = self.cutter.principal_curvatures(u, th)
        M = _chain0(self.generator)
        mirror = np.array([1.0, -1.0, 1.0]) if self.generator.hand.sign > 0 else np.ones(3)
        e1 = mirror * (M @ np.asarray(e_mer, float))
        if e1 @ N < 0:                                     # root -> top: away from the pitch cone's inside
            e1 = -e1
        e2 = np.cross(n, e1)
        return MeanPoint(point=p, normal=n, spiral_angle=float(math.acos(min(1.0, trace @ g))),
                         pressure_angle=float(math.asin(min(1.0, abs(n @ N)))),
                         pressure_angle_root=float(math.asin(min(1.0, abs(n @ Nr)))), hand_sign=hand_sign,
                         k1=float(k_mer), k2=float(k_circ), e1=e1, e2=e2, u=float(u), theta=float(th), psi_c=0.0,
                         depth=float(depth))

    def __repr__(self) -> str:
        return f"FormateFlank({self.member.value} {self.side.value}, {self.hand.value})"


def _chain0(gen):
    """Rotation cutter frame -> member frame at psi_c = 0 (canonical machine)."""
    from .._core.universal_generator import chain

    return chain(np.zeros(()), gen.up).real[:3, :3]


def solve_formate_settings(blank, member, side, cutter: HeadCutter | None = None):
    """Cutter and settings of a Formate flank with the design spiral and pressure angles at the mean point.

    The settings are the basic-settings family of ``spiralbevel.machine.basic_settings`` (root cone on the cradle
    plane, apex at the machine centre) with the cradle locked; Newton (finite-difference Jacobian) solves the blade
    angle and the machine spiral angle beta' for the design beta_m and alpha_n (as ``solve_basic_settings`` does
    for a generated flank).

    Parameters
    ----------
    blank : BevelBlank
    member : Member
    side : Side
    cutter : HeadCutter, optional
        Start cutter; default ``default_cutter``.

    Returns
    -------
    cutter : HeadCutter; settings : UniversalSettings; flank : FormateFlank
    """
    member, side = Member(member), Side(side)
    view = member_blank(blank, member)
    i = member.index
    start = cutter or default_cutter(view, member, side)
    alpha_d = design_pressure_angle(blank, member, side)
    beta_d = abs(float(getattr(blank, f"beta_m{i}")))

    def build(x):
        c = HeadCutter(point_radius=start.point_radius, blade_angle=float(x[0]), point_width=start.point_width,
                       edge_radius=start.edge_radius, blade=start.blade)
        s = UniversalSettings.from_machine_settings(basic_settings(view, member, c, float(x[1]))).replace(
            generated=False)
        return c, s, FormateFlank(c, s, view, member, side)

    def residual(x):
        mp = build(x)[2].mean_point()
        return np.array([mp.pressure_angle - alpha_d, mp.spiral_angle - beta_d])

    x = np.array([start.blade_angle, beta_d])
    r = residual(x)
    for _ in range(_MAX_ITER):
        if np.max(np.abs(r)) < _ANGLE_TOL:
            return build(x)
        J = np.empty((2, 2))
        for k in range(2):
            e = np.zeros(2)
            e[k] = 1e-6
            J[:, k] = (residual(x + e) - residual(x - e)) / 2e-6
        x = x - np.linalg.solve(J, r)
        r = residual(x)
    raise ConvergenceError(f"{member.value} {side.value}: Formate settings did not reach the design angles",
                           _MAX_ITER, float(np.max(np.abs(r))), x)
