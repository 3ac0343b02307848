"""Checks on the TCA of a developed pair: the bearing inside the flanks, the TE level against the design, the contact
ratio.

Each check returns warnings with the reason and the design-file key to change (docs/conventions.md, "Developed-pair
checks").
"""

from __future__ import annotations

from collections import Counter

import numpy as np

from .tca_result import ARCSEC

__all__ = ["STATIONARY_SHIFT", "TE_LEVEL_TOL", "bearing_warnings", "contact_ratio", "contact_ratio_warnings",
           "parabolic_level", "te_level", "te_level_warnings", "tca_checks"]

#: relative tolerance of the fitted parabolic TE level against the designed one (the acceptance of a developed pair:
#: at the design TE level within 10 %)
TE_LEVEL_TOL = 0.10

#: design-file names of the pinion flank of each side
_PINION_SIDE = {"drive": "concave", "coast": "convex"}


def bearing_warnings(res, side: str, synthesized: bool, given: bool = True, default: bool = False) -> list[str]:
    """The bearing runs off the flank: positions with no real-flank contact or in edge contact.

    Parameters
    ----------
    res : TCAResult
    side : {"drive", "coast"}
    synthesized : bool
        True when the pinion flank of this side comes from local synthesis (its path and ellipse are to change);
        False for given machine settings.
    given : bool, optional
        With ``synthesized`` False: True when the design file gives the pinion flank's machine settings
        (``face_milling.pinion_<side>.machine``), False when they are the basic settings from the blank (a
        ``[synthesis]`` section whose ``sides`` leave this side out). The key the message names depends on it.
    default : bool, optional
        With ``synthesized``: the default synthesis searched the path directions (the design file gives no
        ``synthesis.path_direction``). A given ``synthesis.path_direction`` replaces that search on every side that
        ``synthesis.sides`` lists (left out: both sides), so the message names that key and the range it takes.

    Returns
    -------
    list of str
        Empty when every position has a contact of the real flanks and none is an edge contact.
    """
    te = np.asarray(res.te)
    off = ~np.isfinite(te) | np.asarray(res.edge_contact, bool)
    n_off = int(np.sum(off))
    if n_off == 0:
        return []
    where = Counter(f"{member} {edge}" for _i, _k, member, edge in res.edges)
    what = ", ".join(f"{name} at {n}" for name, n in sorted(where.items())) or "no contact"
    if synthesized and default:
        key = ("the default synthesis found no path direction that keeps it inside; to try another, give "
               "synthesis.path_direction in the [synthesis] section (-60 to 60 deg from the profile direction; "
               "toward the lengthwise direction keeps the path off a tooth top; it replaces the default search on "
               "every side synthesis.sides lists, both when left out) and a shorter synthesis.semi_major_axis")
    elif synthesized:
        key = ("change synthesis.path_direction (toward the lengthwise direction keeps the path off a tooth top) or "
               "shorten synthesis.semi_major_axis")
    elif given:
        key = (f"the given settings face_milling.pinion_{_PINION_SIDE[side]}.machine do not keep the bearing inside; "
               f"leave face_milling.pinion_{_PINION_SIDE[side]} out to have the pinion synthesized, or add a "
               "[synthesis] section")
    else:
        key = (f"the pinion {_PINION_SIDE[side]} flank is not synthesized (its basic settings come from the blank, "
               f"synthesis.sides leaves the {side} side out): add \"{side}\" to synthesis.sides, or leave the "
               "[synthesis] section out to have both sides developed by default")
    return [f"{side} side: the bearing runs off the flank at {n_off} of {te.size} TCA positions (edge contact: "
            f"{what}); {key}"]


def te_level(res, z1: int, window: float = 0.4) -> float | None:
    """Parabolic TE level (arcsec) of a TCA: :func:`parabolic_level` of its TE against the pinion rotation from the
    TCA's mean position. ``None`` with fewer than three contact positions in the window."""
    return parabolic_level(np.asarray(res.phi1) - float(res.phi1_mean), np.asarray(res.te) / ARCSEC, z1, window)


#: the parabola of :func:`parabolic_level` is centred on the TE's stationary point only when that lies more than this
#: fraction of half a mesh cycle from the TCA's mean position: a depth candidate of the default synthesis moves M by
#: about a quarter (0.24 on 10/19 at beta 44.9 deg), while the stationary point of a pitch-point pair, estimated from
#: the sampled TE, scatters by a few hundredths (0.06 on 13/20 at beta 10.3 deg, coast, where an adjacent pair's
#: corner contact bumps one of 21 positions by 0.4 arcsec; bench/bench_robustness.py sample ``100 2``)
STATIONARY_SHIFT = 0.1


def parabolic_level(phi, te, z1: int, window: float = 0.4) -> float | None:
    """Parabolic TE level (arcsec) at the mean contact: a least-squares parabola through the TE within ``window`` of
    half a mesh cycle (pi/z1) around the mean contact, evaluated at half a mesh cycle, as -a2 (pi/z1)^2.

    The mean contact M is where the local synthesis puts the stationary point of the TE (TE' = 0) and prescribes its
    second derivative (the design level). With M at the mean pitch point that is the TCA's mean position (phi = 0);
    with M moved below the pitch line (the default synthesis' depth candidates) it is not, and a parabola fitted
    around phi = 0 reads the TE's third-order part as curvature (10/19 at beta 44.9 deg, bench/bench_robustness.py
    sample ``100 2``, coast: M 0.19 mm below the pitch line, the stationary point at +0.24 of an 18 deg half cycle,
    9.3 arcsec around phi = 0, 7.9 around the stationary point, for a synthesis at 8). The stationary point is that of
    a least-squares cubic through the window around phi = 0 nearest phi = 0; the parabola is centred on it when it
    lies more than ``STATIONARY_SHIFT`` of half a mesh cycle from phi = 0 and inside the window, else on phi = 0.

    Parameters
    ----------
    phi : (n,) float, rad
        Pinion rotation from the TCA's mean position.
    te : (n,) float, arcsec
        Transmission error (NaN where no contact).
    z1 : int
        Pinion teeth.
    window : float
        Half width of the fitted window as a fraction of half a mesh cycle.

    Returns
    -------
    float, arcsec, or None with fewer than three contact positions in the window.
    """
    phi, te = np.asarray(phi, float), np.asarray(te, float)
    half = np.pi / z1
    reach = window * half
    near = np.isfinite(te) & (np.abs(phi) <= reach)
    centre = 0.0
    if np.sum(near) >= 4:
        roots = np.roots(np.polyder(np.polyfit(phi[near], te[near], 3)))
        roots = roots[np.abs(roots.imag) <= 1e-12 * half].real
        if roots.size:
            s = float(roots[np.argmin(np.abs(roots))])
            if STATIONARY_SHIFT * half < abs(s) <= reach:
                centre = s
                near = np.isfinite(te) & (np.abs(phi - centre) <= reach)
    if np.sum(near) < 3:
        return None
    return float(-np.polyfit(phi[near] - centre, te[near], 2)[0] * half ** 2)


def te_level_warnings(res, side: str, design_arcsec: float | None, z1: int) -> list[str]:
    """The parabolic TE level of the TCA (:func:`te_level`) against the designed one (``synthesis.te_magnitude``).

    The local synthesis prescribes the second derivative of the TE at the mean contact, i.e. a parabola that drops
    by the design level over half a mesh cycle on each side. Warns when the level fitted to the TCA is more than
    :data:`TE_LEVEL_TOL` away from the design, or when there is no TE curve to fit.
    """
    if design_arcsec is None or not design_arcsec > 0:
        return []
    level = te_level(res, z1)
    if level is None:
        return [f"{side} side: too few TCA positions with contact near the mean contact to compare the TE level with "
                f"the designed {design_arcsec:.3g} arcsec"]
    dev = level / design_arcsec - 1.0
    if abs(dev) <= TE_LEVEL_TOL:
        return []
    return [f"{side} side: parabolic TE level {level:.3g} arcsec against the designed {design_arcsec:.3g} arcsec "
            f"({dev:+.0%}, allowed +-{TE_LEVEL_TOL:.0%}); change synthesis.te_magnitude"]


def tca_checks(res, side: str, synthesized: bool, design_arcsec: float | None = None, z1: int = 0,
               given: bool = True, default: bool = False) -> list[str]:
    """All TCA checks of one side (:func:`bearing_warnings`, :func:`te_level_warnings`; z1 the pinion teeth; given,
    default: see :func:`bearing_warnings`)."""
    if res is None:
        return []
    return (bearing_warnings(res, side, synthesized, given, default)
            + (te_level_warnings(res, side, design_arcsec, z1) if z1 else [])
            + contact_ratio_warnings(res, side, synthesized, given))


def contact_ratio_warnings(res, side: str, synthesized: bool, given: bool = True) -> list[str]:
    """The contact of one tooth pair ends before the next pair's begins: contact ratio of the TCA
    (:func:`contact_ratio`) below 1."""
    ratio, lower_bound = contact_ratio(res)
    if lower_bound or ratio >= 1.0:
        return []
    key = ("lengthen synthesis.semi_major_axis or turn synthesis.path_direction toward the lengthwise direction"
           if synthesized else f"change face_milling.pinion_{_PINION_SIDE[side]}.machine" if given else
           f"add \"{side}\" to synthesis.sides (the pinion {_PINION_SIDE[side]} flank is not synthesized)")
    return [f"{side} side: contact ratio from the TCA {ratio:.3f} < 1 (one tooth pair leaves the flanks before the "
            f"next one is in contact); {key}"]


def contact_ratio(res) -> tuple[float, bool]:
    """Contact ratio of a TCA: the pinion rotation over which one tooth pair is in contact of the real flanks,
    divided by the angular pitch 2 pi / z1 (the TCA's cycle: its positions span phi10 - pi/z1 to phi10 + pi/z1).

    Pair k of the TCA at the pinion rotation phi1 is the pair at the offset o = phi1 - phi10 + 2 pi k / z1 from its
    own mean contact; over the pairs (-1, 0, 1) and one mesh cycle of positions the offsets cover three angular
    pitches on a uniform grid. The span is the run of offsets around 0 at which the pair has a surface contact
    inside both flanks (``status_pairs`` OK or LINE, whether or not it is the pair that carries: the path of
    contact of that pair alone), each end placed half a grid step beyond the last sample inside, so the span is
    within one grid step (2 pi / (z1 (n - 1))) of the exact one.

    Returns
    -------
    ratio : float
        Span / (2 pi / z1), dimensionless.
    lower_bound : bool
        True when the contact is still inside at an end of the analysed offsets (the span is at least ``ratio``).
    """
    from .tca_result import ContactStatus

    phi = np.asarray(res.phi1, float) - float(res.phi1_mean)
    T = float(phi[-1] - phi[0])
    pairs = np.asarray(res.pairs, int)
    off = (phi[:, None] + pairs[None, :] * T).reshape(-1)
    sp = np.asarray(res.status_pairs).reshape(-1)
    inside = (sp == ContactStatus.OK) | (sp == ContactStatus.LINE)
    step = float(phi[1] - phi[0])
    # one sample per grid node (the nodes at +-T/2 of neighbouring pairs are the same state): inside if either says so
    node = np.round(off / step).astype(int)
    nodes = np.arange(node.min(), node.max() + 1)
    ins = np.zeros(nodes.size, bool)
    np.logical_or.at(ins, node - node.min(), inside)
    i0 = -node.min()                      # the node at offset 0
    if not ins[i0]:
        return 0.0, False
    lo = i0
    while lo > 0 and ins[lo - 1]:
        lo -= 1
    hi = i0
    while hi < nodes.size - 1 and ins[hi + 1]:
        hi += 1
    span = (hi - lo + 1) * step
    return float(span / T), bool(lo == 0 or hi == nodes.size - 1)
