"""Generated tooth flank of a face-milled spiral bevel member (seed 001 §3, seed 003; docs/theory/generation.md, Eqs.
(G5)-(G8) (and (G13)-(G15) for curvatures)).

``generate_flank(cutter, settings, blank, member, side)`` returns a :class:`ToothFlank`: the envelope of the head
cutter (straight or arc blade plus edge radius) in the member frame, clipped to the blank.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.generation.locate import BlankOutline, Locator
from spiralbevel.generation.meshing import Generator
from spiralbevel.generation.results import FlankPoints, MeanPoint  # noqa: F401

__all__ = ["ToothFlank", "generate_flank"]


def _hand(value) -> Hand:
    if isinstance(value, Hand):
        return value
    text = str(value).strip().upper()
    if text in ("RH", "R", "RIGHT"):
        return Hand.RIGHT
    if text in ("LH", "L", "LEFT"):
        return Hand.LEFT
    raise DesignError.single("blank.hand", value, "RH or LH", "-")


class ToothFlank:
    """One generated flank (convex or concave side) of a pinion or gear, in its member frame.

    Parameters
    ----------
    cutter : HeadCutter
        Its blade must cut ``side`` (inner -> convex, outer -> concave).
    settings : MachineSettings
    blank : ISO 23509 blank (``delta1/2, delta_a1/2, delta_f1/2, Rm, Re2, Ri2, ham1/2, hfm1/2, hand1/2``).
    member : Member
    side : Side
    """

    def __init__(self, cutter, settings, blank, member, side):
        self.member, self.side = Member(member), Side(side)
        if cutter.side is not self.side:
            raise DesignError.single("cutter.blade", cutter.blade.value,
                                     f"{'inner' if self.side is Side.CONVEX else 'outer'} "
                                     f"for the {self.side.value} side",
                                     "-")
        self.cutter, self.settings = cutter, settings
        self.hand = _hand(getattr(blank, f"hand{self.member.index}"))
        self.outline = BlankOutline.from_blank(blank, self.member)
        self.generator = Generator(cutter, settings, self.hand)

    @cached_property
    def _locator(self) -> Locator:
        return Locator(self.generator, self.outline)

    # ------------------------------------------------------------------------------------------------------------
    def evaluate(self, u, psi_c, curvature: bool = True) -> FlankPoints:
        """Flank points at blade parameter ``u`` (mm) and cradle angle ``psi_c`` (rad), broadcast together."""
        return self.generator.evaluate(u, psi_c, curvature)

    def locate(self, axial, radius, curvature: bool = True) -> FlankPoints:
        """Flank point on the circle of given axial position and radius about the member axis (batched Newton).

        Parameters
        ----------
        axial : array_like, mm
            z of the point in the member frame.
        radius : array_like, mm
            Distance of the point from the member axis. Broadcast with ``axial``.

        Notes
        -----
        Solves F1 = |r x k| - R = 0, F2 = r.k - L = 0 (seed 003, corrected in docs/theory/generation.md, Eq. (G11))
        for (u, psi_c), with theta in closed form; raises ``GeometryError`` if a point is not on the flank.
        """
        x = self._locator.at_axial_radius(axial, radius)
        return self.generator.evaluate_at(x[..., 0], x[..., 1], x[..., 2], curvature)

    def grid(self, n_face: int = 31, n_profile: int = 15, n_fillet: int = 0, curvature: bool = True) -> FlankPoints:
        """Flank grid clipped to the blank, shape (n_face, n_fillet + n_profile).

        Axis 0 runs from toe (R = R_i) to heel (R = R_e), R being the distance along the pitch generatrix of the point's
        axial section (front and back cones perpendicular to the pitch cone). Axis 1 runs from root to top: first
        ``n_fillet`` rows on the edge-radius fillet, evenly in the blade parameter from the cutter tip (the generated
        root line) to the fillet/blade junction, then ``n_profile`` rows evenly in height from the junction to the
        face cone. The last fillet row and the first blade row coincide. ``fillet`` marks fillet rows.
        """
        for name, n, lo in (("n_face", n_face, 2), ("n_profile", n_profile, 2)):
            if not (isinstance(n, (int, np.integer)) and n >= lo):
                raise DesignError.single(name, n, f"integer >= {lo}", "-")
        if not (isinstance(n_fillet, (int, np.integer)) and (n_fillet == 0 or n_fillet >= 2)):
            raise DesignError.single("n_fillet", n_fillet, "0 or an integer >= 2", "-")
        ol, loc, cp = self.outline, self._locator, self.generator.cp
        R = np.linspace(ol.Ri, ol.Re, n_face)
        # junction line (u = u_j) at each face station, in the (phi, psi_c) chart of the blade (regular where the
        # (u, psi_c) chart folds, docs/conventions.md "Fold of generation")
        mp = self.mean_point()
        xj = loc.junction(R, (mp.theta + np.pi - self.generator.mp["q"] + mp.psi_c, mp.psi_c))
        xj[:, 0] = cp["u_j"]             # the junction row exactly (solved to round-off)
        pj = self.generator.evaluate_at(xj[:, 0], xj[:, 1], xj[:, 2], curvature=False).points
        _, hj = ol.Rh(pj[:, 2], np.hypot(pj[:, 0], pj[:, 1]))
        t = np.linspace(0.0, 1.0, n_profile)
        H = hj[:, None] + t[None, :] * (ol.h_face(R) - hj)[:, None]
        parts = [loc.profile_rows(R, H, xj)]     # row by row up the profile, each from the row below
        if n_fillet:
            uf = np.linspace(cp["u_min"], cp["u_j"], n_fillet)
            xf = loc.fillet_rows(R, uf[-2::-1], xj)[:, ::-1]
            xf = np.concatenate([xf, xj[:, None]], 1)
            parts.insert(0, xf)
        x = np.concatenate(parts, axis=1)
        return self.generator.evaluate_at(x[..., 0], x[..., 1], x[..., 2], curvature)

    def boundary(self, n: int = 31) -> dict:
        """Closed boundary of the flank including its fillet, for CAD export.

        Returns a dict of (k, 3) point arrays (mm, member frame): ``root`` (cutter-tip line, toe->heel),
        ``junction`` (fillet/blade junction), ``top`` (face-cone edge), ``toe`` and ``heel`` (root->top, through the
        fillet).
        """
        g = self.grid(n, n, n_fillet=max(2, n // 3), curvature=False)
        P = g.points
        return dict(root=P[:, 0], junction=P[:, max(2, n // 3) - 1], top=P[:, -1], toe=P[0], heel=P[-1])

    def mean_point(self, depth: float = 0.0) -> MeanPoint:
        """Reference point at the mean cone distance, ``depth`` mm below the pitch line (0: the mean pitch point).

        Seed 003 with docs/theory/generation.md, Eqs. (G10)-(G11) (#mean-point): radius R_m sin(delta) - h cos(delta),
        axial R_m cos(delta) + h sin(delta).
        The spiral angle is measured on the cone of pitch angle through the point, the normal pressure angle is
        asin|n . N| with N the unit normal of that cone (docs/theory/logspiral.md, Eqs. (S10)-(S11) (#cones));
        ``pressure_angle_root`` uses a cone of root
        angle through the point instead (the plane of the generating crown gear). Computed once per depth (the
        flank is immutable); every analysis (reports, phasing, synthesis, tooth assembly) asks for it.
        """
        cache = self.__dict__.setdefault("_mean_points", {})
        key = float(depth)
        if key not in cache:
            cache[key] = self._mean_point(key)
        return cache[key]

    def _mean_point(self, depth: float) -> MeanPoint:
        ol = self.outline
        ax, rad = ol.axial_radius(ol.Rm, -float(depth))
        fp = self.locate(ax, rad)
        p, n = fp.points, fp.normals
        rho_hat = np.array([p[0], p[1], 0.0]) / np.hypot(p[0], p[1])
        z = np.array([0.0, 0.0, 1.0])

        def cone(angle):
            return np.sin(angle) * rho_hat + np.cos(angle) * z, np.cos(angle) * rho_hat - np.sin(angle) * z

        g, N = cone(ol.delta)
        trace = np.cross(N, n)
        trace /= np.linalg.norm(trace)
        if trace @ g < 0:
            trace = -trace
        beta = float(np.arccos(np.clip(trace @ g, -1.0, 1.0)))
        hand_sign = int(np.sign(np.cross(p, trace)[2]))
        _, Nr = cone(ol.delta_f)
        return MeanPoint(point=p, normal=n, spiral_angle=beta, pressure_angle=float(np.arcsin(abs(n @ N))),
                         pressure_angle_root=float(np.arcsin(abs(n @ Nr))), hand_sign=hand_sign,
                         k1=float(fp.k1), k2=float(fp.k2), e1=fp.e1, e2=fp.e2, u=float(fp.u), theta=float(fp.theta),
                         psi_c=float(fp.psi_c), depth=float(depth))

    def meshing_residual(self, u, theta, psi_c):
        """Relative residual n.v/|v| of the equation of meshing at (u, theta, psi_c) (seed 001 Eq. (13))."""
        return self.generator.meshing_residual(u, theta, psi_c)

    def __repr__(self) -> str:
        return (f"ToothFlank({self.member.value} {self.side.value}, {self.hand.value}, "
                f"{self.cutter.blade.value} blade, S_r={self.settings.radial_setting:.3f} mm)")


def generate_flank(cutter, settings, blank, member, side) -> ToothFlank:
    """Generate one flank of a member by a face-milling head cutter on a cradle-type machine.

    Parameters
    ----------
    cutter : HeadCutter
    settings : MachineSettings
    blank : ISO 23509 ``BevelBlank`` (or any object with the same attribute names)
    member : Member
    side : Side

    Returns
    -------
    ToothFlank
    """
    return ToothFlank(cutter, settings, blank, member, side)
