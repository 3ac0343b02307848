"""Tooth contact analysis of a face-milled pair (drive and coast sides) and its report sections."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from ..conventions import Member, Side
from ..errors import ConvergenceError, NoContactError, SpiralBevelWarning
from ..meshing.pair import meshing_pair
from ..meshing.tca import solve_tca
from ..meshing.tca_checks import contact_ratio
from ..meshing.tca_result import ARCSEC

#: fewest positions with a real-flank contact for which a side's TE curve (max, min, peak-to-peak) is reported
MIN_TE_POSITIONS = 3

SIDES = {"drive": (Side.CONCAVE, Side.CONVEX), "coast": (Side.CONVEX, Side.CONCAVE)}  # (pinion side, gear side)


def run_pair_tca(blank, setups, grids, n_positions: int = 41):
    """TCA of both sides. Returns ({side: TCAResult or None}, report section, {side: (outline1, outline2)})."""
    results: dict[str, Any] = {}
    section: dict[str, dict[str, Any]] = {}
    outlines: dict[str, Any] = {}
    for name in SIDES:
        results[name], section[name], outline = side_tca(blank, setups, name, n_positions=n_positions, grids=grids,
                                                          events=True)
        if outline is not None:
            outlines[name] = outline
    return results, section, outlines


def side_tca(blank, setups, name: str, n_positions: int = 41, misalignment=None, grids=None, pair=None,
             events: bool = False):
    """TCA of one side (``"drive"`` or ``"coast"``) of a face-milled pair.

    Returns (TCAResult or None, report section, (pinion outline, gear outline) in the TCA's frames or None). The
    outlines are the flank grids (``grids``, {(member, side): FlankGeometry}) turned as the phased flanks; without
    ``grids`` they are None. A failed solve gives (None, section with ``error``, None). ``pair`` (a
    :class:`~spiralbevel.meshing.pair.MeshingPair`) replaces the spiral bevel assembly of the two flanks, e.g. the
    hypoid pair of a synthesis with its offset kinematics (``gearset.hypoid.hypoid_pair``). With ``events`` the section
    also lists the contacts that lead between the positions (``short_events``, :func:`short_events`), and a short edge
    contact among them on an edge the positions show no contact at is warned of.
    """
    s1, s2 = SIDES[name]
    if pair is None:
        pair = meshing_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, blank)
    try:
        res = solve_tca(pair.pinion, pair.gear, pair.kinematics, misalignment=misalignment, n_positions=n_positions,
                        start=pair.start)
    except (NoContactError, ConvergenceError) as err:
        return None, {"pinion_side": s1.value, "gear_side": s2.value, "error": str(err)}, None
    outline = None if grids is None else (pair.to_pair_frame(grids[(Member.PINION, s1)].points, "pinion"),
                                          pair.to_pair_frame(grids[(Member.GEAR, s2)].points, "gear"))
    section = tca_section(name, res)
    if "error" in section:
        return None, section, None
    if events:
        section["short_events"] = short_events(pair, res, misalignment)
        seen = {(m, e) for _, _, m, e in res.edges}     # an edge the positions already show is warned of as such
        edge = [e for e in section["short_events"] if e["kind"] == "edge" and (e["member"], e["edge"]) not in seen]
        if edge:
            e = max(edge, key=lambda e: e["transmission_error_arcsec"])
            warnings.warn(f"TCA {name} side: a short edge contact ({e['member']} {e['edge']}, pair {e['pair']}, TE "
                          f"{e['transmission_error_arcsec']:.2f} arcsec) leads between positions "
                          f"{e['between_positions'][0]} and {e['between_positions'][1]} of {len(res.phi1)}, which step "
                          "over it (report: short_events): the bearing touches that edge for part of the mesh cycle",
                          SpiralBevelWarning, stacklevel=3)
    return res, section, outline


def short_events(pair, res, misalignment=None) -> list[dict[str, Any]]:
    """The contacts of one side's TCA ``res`` that lead between its positions (an incoming pair's tip edge touching
    first for a percent of the mesh cycle, say), found by solving the intervals where a pair's contact changes kind
    eight times finer (:func:`~spiralbevel.meshing.tca_events.events_between`); [] when no interval is flagged or the
    finer TCA cannot be solved.

    Parameters
    ----------
    pair : MeshingPair
        The pair ``res`` was solved on (same misalignment, start and mean position).
    res : TCAResult
    misalignment : Misalignment or None

    Returns
    -------
    list of dict
        ``pinion_rotation_deg`` (deg), ``transmission_error_arcsec`` (arcsec), ``pair`` (tooth pair k), ``kind``
        ("edge" or "surface": a surface contact above the TE at both ends of its interval), ``member`` and ``edge``
        (of an edge contact, else None), ``between_positions`` ([i, i + 1] of ``res``).
    """
    from ..meshing.tca_events import events_between
    from ..meshing.tca_result import ContactStatus

    mean = 0.5 * float(res.phi1[0] + res.phi1[-1])     # the positions lie evenly about the mean position

    def solve(n):
        return solve_tca(pair.pinion, pair.gear, pair.kinematics, misalignment=misalignment, n_positions=n,
                         phi1_mean=mean, start=pair.start)

    try:
        ev = events_between(solve, res)
    except (NoContactError, ConvergenceError, ValueError):
        return []
    return [{"pinion_rotation_deg": math.degrees(e.phi1), "transmission_error_arcsec": e.te / ARCSEC,
             "pair": e.pair, "kind": "edge" if e.status == ContactStatus.EDGE else "surface",
             "member": e.edge[0] if e.edge else None, "edge": e.edge[1] if len(e.edge) > 1 else None,
             "between_positions": [e.interval, e.interval + 1]} for e in ev]


def tca_section(name: str, res) -> dict:
    """The report.json section of one side's TCA (and the ``to_dict`` of :class:`~spiralbevel.gearset.TCA`)."""
    s1, s2 = SIDES[name]
    te = res.te_arcsec
    fin = np.isfinite(te)
    edge_contacts = [{"position": i, "pinion_rotation_deg": math.degrees(res.phi1[i]), "pair": k, "member": m,
                      "edge": e} for i, k, m, e in res.edges]
    if fin.sum() < MIN_TE_POSITIONS:
        msg = (f"TCA {name} side: contact of the real flanks at {int(fin.sum())} of {len(te)} positions (edge "
               f"contact at {len(res.edges)}): too few to define a transmission-error curve, none reported")
        warnings.warn(msg, SpiralBevelWarning, stacklevel=3)
        return {"pinion_side": s1.value, "gear_side": s2.value, "status": "too few contact positions",
                "positions": int(len(te)), "contact_positions": int(fin.sum()),
                "edge_contacts": edge_contacts, "error": msg}
    edge = np.nonzero(res.edge_contact)[0]
    ratio, lower_bound = contact_ratio(res)
    return {
        "pinion_side": s1.value, "gear_side": s2.value,
        "status": "ok" if not edge.size else "edge contact",
        "positions": int(len(te)), "contact_positions": int(fin.sum()),
        "edge_contacts": edge_contacts,
        # extremes over the positions and the exact transfer points (the envelope's kinks between positions)
        "max_transmission_error_arcsec": res.te_max / ARCSEC,
        "min_transmission_error_arcsec": res.te_min / ARCSEC,
        "peak_to_peak_arcsec": res.peak_to_peak / ARCSEC,
        "no_contact_positions_deg": [math.degrees(x) for x in res.phi1[~fin]],
        "transfer_points_deg": [math.degrees(x) for x in np.atleast_1d(res.transfer_phi1)],
        "edge_contact_positions_deg": [math.degrees(res.phi1[i]) for i in edge],
        "semi_major_axis_mean_mm": _finite_or_none(np.max(res.semi_axes[len(te) // 2])),
        # one pair's contact on the real flanks over the angular pitch (meshing/tca_checks.py: contact_ratio)
        "contact_ratio_from_tca": ratio, "contact_ratio_from_tca_is_lower_bound": lower_bound,
        "pinion_rotation_deg": np.degrees(res.phi1[fin]), "transmission_error_arcsec": te[fin],
    }


def _finite_or_none(x):
    x = float(x)
    return x if math.isfinite(x) else None


#: misalignments of the sensitivity study: (name, Misalignment keyword, value in internal units, value shown, unit)
SENSITIVITY = (
    ("pinion_axial", "pinion_axial", 0.05, 0.05, "mm"),
    ("gear_axial", "gear_axial", 0.05, 0.05, "mm"),
    ("offset", "offset", 0.05, 0.05, "mm"),
    ("shaft_angle", "shaft_angle", math.radians(0.05), 0.05, "deg"),
)


def misalignment_sensitivity(blank, setups, side: str = "drive", n_positions: int = 41, pair=None):
    """TE level and contact-path shift of one side for each misalignment of :data:`SENSITIVITY`.

    The shift is that of the gear contact point at the mean position, in the pitch-generatrix coordinates of the
    gear's blank outline (``contact_R_mm``, ``contact_h_mm`` of the aligned pair): along the face (toward the heel
    > 0) and along the profile (toward the top > 0), mm. Returns a report section (``{"aligned": ..., name: {...}}``).
    ``pair`` (a :class:`~spiralbevel.meshing.pair.MeshingPair`) replaces the spiral bevel assembly, e.g. the hypoid
    pair with its offset kinematics (the misalignments then act on top of the offset).
    """
    from ..meshing.misalignment import Misalignment

    s1, s2 = SIDES[side]
    if pair is None:
        pair = meshing_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, blank)
    c1, c2, kin, start = pair.pinion, pair.gear, pair.kinematics, pair.start
    outline = setups[(Member.GEAR, s2)].flank.outline

    def study(mis):
        res = solve_tca(c1, c2, kin, misalignment=mis, n_positions=n_positions, start=start)
        te = res.te_arcsec
        fin = np.isfinite(te)
        mid = n_positions // 2
        pt = res.point2[mid, list(res.pairs).index(0)] @ c2._R  # gear member frame, unrotated flank
        R, h = outline.Rh(pt[2], math.hypot(pt[0], pt[1]))
        return {"peak_to_peak_arcsec": res.peak_to_peak / ARCSEC if np.any(fin) else None,
                "edge_contact_positions": int(np.sum(res.edge_contact)), "contact_R_mm": float(R),
                "contact_h_mm": float(h)}

    out: dict[str, Any] = {"side": side}
    try:
        base = study(None)
    except (NoContactError, ConvergenceError) as err:
        return dict(out, error=str(err))
    out["aligned"] = base
    for name, key, value, shown, unit in SENSITIVITY:
        try:
            r = study(Misalignment(**{key: value}))
        except (NoContactError, ConvergenceError) as err:
            out[name] = {f"value_{unit}": shown, "error": str(err)}
            continue
        out[name] = {f"value_{unit}": shown, "peak_to_peak_arcsec": r["peak_to_peak_arcsec"],
                     "contact_shift_along_face_mm": r["contact_R_mm"] - base["contact_R_mm"],
                     "contact_shift_along_profile_mm": r["contact_h_mm"] - base["contact_h_mm"],
                     "edge_contact_positions": r["edge_contact_positions"]}
    return out
