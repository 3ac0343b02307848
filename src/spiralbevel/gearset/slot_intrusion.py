"""The intrusion of a flank cutter's opposite blade into the opposite flank, over the fillet of that blade (and, where
that blade runs below the opposite flank's root, the depth of that flank's root edge and fillet in the region the
blade cuts), and its largest value (the measure and its placing: :mod:`~spiralbevel.gearset.slot_check`)."""

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
#: depth (mm) of the opposite blade's tip below the opposite flank's root from which a face station is also measured
#: from the flank's side (``intrusion_field``'s ``with_root_edge``): the root-cone acceptance of a design. Where the
#: tip meets the root (both flanks' roots on the root cone) the field alone is exact (2e-3 mm against the exact solve)
#: and agrees with the brute-force sweep (tests/gearset/test_slot_check.py), while the flank-side measure, a distance
#: in the section, reads up to 0.03 mm (20 %) more on the fillet of the 12/41 design of the tests
_UNDER_MM = 0.01


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
                    n_face: int = SLOT_STATIONS, n_fillet: int = SLOT_FILLET_ROWS, cache: dict | None = None,
                    with_root_edge: bool = False):
    """Intrusion (mm, module docstring) of the opposite blade of the cutter of flank (``member``, ``side``) at each
    point of its fillet grid, with the cone distance R and height above the root cone of each point; -inf where the
    point lies below the opposite flank's generated root (that part is measured from the flank's side: the depth of
    its root edge and fillet points in the region the blade cuts, ``with_root_edge``).

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
    with_root_edge : bool
        Also return the depth from the flank's side (below).

    Returns
    -------
    intrusion, R, height : (n_face, n_fillet) float, mm
    cutter : HeadCutter
        The opposite blade.
    (depth, R, height) : (n_face, k) float, mm, only ``with_root_edge``
        At the opposite flank's profile points (root edge, fillet and blade rows) of each face station where the
        opposite blade reaches below that flank's root: the distance of the point from the blade's profile in the
        section R = const (its fillet rows continued on its blade up to the flank's fillet junction), positive where
        the point lies in the region the blade cuts (:func:`_cut_depth`), times the share sqrt(1 - (n . e_R)^2) of the
        flank's unit normal in that section (the distance along the normal, to first order); -inf elsewhere and
        above the blade's profile.

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
    under = np.full(hb.shape, -np.inf)
    deep = ha.min(1) < hb.min(1) - _UNDER_MM          # face stations where the blade runs below the flank's root
    if with_root_edge and np.any(deep):
        # the opposite blade reaches below the opposite flank's root somewhere: its profile continued on the blade
        # (above its junction) to the height of the opposite flank's fillet, for the depth measured from that flank
        top = hb[:, _B_FILLET_ROWS - 1]
        rise = float(np.max((top - ha.max(1))[deep]))
        if rise > 0.0:
            fa_up = opposite_blade_grid(blank, setups, member, side, point_width, n_face, n_fillet,
                                        rise=rise + 0.1 * (ol.ham + ol.hfm))[0].points
        else:
            fa_up = pa
        _, ha_up, az_up, ra_up = _cyl(ol, fa_up)
    # the share of the opposite flank's unit normal in the section R = const: sqrt(1 - (n . e_R)^2), e_R the cone
    # distance direction (sin delta e_r + cos delta e_z, ``BlankOutline.Rh``)
    rb = np.hypot(pb[..., 0], pb[..., 1])
    n_R = (math.sin(ol.delta) * (nb[..., 0] * pb[..., 0] + nb[..., 1] * pb[..., 1]) / rb
           + math.cos(ol.delta) * nb[..., 2])
    in_plane = np.sqrt(np.clip(1.0 - n_R * n_R, 0.0, 1.0))
    for k in range(n_face):
        order = np.argsort(hb[k])
        phb = np.interp(ha[k], hb[k][order], np.unwrap(fb_az[k][order]))
        cb = np.interp(ha[k], hb[k][order], np.abs(c_az[k][order]))
        d = into * (np.remainder(fa_az[k] - phb + math.pi, 2.0 * math.pi) - math.pi) * ra[k] * cb
        below = ha[k] < hb[k].min()
        out[k] = np.where(below, -np.inf, d)     # below its generated root: measured from the flank's side (below)
        if with_root_edge and deep[k]:
            # the opposite blade reaches below the opposite flank's root: the depth of that flank's root edge and
            # fillet points inside the region the blade cuts, in the section R = const (module docstring)
            ref = fb_az[k, np.argmin(hb[k])]
            xa = into * (np.remainder(az_up[k] - ref + math.pi, 2.0 * math.pi) - math.pi) * ra_up[k]
            xb = into * (np.remainder(fb_az[k] - ref + math.pi, 2.0 * math.pi) - math.pi) * rb[k]
            under[k] = _cut_depth(xa, ha_up[k], xb, hb[k]) * in_plane[k]
    if not with_root_edge:
        return out, Ra, ha - ol.h_root(Ra), opp
    Rb = _cyl(ol, pb)[0]
    return out, Ra, ha - ol.h_root(Ra), opp, (under, Rb, hb - ol.h_root(Rb))


def _cut_depth(xa, ha, xb, hb):
    """Signed distance (mm) of the points (xb, hb) (m,) from the polyline (xa, ha) (n,) in a section plane, positive
    where the point lies in the region that polyline bounds on its side of smaller x for ha[0] <= h <= max(ha) (the
    region a blade cuts whose generated profile it is: x the arc about the member axis, positive into the other
    tooth; h the height); -inf for points above the polyline's top, which it does not bound."""
    a, b = np.stack([xa[:-1], ha[:-1]], -1), np.stack([xa[1:], ha[1:]], -1)
    q = np.stack([xb, hb], -1)
    ab = b - a
    t = np.clip(np.einsum("qsk,sk->qs", q[:, None] - a[None], ab) / np.maximum(np.sum(ab * ab, -1), 1e-300), 0.0, 1.0)
    dist = np.min(np.linalg.norm(q[:, None] - (a[None] + t[..., None] * ab[None]), axis=-1), 1)
    # inside: the polygon of the polyline closed on the side of smaller x (even-odd rule, rays toward +x)
    far = min(float(xa.min()), float(xb.min())) - 1.0
    poly = np.concatenate([np.stack([xa, ha], -1), [[far, ha[-1]], [far, ha[0]]]])
    p0, p1 = poly, np.roll(poly, -1, 0)
    y0, y1 = p0[:, 1][None], p1[:, 1][None]
    crosses = (y0 > hb[:, None]) != (y1 > hb[:, None])
    xc = p0[:, 0][None] + (hb[:, None] - y0) * (p1[:, 0] - p0[:, 0])[None] / np.where(y1 != y0, y1 - y0, 1.0)
    inside = np.sum(crosses & (xc > xb[:, None]), 1) % 2 == 1
    return np.where(hb > ha.max(), -np.inf, np.where(inside, dist, -dist))


def slot_fit(blank, setups, member, side, point_width: float | None = None, cache: dict | None = None) -> SlotFit:
    """Largest intrusion of the opposite blade of the cutter of flank (``member``, ``side``) (module docstring): the
    largest of the field of :func:`intrusion_field` and of the depth from the opposite flank's side where the blade
    runs below that flank's root; where it is comes from the one that is larger.

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
    val, R, h, opp, (under, Rb, hb) = intrusion_field(blank, setups, member, side, point_width, cache=cache,
                                                      with_root_edge=True)
    tip = float(np.min(h[:, 0]))
    if np.max(under) > np.max(val):         # the opposite blade below the opposite flank's root cuts it deepest
        val, R, h = under, Rb, hb
    k = np.unravel_index(int(np.argmax(val)), val.shape)
    ol = setups[(Member(member), Side(side))].flank.outline
    return SlotFit(Member(member), Side(side), float(val[k]), float((R[k] - ol.Ri) / (ol.Re - ol.Ri)), float(h[k]),
                   float(opp.point_width), float(opp.edge_radius), tip)
