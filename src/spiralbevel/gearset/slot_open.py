"""Does a synthesized pinion flank leave a tooth space that some cutter fits? The default synthesis' slot rule.

Local synthesis fixes each pinion side to second order at its mean contact point only; the two sides are synthesized
separately, and away from the mean point their flanks can cross near the root (the settings of one side put its
generated root, or its fillet, inside the tooth that the other side bounds). Then no cutter fits that tooth space:
the opposite blade of a side's cutter (:mod:`~spiralbevel.gearset.slot_check`) cuts into the other flank at every
point width down to ``SLOT_FLOOR`` of the derived one, the floor of the point-width refit
(:func:`~spiralbevel.gearset.slot_check.fit_point_widths`). The default synthesis rejects such a candidate of the
side synthesized last (it sees the finished other side) and tries the next one (docs/conventions.md, "Developed pair
by default").
"""

from __future__ import annotations

from ..conventions import Member, Side
from ..errors import DesignError, GeometryError

__all__ = ["SLOT_FLOOR", "slot_closed"]

#: narrowest point width, as a fraction of the derived one, that the point-width refit tries
#: (``slot_check._largest_fitting_width``)
SLOT_FLOOR = 0.2


def slot_closed(blank, pinion_setups, floors, finished: Side | None = None) -> bool:
    """True when, for some pinion side, no point width of its cutter down to ``floors[side]`` times its own fits.

    Parameters
    ----------
    blank : BevelBlank
    pinion_setups : {Side: FlankSetup}
        Both pinion sides (cutter, settings, flank).
    floors : {Side: float}, -
        Narrowest point width tried per side as a fraction of its cutter's: ``SLOT_FLOOR`` for a derived point width
        (the refit narrows it), 1 for a given one (kept as given).
    finished : Side, optional
        The side synthesized before (its settings final): its cutter does not count where its tip plane lies more
        than ``CHECK_ROOT_MM`` below the root cone (Notes).

    Returns
    -------
    bool
        True also when the check cannot be computed for a side (the developed pair would miss the check).

    Notes
    -----
    One opposite-blade generation per side, at the floor: the intrusion falls as the point narrows (the refit's
    premise), so some width from the cutter's own down to the floor fits exactly when the floor does (by
    ``SLOT_FIT_MM``, what a refit leaves; by ``SLOT_TOL_MM`` at a floor of 1, a width kept as given).

    The rule judges what the candidate can change. The finished side's cutter whose tip plane lies below the root
    cone (where the root raise of the default synthesis, ``pinion_fillet.raise_root``, could not put it: its root is
    not below the root cone over the whole face) runs its opposite blade below the root of the candidate's flank,
    whatever the candidate's settings, and cuts that flank's root edge and fillet: that closure is the finished side's,
    and the cutter-fit check of the developed pair names it with the keys to change (``slot_check.slot_messages``).
    Ranking every candidate down for it would only end the search on a worse bearing.
    """
    from .facemilled import CHECK_ROOT_MM
    from .slot_check import SLOT_FIT_MM, SLOT_TOL_MM, slot_fit

    setups = {(Member.PINION, s): st for s, st in pinion_setups.items()}
    for side in (Side.CONVEX, Side.CONCAVE):
        floor = min(float(floors[side]), 1.0)
        tol = SLOT_TOL_MM if floor >= 1.0 else SLOT_FIT_MM
        try:
            fit = slot_fit(blank, setups, Member.PINION, side, floor * float(pinion_setups[side].cutter.point_width))
        except (GeometryError, DesignError):
            return True
        if fit.intrusion > tol and not (side is finished and fit.tip_height < -CHECK_ROOT_MM):
            return True
    return False
