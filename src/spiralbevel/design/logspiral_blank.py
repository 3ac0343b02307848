"""A log-spiral pair from an ISO 23509 blank: blank boundaries, and the design-file key and value to change when the
pair cannot be made.

A log-spiral flank (seed 000) is similar to itself about the pitch apex O: every cone through O cuts it along the same
log spiral turned and scaled, so its tooth is bounded by root and face cones *through O*, and its depth grows in
proportion to the cone distance (the standard taper of ISO 23509). The ISO blank's root and face cones of the duplex
and tilted-root-line tapers have their apexes elsewhere; they are replaced by the cones through O that keep the ISO
mean addendum and dedendum at the mean cone distance:

    delta_f = delta - atan(h_fm / R_m),    delta_a = delta + atan(h_am / R_m).

With ``taper = "given"`` the given dedendum angles are taken as they are, as root and face angles of cones through O
(the seed 001 example gives Table 1's root angles this way). A parallel-depth blank (``taper = "uniform"``, root and
face angle equal to the pitch angle) has no log-spiral tooth: the depth of a flank similar to itself about O cannot
stay constant along the face; it is refused with the keys to change.

Two limits of the flank are checked first, each with the value of a design-file key that clears it:

* the root cone must lie outside the base cone (the flank's singular edge psi = 0, docs/theory/logspiral.md):
  delta_f > delta_b with sin(delta_b) = sin(delta) cos(alpha_t), tan(alpha_t) = tan(alpha_n) / cos(beta_m); the
  normal pressure angle that reaches it is alpha_n = atan(tan(acos(sin delta_f / sin delta)) cos(beta_m));
* on the concave flank |psi| + |beta| < 90 deg up to the face cone (|psi| = acos(cos delta_a / cos delta_b), beta the
  spiral angle in the base-cone tangent plane, sin(beta) = cos(alpha_n) sin(beta_m)): beyond it the profile has an
  inflection (docs/theory/logspiral.md, Eq. (S9)). The mean spiral angle that reaches it is solved with the mean
  addendum scaled like the mean normal module, cos(beta_m).
"""

from __future__ import annotations

import math

from spiralbevel.conventions import Hand, Member
from spiralbevel.design.logspiral_pair import BlankBoundaries, design_logspiral_pair, pair_recipe
from spiralbevel.errors import GeometryError

__all__ = ["logspiral_boundaries", "logspiral_pair_from_blank"]

#: margins of the suggested values: 0.5 deg on the pressure angle, 0.5 deg on the spiral angle
_STEP = 0.5
_MEMBERS = ((Member.PINION, 1), (Member.GEAR, 2))


def logspiral_boundaries(blank) -> dict:
    """Per-member :class:`BlankBoundaries` of a log-spiral pair from an ISO 23509 blank (module docstring).

    Parameters
    ----------
    blank : BevelBlank

    Returns
    -------
    dict
        {Member: BlankBoundaries}: toe and heel cone distances (mm), root and face angles of cones through O (rad).
    """
    # given: the user's angles; uniform: root and face angle equal to the pitch angle, refused by the pair design with
    # the keys to change
    given = getattr(blank, "taper", "") in ("given", "uniform")
    out = {}
    for m, k in _MEMBERS:
        d = float(getattr(blank, f"delta{k}"))
        if given:
            df, da = float(getattr(blank, f"delta_f{k}")), float(getattr(blank, f"delta_a{k}"))
        else:
            df = d - math.atan(float(getattr(blank, f"hfm{k}")) / float(blank.Rm))
            da = d + math.atan(float(getattr(blank, f"ham{k}")) / float(blank.Rm))
        out[m] = BlankBoundaries(float(getattr(blank, f"Ri{k}")), float(getattr(blank, f"Re{k}")), df, da)
    return out


def _scaled(blank, name, k, beta_m, beta_m0):
    """The blank's mean depth ``name`` (ham/hfm) of member k at another mean spiral angle: ISO 23509 mean depths are
    proportional to the mean normal module m_mn = m_mt cos(beta_m), m_mt fixed by the module and the tooth counts."""
    return float(getattr(blank, f"{name}{k}")) * math.cos(beta_m) / math.cos(beta_m0)


def _root_margin(z1, z2, sigma, alpha_n, beta_m, blank, beta_m0, k):
    """delta_f - delta_b (rad) of member k: positive when the root cone lies outside the base cone."""
    g1, g2, _at, d1, d2, _b = pair_recipe(z1, z2, sigma, alpha_n, beta_m)
    g, d = (g1, d1) if k == 1 else (g2, d2)
    return g - math.atan(_scaled(blank, "hfm", k, beta_m, beta_m0) / float(blank.Rm)) - d


def _profile_excess(z1, z2, sigma, alpha_n, beta_m, blank, beta_m0, k):
    """|psi| + |beta| - 90 deg (rad) at the face cone of member k's concave flank (negative: no inflection)."""
    g1, g2, _at, d1, d2, beta = pair_recipe(z1, z2, sigma, alpha_n, beta_m)
    g, d = (g1, d1) if k == 1 else (g2, d2)
    da = g + math.atan(_scaled(blank, "ham", k, beta_m, beta_m0) / float(blank.Rm))
    psi = math.acos(min(1.0, math.cos(da) / math.cos(d)))
    return psi + abs(beta) - 0.5 * math.pi


def _clearing_values(z1, z2, sigma, alpha_n, beta_m, blank):
    """(alpha_n, beta_m) in deg, on the 0.5 deg steps, nearest the design that clear both limits of both members:
    the pressure angle raised until every root cone lies outside its base cone, the spiral angle lowered until no
    concave profile turns over, alternately (the first raises the profile excess, the second the root depth) until
    neither changes. ``None`` where no such pair exists below 45 deg / above 1 deg."""
    from scipy.optimize import brentq

    a, b = math.degrees(alpha_n), math.degrees(beta_m)
    for _ in range(40):
        a0, b0 = a, b
        for k in (1, 2):
            f = lambda x, k=k: _root_margin(z1, z2, sigma, math.radians(x), math.radians(b), blank, beta_m, k)  # noqa
            if f(a) <= 0:
                if f(44.5) <= 0:
                    return None
                a = _STEP * math.ceil(brentq(f, a, 44.5, xtol=1e-10) / _STEP + 1e-9)
        for k in (1, 2):
            g = lambda x, k=k: _profile_excess(z1, z2, sigma, math.radians(a), math.radians(x), blank, beta_m, k)  # noqa
            if g(b) >= 0:
                if g(1.0) >= 0:
                    return None
                b = _STEP * math.floor(brentq(g, 1.0, b, xtol=1e-10) / _STEP - 1e-9)
        if (a, b) == (a0, b0):
            return a, b
    return None


def _limits(z1, z2, sigma, alpha_n, beta_m, blank, bounds):
    """GeometryError naming the key(s) and value(s) that clear the root and profile limits, else None."""
    g1, g2, _at, d1, d2, beta = pair_recipe(z1, z2, sigma, alpha_n, beta_m)
    reasons, field = [], None
    for (m, _k), d in zip(_MEMBERS, (d1, d2)):
        df = bounds[m].root_angle
        if not df > d:
            field = field or "gear_set.normal_pressure_angle"
            reasons.append(f"the {m.value}'s root cone (root angle {math.degrees(df):.4f} deg) lies inside its base "
                           f"cone ({math.degrees(d):.4f} deg), where the log-spiral flank has its singular edge (a "
                           "larger pressure angle shrinks the base cone)")
    for (m, _k), d in zip(_MEMBERS, (d1, d2)):
        psi = math.acos(min(1.0, math.cos(bounds[m].face_angle) / math.cos(d)))
        if not psi + abs(beta) < 0.5 * math.pi:
            field = field or "gear_set.mean_spiral_angle"
            worst = math.degrees(psi + abs(beta))
            reasons.append(f"on the {m.value}'s concave flank |psi| + |beta| reaches {worst:.3f} deg at the face cone "
                           "(90 deg or more: the spherical-involute profile turns over, docs/theory/logspiral.md "
                           "Eq. (S9); a smaller spiral angle or pressure angle lowers it)")
    if field is None:
        return None
    values = _clearing_values(z1, z2, sigma, alpha_n, beta_m, blank)
    now = {"gear_set.normal_pressure_angle": math.degrees(alpha_n), "gear_set.mean_spiral_angle": math.degrees(beta_m)}
    if values is None:
        todo = ("no pressure angle below 45 deg and spiral angle above 1 deg clears it for these tooth counts: "
                "change gear_set.pinion_teeth or flank.kind = 'face-milled'")
        allowed = "a design inside the log-spiral flank's limits"
    else:
        new = dict(zip(now, values))
        todo = "change " + " and ".join(f"{k} to {v:g} deg" for k, v in new.items() if abs(v - now[k]) > 1e-9)
        todo += (" (or give the pinion a smaller dedendum / the member a smaller addendum with "
                 "gear_set.depth.mean_addendum_factor)")
        # the bound is numeric so that the unit follows it ("allowed >= 21.5 deg"); that it holds for these tooth
        # counts and depths only is said in the reason
        allowed = f"{'>=' if field.endswith('pressure_angle') else '<='} {new[field]:g}"
        todo = "for this design " + todo
    return GeometryError.single(field, round(now[field], 6), allowed, "deg", "; ".join(reasons) + ": " + todo)


def logspiral_pair_from_blank(blank, z1, z2, shaft_angle, normal_pressure_angle, spiral_angle, pinion_hand):
    """The conjugate log-spiral pair of a design on its ISO 23509 blank.

    Parameters
    ----------
    blank : BevelBlank
    z1, z2 : int
    shaft_angle, normal_pressure_angle, spiral_angle : float, rad
    pinion_hand : Hand or {"RH", "LH"}

    Returns
    -------
    LogSpiralPair

    Raises
    ------
    GeometryError
        The pair cannot be made; the message names the design-file key and the value that clears the limit.
    DesignError
        Bad scalar input (from :func:`design_logspiral_pair`).
    """
    bounds = logspiral_boundaries(blank)
    if getattr(blank, "taper", "") != "uniform":   # uniform: refused by design_logspiral_pair with its keys
        err = _limits(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle, blank, bounds)
        if err is not None:
            raise err
    try:
        return design_logspiral_pair(z1, z2, shaft_angle, normal_pressure_angle, spiral_angle, Hand(pinion_hand),
                                     bounds, thickness=getattr(blank, "smn1", None))
    except GeometryError as err:
        text = str(err)
        if "pointed" in text or "space closes" in text:
            raise GeometryError.single(
                "gear_set.depth.thickness_factor", float(getattr(blank, "x_smn", 0.0)) * 2.0,
                "a thickness that leaves a top land and a root space", "-",
                f"{text}; change gear_set.depth.thickness_factor (the pinion's share of the thickness) or "
                "gear_set.depth.mean_addendum_factor") from err
        raise
