"""Formate (non-generated) flanks: the flank is the cutter surface placed on the universal generator with the cradle
locked (docs/theory/universal.md#formate-non-generated-members), and its basic settings from the blank.

:class:`FormateFlank` offers what local synthesis and the reports read from a generated ``ToothFlank`` (``member``,
``side``, ``hand``, ``outline``, ``mean_point``, ``evaluate``, ``locate``; parameters (u, theta): blade parameter mm,
cutter angle rad). :func:`solve_formate_settings` solves the blade angle and the machine spiral angle so that the mean
point has the design spiral and pressure angles. (The TCA of a Formate wheel is not offered yet: a Formate wheel
needs a pinion generated with tilt or helical motion to match it beyond the mean point, which the local synthesis
here does not solve for.)
"""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member, Side
from ..design.hypoid_member import member_blank
from ..errors import ConvergenceError, DesignError, GeometryError
from ..generation.flank import _hand
from ..generation.locate import BlankOutline
from ..generation.results import MeanPoint
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

    def locate(self, axial: float, radius: float, x0=None) -> np.ndarray:
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
        u, th = self.locate(ax, rad)
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
