"""The opposite blade of a flank's cutter and the fillet it generates with that flank's settings, for the slot check
(:mod:`~spiralbevel.gearset.slot_check`, whose docstring states what is checked and why).

The fillet grid of the opposite blade is built from its generated root (the tip line, blade parameter u_min) up to
its fillet/blade junction (u_j), row by row at fixed u: at each face station the unknowns are the cutter angle phi and
the cradle angle psi_c, the equations the equation of meshing f(u, phi, psi_c) = 0 (seed 001 Eq. (13)) and the cone
distance R(u, phi, psi_c) = R. That system is regular across the fold of the (u, psi_c) chart (where the two cutter
angles that solve f = 0 merge) and needs no point of the surface on the pitch cone: the opposite blade, generated with
settings made for the other blade, often reaches neither the pitch cone nor the root the closed-form contact
(``Generator.contact``) picks, so the flank grid (``ToothFlank.grid``, started from the mean point on the pitch cone)
cannot be used for it.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .._core.newton import solve_batched
from ..conventions import TOL, Member, Side
from ..errors import GeometryError

__all__ = ["opposite_blade", "opposite_blade_grid", "SLOT_STATIONS", "SLOT_FILLET_ROWS"]

#: face stations (toe and heel included) and fillet rows (tip line to junction) of the opposite blade's surface
SLOT_STATIONS = 11
SLOT_FILLET_ROWS = 9
#: cradle angles (rad, about the machine's zero roll) and samples of the tabulated tip line: the span of the
#: generation tables of ``generation.locate.Locator``, sampled every 2e-3 rad
_PSI_SPAN, _N_PSI = 1.2, 1201
#: a tabulated crossing at a station is on the branch of its neighbour's when it lies within this many times the
#: stations' spacing in cone distance (plus 1 mm) of the neighbour's point: along the tip line a point moves by
#: dR / cos(beta) lengthwise and the line's rise over the face, a few dR at the spiral angles of bevel gears
_BRANCH_STEP = 4.0
#: steps of R between two face stations where the tip line is continued by Newton's method
_N_CONTINUE = 8
#: largest height step (fraction of the whole depth) between two fillet rows, and levels of bisection to reach it
_ROW_GAP, _REFINE_LEVELS = 0.05, 7
#: rows on the blade above the junction when asked for (``opposite_blade_grid``'s ``rise``)
_BLADE_ROWS = 6


def _other(side: Side) -> Side:
    return Side.CONCAVE if side is Side.CONVEX else Side.CONVEX


def _edge_limit(point_width: float, blade_angle: float) -> float:
    """Largest edge radius (mm) a blade point of width W holds: rho (1 - sin a) / cos a <= W / 2 (``HeadCutter``)."""
    return 0.5 * point_width * math.cos(blade_angle) / (1.0 - math.sin(blade_angle))


def opposite_blade(cutter, other_cutter, point_width: float | None = None):
    """The opposite blade of ``cutter``: point radius R_h - s W, blade angle and edge radius of ``other_cutter`` (the
    opposite flank's cutter; the edge radius at most what the point width holds, times ``EDGE_RADIUS_FILL``).

    Parameters
    ----------
    cutter, other_cutter : HeadCutter
    point_width : float, mm, optional
        Default: ``cutter.point_width``.

    Returns
    -------
    HeadCutter
    """
    from ..machine.cutter import Blade
    from ..machine.default_cutter import EDGE_RADIUS_FILL

    W = float(cutter.point_width if point_width is None else point_width)
    a = float(other_cutter.blade_angle)
    rho = min(float(other_cutter.edge_radius), EDGE_RADIUS_FILL * _edge_limit(W, a))
    return dataclasses.replace(cutter, point_radius=cutter.point_radius - cutter.sign * W, point_width=W,
                               blade=Blade.for_side(_other(cutter.side)), blade_angle=a, edge_radius=rho,
                               profile_radius=math.inf)


def _solve_rows(gen, ol, R, u, y0):
    """(phi, psi_c) (n, 2) of the generated points at blade parameter u (mm) and cone distances R (n,) mm, Newton
    from ``y0`` (n, 2), and whether each converged (the equations of the module docstring)."""
    def fun(y):
        ax, rad, f = gen.point_at(u, y[..., 0], y[..., 1])
        return np.stack([f, ol.Rh(ax, rad)[0] - R], -1)

    res = solve_batched(fun, y0, tol=TOL.newton_abs * 10, max_iter=TOL.max_iter, max_step=np.array([0.05, 0.05]))
    return res.x, res.converged


def _tip_line(gen, ol, R, near):
    """(phi, psi_c) (n, 2) of the tip line (u = u_min) at the cone distances R (n,) mm (ascending).

    Starts: the tip line tabulated on both roots of the equation of meshing (``Generator.contact`` with the root
    nearest the reference angle and the other one, nearest it plus pi) over cradle angles +-``_PSI_SPAN``, and its
    crossings of each R by linear interpolation. Where several crossings exist (other branches of the envelope, far
    from the slot), the station nearest the mean cone distance takes the one nearest ``near`` (3,) mm (the cut
    flank's mean point: the opposite blade works W away from the cutting blade in the same slot), each further
    station the one nearest the point chosen at its neighbour toward the middle."""
    u0 = float(gen.cp["u_min"])
    psi = np.linspace(-_PSI_SPAN, _PSI_SPAN, _N_PSI)
    cands: list[list[tuple[np.ndarray, float, float]]] = [[] for _ in R]
    for dphi in (0.0, math.pi):
        sol = gen.contact(u0, psi, dphi)
        ok = np.abs(sol["disc"]) <= 1.0
        phi = np.where(ok, sol["phi"], 0.0)
        p = gen.evaluate_at(np.full(psi.shape, u0), phi, psi, curvature=False).points
        Rt, _ = ol.Rh(p[:, 2], np.hypot(p[:, 0], p[:, 1]))
        dp = np.remainder(np.diff(phi) + math.pi, 2.0 * math.pi) - math.pi
        pair = ok[:-1] & ok[1:] & (np.abs(dp) < 0.2)     # neighbours on one branch
        for k, Rk in enumerate(R):
            s = Rt - Rk
            for i in np.nonzero(pair & (s[:-1] * s[1:] <= 0.0) & (s[:-1] != s[1:]))[0]:
                t = s[i] / (s[i] - s[i + 1])
                cands[k].append((p[i] + t * (p[i + 1] - p[i]), phi[i] + t * dp[i], psi[i] + t * (psi[i + 1] - psi[i])))
    have = [k for k, c in enumerate(cands) if c]
    if not have:
        raise GeometryError.single(
            "slot check (opposite blade)", f"{ol.Ri:.2f}-{ol.Re:.2f} mm", "cone distances the opposite blade's tip "
            "reaches", "mm", "the opposite blade of the cutter, generated with this flank's settings, reaches no "
            f"face station between toe and heel within cradle angles of +-{_PSI_SPAN} rad, so its cut cannot be "
            "compared with the opposite flank")
    y0 = np.empty((len(R), 2))
    chosen = np.empty((len(R), 3))
    k0 = min(have, key=lambda j: abs(R[j] - ol.Rm))
    for k in sorted(range(len(R)), key=lambda j: abs(j - k0)):
        if k == k0:
            best = min(cands[k], key=lambda c: float(np.linalg.norm(c[0] - near)))
            chosen[k], y0[k] = best[0], (best[1], best[2])
            continue
        nb = k + 1 if k < k0 else k - 1
        best = min(cands[k], key=lambda c: float(np.linalg.norm(c[0] - chosen[nb]))) if cands[k] else None
        if best is not None and np.linalg.norm(best[0] - chosen[nb]) <= _BRANCH_STEP * abs(R[k] - R[nb]) + 1.0:
            chosen[k], y0[k] = best[0], (best[1], best[2])
            continue
        # no tabulated crossing on this branch (the tip line passes from one root to the other there, the fold of the
        # (u, psi_c) chart; a crossing farther from the neighbour's point than the branch can run lies on another
        # branch of the envelope: 76 mm above the root cone at the toe of a 15/45 gear at beta 5 deg):
        # continued from the neighbouring station in small steps of R, regular across the fold
        y = y0[nb][None]
        for Rs in np.linspace(R[nb], R[k], _N_CONTINUE + 1)[1:]:
            y, conv = _solve_rows(gen, ol, np.array([Rs]), u0, y)
            if not conv[0]:
                raise GeometryError.single(
                    "slot check (opposite blade)", f"R = {R[k]:.2f} mm", "face stations the opposite blade's tip "
                    "reaches", "mm", f"the opposite blade's tip line, continued from R = {R[nb]:.2f} mm, ends at "
                    f"R = {Rs:.2f} mm (toe {ol.Ri:.2f} mm, heel {ol.Re:.2f} mm): its cut cannot be compared there")
        y0[k] = y[0]
        chosen[k] = gen.evaluate_at(u0, y[0, 0], y[0, 1], curvature=False).points
    y, conv = _solve_rows(gen, ol, R, u0, y0)
    if not np.all(conv):
        raise GeometryError.single(
            "slot check (opposite blade)", f"{int((~conv).sum())} of {len(R)} face stations", "points on the "
            "opposite blade's generated tip line", "mm", "Newton's method did not settle on the tip line there")
    return y


def opposite_blade_grid(blank, setups, member, side, point_width: float | None = None,
                        n_face: int = SLOT_STATIONS, n_fillet: int = SLOT_FILLET_ROWS, rise: float = 0.0):
    """The fillet the opposite blade of the cutter of flank (``member``, ``side``) generates with that flank's settings
    (module docstring): ``n_fillet`` rows evenly in the blade parameter from the tip line (u_min) to the junction
    (u_j), at ``n_face`` face stations evenly in cone distance from toe to heel (the rows of
    ``ToothFlank.grid(n_face, ., n_fillet)`` of that surface, where that grid can be built).

    Parameters
    ----------
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
    member : Member
    side : Side
        The cut flank.
    point_width : float, mm, optional
        Default: the cutter's.
    n_face, n_fillet : int
        At least 2 each.
    rise : float, mm, optional
        When positive, ``_BLADE_ROWS`` rows on the blade above the junction are added, evenly in u up to
        u_j + rise / cos(alpha) (alpha the blade angle: about ``rise`` of height), each solved from the row below.

    Returns
    -------
    FlankPoints
        Shape (n_face, k), member frame, mm: k >= ``n_fillet`` rows, more where the fillet climbs steeply (rows
        bisected in u until no two are more than ``_ROW_GAP`` of the whole depth apart in height).
    HeadCutter
        The opposite blade.

    Raises
    ------
    GeometryError
        Where the opposite blade's tip line does not reach a face station, or a row does not converge (the message
        says which).
    """
    from ..generation.flank import generate_flank

    member, side = Member(member), Side(side)
    other = _other(side)
    A, B = setups[(member, side)], setups[(member, other)]
    opp = opposite_blade(A.cutter, B.cutter, point_width)
    gen, ol = generate_flank(opp, A.settings, blank, member, other).generator, A.flank.outline
    R = np.linspace(ol.Ri, ol.Re, n_face)
    u = np.linspace(gen.cp["u_min"], gen.cp["u_j"], n_fillet)
    x = np.empty((n_face, n_fillet, 3))
    x[..., 0] = u
    x[:, 0, 1:] = _tip_line(gen, ol, R, A.flank.mean_point().point)
    for j in range(1, n_fillet):                # each row from the row below (continuation in u)
        x[:, j, 1:] = _row(gen, ol, R, u[j], (x[:, j - 1, 1:],))
    # rows added where the generated fillet climbs steeply between two rows (near a fold of its contact line the
    # height changes by millimetres over a small step of u): bisection in u until no two rows are more than
    # ``_ROW_GAP`` of the whole depth apart in height, at most ``_REFINE_LEVELS`` times
    limit = _ROW_GAP * (ol.ham + ol.hfm)
    for _ in range(_REFINE_LEVELS):
        p = gen.evaluate_at(x[..., 0], x[..., 1], x[..., 2], curvature=False).points
        _, h = ol.Rh(p[..., 2], np.hypot(p[..., 0], p[..., 1]))
        wide = [int(k) for k in np.nonzero(np.max(np.abs(np.diff(h, axis=1)), axis=0) > limit)[0]]
        if not wide:
            break
        mid = [_row(gen, ol, R, 0.5 * (x[0, j, 0] + x[0, j + 1, 0]), (x[:, j, 1:], x[:, j + 1, 1:])) for j in wide]
        rows = [x[:, j] for j in range(x.shape[1])]
        for j, y in sorted(zip(wide, mid), key=lambda t: -t[0]):
            rows.insert(j + 1, np.concatenate([np.full((n_face, 1), 0.5 * (x[0, j, 0] + x[0, j + 1, 0])), y], -1))
        x = np.stack(rows, 1)
    if rise > 0.0:
        ub = gen.cp["u_j"] + rise / math.cos(opp.blade_angle) * np.linspace(0.0, 1.0, _BLADE_ROWS + 1)[1:]
        blade = [x[:, -1]]
        for uk in ub:
            blade.append(np.concatenate([np.full((n_face, 1), uk), _row(gen, ol, R, uk, (blade[-1][:, 1:],))], -1))
        x = np.concatenate([x, np.stack(blade[1:], 1)], 1)
    return gen.evaluate_at(x[..., 0], x[..., 1], x[..., 2], curvature=False), opp


def _row(gen, ol, R, u, starts):
    """(phi, psi_c) (n, 2) of the row at blade parameter u (mm), from the first of ``starts`` ((n, 2) each) that
    converges at every station."""
    for y0 in starts:
        y, conv = _solve_rows(gen, ol, R, u, y0)
        if np.all(conv):
            return y
    raise GeometryError.single(
        "slot check (opposite blade)", f"{int((~conv).sum())} of {len(R)} points at u = {u:.4g} mm",
        "points on the opposite blade's generated fillet", "mm", "the edge radius does not generate them")
