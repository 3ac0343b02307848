"""The intrusion of a flank cutter's opposite blade into the opposite flank, over the fillet of that blade, and its
largest value (the measure and its placing: :mod:`~spiralbevel.gearset.slot_check`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..conventions import Member, Side
from .slot_blade import SLOT_FILLET_ROWS, SLOT_STATIONS, _other, opposite_blade_grid

__all__ = ["SlotFit", "intrusion_field", "slot_fit", "SLOT_TOL_MM", "SLOT_FIT_MM"]

#: rows of the opposite flank's profile used for the interpolation: fillet rows, and blade rows up to the face cone
_B_FILLET_ROWS, _B_PROFILE_ROWS = 33, 15
#: an intrusion above this is reported (mm): the interpolation along the opposite flank's profile is exact to about
#: 2e-3 mm (tests/gearset/test_slot_check.py), and 0.005 mm is below the flank tolerance of any accuracy grade
SLOT_TOL_MM = 0.005
#: largest intrusion (mm) a refitted point width leaves: half the reported level (the opposite blade's tip meets the
#: opposite flank's root edge tangentially, so no clearance can be asked for there)
SLOT_FIT_MM = 0.5 * SLOT_TOL_MM


@dataclass(frozen=True)
class SlotFit:
    """Largest intrusion of the opposite blade of the cutter of flank (``member``, ``side``) into the opposite flank.

    Attributes
    ----------
    member, side : Member, Side
        The flank whose cutter is checked.
    intrusion : float, mm
        Largest distance, along the opposite flank's normal, by which the opposite blade's surface lies inside the
        opposite flank's tooth (negative: the smallest clearance; -inf: the opposite blade stays below the opposite
        flank's root).
    face_position : float, -
        Where: (R - R_i) / (R_e - R_i), 0 at the toe, 1 at the heel.
    height : float, mm
        Where: height of that point above the blank's root cone.
    point_width, edge_radius : float, mm
        W of the cutter and the edge radius of its opposite blade.
    tip_height : float, mm
        Lowest height of the opposite blade's tip line above the root cone over the face width: that of the cutter's
        tip plane, where the cut flank's own root lies (0 when the settings put that root on the root cone; negative:
        the cutter, and with it the opposite blade, runs that much deeper).
    """

    member: Member
    side: Side
    intrusion: float
    face_position: float
    height: float
    point_width: float
    edge_radius: float
    tip_height: float = math.nan

    @property
    def fits(self) -> bool:
        return self.intrusion <= SLOT_TOL_MM

    def to_dict(self) -> dict:
        return {"intrusion_mm": self.intrusion if math.isfinite(self.intrusion) else None,
                "face_position": self.face_position, "height_above_root_mm": self.height,
                "point_width_mm": self.point_width, "opposite_edge_radius_mm": self.edge_radius, "fits": self.fits}

def _cyl(outline, p):
    r = np.hypot(p[..., 0], p[..., 1])
    R, h = outline.Rh(p[..., 2], r)
    return R, h, np.arctan2(p[..., 1], p[..., 0]), r


def _space_shift(blank, setups, member, side) -> float:
    """Rotation (rad, about +z) that puts the opposite flank (as generated) where it bounds the tooth space of the
    flank ``side``: its place in the assembled tooth (``tooth_rotation``) plus the whole pitches that bring its mean
    point within one pitch of the cut flank's mean point on the side that flank's outward normal faces."""
    from .facemilled import tooth_rotation

    rot = tooth_rotation(blank, setups, member)
    base = rot if side is Side.CONVEX else -rot          # the concave flank turned by rot makes the tooth
    z = int(blank.z1 if member is Member.PINION else blank.z2)
    pitch = 2.0 * math.pi / z
    ma = setups[(member, side)].flank.mean_point()
    mb = setups[(member, _other(side))].flank.mean_point()
    az_a, az_b = math.atan2(ma.point[1], ma.point[0]), math.atan2(mb.point[1], mb.point[0])
    toward = 1.0 if ma.normal @ np.array([-math.sin(az_a), math.cos(az_a), 0.0]) > 0.0 else -1.0
    gap = toward * (az_b + base - az_a)                 # the space lies toward +toward from the cut flank
    return base + toward * pitch * (math.floor(-gap / pitch) + 1.0)


def _profile_rows(flank, R, h_top):
    """Points and outward normals (n, k, 3) of ``flank`` at the face stations R (n,) mm: ``_B_FILLET_ROWS`` rows on
    the fillet (tip line to junction) and ``_B_PROFILE_ROWS`` - 1 rows on the blade above it, evenly in the blade
    parameter u, the blade rows reaching at least ``h_top`` (n,) mm above the pitch line. Every row is solved at fixed
    u and R from the row below (``Locator.fillet_rows``: the equation of meshing itself, regular across the fold of
    the generation chart; the blade chart of ``ToothFlank.grid`` can miss points just above the junction)."""
    gen, ol, loc = flank.generator, flank.outline, flank._locator
    cp = gen.cp
    mp = flank.mean_point()
    xj = loc.junction(R, (mp.theta + np.pi - gen.mp["q"] + mp.psi_c, mp.psi_c))
    xj[:, 0] = cp["u_j"]
    pj = gen.evaluate_at(xj[:, 0], xj[:, 1], xj[:, 2], curvature=False).points
    _, hj = ol.Rh(pj[:, 2], np.hypot(pj[:, 0], pj[:, 1]))
    du = 1.2 * max(float(np.max(h_top - hj)), 0.1) / math.cos(flank.cutter.blade_angle)
    uf = np.linspace(cp["u_min"], cp["u_j"], _B_FILLET_ROWS)
    ub = cp["u_j"] + du * np.linspace(0.0, 1.0, _B_PROFILE_ROWS)[1:]
    x = np.concatenate([loc.fillet_rows(R, uf[-2::-1], xj)[:, ::-1], xj[:, None],
                        loc.fillet_rows(R, ub, xj)], 1)
    fp = gen.evaluate_at(x[..., 0], x[..., 1], x[..., 2], curvature=False)
    return fp.points, fp.normals


def intrusion_field(blank, setups, member, side, point_width: float | None = None,
                    n_face: int = SLOT_STATIONS, n_fillet: int = SLOT_FILLET_ROWS, cache: dict | None = None):
    """Intrusion (mm, module docstring) of the opposite blade of the cutter of flank (``member``, ``side``) at each
    point of its fillet grid, with the cone distance R and height above the root cone of each point; -inf where the
    point lies below the opposite flank's generated root (there the cut flank's cutter makes the slot's bottom).

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
    cache : dict, optional
        Reuse of the opposite flank's profile rows over calls for other point widths (a search over the point width):
        the rows do not depend on it. Filled by the first call; solved again (reaching higher) when an opposite
        blade's fillet reaches above them (a narrower point's generated fillet is not always lower).

    Returns
    -------
    intrusion, R, height : (n_face, n_fillet) float, mm
    cutter : HeadCutter
        The opposite blade.

    Raises
    ------
    GeometryError
        Where the opposite blade's fillet (:func:`~spiralbevel.gearset.slot_blade.opposite_blade_grid`) or the
        opposite flank's profile cannot be located; the message says where and why.
    """
    member, side = Member(member), Side(side)
    B = setups[(member, _other(side))]
    ol = B.flank.outline
    fa, opp = opposite_blade_grid(blank, setups, member, side, point_width, n_face, n_fillet)
    pa = fa.points
    Ra, ha, fa_az, ra = _cyl(ol, pa)
    R = np.linspace(ol.Ri, ol.Re, n_face)
    rows = None if cache is None else cache.get("rows")
    if rows is not None and np.any(ha.max(1) > rows[2]):
        rows = None                 # this opposite blade's fillet reaches above the cached rows: solved again
    if rows is None:
        pb, nb = _profile_rows(B.flank, R, ha.max(1) + 0.05 * (ol.ham + ol.hfm))
        rows = (pb, nb, _cyl(ol, pb)[1].max(1))
        if cache is not None:
            cache["rows"] = rows
    pb, nb, _ = rows
    _, hb, fb_az, _ = _cyl(ol, pb)
    # the opposite flank's outward normal points into the space: its tooth lies toward -sign(n . e_azimuth)
    c_az = np.sum(nb[..., :2] * np.stack([-np.sin(fb_az), np.cos(fb_az)], -1), -1)
    into = -np.sign(np.median(c_az))
    fb_az = fb_az + _space_shift(blank, setups, member, side)
    out = np.empty(ha.shape)
    for k in range(n_face):
        order = np.argsort(hb[k])
        phb = np.interp(ha[k], hb[k][order], np.unwrap(fb_az[k][order]))
        cb = np.interp(ha[k], hb[k][order], np.abs(c_az[k][order]))
        d = into * (np.remainder(fa_az[k] - phb + math.pi, 2.0 * math.pi) - math.pi) * ra[k] * cb
        out[k] = np.where(ha[k] >= hb[k].min(), d, -np.inf)     # below its generated root: the slot's bottom
    return out, Ra, ha - ol.h_root(Ra), opp


def slot_fit(blank, setups, member, side, point_width: float | None = None, cache: dict | None = None) -> SlotFit:
    """Largest intrusion of the opposite blade of the cutter of flank (``member``, ``side``) (module docstring).

    Parameters
    ----------
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
    member : Member
    side : Side
    point_width : float, mm, optional
    cache : dict, optional
        As :func:`intrusion_field`'s.

    Returns
    -------
    SlotFit
    """
    val, R, h, opp = intrusion_field(blank, setups, member, side, point_width, cache=cache)
    k = np.unravel_index(int(np.argmax(val)), val.shape)
    ol = setups[(Member(member), Side(side))].flank.outline
    return SlotFit(Member(member), Side(side), float(val[k]), float((R[k] - ol.Ri) / (ol.Re - ol.Ri)), float(h[k]),
                   float(opp.point_width), float(opp.edge_radius), float(np.min(h[:, 0])))
