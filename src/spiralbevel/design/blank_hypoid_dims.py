"""Pitch cone, depths, cones, face widths and spiral angles of a hypoid blank (ISO 23509 Method 1, face milling).

:func:`hypoid_quantities` gives every quantity of the dimension sheet up to (not including) the tooth thickness,
keyed by ISO symbol in ASCII; :func:`~spiralbevel.design.blank.compute_blank` adds thickness, checks and top lands as
for Method 0. Lengths mm, angles rad.

References
----------
ISO 23509:2016 (= ANSI/AGMA ISO 23509-B17), Method 1 (Gleason) and the gear dimensions for a != 0: wheel root and face
angles from the taper, pinion face and root angles from the wheel's root and face cones through the offset angles in
the root and face planes ζR, ζo; face and root apexes; pinion face width from the wheel face width projected through
the offset (λ', b_reri1, Δb_x1, Δg_xe, Δg_xi); pinion heel and toe spiral angles from the wheel's at the pinion's
boundary points. Annex F.3 Sample 2 (tests/design/test_blank_hypoid.py).
"""

from __future__ import annotations

import math

from ..errors import DesignError, GeometryError, Problem
from .blank_dimensions import member_dimensions
from .blank_hypoid import hypoid_offset_angles, hypoid_pitch_cone
from .blank_input import BlankInput
from .blank_taper import taper_angles
from .blank_thickness import spiral_angle_at

__all__ = ["hypoid_quantities"]


def _asin(x: float, sym: str, what: str) -> float:
    if not -1.0 <= x <= 1.0:
        raise GeometryError([Problem(sym, round(x, 6), "-1 <= sin <= 1", "-", f"{what} is not defined: the offset "
                                     "a is too large for this wheel")])
    return math.asin(x)


def _spiral(r, rm2, beta_m2, rc0, sym):
    beta = spiral_angle_at(r, rm2, beta_m2, rc0)
    if beta is None:
        raise GeometryError([Problem("rc0", rc0, f"a cutter circle through the mean point reaching cone distance "
                                     f"{r:.6g} mm", "mm", f"{sym}: the cutter circle does not reach this end of the "
                                     "face")])
    return beta


def hypoid_quantities(inp: BlankInput) -> dict:
    """Dimension-sheet quantities of a hypoid pair (a != 0) before the tooth thickness; see :func:`_quantities`.

    Raises
    ------
    GeometryError
        Naming ``a`` when a formula of Method 1 is not defined for these data (an inverse sine or tangent out of
        range: the offset is too large for the wheel, or the face too wide), never a bare ``ValueError``.
    """
    try:
        return _quantities(inp)
    except DesignError:
        raise
    except (ValueError, ZeroDivisionError, OverflowError) as err:
        raise GeometryError([Problem("a", inp.a, "an offset for which the ISO 23509 Method 1 formulas are defined",
                                     "mm", f"the hypoid geometry has no solution for these data ({err}); reduce the "
                                     "offset, the face width or the spiral angle")]) from None


def _quantities(inp: BlankInput) -> dict:
    """Dimension-sheet quantities of a hypoid pair (a != 0) before the tooth thickness.

    Parameters
    ----------
    inp : BlankInput
        Validated basic data with a != 0; ``beta_m`` is the desired pinion mean spiral angle βΔ1.

    Returns
    -------
    dict
        ISO symbols as in ``blank_meta.QUANTITIES`` (without thickness and top lands).

    Raises
    ------
    GeometryError
        When the pitch-cone iteration or an offset angle has no solution.

    Notes
    -----
    Wheel: Re2 = Rm2 + c_be2·b2, Ri2 = Re2 − b2, met = de2/z2, mmn = dm2·cos βm2/z2; the taper is that of Method 0
    with the wheel's Rm2, βm2. Pinion: ζR = asin(a·sin δf2/(Rm2·cos θf2 − t_z2·cos δf2)) (Σ = 90°; the standard's
    auxiliary angle φR corrects Σ != 90°), δa1 = asin(sin ΔΣ·sin δf2 + cos ΔΣ·cos δf2·cos ζR), likewise δf1 from the
    wheel face cone and ζo; θa1 = δa1 − δ1, θf1 = δ1 − δf1; t_zF1 = (a·sin ζR·cos δf2 − t_zR2·sin δf2 − c)/sin δa1,
    t_zR1 = (a·sin ζo·cos δa2 − t_zF2·sin δa2 − c)/sin δf1; h_t1 in the standard's form
    ((t_zF1 + t_xo1)/cos δa1)·sin(θa1 + θf1) − (t_zR1 − t_zF1)·sin δf1.
    """
    a, z1, z2, sig = float(inp.a), inp.z1, inp.z2, inp.shaft_angle
    u = z2 / z1
    de2, b2, rc0 = inp.de2_value, float(inp.b), float(inp.rc0)
    pc = hypoid_pitch_cone(a=a, z1=z1, z2=z2, shaft_angle=sig, de2=de2, b2=b2, beta_m1=float(inp.beta_m), rc0=rc0)
    d1, d2, rm1, rm2, bm1, bm2 = (pc[k] for k in ("delta1", "delta2", "Rm1", "Rm2", "beta_m1", "beta_m2"))
    cbe2 = pc["c_be2"]
    off = hypoid_offset_angles(a=a, rm1=rm1, rm2=rm2, delta1=d1, delta2=d2, shaft_angle=sig)
    zmp, ap = off["zeta_mp"], off["ap"]
    dsig = sig - 0.5 * math.pi
    s1, s2 = math.sin(d1), math.sin(d2)
    dm1, dm2 = 2.0 * rm1 * s1, 2.0 * rm2 * s2
    re2 = rm2 + cbe2 * b2
    ri2 = re2 - b2
    met = de2 / z2
    mmn = dm2 * math.cos(bm2) / z2

    alim = pc["alpha_lim"]
    alpha_nD, alpha_nC, alpha_eD, alpha_eC, alpha_n = inp.pressure_angles(alim)

    c_ham = inp.c_ham_value
    hmw, c, ham1, ham2, hfm1, hfm2 = inp.mean_depths(mmn)
    ta = taper_angles(inp.taper, hfm1=hfm1, hfm2=hfm2, rm=rm2, re2=re2, met=met, beta_m=bm2,
                      tan_alpha=math.tan(alpha_n), rc0=rc0, c_ham=c_ham,
                      given={k: getattr(inp, k) for k in ("theta_a1", "theta_a2", "theta_f1", "theta_f2")})
    th_a2, th_f2 = ta.theta_a2, ta.theta_f2
    da2, df2 = d2 + th_a2, d2 - th_f2
    tz2 = rm2 * math.cos(d2) - off["tzm2"]

    def pinion_cone(d_w, th_w, sym):  # offset angle in the wheel's root (face) plane and the pinion's mating cone
        den = rm2 * math.cos(th_w) - tz2 * math.cos(d_w)
        phi = math.atan(a * math.tan(dsig) * math.cos(th_w) / den)
        zeta = _asin(a * math.cos(phi) * math.sin(d_w) / den, sym, "the pinion offset angle") - phi
        return zeta, _asin(math.sin(dsig) * math.sin(d_w) + math.cos(dsig) * math.cos(d_w) * math.cos(zeta),
                           sym, "the pinion cone angle")

    zeta_R, da1 = pinion_cone(df2, th_f2, "zeta_R")
    zeta_o, df1 = pinion_cone(da2, th_a2, "zeta_o")
    th_a1, th_f1 = da1 - d1, d1 - df1

    # pinion face width (the wheel face width projected through the offset)
    lam = math.atan(math.sin(zmp) * math.cos(d2) / (u * math.cos(d1) + math.cos(d2) * math.cos(zmp)))
    breri1 = b2 * math.cos(lam) / math.cos(zmp - lam)
    dbx1 = hmw * math.sin(zeta_R) * (1.0 - 1.0 / u)
    dgxe = cbe2 * breri1 / math.cos(th_a1) * math.cos(da1) + dbx1 - (hfm2 - c) * s1
    dgxi = (1.0 - cbe2) * breri1 * math.cos(da1) / math.cos(th_a1) + dbx1 + (hfm2 - c) * s1
    be1 = (dgxe + ham1 * s1) / math.cos(da1) * math.cos(th_a1)
    bi1 = (dgxi - ham1 * s1) / (math.cos(d1) - math.tan(th_a1) * s1)
    re1, ri1 = rm1 + be1, rm1 - bi1

    # spiral angles at heel and toe: the wheel's cutter circle, seen from the pinion's boundary points
    re21 = math.sqrt(rm2 * rm2 + be1 * be1 + 2.0 * rm2 * be1 * math.cos(zmp))
    ri21 = math.sqrt(rm2 * rm2 + bi1 * bi1 - 2.0 * rm2 * bi1 * math.cos(zmp))
    betas = dict(beta_e2=_spiral(re2, rm2, bm2, rc0, "beta_e2"), beta_i2=_spiral(ri2, rm2, bm2, rc0, "beta_i2"),
                 beta_e1=_spiral(re21, rm2, bm2, rc0, "beta_e1") + math.asin(ap / re21),
                 beta_i1=_spiral(ri21, rm2, bm2, rc0, "beta_i1") + math.asin(ap / ri21))

    q: dict = dict(z1=z1, z2=z2, u=u, Sigma=sig, a=a, hand1=inp.hand1, hand2=inp.hand1.opposite, taper=inp.taper,
                   rc0=rc0, c_ham=c_ham, k_d=float(inp.k_d), k_c=float(inp.k_c), k_t=float(inp.k_t),
                   delta1=d1, delta2=d2, zp=z2 / s2, b1=be1 + bi1, b2=b2, Re1=re1, Re2=re2, Rm=rm2, Rm1=rm1, Rm2=rm2,
                   Ri1=ri1, Ri2=ri2, de1=2.0 * re1 * s1, de2=2.0 * re2 * s2, dm1=dm1, dm2=dm2, di1=2.0 * ri1 * s1,
                   di2=2.0 * ri2 * s2, met=met, mmt=dm2 / z2, mmn=mmn, beta_m1=bm1, beta_m2=bm2, **betas,
                   alpha_nD=alpha_nD, alpha_nC=alpha_nC, alpha_lim=alim, alpha_eD=alpha_eD, alpha_eC=alpha_eC,
                   alpha_e=0.5 * (alpha_eD + alpha_eC), hmw=hmw, c=c, hm=hmw + c, x_hm1=(ham1 - ham2) / (2.0 * mmn),
                   ham1=ham1, ham2=ham2, hfm1=hfm1, hfm2=hfm2, sum_theta_f=th_f1 + th_f2,
                   sum_theta_fS=ta.sum_theta_fS, sum_theta_fC=ta.sum_theta_fC, sum_theta_fM=ta.sum_theta_fM,
                   theta_a1=th_a1, theta_a2=th_a2, theta_f1=th_f1, theta_f2=th_f2, eta=pc["eta"],
                   zeta_m=off["zeta_m"], zeta_mp=zmp, ap=ap, zeta_R=zeta_R, zeta_o=zeta_o, c_be2=cbe2,
                   rho_lim=pc["rho_lim"])
    for k, delta, rm, re, ri in ((1, d1, rm1, re1, ri1), (2, d2, rm2, re2, ri2)):
        dims = member_dimensions(delta=delta, rm=rm, re=re, ri=ri, theta_a=q[f"theta_a{k}"], theta_f=q[f"theta_f{k}"],
                                 ham=q[f"ham{k}"], hfm=q[f"hfm{k}"], tzm=off[f"tzm{k}"])
        q.update({f"{name}{k}": v for name, v in dims.items()})
    # the pinion's face and root apexes from the wheel's root and face cones plus the clearance (ISO 23509)
    tzF1 = (a * math.sin(zeta_R) * math.cos(df2) - q["tzR2"] * math.sin(df2) - c) / math.sin(da1)
    tzR1 = ((a * math.sin(zeta_o) * math.cos(da2) - q["tzF2"] * math.sin(da2) - c) / math.sin(df1)
            if df1 > 0.0 else math.inf)
    ht1 = (tzF1 + q["txo1"]) / math.cos(da1) * math.sin(th_a1 + th_f1) - (tzR1 - tzF1) * math.sin(df1)
    q.update(tzF1=tzF1, tzR1=tzR1, ht1=ht1)
    return q
