"""Pitch cones of a hypoid pair: ISO 23509 Method 1 (Gleason), face milling.

:func:`hypoid_pitch_cone` finds the pitch cones, mean cone distances and the two mean spiral angles of a hypoid pair
from the offset, the ratio, the wheel size and the desired pinion spiral angle; :func:`hypoid_offset_angles` gives the
offset angles and the offset in the pitch plane. Scalars in, a dict keyed by ISO symbol out; lengths mm, angles rad.

Sign of the offset (``docs/conventions.md``): a > 0 when the pinion offset follows the hand of spiral of the wheel
(ISO 23509 B.3; the usual automotive hypoid, βm1 > βm2). a = 0 is the spiral bevel pair of Method 0.

References
----------
ISO 23509:2016 (= ANSI/AGMA ISO 23509-B17) 6.2.2, Method 1: approximate wheel pitch angle
δint2 = atan(u·cos ΔΣ / (1.2·(1 − u·sin ΔΣ))), ΔΣ = Σ − 90°, wheel mean pitch radius r_mpt2 = (de2 − b2·sin δint2)/2
(kept for the whole iteration), hypoid dimension factor K1 = tan βΔ1·sin ε'i + cos ε'i, iteration on the wheel offset
angle η until the lengthwise radius of curvature of the tooth, ρ_mβ = rc0 (face milling), equals the limit radius
ρ_lim; limit pressure angle α_lim. Annex F.3 Sample 2 (tests/design/test_blank_hypoid.py).
"""

from __future__ import annotations

import math

from scipy.optimize import brentq

from ..errors import GeometryError, Problem

__all__ = ["hypoid_pitch_cone", "hypoid_offset_angles", "limit_pressure_angle"]


def limit_pressure_angle(rm1: float, rm2: float, delta1: float, delta2: float, beta_m1: float,
                         beta_m2: float) -> float:
    """Limit pressure angle α_lim of a hypoid pair at the mean point (ISO 23509), rad.

    Parameters
    ----------
    rm1, rm2 : float, mm
        Mean cone distances.
    delta1, delta2 : float, rad
        Pitch angles.
    beta_m1, beta_m2 : float, rad
        Mean spiral angles; ζmp = βm1 − βm2 is the offset angle in the pitch plane.

    Returns
    -------
    float, rad
        α_lim = −atan(tan δ1·tan δ2/cos ζmp · (Rm1·sin βm1 − Rm2·sin βm2)/(Rm1·tan δ1 + Rm2·tan δ2)); 0 for a = 0.
    """
    t1, t2 = math.tan(delta1), math.tan(delta2)
    zmp = beta_m1 - beta_m2
    return -math.atan(t1 * t2 / math.cos(zmp) * (rm1 * math.sin(beta_m1) - rm2 * math.sin(beta_m2))
                      / (rm1 * t1 + rm2 * t2))


def _limit_curvature(rm1, rm2, d1, d2, b1, b2, alim):
    """1/ρ_lim (1/mm): finite and smooth through the offsets where ρ_lim itself passes through infinity."""
    ta = math.tan(alim)
    den = (-ta * (math.tan(b1) / (rm1 * math.tan(d1)) + math.tan(b2) / (rm2 * math.tan(d2)))
           + 1.0 / (rm1 * math.cos(b1)) - 1.0 / (rm2 * math.cos(b2)))
    return math.cos(alim) * den / (math.tan(b1) - math.tan(b2))


def _chain(eta: float, a: float, u: float, dsig: float, rmpt2: float, rmn1: float, k1: float, tb_desired: float):
    """One pass of the Method 1 formulas for a trial wheel offset angle η (rad)."""
    cs, ts = math.cos(dsig), math.tan(dsig)
    eps2 = math.asin((a - rmn1 * math.sin(eta)) / rmpt2)
    dint1 = math.atan(math.sin(eta) / (math.tan(eps2) * cs) + ts * math.cos(eta))
    eps2p = math.asin(math.sin(eps2) * cs / math.cos(dint1))
    bint1 = math.atan((k1 - math.cos(eps2p)) / math.sin(eps2p))
    dk = math.sin(eps2p) * (tb_desired - math.tan(bint1))
    drmpt1 = rmpt2 * dk / u
    eps1 = math.asin(math.sin(eps2) - drmpt1 / rmpt2 * math.sin(eta))
    delta1 = math.atan(math.sin(eta) / (math.tan(eps1) * cs) + ts * math.cos(eta))
    eps1p = math.asin(math.sin(eps1) * cs / math.cos(delta1))
    beta_m1 = math.atan((k1 + dk - math.cos(eps1p)) / math.sin(eps1p))
    beta_m2 = beta_m1 - eps1p
    delta2 = math.atan(math.sin(eps1) / (math.tan(eta) * cs) + math.cos(eps1) * ts)
    rm1 = (rmn1 + drmpt1) / math.sin(delta1)
    rm2 = rmpt2 / math.sin(delta2)
    alim = limit_pressure_angle(rm1, rm2, delta1, delta2, beta_m1, beta_m2)
    return dict(eta=eta, delta1=delta1, delta2=delta2, Rm1=rm1, Rm2=rm2, beta_m1=beta_m1, beta_m2=beta_m2,
                alpha_lim=alim, k_lim=_limit_curvature(rm1, rm2, delta1, delta2, beta_m1, beta_m2, alim))


def hypoid_pitch_cone(*, a: float, z1: int, z2: int, shaft_angle: float, de2: float, b2: float, beta_m1: float,
                      rc0: float) -> dict[str, float]:
    """Pitch cone parameters of a hypoid pair, ISO 23509 Method 1 (face milling, ρ_mβ = rc0).

    Parameters
    ----------
    a : float, mm
        Hypoid offset, ISO sign (positive: the pinion offset follows the hand of spiral of the wheel); a != 0.
    z1, z2 : int
        Numbers of teeth.
    shaft_angle : float, rad
        Σ.
    de2 : float, mm
        Outer pitch diameter of the wheel.
    b2 : float, mm
        Wheel face width.
    beta_m1 : float, rad
        Desired mean spiral angle of the pinion βΔ1.
    rc0 : float, mm
        Cutter radius (the lengthwise radius of curvature ρ_mβ of a face-milled tooth).

    Returns
    -------
    dict of str to float
        ``eta`` (wheel offset angle in the axial plane, rad), ``delta1, delta2`` (rad), ``Rm1, Rm2`` (mm),
        ``beta_m1, beta_m2`` (rad), ``alpha_lim`` (rad), ``rho_lim`` (mm, = rc0 at the solution) and ``c_be2``
        (face width factor, (de2/(2 sin δ2) − Rm2)/b2).

    Raises
    ------
    GeometryError
        When no wheel offset angle makes ρ_lim equal rc0 (offset too large for the wheel, or a cutter radius out of
        reach), naming ``a`` and ``rc0``.

    Notes
    -----
    The standard iterates on η; here 1/ρ_lim(η) − 1/rc0 = 0 (smooth where ρ_lim passes through infinity, which
    for small offsets lies next to the root) is bracketed on a grid of η between 0 and asin(|a|/r_mn1)
    (beyond it the pinion offset angle ε2 changes sign) and solved by Brent's method to 1e-13 rad. The result is the
    same root the
    standard's iteration converges to (its stopping rule |rc0/ρ_lim − 1| <= 0.01 % is far looser).
    """
    u = z2 / z1
    dsig = shaft_angle - 0.5 * math.pi
    dint2 = math.atan(u * math.cos(dsig) / (1.2 * (1.0 - u * math.sin(dsig))))
    if dint2 < 0.0:
        dint2 += math.pi
    rmpt2 = 0.5 * (de2 - b2 * math.sin(dint2))
    epsi = math.asin(a * math.sin(dint2) / rmpt2)
    k1 = math.tan(beta_m1) * math.sin(epsi) + math.cos(epsi)
    rmn1 = rmpt2 * k1 / u
    tb = math.tan(beta_m1)

    def resid(eta):
        try:
            r = _chain(eta, a, u, dsig, rmpt2, rmn1, k1, tb)
        except (ValueError, ZeroDivisionError):
            return math.nan
        ok = 0.0 < r["delta1"] < math.pi and 0.0 < r["delta2"] < math.pi and r["Rm1"] > 0.0
        return r["k_lim"] - 1.0 / rc0 if ok else math.nan

    # eps2 keeps the sign of a only while |sin eta| < |a|/rmn1: the physical branch lies in that interval
    eta_max = math.asin(min(1.0, abs(a) / rmn1))
    sgn = 1.0 if a > 0 else -1.0
    etas = [sgn * eta_max * i / 400 for i in range(1, 400)]
    vals = [resid(e) for e in etas]
    root = None
    for e0, e1, v0, v1 in zip(etas, etas[1:], vals, vals[1:]):
        if math.isfinite(v0) and math.isfinite(v1) and v0 * v1 <= 0.0:
            root = brentq(resid, e0, e1, xtol=1e-14, rtol=1e-14)
            break
    if root is None:
        raise GeometryError([Problem("a", a, "an offset for which ISO 23509 Method 1 finds pitch cones with "
                                     f"rho_lim = rc0 = {rc0:g} mm", "mm",
                                     "no wheel offset angle gives a limit radius of curvature equal to the cutter "
                                     "radius: reduce the offset or change rc0")])
    out = _chain(root, a, u, dsig, rmpt2, rmn1, k1, tb)
    out["rho_lim"] = 1.0 / out.pop("k_lim")
    out["c_be2"] = (de2 / (2.0 * math.sin(out["delta2"])) - out["Rm2"]) / b2
    return out


def hypoid_offset_angles(*, a: float, rm1: float, rm2: float, delta1: float, delta2: float,
                         shaft_angle: float) -> dict[str, float]:
    """Offset angles, offset in the pitch plane and crossing-point distances of a hypoid pair (ISO 23509).

    Parameters
    ----------
    a : float, mm
        Hypoid offset (ISO sign).
    rm1, rm2 : float, mm
        Mean cone distances.
    delta1, delta2 : float, rad
        Pitch angles.
    shaft_angle : float, rad
        Σ.

    Returns
    -------
    dict of str to float
        ``zeta_m`` (pinion offset angle in the axial plane, rad), ``zeta_mp`` (in the pitch plane, rad), ``ap``
        (offset in the pitch plane, mm), ``tzm1, tzm2`` (crossing point to the mean point along each axis, mm).

    Notes
    -----
    With dm = 2·Rm·sin δ: ζm = asin(2a/(dm2 + dm1·cos δ2/cos δ1)), ζmp = asin(sin ζm·sin Σ/cos δ1),
    ap = Rm2·sin ζmp, t_zm2 = dm1·sin δ2/(2 cos δ1) − ½·cos ζm·tan ΔΣ·(dm2 + dm1·cos δ2/cos δ1),
    t_zm1 = ½·dm2·cos ζm·cos ΔΣ − t_zm2·sin ΔΣ (ΔΣ = Σ − 90°).
    """
    dm1, dm2 = 2.0 * rm1 * math.sin(delta1), 2.0 * rm2 * math.sin(delta2)
    dsig = shaft_angle - 0.5 * math.pi
    w = dm2 + dm1 * math.cos(delta2) / math.cos(delta1)
    zm = math.asin(2.0 * a / w)
    zmp = math.asin(math.sin(zm) * math.sin(shaft_angle) / math.cos(delta1))
    tzm2 = dm1 * math.sin(delta2) / (2.0 * math.cos(delta1)) - 0.5 * math.cos(zm) * math.tan(dsig) * w
    tzm1 = 0.5 * dm2 * math.cos(zm) * math.cos(dsig) - tzm2 * math.sin(dsig)
    return {"zeta_m": zm, "zeta_mp": zmp, "ap": rm2 * math.sin(zmp), "tzm1": tzm1, "tzm2": tzm2}
