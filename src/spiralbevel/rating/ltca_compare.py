"""The contact pressure of the loaded tooth contact analysis against the ISO 10300 contact stress:
:func:`compare_with_ltca`."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import DesignError
from .inputs import RatingInput
from .rate import rate_iso10300

__all__ = ["compare_with_ltca"]


def compare_with_ltca(blank, inp: RatingInput, ltca) -> dict:
    """Maximum contact pressure of an LTCA over the mesh cycle against sigma_H0 and sigma_H of Method B1 at the same
    torque.

    Parameters
    ----------
    blank : spiralbevel.design.blank_result.BevelBlank
        ISO 23509 blank of the pair (no offset).
    inp : RatingInput
        Rating data; its torque is replaced by the LTCA's.
    ltca : spiralbevel.meshing.ltca.result.LTCAResult
        Loaded TCA of the drive side (read: ``torque`` (gear, N mm), ``max_pressure`` (n_pos,) N/mm^2,
        ``pinion_angles`` (n_pos,) rad, ``load_share`` (n_pos, n_pairs)).

    Returns
    -------
    dict
        ``T1_ltca`` (pinion torque of the LTCA, N m), ``p_max_ltca`` (N/mm^2), ``phi1_at_p_max`` (deg, pinion
        rotation of that position), ``pairs_at_p_max`` (pairs carrying > 0.1 % of the load there), ``sigma_H0`` and
        ``sigma_H`` of Method B1 rated at T1_ltca (N/mm^2), and the ratios ``p_max/sigma_H0``, ``p_max/sigma_H``.

    Notes
    -----
    The pair is re-rated at the LTCA's torque T1 = T2/u (no losses), so the load-dependent factors (K_v, K_Halpha)
    are those of that torque. sigma_H0 is a nominal Hertzian line-contact pressure on the middle contact line, sized
    by an assumed contact pattern (b_veff = 0.85 b) and load sharing (Z_LS); sigma_H adds the load factors K_A, K_v,
    K_Hbeta, K_Halpha that the static LTCA does not have. The LTCA pressure is that of the pair's actual flanks and
    ease-off under the torque: see docs/rating.md for where the two differ.
    """
    p = np.asarray(ltca.max_pressure, dtype=float)
    if p.size == 0 or not np.any(np.isfinite(p)):
        raise DesignError.single("ltca", "<no pressure>", "an LTCA with at least one loaded position", "N/mm^2")
    u = blank.z2 / blank.z1
    T1 = float(ltca.torque) / (1000.0 * u)
    i = int(np.nanargmax(p))
    res = rate_iso10300(blank, dataclasses.replace(inp, T1=T1))
    p_max = float(p[i])
    share = np.asarray(ltca.load_share, dtype=float)[i]
    return {
        "T1_ltca": T1, "p_max_ltca": p_max, "phi1_at_p_max": math.degrees(float(ltca.pinion_angles[i])),
        "pairs_at_p_max": int(np.sum(share > 1e-3)),
        "sigma_H0": res["sigma_H0"], "sigma_H": res["sigma_H"],
        "p_max/sigma_H0": p_max / res["sigma_H0"], "p_max/sigma_H": p_max / res["sigma_H"],
    }
