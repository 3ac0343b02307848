"""Edge radius of the derived cutters of a hypoid member fitted to the generated tooth space at the root.

The derived cutter (:func:`~spiralbevel.machine.default_cutter.default_cutter`) takes the largest edge radius that
fits the slot of a straight-sided tooth space in the mean normal section: point width W = (pi m_mn - s_mn) -
h_fm (tan alpha_nD + tan alpha_nC), and a fillet that takes rho (1 - sin alpha) / cos alpha of it per side. The
generated slot of a hypoid pinion is narrower at the root than that model says, for two reasons:

* its two flanks are cut separately (fixed setting), each with its own cutter radius and settings from the local
  synthesis (Sample 2: 60.2 mm inner blade, 56.3 mm outer blade), so the two sides of the slot are not concentric
  circles and the slot narrows from the mean section toward the toe and the heel;
* the generated profile of a pinion of few teeth is curved (its pressure angle falls toward the root), so the flank
  runs out less over the dedendum than a straight blade line does.

With Sample 2's derived 0.90 mm edge radius the generated fillets of neighbouring pinion teeth cross by 0.04 mm at
the mean section and by 0.62 mm at the heel: the slot does not hold the cutter. The blade surface does not depend on
the edge radius (the blade is defined by its virtual sharp point), so the edge radius is refitted after the basic
settings and the local synthesis without changing them: the largest edge radius at which the generated fillets of
neighbouring teeth meet nowhere along the face, times ``EDGE_RADIUS_FILL`` (the derived cutters' margin).
Only derived edge radii are refitted; a given one is kept (the CAD step then names the key if it does not fit).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.optimize import brentq

from ..conventions import Member, Side
from ..errors import GeometryError
from ..machine.default_cutter import EDGE_RADIUS_FILL

__all__ = ["generated_root_slot", "fit_edge_radii", "largest_fitting_radius", "SLOT_FACE_STATIONS"]

#: face stations at which the generated root slot is checked (toe and heel included)
SLOT_FACE_STATIONS = 31


def _flanks(blank, setups, member, rho):
    from ..design.hypoid_member import member_blank
    from ..generation.flank import generate_flank

    view = member_blank(blank, member)
    out = {}
    for s in (Side.CONVEX, Side.CONCAVE):
        st = setups[(member, s)]
        cutter = st.cutter if rho is None else dataclasses.replace(st.cutter, edge_radius=float(rho))
        out[s] = (cutter, generate_flank(cutter, st.settings, view, member, s))
    return out


def generated_root_slot(blank, setups, member, rho=None, n_face: int = SLOT_FACE_STATIONS) -> np.ndarray:
    """Width (mm, arc at the root, negative where the fillets of neighbouring teeth cross) of the generated tooth
    space of ``member`` at the root at ``n_face`` stations from toe to heel, with the cutters of ``setups`` (edge
    radius ``rho`` mm on both sides, default their own).

    Parameters
    ----------
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
    member : Member
    rho : float, mm, optional
    n_face : int

    Returns
    -------
    (n_face,) float, mm
    """
    from ..geometry.solid import root_slot_width
    from .facemilled import rotate_grid, tooth_rotation
    from .outputs import CAD_FILLET_ROWS

    fl = _flanks(blank, setups, member, rho)
    g = {s: f.grid(n_face, 2, n_fillet=CAD_FILLET_ROWS, curvature=False) for s, (_, f) in fl.items()}
    rot = tooth_rotation(blank, setups, member)     # from the mean points on the blades: independent of rho
    cc = rotate_grid(g[Side.CONCAVE].points, g[Side.CONCAVE].normals, rot)[0]
    z = int(blank.z1 if member is Member.PINION else blank.z2)
    return root_slot_width(g[Side.CONVEX].points, cc, z)


def largest_fitting_radius(room, rho0: float) -> float | None:
    """The edge radius (mm) in (rho0/1000, rho0) at which ``room`` (a function of the edge radius, mm, > 0 where the
    fillet fits) changes sign, by Brent's method to 1e-4 rho0; ``None`` when even rho0/1000 does not fit.

    Parameters
    ----------
    room : callable float -> float
    rho0 : float, mm
        The derived edge radius, at which ``room`` is <= 0.

    Returns
    -------
    float, mm, or None
    """
    lo = 1e-3 * rho0
    if room(lo) <= 0.0:
        return None
    return float(brentq(room, lo, rho0, xtol=1e-4 * rho0))


def fit_edge_radii(spec, blank, setups, synthesis=None):
    """Refit the derived edge radius of each member whose generated root slot does not hold it (module docstring).

    Parameters
    ----------
    spec : DesignFile
    blank : BevelBlank
    setups : {(Member, Side): FlankSetup}
        Modified in place: the cutter and the flank of both sides of a refitted member.
    synthesis : {side name: HypoidSynthesis}, optional
        Modified in place: the pinion cutter and flank of each side follow the refitted setups.

    Returns
    -------
    {Member: (float, float)}
        (derived, fitted) edge radius, mm, of each refitted member.
    """
    from .facemilled import PAIR_SIDES, SIDES, FlankSetup
    from .hypoid import is_formate

    fm = spec.face_milling
    fitted = {}
    for m in (Member.PINION, Member.GEAR):
        if fm.edge_radius is not None or any(getattr(fm, f"{m.value}_{s.value}").cutter is not None for s in SIDES):
            continue                                    # a given edge radius or cutter is the user's
        if m is Member.GEAR and is_formate(spec):
            continue                                    # a Formate gear's slot is the cutter's own: no generated fillet
        rho0 = min(setups[(m, s)].cutter.edge_radius for s in SIDES)
        if generated_root_slot(blank, setups, m).min() > 0.0:
            continue

        def f(r, m=m):
            return float(generated_root_slot(blank, setups, m, r).min())

        try:
            rho_lim = largest_fitting_radius(f, rho0)
        except GeometryError:
            continue
        if rho_lim is None:
            continue                                    # even a sharp blade does not fit: the CAD step says so
        rho = EDGE_RADIUS_FILL * rho_lim
        for s, (cutter, flank) in _flanks(blank, setups, m, rho).items():
            st = setups[(m, s)]
            setups[(m, s)] = FlankSetup(m, s, cutter, st.settings, flank,
                                        f"{st.source}; edge radius {rho:.3f} mm fitted to the generated root slot "
                                        f"(derived {st.cutter.edge_radius:.3f} mm)", st.fit)
        fitted[m] = (float(rho0), float(rho))
        if m is Member.PINION and synthesis:
            for name, res in list(synthesis.items()):
                s1 = PAIR_SIDES[name][0]
                synthesis[name] = dataclasses.replace(res, pinion_cutter=setups[(m, s1)].cutter,
                                                      pinion_flank=setups[(m, s1)].flank)
    return fitted
