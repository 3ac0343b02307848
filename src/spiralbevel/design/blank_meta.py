"""Names, descriptions and units of every quantity of :class:`~spiralbevel.design.blank.BevelBlank`.

One table drives ``BevelBlank.to_dict``, the dimension sheet (``spiralbevel.io.dimension_sheet``) and the glossary
(``docs/glossary.md``; a test checks that the glossary lists every symbol).

Each entry is ``(base, description, kind, scope)``:

* ``kind`` is ``"angle"`` (rad inside, degrees on display), ``"length"`` (mm), ``"ratio"`` (dimensionless),
  ``"count"`` (integer) or ``"text"``;
* ``scope`` is ``"pair"`` (attribute ``base``) or ``"member"`` (attributes ``base + "1"`` for the pinion and
  ``base + "2"`` for the wheel).
"""

from __future__ import annotations

__all__ = ["QUANTITIES", "attribute_names", "unit_of", "metadata"]

QUANTITIES: tuple[tuple[str, str, str, str], ...] = (
    # --- basic data
    ("z", "number of teeth", "count", "member"),
    ("u", "gear ratio z2/z1", "ratio", "pair"),
    ("Sigma", "shaft angle", "angle", "pair"),
    ("a", "hypoid offset (0: spiral bevel)", "length", "pair"),
    ("hand", "hand of spiral", "text", "member"),
    ("taper", "depthwise taper system", "text", "pair"),
    ("rc0", "cutter radius", "length", "pair"),
    ("c_ham", "mean addendum factor of the wheel", "ratio", "pair"),
    ("k_d", "depth factor", "ratio", "pair"),
    ("k_c", "clearance factor", "ratio", "pair"),
    ("k_t", "thickness factor (x_smn = k_t/2)", "ratio", "pair"),
    # --- pitch cone
    ("delta", "pitch angle", "angle", "member"),
    ("zp", "number of teeth of the crown gear", "ratio", "pair"),
    ("b", "face width", "length", "member"),
    ("be", "face width from the mean point to the heel (outer end)", "length", "member"),
    ("bi", "face width from the mean point to the toe (inner end)", "length", "member"),
    ("Re", "outer cone distance", "length", "member"),
    ("Rm", "mean cone distance (design point)", "length", "pair"),
    ("Rm", "mean cone distance", "length", "member"),
    ("Ri", "inner cone distance", "length", "member"),
    ("de", "outer pitch diameter", "length", "member"),
    ("dm", "mean pitch diameter", "length", "member"),
    ("di", "inner pitch diameter", "length", "member"),
    ("met", "outer transverse module", "length", "pair"),
    ("mmt", "mean transverse module", "length", "pair"),
    ("mmn", "mean normal module", "length", "pair"),
    ("beta_m", "mean spiral angle", "angle", "member"),
    ("beta_e", "outer (heel) spiral angle", "angle", "member"),
    ("beta_i", "inner (toe) spiral angle", "angle", "member"),
    ("alpha_nD", "generated normal pressure angle, drive side", "angle", "pair"),
    ("alpha_nC", "generated normal pressure angle, coast side", "angle", "pair"),
    ("alpha_lim", "limit pressure angle (0 without offset)", "angle", "pair"),
    ("alpha_eD", "effective pressure angle, drive side", "angle", "pair"),
    ("alpha_eC", "effective pressure angle, coast side", "angle", "pair"),
    ("alpha_e", "effective pressure angle, mean of drive and coast", "angle", "pair"),
    # --- depths at the mean point
    ("hmw", "mean working depth", "length", "pair"),
    ("c", "clearance", "length", "pair"),
    ("hm", "mean whole depth", "length", "pair"),
    ("x_hm1", "mean profile shift coefficient of the pinion", "ratio", "pair"),
    ("x_smn", "theoretical thickness modification coefficient (k_t/2)", "ratio", "pair"),
    ("ham", "mean addendum", "length", "member"),
    ("hfm", "mean dedendum", "length", "member"),
    # --- taper and cones
    ("sum_theta_f", "dedendum angle sum used", "angle", "pair"),
    ("sum_theta_fS", "dedendum angle sum, standard taper", "angle", "pair"),
    ("sum_theta_fC", "dedendum angle sum, duplex taper (from rc0)", "angle", "pair"),
    ("sum_theta_fM", "dedendum angle sum, tilted root line taper", "angle", "pair"),
    ("theta_a", "addendum angle", "angle", "member"),
    ("theta_f", "dedendum angle", "angle", "member"),
    ("delta_a", "face angle", "angle", "member"),
    ("delta_f", "root angle", "angle", "member"),
    # --- heel and toe
    ("hae", "outer addendum", "length", "member"),
    ("hfe", "outer dedendum", "length", "member"),
    ("he", "outer whole depth", "length", "member"),
    ("hai", "inner addendum", "length", "member"),
    ("hfi", "inner dedendum", "length", "member"),
    ("hi", "inner whole depth", "length", "member"),
    ("ht", "whole depth perpendicular to the root cone, at the outer crown point", "length", "member"),
    ("dae", "outside diameter", "length", "member"),
    ("dai", "inner outside diameter", "length", "member"),
    ("dfe", "outer root diameter", "length", "member"),
    ("dfi", "inner root diameter", "length", "member"),
    ("tzm", "crossing point to mean point along the axis", "length", "member"),
    ("tz", "pitch apex beyond crossing point", "length", "member"),
    ("txo", "outer crown point to crossing point", "length", "member"),
    ("txi", "inner crown point to crossing point", "length", "member"),
    ("tzF", "face apex beyond crossing point", "length", "member"),
    ("tzR", "root apex beyond crossing point", "length", "member"),
    # --- thickness
    ("jen", "outer normal backlash", "length", "pair"),
    ("jet", "outer transverse backlash", "length", "pair"),
    ("jmn", "mean normal backlash", "length", "pair"),
    ("x_sm", "thickness modification coefficient with backlash", "ratio", "member"),
    ("smn", "mean normal circular thickness (with backlash)", "length", "member"),
    ("smt", "mean transverse circular thickness (with backlash)", "length", "member"),
    ("dvn", "virtual normal reference diameter at the mean point", "length", "member"),
    ("smnc", "mean normal chordal thickness", "length", "member"),
    ("hamc", "mean chordal addendum", "length", "member"),
    ("sai", "normal top land at the toe (completing face-milling slot)", "length", "member"),
    ("sam", "normal top land at the mean point", "length", "member"),
    ("sae", "normal top land at the heel (completing face-milling slot)", "length", "member"),
    ("hlim", "undercut limit depth below the pitch line, mean section", "length", "member"),
)

_MEMBER_NAME = {"1": "pinion", "2": "wheel"}


def _expand(base: str, scope: str) -> list[tuple[str, str]]:
    if scope == "pair":
        return [(base, "")]
    return [(base + "1", "1"), (base + "2", "2")]


def attribute_names() -> list[str]:
    """Every quantity attribute of :class:`BevelBlank`, in table order (``z1, z2, u, Sigma, ...``)."""
    return [name for base, _d, _k, scope in QUANTITIES for name, _m in _expand(base, scope)]


def unit_of(kind: str, degrees: bool = True) -> str:
    """Display unit of a quantity kind: ``deg``/``rad``, ``mm`` or ``-``."""
    if kind == "angle":
        return "deg" if degrees else "rad"
    if kind == "length":
        return "mm"
    return "-"


def metadata(degrees: bool = True) -> list[tuple[str, str, str]]:
    """``(symbol, description, unit)`` of every quantity; member quantities carry ", pinion" / ", wheel"."""
    out = []
    for base, desc, kind, scope in QUANTITIES:
        for name, m in _expand(base, scope):
            d = f"{desc}, {_MEMBER_NAME[m]}" if m else desc
            out.append((name, d, unit_of(kind, degrees)))
    return out
