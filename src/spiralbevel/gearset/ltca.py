"""Loaded tooth contact analysis of a face-milled pair (design-file section ``[ltca]``) and its report section."""

from __future__ import annotations

import warnings

import numpy as np

from .._core.rotations import rot_z
from ..conventions import Member, Side
from ..errors import NoContactError, SpiralBevelWarning
from ..meshing.pair import meshing_pair
from ..meshing.tca import solve_tca
from ..meshing.tca_result import ContactStatus
from .facemilled import tooth_rotation
from .tca import SIDES


def _rz(a):
    return rot_z(float(a))


def _tooth_grids(grids, member, tca_side, surface_rotation, rot):
    """(convex, concave) point grids of one tooth in the TCA surface's frame: the TCA flank carries the surface's
    phasing rotation; the other flank of the tooth is placed by the tooth rotation ``rot`` (concave = convex turned
    by rot, gearset.facemilled.tooth_rotation)."""
    cx, cc = grids[(member, Side.CONVEX)], grids[(member, Side.CONCAVE)]
    if tca_side is Side.CONCAVE:
        return cx @ _rz(surface_rotation - rot).T, cc @ _rz(surface_rotation).T
    return cx @ _rz(surface_rotation).T, cc @ _rz(surface_rotation + rot).T


def _surface_peak(res, model):
    """Largest pressure (N/mm^2) over the loaded points of pairs in surface contact (not ``PairContact.edge``: TCA
    status ok/line)."""
    best = 0.0
    for i, (pr, p) in enumerate(zip(res.pair_of_point, res.pressure)):
        edge = np.array([pc is not None and pc.edge for pc in model.positions[i].pairs], bool)
        surf = ~edge[np.asarray(pr, int)]
        if np.any(surf):
            best = max(best, float(np.nanmax(np.asarray(p)[surf], initial=0.0)))
    return best


def _mean_extents(model):
    """Half extents (mm) of the potential-contact grid of the leading pair at the position nearest phi1 = phi10."""
    i = int(np.argmin([abs(p.pinion_angle) for p in model.positions]))
    ext = [pc.extents for pc in model.positions[i].pairs if pc is not None and pc.extents is not None]
    return [float(v) for v in ext[0]] if ext else [model.half_length, model.half_width]


def run_ltca_job(spec, blank, setups):
    """Unloaded TCA, FE tooth compliance and the loaded cycle of the design's ``[ltca]`` section. Returns
    (LTCAResult or None, report section)."""
    return run_ltca(blank, setups, spec.ltca)


def run_ltca(blank, setups, lt, pair=None):
    """Unloaded TCA, FE tooth compliance and the loaded cycle with the options ``lt`` (an ``[ltca]`` section,
    :class:`~spiralbevel.io.design_schema.LTCASpec`). Returns (LTCAResult or None, report section).

    ``pair`` (a :class:`~spiralbevel.meshing.pair.MeshingPair` of the ``lt.side`` flanks of ``setups``) replaces the
    intersecting-axes assembly of the blank: the hypoid pair with the offset kinematics
    (:func:`~spiralbevel.gearset.hypoid.hypoid_pair`). The FE tooth segments are built from the same flank grids in
    each member's own frame either way; the pair's kinematics place them, so loads act along the common normal and
    the moment arms are taken about each member's own axis."""
    from ..meshing.ltca import Material, ltca_model

    s1, s2 = SIDES[lt.side]
    if pair is None:
        pair = meshing_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, blank)
    c1, c2, kin = pair.pinion, pair.gear, pair.kinematics
    tca = solve_tca(c1, c2, kin, n_positions=lt.positions, start=pair.start)
    nf, npf = lt.flank_grid
    grids = {k: st.flank.grid(nf, npf, curvature=False).points for k, st in setups.items()}
    pin = _tooth_grids(grids, Member.PINION, s1, c1.rotation, tooth_rotation(blank, setups, Member.PINION))
    gear = _tooth_grids(grids, Member.GEAR, s2, c2.rotation, tooth_rotation(blank, setups, Member.GEAR))
    material = Material(youngs_modulus=lt.youngs_modulus, poisson_ratio=lt.poisson_ratio)
    try:
        model = ltca_model(c1, c2, kin, tca, pinion_grids=pin, gear_grids=gear, sides=(s1.value, s2.value),
                           material=material, grid=tuple(lt.contact_grid))
    except NoContactError as err:
        # a position without a contact of the real flanks (edge contact only, or none): no loaded cycle
        msg = f"LTCA {lt.side} side: {err}; no loaded transmission error or pressure reported"
        warnings.warn(msg, SpiralBevelWarning, stacklevel=2)
        return None, {"side": lt.side, "status": "too few contact positions", "error": msg,
                      "edge_contacts": [{"position": i, "pair": k, "member": m, "edge": e}
                                        for i, k, m, e in tca.edges]}
    T_app = model.approach_torque()
    T = T_app if lt.torque == "approach" else float(lt.torque) * 1000.0
    res = model.run(T)
    te_l, te_u = np.asarray(res.te_loaded), np.asarray(res.te_unloaded)
    fin_l, fin_u = np.isfinite(te_l), np.isfinite(te_u)
    if not np.any(fin_l) or not np.any(fin_u):
        raise NoContactError(f"loaded TCA, {lt.side} side: no contact at any of the {lt.positions} positions")
    ext = te_l[fin_l][np.argmax(np.abs(te_l[fin_l]))]
    section = {
        "side": lt.side, "torque_N_m": T / 1000.0, "torque_for_approach_N_m": T_app / 1000.0,
        "approach_mm": 0.00635,
        # the signed TE of largest magnitude over the cycle (negative: the gear lags), loaded and unloaded
        "loaded_transmission_error_largest_magnitude_arcsec": float(ext),
        "unloaded_transmission_error_largest_magnitude_arcsec": float(te_u[fin_u][np.argmax(np.abs(te_u[fin_u]))]),
        "loaded_te_peak_to_peak_arcsec": float(np.ptp(te_l[fin_l])),
        "status": "ok",
        "max_contact_pressure_N_per_mm2": float(np.nanmax(res.max_pressure)),
        # surface contacts only: at an edge contact (a sharp boundary curve of one flank on the other, TCA status
        # edge) the pressure peaks at the edge and grows with the grid; the surface-contact peak is the converged one
        "max_contact_pressure_surface_N_per_mm2": _surface_peak(res, model),
        "edge_contact_positions": int(np.sum(tca.status == ContactStatus.EDGE)),
        # the pressure is that of the solved field on each contact's own grid (uniform-pressure cells); the grid of
        # each position and pair spans 1.25 x the Hertz ellipse of that contact at an approach of 4 x 0.00635 mm
        "contact_grid": {"points": list(model.grid), "half_extents_at_mean_mm": _mean_extents(model)},
        "positions_with_two_pairs_loaded": int(np.sum(np.sum(res.load_share > 1e-3, axis=1) > 1)),
        "pinion_rotation_deg": np.degrees(res.pinion_angles), "loaded_transmission_error_arcsec": te_l,
        "unloaded_transmission_error_arcsec": te_u, "load_share": res.load_share,
        "pair_names": list(res.pair_names),
        "material": {"youngs_modulus_N_per_mm2": lt.youngs_modulus, "poisson_ratio": lt.poisson_ratio},
    }
    return res, section
