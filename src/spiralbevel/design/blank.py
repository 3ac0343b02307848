"""Blank geometry of a bevel gear pair, face milling: ISO 23509 Method 0 (a = 0) and Method 1 (Gleason, hypoid).

:func:`compute_blank` turns a :class:`~spiralbevel.design.blank_input.BlankInput` into a
:class:`~spiralbevel.design.blank_result.BevelBlank` (the "dimension sheet"), runs the checks of
:mod:`spiralbevel.design.blank_checks`, raises impossible geometry as ``GeometryError`` and emits the rest as
``DesignWarning``.

References
----------
ISO 23509:2016 (= ANSI/AGMA ISO 23509-B17) clauses 5-6 for a = 0: pitch cone parameters, mean depths
(data type I: hmw = k_d·mmn, c = k_c·hmw, ham2 = c_ham·hmw), addendum/dedendum angles, outer and inner depths,
diameters, crown-to-crossing-point distances, tooth thickness; verified against Annex F.2 Sample 1 and seed 001
Table 1 (Liu, Chen, Li, Machines 2024, 12, 34); see tests/design/test_blank_sample1.py for which figures are
published and which are checked by an independent construction.
"""

from __future__ import annotations

import math
import warnings

from ..errors import DesignWarning, GeometryError, Problem
from .blank_checks import check_blank, top_land
from .blank_input import TAPERS, BlankInput
from .blank_result import BevelBlank
from .blank_taper import taper_angles
from .blank_dimensions import member_dimensions, pinion_apex_distances
from .blank_thickness import (
    chordal_values,
    mean_normal_thickness,
    thickness_modification_coefficients,
    spiral_angle_at,
    undercut_limit_depth,
    virtual_normal_diameter,
)

__all__ = ["compute_blank", "BlankInput", "BevelBlank", "TAPERS"]


def _spiral_angles(inp: BlankInput, rm: float, re: tuple[float, float], ri: tuple[float, float]) -> dict:
    out, problems = {}, []
    sb = math.sin(inp.beta_m)
    for k in (1, 2):
        for where, r in (("e", re[k - 1]), ("i", ri[k - 1])):
            beta = spiral_angle_at(r, rm, inp.beta_m, inp.rc0)
            if beta is None:
                end = "heel" if where == "e" else "toe"
                reason = (f"the cutter circle through the mean point does not reach the {end} of member {k} "
                          f"(cone distance {r:.6g} mm)")
                if where == "e":
                    lim = (r * r - rm * rm) / (2 * (r - rm * sb))
                    problems.append(Problem("rc0", inp.rc0, f"rc0 >= (Re^2 - Rm^2)/(2*(Re - Rm*sin(beta_m))) = "
                                            f"{lim:.6g}", "mm", reason))
                else:
                    lo = (rm * rm - r * r) / (2 * (r + rm * sb))
                    if r >= rm * sb:
                        allowed = f"rc0 >= (Rm^2 - Ri^2)/(2*(Ri + Rm*sin(beta_m))) = {lo:.6g}"
                    else:  # the toe lies inside the circle the straight trace (rc0 -> inf) is tangent to
                        hi = (rm * rm - r * r) / (2 * (rm * sb - r))
                        allowed = f"{lo:.6g} <= rc0 <= {hi:.6g}"
                    problems.append(Problem("rc0", inp.rc0, allowed, "mm", reason))
            out[f"beta_{where}{k}"] = beta
    if problems:
        raise GeometryError(problems)
    return out


def compute_blank(inp: BlankInput) -> BevelBlank:
    """Compute the blank dimensions of a bevel pair (ISO 23509, face milling): Method 0 for a = 0, Method 1 otherwise.

    A hypoid (a != 0) takes its pitch cones, spiral angles, cones and face widths from
    :func:`~spiralbevel.design.blank_hypoid_dims.hypoid_quantities`; thickness, checks and top lands below are shared,
    with the wheel's Rm2, βm2 where the standard uses them and each member's own Rm, βm for its virtual gear.

    Parameters
    ----------
    inp : BlankInput
        Validated basic data (mm, rad).

    Returns
    -------
    BevelBlank
        Every Method 0 quantity, named by its ISO symbol (angles rad, lengths mm); ``warnings`` lists the
        DesignWarning messages.

    Raises
    ------
    GeometryError
        For impossible geometry (vanishing dedendum, pointed teeth at the mean point, active-flank undercut of the
        pinion, cutter circle not reaching toe or heel), listing every problem.

    Warns
    -----
    DesignWarning
        Face width above 0.3·Re or 10·met, small top land, root undercut, steep taper; see ``blank_checks``.

    Notes
    -----
    Pitch cone: δ1 = atan2(sin Σ, cos Σ + u), δ2 = Σ − δ1; Re2 = de2/(2 sin δ2); Rm = Re2 − b2/2 (the design
    point at mid-face of the wheel, Rm1 = Rm2 = Rm); Ri2 = Re2 − b2; a wider pinion is extended equally at toe and
    heel, Re1 = Rm + b1/2. mmn = dm2·cos βm / z2. Depths (data type II): hmw = k_d·mmn, c = k_c·hmw, hm = hmw + c,
    ham2 = c_ham·hmw, ham1 = hmw − ham2, hfm1 = ham2 + c, hfm2 = ham1 + c, x_hm1 = (ham1 − ham2)/(2·mmn). Heel and
    toe dimensions, diameters and axial positions: :func:`~spiralbevel.design.blank_dimensions.member_dimensions`;
    the pinion's face and root apexes and h_t1 from the wheel's cones and the clearance, as the standard does
    (:func:`~spiralbevel.design.blank_dimensions.pinion_apex_distances`).
    Thickness: x_smn = k_t/2; the outer normal backlash jen (or jet, jen = jet·cos βe2·cos αn) is taken half from
    each member (x_sm1, x_sm2); smn from :func:`~spiralbevel.design.blank_thickness.mean_normal_thickness`;
    jmn = jen·(Rm/Re2)·cos βm/cos βe2 is the mean normal backlash.
    """
    if inp.a != 0.0:
        from .blank_hypoid_dims import hypoid_quantities

        q = hypoid_quantities(inp)
    else:
        q = _method0_quantities(inp)
    rm, beta_m, alpha_n = q["Rm2"], q["beta_m2"], 0.5 * (q["alpha_nD"] + q["alpha_nC"])
    re2, mmn, x_hm1 = q["Re2"], q["mmn"], q["x_hm1"]
    alpha_nD, alpha_nC = q["alpha_nD"], q["alpha_nC"]

    # backlash and thickness (ISO 23509: x_smn = k_t/2 for data type II, backlash half from each member)
    cbe2 = math.cos(q["beta_e2"])
    if inp.jet is not None:
        jet = float(inp.jet)
        jen = jet * cbe2 * math.cos(alpha_n)
    else:
        jen = float(inp.jen or 0.0)
        jet = jen / (cbe2 * math.cos(alpha_n))
    x_smn = 0.5 * float(inp.k_t)
    x_sm1, x_sm2 = thickness_modification_coefficients(x_smn, jen, mmn, rm, re2, beta_m, q["beta_e2"], alpha_n)
    smn1, smn2 = mean_normal_thickness(mmn, x_hm1, x_sm1, x_sm2, alpha_n)
    q.update(jen=jen, jet=jet, jmn=jen * rm * math.cos(beta_m) / (re2 * cbe2), x_smn=x_smn, x_sm1=x_sm1,
             x_sm2=x_sm2, smn1=smn1, smn2=smn2, smt1=smn1 / math.cos(q["beta_m1"]), smt2=smn2 / math.cos(beta_m))
    cos2 = math.cos(alpha_n) ** 2
    for k in (1, 2):
        delta = q[f"delta{k}"]
        dvn = virtual_normal_diameter(q[f"Rm{k}"], delta, q[f"beta_m{k}"], cos2)
        smnc, hamc = chordal_values(q[f"smn{k}"], q[f"ham{k}"], dvn, delta)
        q.update({f"dvn{k}": dvn, f"smnc{k}": smnc, f"hamc{k}": hamc,
                  f"hlim{k}": undercut_limit_depth(dvn, min(alpha_nD, alpha_nC))})

    blank = BevelBlank(**{**q, **{f"sa{w}{k}": math.nan for k in (1, 2) for w in "ime"}}, inp=inp)
    errors, warns = check_blank(blank)
    if errors:
        raise GeometryError(errors)
    lands = {f"sa{w}{k}": top_land(blank, k, w) for k in (1, 2) for w in "ime"}
    for msg in warns:
        warnings.warn(msg, DesignWarning, stacklevel=2)
    return BevelBlank(**{**q, **lands}, warnings=tuple(warns), inp=inp)


def _method0_quantities(inp: BlankInput) -> dict:
    """Every Method 0 quantity (a = 0) before the tooth thickness, keyed by ISO symbol."""
    z1, z2 = inp.z1, inp.z2
    u = z2 / z1
    sigma = inp.shaft_angle
    delta1 = math.atan2(math.sin(sigma), math.cos(sigma) + u)
    delta2 = sigma - delta1
    de2 = inp.de2_value
    met = de2 / z2
    b2, b1 = float(inp.b), inp.b1_value
    re2 = de2 / (2.0 * math.sin(delta2))
    rm = re2 - 0.5 * b2
    ri2 = re2 - b2
    re1, ri1 = rm + 0.5 * b1, rm - 0.5 * b1
    s1, s2 = math.sin(delta1), math.sin(delta2)
    beta_m = float(inp.beta_m)
    dm1, dm2 = 2.0 * rm * s1, 2.0 * rm * s2
    mmt = dm2 / z2
    mmn = mmt * math.cos(beta_m)
    betas = _spiral_angles(inp, rm, (re1, re2), (ri1, ri2))

    alpha_lim = 0.0  # ISO 23509 limit pressure angle, identically 0 when a = 0 (Rm1 = Rm2, beta_m1 = beta_m2)
    alpha_nD, alpha_nC, alpha_eD, alpha_eC, alpha_n = inp.pressure_angles(alpha_lim)

    c_ham = inp.c_ham_value
    hmw, c, ham1, ham2, hfm1, hfm2 = inp.mean_depths(mmn)
    x_hm1 = (ham1 - ham2) / (2.0 * mmn)

    ta = taper_angles(inp.taper, hfm1=hfm1, hfm2=hfm2, rm=rm, re2=re2, met=met, beta_m=beta_m,
                      tan_alpha=math.tan(alpha_n), rc0=inp.rc0, c_ham=c_ham,
                      given={k: getattr(inp, k) for k in ("theta_a1", "theta_a2", "theta_f1", "theta_f2")})
    sum_used = ta.theta_f1 + ta.theta_f2

    q: dict = dict(eta=0.0, zeta_m=0.0, zeta_mp=0.0, ap=0.0, zeta_R=0.0, zeta_o=0.0, c_be2=0.5,
                   rho_lim=math.inf, z1=z1, z2=z2, u=u, Sigma=sigma, a=0.0, hand1=inp.hand1, hand2=inp.hand1.opposite,
                   taper=inp.taper, rc0=float(inp.rc0), c_ham=c_ham, k_d=float(inp.k_d), k_c=float(inp.k_c),
                   k_t=float(inp.k_t), delta1=delta1, delta2=delta2, zp=z2 / s2, b1=b1, b2=b2, Re1=re1, Re2=re2,
                   Rm=rm, Rm1=rm, Rm2=rm, Ri1=ri1, Ri2=ri2, de1=2.0 * re1 * s1, de2=2.0 * re2 * s2, dm1=dm1, dm2=dm2,
                   di1=2.0 * ri1 * s1, di2=2.0 * ri2 * s2, met=met, mmt=mmt, mmn=mmn, beta_m1=beta_m,
                   beta_m2=beta_m, **betas, alpha_nD=alpha_nD, alpha_nC=alpha_nC, alpha_lim=alpha_lim,
                   alpha_eD=alpha_eD, alpha_eC=alpha_eC, alpha_e=0.5 * (alpha_eD + alpha_eC), hmw=hmw, c=c,
                   hm=hmw + c, x_hm1=x_hm1, ham1=ham1, ham2=ham2, hfm1=hfm1, hfm2=hfm2, sum_theta_f=sum_used,
                   sum_theta_fS=ta.sum_theta_fS, sum_theta_fC=ta.sum_theta_fC, sum_theta_fM=ta.sum_theta_fM,
                   theta_a1=ta.theta_a1, theta_a2=ta.theta_a2, theta_f1=ta.theta_f1, theta_f2=ta.theta_f2)

    for k, delta, re, ri in ((1, delta1, re1, ri1), (2, delta2, re2, ri2)):
        dims = member_dimensions(delta=delta, rm=rm, re=re, ri=ri, theta_a=q[f"theta_a{k}"],
                                 theta_f=q[f"theta_f{k}"], ham=q[f"ham{k}"], hfm=q[f"hfm{k}"])
        q.update({f"{name}{k}": v for name, v in dims.items()})
    # the standard takes the pinion's face and root apexes (and so h_t1) from the wheel's cones plus the clearance
    q.update({f"{name}1": v for name, v in pinion_apex_distances(
        delta1=delta1, rm=rm, theta_a1=q["theta_a1"], theta_f1=q["theta_f1"], ham2=ham2, hfm2=hfm2, c=c,
        txo1=q["txo1"]).items()})

    return q
