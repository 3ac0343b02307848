"""Heel and toe dimensions of one member of a bevel blank without offset (ISO 23509 Method 0, gear dimensions).

:func:`member_dimensions` turns the mean-point depths and the taper angles of one member into its face and root
cones, heel/toe depths, tip and root diameters, axial positions measured from the crossing point and the whole depth
perpendicular to the root cone. Scalars in, a dict keyed by ISO symbol (without the member suffix) out; lengths mm,
angles rad.

Axial positions (``docs/conventions.md``) are measured along the member axis from the crossing point (the common
apex when a = 0): ``tzm``, ``txo``, ``txi`` positive toward the back of the member (the body); ``tz``, ``tzF``,
``tzR`` positive when the apex lies *beyond* the crossing point, away from the body.

References
----------
ISO 23509:2016 (= ANSI/AGMA ISO 23509-B17), gear dimensions: outer and inner addenda/dedenda from the face widths
be = Re − Rm and bi = Rm − Ri, face and root angles, outside/inner/root diameters, crossing point to mean point t_zm,
pitch/face/root apex beyond the crossing point t_z, t_zF, t_zR, crown to crossing point t_xo, t_xi, and the pinion
whole depth perpendicular to the root cone h_t1.
"""

from __future__ import annotations

import math

__all__ = ["member_dimensions", "pinion_apex_distances"]


def member_dimensions(
    *, delta: float, rm: float, re: float, ri: float, theta_a: float, theta_f: float, ham: float, hfm: float
) -> dict[str, float]:
    """Dimensions of one member from its mean-point depths and taper angles (a = 0).

    Parameters
    ----------
    delta : float, rad
        Pitch angle δ.
    rm, re, ri : float, mm
        Mean, outer and inner cone distance of the member.
    theta_a, theta_f : float, rad
        Addendum and dedendum angle.
    ham, hfm : float, mm
        Mean addendum and mean dedendum.

    Returns
    -------
    dict of str to float
        ``be, bi`` (mm), ``delta_a, delta_f`` (rad), ``hae, hfe, he, hai, hfi, hi`` (mm), ``dae, dai, dfe, dfi``
        (mm), ``tzm, tz, txo, txi, tzF, tzR`` (mm), ``ht`` (mm). ``tzR`` is ``inf`` when the root angle is not
        positive (the root cone has no apex on the member's side; the blank checks report it).

    Notes
    -----
    With a = 0 the crossing point is the pitch apex, so t_zm = Rm·cos δ and t_z = Rm·cos δ − t_zm = 0;

    * hae = ham + be·tan θa, hfe = hfm + be·tan θf, hai = ham − bi·tan θa, hfi = hfm − bi·tan θf, he = hae + hfe,
      hi = hai + hfi; δa = δ + θa, δf = δ − θf;
    * dae = de + 2·hae·cos δ, dai = di + 2·hai·cos δ, dfe = de − 2·hfe·cos δ, dfi = di − 2·hfi·cos δ;
    * t_xo = t_zm + be·cos δ − hae·sin δ, t_xi = t_zm − bi·cos δ − hai·sin δ (tip points at heel and toe);
    * t_zF = t_z − (Rm·sin θa − ham·cos θa)/sin δa, t_zR = t_z + (Rm·sin θf − hfm·cos θf)/sin δf;
    * h_t: distance from the heel tip point (t_xo, dae/2) to the root cone line, measured along the root cone's
      normal. The standard writes it as ((t_zF + t_xo)/cos δa)·sin(θa + θf) − (t_zR − t_zF)·sin δf; here it is the
      point-to-line distance to the line through the mean root point, which stays finite for δa = 90° and δf <= 0
      (same value; tests/design compare both). Since the heel tip lies h_e above the heel root point along the
      pitch-cone normal, h_t = h_e·cos θf.
    * For the pinion the standard's t_zF1, t_zR1 and h_t1 come from the wheel's cones instead
      (:func:`pinion_apex_distances`, which :func:`~spiralbevel.design.blank.compute_blank` applies).
    """
    sd, cd = math.sin(delta), math.cos(delta)
    be, bi = re - rm, rm - ri
    ta, tf = math.tan(theta_a), math.tan(theta_f)
    hae, hfe = ham + be * ta, hfm + be * tf
    hai, hfi = ham - bi * ta, hfm - bi * tf
    da, df = delta + theta_a, delta - theta_f
    de, di = 2.0 * re * sd, 2.0 * ri * sd
    tzm = rm * cd
    tz = rm * cd - tzm
    txo = tzm + be * cd - hae * sd
    dae = de + 2.0 * hae * cd
    # root cone line through the mean root point (axial z from the crossing point, radius r); unit normal outward
    z_root, r_root = rm * cd + hfm * sd, rm * sd - hfm * cd
    ht = (txo - z_root) * -math.sin(df) + (0.5 * dae - r_root) * math.cos(df)
    return {
        "be": be, "bi": bi, "delta_a": da, "delta_f": df,
        "hae": hae, "hfe": hfe, "he": hae + hfe, "hai": hai, "hfi": hfi, "hi": hai + hfi,
        "dae": dae, "dai": di + 2.0 * hai * cd, "dfe": de - 2.0 * hfe * cd, "dfi": di - 2.0 * hfi * cd,
        "tzm": tzm, "tz": tz, "txo": txo, "txi": tzm - bi * cd - hai * sd,
        "tzF": tz - (rm * math.sin(theta_a) - ham * math.cos(theta_a)) / math.sin(da),
        "tzR": tz + (rm * math.sin(theta_f) - hfm * math.cos(theta_f)) / math.sin(df) if df > 0 else math.inf,
        "ht": ht,
    }


def pinion_apex_distances(
    *, delta1: float, rm: float, theta_a1: float, theta_f1: float, ham2: float, hfm2: float, c: float, txo1: float
) -> dict[str, float]:
    """Face and root apex of the pinion and its whole depth h_t1 as the standard defines them (a = 0).

    Parameters
    ----------
    delta1 : float, rad
        Pinion pitch angle.
    rm : float, mm
        Mean cone distance.
    theta_a1, theta_f1 : float, rad
        Pinion addendum and dedendum angles (= θf2 and θa2: uniform clearance).
    ham2, hfm2 : float, mm
        Mean addendum and dedendum of the wheel.
    c : float, mm
        Clearance.
    txo1 : float, mm
        Crossing point to the pinion's outer crown point.

    Returns
    -------
    dict of str to float
        ``tzF``, ``tzR`` (mm, apex beyond the crossing point; ``tzR`` is ``inf`` for a root angle <= 0) and ``ht``
        (mm).

    Notes
    -----
    ISO 23509 does not take the pinion's face and root apexes from its own mean addendum and dedendum but from the
    wheel: the pinion face cone lies at the clearance c, measured perpendicular to the cones, from the wheel's root
    cone, and the pinion root cone at c from the wheel's face cone. With a = 0 this is
    t_zF1 = (−t_zR2·sin δf2 − c)/sin δa1 and t_zR1 = (−t_zF2·sin δa2 − c)/sin δf1. The mean addendum ham1 = hfm2 − c is
    measured along the pitch-cone normal instead, so this face cone lies c·(1 − cos θa1) (0.005 mm in Annex F
    Sample 1) inside the one through the outside diameter d_ae1 = d_e1 + 2·h_ae1·cos δ1, which the standard computes
    from h_ae1. h_t1 is the distance of the crown point of this face cone (axial position t_xo1) from this root cone,
    ((t_zF1 + t_xo1)/cos δa1)·sin(θa1 + θf1) − (t_zR1 − t_zF1)·sin δf1 in the standard's form. Here both lines are
    built in the pinion's axial plane (z from the crossing point toward the body, r radial) from the wheel's mean
    points, which stays finite for δf1 <= 0.
    """
    p = (math.cos(delta1), math.sin(delta1))  # pitch generator
    n = (-math.sin(delta1), math.cos(delta1))  # pitch-cone normal, away from the pinion axis (toward the wheel)
    da, df = delta1 + theta_a1, delta1 - theta_f1
    u, nu = (math.cos(da), math.sin(da)), (-math.sin(da), math.cos(da))
    v, nv = (math.cos(df), math.sin(df)), (-math.sin(df), math.cos(df))
    # pinion face line: c below the wheel root line (through the wheel's mean root point, direction u)
    pz = rm * p[0] + hfm2 * n[0] - c * nu[0]
    pr = rm * p[1] + hfm2 * n[1] - c * nu[1]
    # pinion root line: c below the wheel face line (through the wheel's mean tip point, direction v)
    qz = rm * p[0] - ham2 * n[0] - c * nv[0]
    qr = rm * p[1] - ham2 * n[1] - c * nv[1]
    tzF = -(pz - pr * u[0] / u[1])
    tzR = -(qz - qr * v[0] / v[1]) if v[1] > 0.0 else math.inf
    t = (txo1 - pz) / u[0]  # crown point of the face line at the axial position t_xo1
    fz, fr = pz + t * u[0], pr + t * u[1]
    ht = (fz - qz) * nv[0] + (fr - qr) * nv[1]
    return {"tzF": tzF, "tzR": tzR, "ht": ht}
