"""Does each face-milling cutter fit the tooth space it cuts? The opposite blade of every flank's cutter against the
finished opposite flank.

A flank's cutter is one blade of a head cutter with point width W (:class:`~spiralbevel.machine.cutter.HeadCutter`):
the blades of the other kind sit W away in the tip plane, at point radius R_h - s W (s = +1 outer, -1 inner blade).
While the flank is generated they sweep the same tooth space near its other flank, with the same machine settings.
The two flanks of a tooth space are generated separately when their settings differ (every derived or synthesized
side here), so nothing ties that opposite blade to the opposite flank: if it reaches past it, cutting the first flank
removes material of the finished second one (the tooth comes out thinner than designed, its fillet undercut).

The check generates that opposite blade's surface (blade angle and edge radius of the opposite flank's own cutter, the
edge radius no larger than the point width holds) with the settings of the cut flank and measures, at
``SLOT_STATIONS`` face stations from toe to heel and on ``SLOT_FILLET_ROWS`` rows from its generated root (the tip
line) to its fillet/blade junction, how far it lies inside the material of the opposite flank, which is placed as in
the assembled tooth (:func:`~spiralbevel.gearset.facemilled.tooth_rotation`, the neighbouring tooth's flank that
bounds the same space). The measure is the distance along the opposite flank's normal, positive into its tooth: the
arc, on the circle about the member axis through the point, from the opposite flank to the point, times the azimuthal
component |n . e_phi| of that flank's unit normal there (first order in the distance; the arc alone, the measure of
the CAD root-slot width :func:`~spiralbevel.geometry.solid.root_slot_width`, is ill-conditioned on the fillet's
bottom, where the flank runs nearly along the circle). Both surfaces are compared at equal cone distance R and equal
height h, the opposite flank's azimuth and normal interpolated along its generated profile (fillet and blade rows).
Below the opposite flank's generated root the opposite blade only cuts the slot's bottom (whose depth the root-cone
check judges), not the flank.

The generated flank itself does not depend on W (the kernel sees only the cutting blade), so a derived point width
that intrudes is refitted without changing any flank: the largest W at which the opposite blade intrudes nowhere by
more than ``SLOT_FIT_MM``, the edge radius reduced only if the narrower point cannot
hold it (then the fillet of the flank is generated again). A point width from the design file is kept and the check
names its key.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..conventions import Member, Side
from ..errors import DesignError, GeometryError

__all__ = ["SlotFit", "opposite_blade", "intrusion_field", "slot_fit", "slot_checks", "slot_report",
           "fit_point_widths", "SLOT_STATIONS", "SLOT_FILLET_ROWS", "SLOT_TOL_MM", "SLOT_FIT_MM"]

#: face stations (toe and heel included) and fillet rows (tip line to junction) of the opposite blade's surface
SLOT_STATIONS = 11
SLOT_FILLET_ROWS = 9
#: rows of the opposite flank's profile used for the interpolation: fillet rows, and blade rows up to the face cone
_B_FILLET_ROWS, _B_PROFILE_ROWS = 33, 15
#: an intrusion above this is reported (mm): the interpolation along the opposite flank's profile is exact to about
#: 2e-3 mm (tests/gearset/test_slot_check.py), and 0.005 mm is below the flank tolerance of any accuracy grade
SLOT_TOL_MM = 0.005
#: largest intrusion (mm) a refitted point width leaves: half the reported level (the opposite blade's tip meets the
#: opposite flank's root edge tangentially, so no clearance can be asked for there)
SLOT_FIT_MM = 0.5 * SLOT_TOL_MM
#: passes of the point-width refit over the four flanks: a refit that regenerates a fillet can make the other side's
#: opposite flank intrude again (5 of 100 designs of bench/bench_robustness.py, seed 2, e.g. 9/19 and 20/39; all 5 fit
#: after the passes); the loop ends early once a pass regenerates no fillet
_FIT_PASSES = 3


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
    """

    member: Member
    side: Side
    intrusion: float
    face_position: float
    height: float
    point_width: float
    edge_radius: float

    @property
    def fits(self) -> bool:
        return self.intrusion <= SLOT_TOL_MM

    def to_dict(self) -> dict:
        return {"intrusion_mm": self.intrusion if math.isfinite(self.intrusion) else None,
                "face_position": self.face_position, "height_above_root_mm": self.height,
                "point_width_mm": self.point_width, "opposite_edge_radius_mm": self.edge_radius, "fits": self.fits}


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
        Reuse of the opposite flank's profile rows over calls for point widths no larger than the first call's (a
        search over the point width): the rows do not depend on it, and reaching up to the first opposite blade's
        junction they cover every narrower one's (its edge radius, and with it its junction, can only be smaller).
        Filled by the first call.

    Returns
    -------
    intrusion, R, height : (n_face, n_fillet) float, mm
    cutter : HeadCutter
        The opposite blade.
    """
    from ..generation.flank import generate_flank

    member, side = Member(member), Side(side)
    other = _other(side)
    A, B = setups[(member, side)], setups[(member, other)]
    opp = opposite_blade(A.cutter, B.cutter, point_width)
    fa = generate_flank(opp, A.settings, blank, member, other)
    ol = fa.outline
    pa = fa.grid(n_face, 2, n_fillet=n_fillet, curvature=False).points[:, :n_fillet]
    Ra, ha, fa_az, ra = _cyl(ol, pa)
    R = np.linspace(ol.Ri, ol.Re, n_face)
    if cache is not None and "rows" in cache:
        pb, nb = cache["rows"]
    else:
        pb, nb = _profile_rows(B.flank, R, ha.max(1) + 0.05 * (ol.ham + ol.hfm))
        if cache is not None:
            cache["rows"] = (pb, nb)
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
                   float(opp.point_width), float(opp.edge_radius))


def slot_checks(blank, setups) -> dict:
    """{(member, side): SlotFit, or the GeometryError that kept it from being computed} over the four flanks."""
    from .facemilled import MEMBERS, SIDES

    out: dict[tuple[Member, Side], SlotFit | Exception] = {}
    for m in MEMBERS:
        for s in SIDES:
            if (m, s) not in setups or (m, _other(s)) not in setups:
                continue
            try:
                out[(m, s)] = slot_fit(blank, setups, m, s)
            except (GeometryError, DesignError) as err:
                out[(m, s)] = err
    return out


def _point_width_key(spec, member, side) -> str:
    key = f"face_milling.{member.value}_{side.value}"
    if getattr(spec.face_milling, f"{member.value}_{side.value}").cutter is not None:
        return f"{key}.cutter.point_width"
    return "face_milling.point_width"


def _largest_fitting_width(blank, setups, member, side, w0: float) -> float | None:
    """Largest point width (mm) in (0.2 w0, w0] whose opposite blade intrudes by at most ``SLOT_FIT_MM``, to 1e-3
    mm; ``None`` when even 0.2 w0 intrudes.

    The search starts from the first-order estimate: narrowing the point by dW moves the opposite blade's straight
    part by dW cos(alpha) along its normal (alpha its blade angle), so w0 - (intrusion - SLOT_FIT_MM) / cos(alpha),
    refined by secant steps (three or four evaluations); should they not settle, Brent's method on a bracket widened
    by halves of the remaining range."""
    from scipy.optimize import brentq

    rows: dict = {}     # the opposite flank's rows, solved once (every w tried is at most w0)

    def room(w):
        return SLOT_FIT_MM - slot_fit(blank, setups, member, side, w, cache=rows).intrusion

    r0 = room(w0)
    if r0 >= 0.0:
        return w0
    lo_end = 0.2 * w0
    ca = math.cos(setups[(Member(member), _other(Side(side)))].cutter.blade_angle)
    # secant steps from the first-order estimate (the intrusion is nearly linear in W): done when a fitting width
    # moved by less than 1e-3 mm
    wa, ra, wb = w0, r0, max(lo_end, w0 + r0 / ca)
    rb = room(wb)
    for _ in range(6):
        if rb == ra:
            break
        wc = min(max(wb - rb * (wb - wa) / (rb - ra), lo_end), w0)
        rc = room(wc)
        wa, ra, wb, rb = wb, rb, wc, rc
        if rb >= 0.0 and abs(wb - wa) < 1e-3:
            return float(wb)
    hi, lo = w0, max(lo_end, w0 + r0 / ca)
    while True:
        r = room(lo)
        if r > 0.0:
            break
        if lo <= lo_end:
            return None
        hi, lo = lo, max(lo_end, lo - 0.5 * (lo - lo_end) - 0.05 * w0)
    return float(brentq(room, lo, hi, xtol=1e-3))


def slot_messages(spec, blank, setups, checks) -> dict:
    """{(member, side): [warning]} for the flanks whose cutter does not fit, each naming the design-file key and the
    largest point width that fits."""
    out = {}
    for (m, s), res in checks.items():
        key = _point_width_key(spec, m, s)
        if isinstance(res, Exception):
            out[(m, s)] = [f"cutter fit in the slot not checked: {str(res).splitlines()[0]}"]
            continue
        if res.fits:
            continue
        where = f"{res.face_position:.2f} of the face width from the toe, {res.height:.3f} mm above the root cone"
        try:
            w = _largest_fitting_width(blank, setups, m, s, res.point_width)
        except (GeometryError, DesignError):
            w = None
        synthesized = [x.value for x in (s, _other(s)) if "synthesis" in setups[(m, x)].source]
        keys = ("synthesis.path_direction / synthesis.semi_major_axis (the [synthesis] section) of the synthesized "
                f"{' and '.join(synthesized)} side" if synthesized else
                f"face_milling.{m.value}_{s.value}.machine or face_milling.{m.value}_{_other(s).value}.machine")
        todo = (f"reduce {key} to {w:.3f} mm or less" if w is not None else
                f"no point width fits: the two flanks' settings leave no tooth space there (the flanks cross); "
                f"change {keys}, or the tooth thickness")
        out[(m, s)] = [f"the cutter does not fit the tooth space: its opposite blade (point width "
                       f"{res.point_width:.3f} mm) cuts {res.intrusion:.3f} mm into the {_other(s).value} flank "
                       f"({where}); {todo}"]
    return out


def slot_report(spec, blank, setups, flanks) -> None:
    """Add each flank's ``slot`` section and its slot warnings to ``flanks`` (the report's ``flanks`` section, from
    ``facemilled.flank_report``), and issue them as ``DesignWarning``."""
    import warnings

    from ..errors import DesignWarning

    checks = slot_checks(blank, setups)
    msgs = slot_messages(spec, blank, setups, checks)
    for (m, s), res in checks.items():
        d = flanks.setdefault(m.value, {}).setdefault(s.value, {})
        if not isinstance(res, Exception):
            d["slot"] = res.to_dict()
        for text in msgs.get((m, s), ()):
            d.setdefault("checks", []).append(text)
            warnings.warn(f"{m.value} {s.value}: {text}", DesignWarning, stacklevel=2)


def fit_point_widths(spec, blank, setups, synthesis=None) -> dict:
    """Refit each derived point width whose opposite blade cuts into the opposite flank (module docstring).

    Parameters
    ----------
    spec : DesignFile
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
        Modified in place: the cutter (and, when its edge radius had to shrink, the flank) of each refitted side.
    synthesis : {side name: SynthesisResult}, optional
        Modified in place: the pinion cutter and flank follow the refitted setups.

    Returns
    -------
    {(Member, Side): (float, float)}
        (derived, fitted) point width, mm, of each refitted flank.
    """
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL
    from .facemilled import MEMBERS, PAIR_SIDES, SIDES, FlankSetup

    fm = spec.face_milling
    fitted: dict = {}
    if fm.point_width is not None:
        return fitted                                    # the user's point width: the check names the key
    derived: dict = {}                                   # (member, side): (derived cutter, source before the refit)
    # a refit that shrinks the edge radius generates its flank's fillet again, and that flank is the opposite flank
    # of the other side's check (done before it in the pass): passes until no flank changes (``_FIT_PASSES``)
    for _ in range(_FIT_PASSES):
        changed = False
        for m in MEMBERS:
            for s in SIDES:
                st = setups.get((m, s))
                if (st is None or (m, _other(s)) not in setups
                        or getattr(fm, f"{m.value}_{s.value}").cutter is not None):
                    continue
                try:
                    if slot_fit(blank, setups, m, s).fits:
                        continue
                    w = _largest_fitting_width(blank, setups, m, s, st.cutter.point_width)
                except (GeometryError, DesignError):
                    continue
                if w is None:
                    continue                             # nothing fits: the check says so
                c0, src0 = derived.setdefault((m, s), (st.cutter, st.source))
                c = st.cutter
                rho = min(c.edge_radius, EDGE_RADIUS_FILL * _edge_limit(w, c.blade_angle))
                new = dataclasses.replace(c, point_width=w, edge_radius=rho)
                try:
                    flank = st.flank if rho == c.edge_radius else generate_flank(new, st.settings, blank, m, s)
                except GeometryError:
                    continue
                changed = changed or rho != c.edge_radius
                setups[(m, s)] = FlankSetup(m, s, new, st.settings, flank,
                                            f"{src0}; point width {w:.3f} mm fitted to the tooth space "
                                            f"(derived {c0.point_width:.3f} mm)", st.fit)
                fitted[(m, s)] = (float(c0.point_width), float(w))
                if m is Member.PINION and synthesis:
                    for name, res in list(synthesis.items()):
                        if PAIR_SIDES[name][0] is s and hasattr(res, "pinion_cutter"):
                            synthesis[name] = dataclasses.replace(res, pinion_cutter=new, pinion_flank=flank)
        if not changed:
            break
    return fitted
