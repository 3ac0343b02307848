"""Tooth contact analysis of a face-milled pair in the main job (drive and coast sides)."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member, Side
from ..errors import ConvergenceError, NoContactError
from ..meshing.generated_surface import phased_for_pair
from ..meshing.kinematics import BevelPairKinematics
from ..meshing.tca import solve_tca

SIDES = {"drive": (Side.CONCAVE, Side.CONVEX), "coast": (Side.CONVEX, Side.CONCAVE)}  # (pinion side, gear side)


def run_pair_tca(blank, setups, grids, n_positions: int = 41):
    """TCA of both sides. Returns ({side: TCAResult or None}, report section, {side: (outline1, outline2)})."""
    kin = BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
    results, section, outlines = {}, {}, {}
    for name, (s1, s2) in SIDES.items():
        p, g = setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank
        c1, c2 = phased_for_pair(p, g)
        start = np.r_[c1.reference_params, c2.reference_params, 0.0]
        try:
            res = solve_tca(c1, c2, kin, n_positions=n_positions, start=start)
        except (NoContactError, ConvergenceError) as err:
            results[name] = None
            section[name] = {"pinion_side": s1.value, "gear_side": s2.value, "error": str(err)}
            continue
        results[name] = res
        outlines[name] = (grids[(Member.PINION, s1)].points @ c1._R.T, grids[(Member.GEAR, s2)].points @ c2._R.T)
        te = res.te_arcsec
        fin = np.isfinite(te)
        if not np.any(fin):
            results[name] = None
            section[name] = {"pinion_side": s1.value, "gear_side": s2.value, "error": "no contact at any position"}
            continue
        edge = np.nonzero(res.edge_contact)[0]
        section[name] = {
            "pinion_side": s1.value, "gear_side": s2.value,
            "positions": int(len(te)),
            "max_transmission_error_arcsec": float(np.max(te[fin])),
            "min_transmission_error_arcsec": float(np.min(te[fin])),
            "peak_to_peak_arcsec": float(np.ptp(te[fin])),
            "no_contact_positions_rad": [float(x) for x in res.phi1[~fin]],
            "transfer_points_rad": [float(x) for x in np.atleast_1d(res.transfer_phi1)],
            "edge_contact_positions_rad": [float(res.phi1[i]) for i in edge],
            "semi_major_axis_mean_mm": _finite_or_none(np.max(res.semi_axes[len(te) // 2])),
            "pinion_rotation_rad": res.phi1[fin], "transmission_error_arcsec": te[fin],
        }
    return results, section, outlines


def _finite_or_none(x):
    x = float(x)
    return x if math.isfinite(x) else None
