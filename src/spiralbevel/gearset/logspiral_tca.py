"""TCA of a designed log-spiral pair and its report section: line contact and zero transmission error expected."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..conventions import Member, Side
from ..errors import ConvergenceError, NoContactError
from ..meshing.kinematics import BevelPairKinematics
from ..meshing.tca import solve_tca
from ..meshing.tca_surfaces import LogSpiralSurface


def contact_surface(pair, member, side) -> LogSpiralSurface:
    """The placed flank of a :class:`LogSpiralPair` as a TCA contact surface, parameters (varphi, phi)."""
    f = pair.flank(member, side)
    d = f.domain
    return LogSpiralSurface(rho0=f.surface.rho0, delta=f.surface.base_cone_angle, beta=f.surface.spiral_angle,
                            azimuth=f.rotation, psi_range=(d.psi_min, d.psi_max), phi_range=(d.phi_min, d.phi_max),
                            reference_params=tuple(pair.mean_parameters(member, side)))


#: pinion positions of the TCA of a designed log-spiral pair over one mesh cycle (line contact, zero TE expected)
LOGSPIRAL_TCA_POSITIONS = 21

#: the two pair sides of a log-spiral pair: (pinion side, gear side)
LOGSPIRAL_SIDES = {"convex-concave": (Side.CONVEX, Side.CONCAVE), "concave-convex": (Side.CONCAVE, Side.CONVEX)}


def logspiral_tca(pair, n_positions: int = LOGSPIRAL_TCA_POSITIONS):
    """TCA of both sides of the pair. Returns ({name: TCAResult or None}, report section)."""
    results: dict[str, Any] = {}
    section: dict[str, dict[str, Any]] = {}
    for name in LOGSPIRAL_SIDES:
        results[name], section[name] = logspiral_side_tca(pair, name, n_positions)
    return results, section


def logspiral_side_tca(pair, name: str, n_positions: int = LOGSPIRAL_TCA_POSITIONS):
    """TCA of one side (``"convex-concave"`` or ``"concave-convex"``, pinion side first). Returns (TCAResult or None,
    report section)."""
    from ..errors import DesignError

    if name not in LOGSPIRAL_SIDES:
        raise DesignError.single("side", name, "'convex-concave' or 'concave-convex' (log-spiral pair)", "-")
    kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
    s1, s2 = LOGSPIRAL_SIDES[name]
    c1, c2 = contact_surface(pair, Member.PINION, s1), contact_surface(pair, Member.GEAR, s2)
    p1 = pair.mean_point(Member.PINION, s1).point
    phi1_mean = -math.atan2(p1[1], p1[0])          # turns the pinion mean point onto the pitch line
    start = np.r_[c1.reference_params, c2.reference_params, -kin.ratio * phi1_mean]
    try:
        res = solve_tca(c1, c2, kin, phi1_mean=phi1_mean, n_positions=n_positions, start=start)
    except (NoContactError, ConvergenceError) as err:
        return None, {"error": str(err)}
    te = res.te_arcsec
    fin = np.isfinite(te)
    return res, {
        "pinion_side": s1.value, "gear_side": s2.value, "positions": int(len(te)),
        "line_contact_positions": int(np.sum(res.line_contact)),
        "max_abs_transmission_error_arcsec": float(np.max(np.abs(te[fin]))) if np.any(fin) else None,
    }
