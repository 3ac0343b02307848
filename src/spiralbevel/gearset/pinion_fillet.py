"""Edge radius of a synthesized pinion's cutter refitted so that its generated fillet stays below the gear's top.

The local synthesis moves the pinion's machine settings off the blank's basic ones (blank offset, machine centre to
back, ratio of roll), and with them the generated root: on a 36/61 design at a 1.1 deg spiral angle the synthesized
coast pinion's root lies 0.81 mm above the root cone at the heel. The fillet/blade junction of the generated flank
lies about rho (1 - sin alpha) above the generated root (edge radius rho, blade angle alpha: 1.1 mm for the derived
1.669 mm), so 1.9 mm above the root cone, while the gear's top reaches only the clearance c (1.16 mm) above it: the
gear's tooth meets the pinion's fillet, and the TCA shows an edge contact.

The blade surface does not depend on the edge radius (the blade is defined by its virtual sharp point:
``HeadCutter``), so the edge radius is refitted after the synthesis without changing the blade, the settings or the
mean-point fit: the largest edge radius at which the junction line lies at or below the gear's top at every face
station, times ``EDGE_RADIUS_FILL`` (the derived cutters' margin), the same search as the hypoid slot fit
(:func:`~spiralbevel.gearset.hypoid_fillet.largest_fitting_radius`). Only a derived edge radius is refitted, and
only made smaller.

The gear's top in the pinion's axial section: both members share the pitch generatrix, so at the cone distance R the
gear's face cone lies c(R) = h_f1(R) - h_a2(R) above the pinion's root cone, with h_f1(R) = h_fm1 + (R - R_m)
tan(theta_f1) and h_a2(R) = h_am2 + (R - R_m) tan(theta_a2) (ISO 23509 dedendum and addendum angles).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..conventions import Member

__all__ = ["junction_height", "gear_top_height", "fit_pinion_edge_radius", "JUNCTION_STATIONS"]

#: face stations (toe to heel, both included) at which the junction line is held below the gear's top
JUNCTION_STATIONS = 7


def junction_height(flank, n_face: int = JUNCTION_STATIONS) -> np.ndarray:
    """Height (mm) of the generated fillet/blade junction line (u = u_j) above the blank's root cone at ``n_face``
    face stations evenly in cone distance from toe to heel.

    Parameters
    ----------
    flank : ToothFlank
    n_face : int

    Returns
    -------
    (n_face,) float, mm
    """
    ol, gen = flank.outline, flank.generator
    R = np.linspace(ol.Ri, ol.Re, n_face)
    mp = flank.mean_point()
    xj = flank._locator.junction(R, (mp.theta + np.pi - gen.mp["q"] + mp.psi_c, mp.psi_c))   # as ToothFlank.grid
    p = gen.evaluate_at(np.full(n_face, gen.cp["u_j"]), xj[:, 1], xj[:, 2], curvature=False).points
    Rx, h = ol.Rh(p[:, 2], np.hypot(p[:, 0], p[:, 1]))
    return h - ol.h_root(Rx)


def gear_top_height(blank, R) -> np.ndarray:
    """Height (mm) of the gear's face cone above the pinion's root cone at cone distances ``R`` (mm), (module
    docstring): the clearance, growing or shrinking along the face with theta_f1 - theta_a2.

    Parameters
    ----------
    blank : BevelBlank
    R : (n,) float, mm

    Returns
    -------
    (n,) float, mm
    """
    R = np.asarray(R, float)
    rm = float(blank.Rm)
    hf1 = float(blank.hfm1) + (R - rm) * math.tan(float(blank.delta1) - float(blank.delta_f1))
    ha2 = float(blank.ham2) + (R - rm) * math.tan(float(blank.delta_a2) - float(blank.delta2))
    return hf1 - ha2


def fit_pinion_edge_radius(blank, res, n_face: int = JUNCTION_STATIONS):
    """The synthesis result ``res`` with its pinion cutter's edge radius refitted (module docstring), or ``res``
    itself when its fillet already stays below the gear's top or no edge radius fits (then the TCA shows the fillet
    contact).

    Parameters
    ----------
    blank : BevelBlank
    res : SynthesisResult
    n_face : int

    Returns
    -------
    SynthesisResult
    """
    from ..errors import GeometryError
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL
    from .hypoid_fillet import largest_fitting_radius

    cutter, settings, side = res.pinion_cutter, res.pinion_settings, res.pinion_flank.side
    R = np.linspace(res.pinion_flank.outline.Ri, res.pinion_flank.outline.Re, n_face)
    top = gear_top_height(blank, R)

    def flank(r):
        return generate_flank(dataclasses.replace(cutter, edge_radius=float(r)), settings, blank, Member.PINION, side)

    def room(r):   # > 0: the junction lies below the gear's top at every station
        return float(np.min(top - junction_height(flank(r), n_face)))

    try:
        if room(cutter.edge_radius) > 0.0:
            return res
        rho = largest_fitting_radius(room, cutter.edge_radius)
    except GeometryError:
        return res
    if rho is None:
        return res
    rho *= EDGE_RADIUS_FILL
    new = dataclasses.replace(cutter, edge_radius=rho)
    return dataclasses.replace(res, pinion_cutter=new, pinion_flank=flank(rho))
