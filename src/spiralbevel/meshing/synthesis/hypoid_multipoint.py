"""Multi-point control of a hypoid pair: the pinion's blank offset varied with the cradle angle so that the TE follows a
predesigned motion curve (e.g. the fourth-order combined motion curve, CMC) at chosen pinion rotations, with the
crossed-axes kinematics of the pair.

The method is that of the spiral bevel pair (:mod:`~spiralbevel.meshing.synthesis.multipoint`: Fuentes, Litvin et al.,
seed 001 §4.3.1, Eqs. (16)-(17), docs/theory/tca.md, Eqs. (T5), (T8)); what assumed intersecting axes there is the
placement of the two members in the pair frame. The control-point systems (``_multipoint_system``, compiled
``_core.multipoint_newton``) carry the pitch apexes o1 = (0, E, 0) + t1 a1 and o2 = t2 a2 of
:class:`~spiralbevel.meshing.hypoid_kinematics.HypoidPairKinematics` (zero for intersecting axes: the spiral bevel
systems unchanged), and the TCA that verifies the control points and runs over the mesh cycle (``ContactProblem``,
``solve_tca``) places the pair by the same ``axes()``. The hypoid local synthesis
(:func:`~spiralbevel.meshing.synthesis.hypoid_local.synthesize_hypoid_pinion`) supplies the start: M is the pitch
point of the blank and E_m10 the synthesized pinion's blank offset (the blank offset of the generating machine, the
constant term of the universal generator's vertical motion; the law found here is its variation with psi_c).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from ...errors import DesignError
from ..tca_result import ARCSEC
from ..motion_curves import seed001_cmc
from .cmc_design import active_range, te_summary
from .hypoid_local import HypoidSynthesis
from .multipoint import MultiPointResult, multipoint_control

__all__ = ["HypoidCMCSynthesis", "as_multipoint_synthesis", "design_hypoid_cmc", "hypoid_multipoint_control",
           "hypoid_multipoint_tca", "multipoint_surfaces"]


def as_multipoint_synthesis(synthesis):
    """The view of a :class:`~spiralbevel.meshing.synthesis.hypoid_local.HypoidSynthesis` that multi-point control
    reads (the attributes of the spiral bevel ``SynthesisResult`` it uses: flanks, settings, cutter, phi10, phi20,
    the pinion parameters of M and ``mean`` with the point, normal, gear parameters, drive sign and kinematics).

    The hypoid synthesis' own ``summary()`` is kept for reports.
    """
    mp = synthesis.gear_flank.mean_point()     # M on the wheel (its mean point turned into the pitch point)
    mean = SimpleNamespace(point=np.asarray(synthesis.point, float), normal=np.asarray(synthesis.normal, float),
                           gear_params=np.array([mp.u, mp.psi_c], float), drive_sign=int(synthesis.drive_sign),
                           kinematics=synthesis.kinematics)
    return SimpleNamespace(pinion_cutter=synthesis.pinion_cutter, pinion_settings=synthesis.pinion_settings,
                           pinion_flank=synthesis.pinion_flank, gear_flank=synthesis.gear_flank, mean=mean,
                           phi1_mean=float(synthesis.phi1_mean), phi2_mean=float(synthesis.phi2_mean),
                           pinion_params=np.asarray(synthesis.pinion_params, float), summary=synthesis.summary,
                           hypoid=synthesis)


def hypoid_multipoint_control(synthesis, cmc, control_points, **kw) -> MultiPointResult:
    """Blank-offset law E_m1(psi_c1) of a hypoid pinion that makes the TE pass through a predesigned motion curve at
    the control points (crossed axes at the pair's offset E).

    Parameters
    ----------
    synthesis : HypoidSynthesis
        Local synthesis of the hypoid pinion (its blank offset E_m10 is kept at the mean contact point M, the pitch
        point); a spiral bevel ``SynthesisResult`` is passed through unchanged.
    cmc, control_points, **kw
        As :func:`~spiralbevel.meshing.synthesis.multipoint.multipoint_control` (``tol_abs``, ``interpolation``,
        ``max_outer``, ``step``, ``straight_blades``).

    Returns
    -------
    MultiPointResult
        ``synthesis`` is the view of :func:`as_multipoint_synthesis` (``.hypoid`` the HypoidSynthesis); its
        ``mean.kinematics`` the pair's ``HypoidPairKinematics``.

    Raises
    ------
    DesignError, ConvergenceError
        As ``multipoint_control``.
    """
    view = synthesis if hasattr(synthesis, "mean") else as_multipoint_synthesis(synthesis)
    return multipoint_control(view, cmc, control_points, **kw)


def multipoint_surfaces(result: MultiPointResult):
    """TCA contact surfaces of the controlled pair in the (phi, psi_c) chart of
    :class:`~spiralbevel.meshing.generated_surface.GeneratedSurface` (the chart of the hypoid TCA,
    :func:`~.hypoid_local.tca_surfaces`), turned by phi10, phi20 so that phi1 = phi2 = 0 is M.

    ``MultiPointResult.tca_surfaces`` gives the (u, psi_c) chart of the control systems; at a position where a tooth
    pair meets at the fillet edge the TCA in that chart may report a surface contact on the blade continued past the
    fillet junction (Sample 2, drive, at the end of the mesh cycle: 0.31 arcsec off the brute-force oracle, while
    this chart agrees with it to 2e-6 arcsec).

    Returns
    -------
    pinion, gear : GeneratedSurface
    start : (5,) float
        (phi_1, psi_c1, phi_2, psi_c2, phi2) of the contact at M for ``solve_tca``.
    """
    from ..generated_surface import GeneratedSurface

    s, i = result.synthesis, result.mean_index
    out = []
    flank: Any
    for flank, rot, (u, psi) in ((result.pinion_flank, s.phi1_mean, result.pinion_params[i]),
                                 (s.gear_flank, s.phi2_mean, result.gear_params[i])):
        surf = GeneratedSurface(flank, rot)
        phi = float(flank.generator.contact(np.array(u), np.array(psi))["phi"])
        surf.reference_params = np.array([phi, float(psi)])
        out.append(surf)
    pin, gear = out
    return pin, gear, np.r_[pin.reference_params, gear.reference_params, result.phi2[i] - s.phi2_mean]


def hypoid_multipoint_tca(result: MultiPointResult, *, n_positions: int = 61, pairs=(-1, 0, 1), misalignment=None,
                          **kw):
    """TCA of the controlled hypoid pair over one mesh cycle centred on M (phi1 = 0 at phi10), with the pair's offset
    kinematics, on the surfaces of :func:`multipoint_surfaces` (keywords pass through to
    :func:`~spiralbevel.meshing.tca.solve_tca`, e.g. ``misalignment``).

    Parameters
    ----------
    result : MultiPointResult
        With a smooth law ("spline" or "polynomial"), as ``multipoint_tca``.
    """
    from ..tca import solve_tca

    if result.law.kind == "linear":
        raise DesignError.single("interpolation", "linear", "'spline' or 'polynomial' for TCA of the whole cycle", "-",
                         "the pinion generated with a piecewise-linear blank offset is not one smooth surface")
    pin, gear, start = multipoint_surfaces(result)
    return solve_tca(pin, gear, result.synthesis.mean.kinematics, misalignment=misalignment, phi1_mean=0.0,
                     n_positions=n_positions, pairs=pairs, start=start, **kw)


@dataclass(frozen=True, eq=False)
class HypoidCMCSynthesis(HypoidSynthesis):
    """A hypoid local synthesis whose pinion is then controlled to a predesigned motion curve
    (:func:`design_hypoid_cmc`): the fields of :class:`~.hypoid_local.HypoidSynthesis` with the controlled pinion
    (``pinion_settings`` carry the blank-offset law, ``pinion_flank`` is generated with it), plus

    Attributes
    ----------
    local : HypoidSynthesis
        The local synthesis the control starts from (constant blank offset E_m10).
    multipoint : MultiPointResult
    tca : TCAResult or None
        TCA of the controlled pair over one mesh cycle (None with the linear law).
    """

    local: Any = None
    multipoint: Any = None
    tca: Any = None

    def summary(self) -> dict:
        """The local synthesis' summary (its settings: the synthesis before the control), the multi-point control
        (``multipoint``), the final pinion settings and the TCA against the curve (``tca``, arcsec)."""
        out = self.local.summary()
        out["multipoint"] = self.multipoint.summary()
        out["pinion_settings_final"] = self.pinion_settings.to_dict(degrees=True)
        cmc = self.multipoint.cmc
        if hasattr(cmc, "a"):
            out["cmc"] = {"a": list(cmc.a), "b1_deg": math.degrees(cmc.b1), "b2_arcsec": cmc.b2 / ARCSEC,
                          "b3_deg": math.degrees(cmc.b3), "shift_arcsec": cmc.shift / ARCSEC,
                          "units": "a2 1/rad, a3 1/rad^2, a4 1/rad^3 (x and Delta phi2 in rad)"}
        if self.tca is not None:
            out["tca"] = te_summary(self.tca, self.multipoint)
        return out


def design_hypoid_cmc(synthesis, *, te_magnitude: float, n_control: int = 11, interpolation: str = "spline",
                      cmc=None, n_positions: int = 61) -> HypoidCMCSynthesis:
    """Multi-point control of a synthesized hypoid pinion to the predesigned combined motion curve (the hypoid
    counterpart of :func:`~spiralbevel.meshing.synthesis.cmc_design.design_seed001_style` after its synthesis).

    Parameters
    ----------
    synthesis : HypoidSynthesis
    te_magnitude : float, rad
        Magnitude of the CMC (seed 001 Steps 1-4, ``seed001_cmc``), e.g. the synthesis' TE level.
    n_control : int
        Control points, evenly spread over the part of the mesh cycle where the contact stays on the active flanks
        of both members (``active_range``).
    interpolation : {"spline", "linear", "polynomial"}
        Blank-offset law between the nodes; the TCA of the whole cycle needs "spline" or "polynomial".
    cmc : callable, optional
        Predesigned Delta phi2(x) (default ``seed001_cmc(te_magnitude, z1)``).
    n_positions : int
        TCA positions over one mesh cycle.

    Returns
    -------
    HypoidCMCSynthesis
    """
    if isinstance(n_control, bool) or not isinstance(n_control, int) or n_control < 3:
        raise DesignError.single("n_control", n_control, "integer >= 3", "-")
    view = as_multipoint_synthesis(synthesis)
    z1 = synthesis.kinematics.z1
    if cmc is None:
        cmc = seed001_cmc(te_magnitude, z1)
    lo, hi = active_range(view)
    mp = multipoint_control(view, cmc, np.linspace(lo, hi, n_control), interpolation=interpolation)
    tca = hypoid_multipoint_tca(mp, n_positions=n_positions) if interpolation != "linear" else None
    fields = {f.name: getattr(synthesis, f.name) for f in dataclasses.fields(HypoidSynthesis)}
    fields.update(pinion_settings=mp.pinion_settings, pinion_flank=mp.pinion_flank)
    return HypoidCMCSynthesis(**fields, local=synthesis, multipoint=mp, tca=tca)
