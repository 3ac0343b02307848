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

from types import SimpleNamespace

import numpy as np

from .multipoint import MultiPointResult, multipoint_control, multipoint_tca

__all__ = ["as_multipoint_synthesis", "hypoid_multipoint_control", "hypoid_multipoint_tca"]


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


def hypoid_multipoint_tca(result: MultiPointResult, **kw):
    """TCA of the controlled hypoid pair over the mesh cycle centred on M, with the pair's offset kinematics
    (:func:`~spiralbevel.meshing.synthesis.multipoint.multipoint_tca`; keywords pass through, e.g. ``misalignment``,
    ``n_positions``)."""
    return multipoint_tca(result, **kw)
