"""The point-width refit: the largest point width whose opposite blade fits the tooth space, and the passes that
refit every derived point width that does not (the why: :mod:`~spiralbevel.gearset.slot_check`)."""

from __future__ import annotations

import dataclasses
import math

from ..conventions import Member, Side
from ..errors import DesignError, GeometryError
from .slot_blade import _edge_limit, _other
from .slot_intrusion import SLOT_FIT_MM, slot_fit

__all__ = ["fit_point_widths", "refit_side"]

#: passes of the point-width refit over the four flanks: a refit that regenerates a fillet can make the other side's
#: opposite flank intrude again (5 of 100 designs of bench/bench_robustness.py, seed 2, e.g. 9/19 and 20/39; all 5 fit
#: after the passes); the loop ends early once a pass regenerates no fillet
_FIT_PASSES = 3


def _largest_fitting_width(blank, setups, member, side, w0: float) -> float | None:
    """Largest point width (mm) in (0.2 w0, w0] whose opposite blade intrudes by at most ``SLOT_FIT_MM``, to 1e-3
    mm; ``None`` when even 0.2 w0 intrudes.

    The search starts from the first-order estimate: narrowing the point by dW moves the opposite blade's straight
    part by dW cos(alpha) along its normal (alpha its blade angle), so w0 - (intrusion - SLOT_FIT_MM) / cos(alpha),
    refined by secant steps (three or four evaluations); should they not settle, Brent's method on a bracket widened
    by halves of the remaining range."""
    from scipy.optimize import brentq

    rows: dict = {}     # the opposite flank's rows, solved once (again only where a fillet reaches above them)

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


def refit_side(blank, setups, member, side):
    """The refit of one flank's derived point width against the other flank of its tooth space, as
    :func:`fit_point_widths` does it in one pass.

    Parameters
    ----------
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
        At least ``(member, side)`` and the other side of the same member; not modified.
    member : Member
    side : Side

    Returns
    -------
    (HeadCutter, ToothFlank) or None
        The cutter with the largest point width that fits (its edge radius reduced to what that width holds, times
        ``EDGE_RADIUS_FILL``, only when it holds less) and the flank it generates (the same flank object when the
        edge radius is kept); ``None`` when the cutter fits as it is or no width down to 0.2 of it fits.

    Raises
    ------
    GeometryError, DesignError
        When the intrusion or the flank cannot be computed.
    """
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL

    st = setups[(member, side)]
    if slot_fit(blank, setups, member, side).fits:
        return None
    c = st.cutter
    w = _largest_fitting_width(blank, setups, member, side, c.point_width)
    if w is None:
        return None
    rho = min(c.edge_radius, EDGE_RADIUS_FILL * _edge_limit(w, c.blade_angle))
    new = dataclasses.replace(c, point_width=w, edge_radius=rho)
    flank = st.flank if rho == c.edge_radius else generate_flank(new, st.settings, blank, member, side)
    return new, flank


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
                    got = refit_side(blank, setups, m, s)
                except (GeometryError, DesignError):
                    continue
                if got is None:
                    continue                             # fits, or nothing fits: the check says so
                new, flank = got
                w = float(new.point_width)
                c0, src0 = derived.setdefault((m, s), (st.cutter, st.source))
                c = st.cutter
                rho = new.edge_radius
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
