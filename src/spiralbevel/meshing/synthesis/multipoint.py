"""Extended local synthesis with multi-point control (seed 001 §4.3.1, Eqs. (16)-(17) as decoded in docs/theory/tca.md,
Eqs. (T5), (T8)).

The pinion of a local synthesis (:func:`~spiralbevel.meshing.synthesis.synthesize_pinion`) meets the gear at the mean
contact point M with a parabolic TE. Multi-point control makes the TE follow a predesigned motion curve, e.g. the
combined motion curve (CMC) of seed 001 §2.2, at chosen pinion rotations (the control points), by giving the pinion's
blank offset E_m1 a different value at every cradle angle:

1. at each control point x_k = phi1 - phi10, solve the 8 x 8 system of docs/theory/tca.md, Eqs. (T5), (T8) — contact of
   the pinion generated
   with the instantaneous offset E_m1 and the gear (coincident points, collinear normals, both equations of meshing of
   generation) plus the CMC condition Delta phi2(x_k) = CMC(x_k) - CMC(0) of Eq. (17) with an absolute tolerance — for
   E_m1 and the contact parameters (``_multipoint_system``: u_1, u_2 from the equations of meshing inside the
   compiled (phi, psi_c) jets, a 6 x 6 system, all control points in one compiled Newton call,
   ``_core.multipoint_newton``, started by continuation from M);
2. the cradle angle psi_c1 at which each control-point contact is generated is the node of the law E_m1(psi_c1);
   between nodes the law is linear (seed 001 §4.3.1 step 3) or the interpolating polynomial (``OffsetLaw``);
3. the pinion generated with a variable offset has dE_m1/dt in its relative velocity (docs/theory/generation.md, Eqs.
   (G5)-(G6)), which
   moves the generated point along the cutter: the rate at every node is taken from the law itself and steps 1-2 are
   repeated until the nodes stop moving (fixed point), so the pinion generated with the final law passes the control
   points exactly;
4. the final pinion flank is regenerated with the law, and the TE at every control point is measured again by the TCA
   contact solver (``ContactProblem``, an independent code path): ``control_point_errors``.

TE is that of :class:`~spiralbevel.meshing.tca_result.TCAResult` (docs/conventions.md), relative to the contact at M:
the target at x is CMC(x) - CMC(0), so that both curves are zero at the mean contact point.
"""

from __future__ import annotations

import math
import numbers
import time
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..._core.rotations import rot_z
from ...conventions import Member
from ...errors import ConvergenceError, DesignError, Problem
from ...generation import generate_flank
from ..contact_problem import ContactProblem
from ..generated_surface import GeneratedSurfaceUPsi
from ..tca import solve_tca
from ..tca_result import ARCSEC
from ._multipoint_system import MultiPointSystem
from .offset_law import INTERPOLATIONS, OffsetLaw

__all__ = ["MultiPointResult", "multipoint_control", "multipoint_tca"]


class _Surface(GeneratedSurfaceUPsi):
    """A generated flank as a TCA contact surface with given reference parameters (the contact at M): the flank's
    own mean point is not located (on a flank generated with a piecewise-linear offset law it may fall between the
    characteristics of two law segments)."""

    def __init__(self, flank, rotation, reference_params):
        self.flank = flank
        self.rotation = float(rotation)
        self._R = rot_z(self.rotation)
        self.reference_params = np.asarray(reference_params, float).copy()


@dataclass(frozen=True, eq=False)
class MultiPointResult:
    """Outcome of :func:`multipoint_control`. Per-control-point arrays are sorted by ``control_points``.

    Attributes
    ----------
    synthesis : SynthesisResult
        The local synthesis the control starts from (cutter, settings with E_m10, gear flank, M, phi10, phi20).
    cmc : callable
        The predesigned motion curve Delta phi2(x), rad of x rad.
    control_points : (n,) float, rad
        x_k = phi1 - phi10, ascending; the mean contact point x = 0 is always one of them (``mean_index``).
    target : (n,) float, rad
        CMC(x_k) - CMC(0).
    offsets : (n,) float, mm
        E_m1 at the control points (E_m10 at the mean point).
    psi_c1 : (n,) float, rad
        Cradle angle at which each control-point contact is generated on the pinion: the nodes of ``law``.
    pinion_params, gear_params : (n, 2) float
        (u mm, psi_c rad) of the contact points on the pinion and the gear.
    phi2 : (n,) float, rad
        Gear rotations at the control points.
    law : OffsetLaw
    pinion_settings : MachineSettings
        The synthesis settings with the law as blank offset.
    pinion_flank : ToothFlank
        The pinion flank generated with the law.
    control_point_errors : (n,) float, rad
        |Delta phi2^t - target| at the control points, measured on the regenerated flank by the TCA contact solver.
    tol_abs : float, rad
    outer_iterations : int
        Fixed-point iterations on the offset rates (step 3).
    elapsed : float, s
    """

    synthesis: Any
    cmc: object
    control_points: np.ndarray
    mean_index: int
    target: np.ndarray
    offsets: np.ndarray
    psi_c1: np.ndarray
    pinion_params: np.ndarray
    gear_params: np.ndarray
    phi2: np.ndarray
    law: OffsetLaw
    pinion_settings: object
    pinion_flank: object
    control_point_errors: np.ndarray
    tol_abs: float
    outer_iterations: int
    elapsed: float
    straight_blades: bool = False

    @property
    def offset_increments(self) -> np.ndarray:
        """E_m1 - E_m10 at the control points, mm (seed 001 Figure 6)."""
        return self.offsets - self.law.base

    @property
    def offset_range(self) -> tuple[float, float]:
        """(min, max) of E_m1 - E_m10 over the control points, mm."""
        d = self.offset_increments
        return float(d.min()), float(d.max())

    def tca_surfaces(self):
        """TCA contact surfaces of the final pinion and the gear, turned so that phi1 = phi2 = 0 is M (phi10, phi20).

        Returns
        -------
        pinion, gear : GeneratedSurface
        start : (5,) float
            (u1, psi_c1, u2, psi_c2, phi2) of the contact at M for :func:`~spiralbevel.meshing.tca.solve_tca`.
        """
        s = self.synthesis
        i = self.mean_index
        pin = _Surface(self.pinion_flank, s.phi1_mean, self.pinion_params[i])
        gear = _Surface(s.gear_flank, s.phi2_mean, self.gear_params[i])
        start = np.r_[self.pinion_params[i], self.gear_params[i], self.phi2[i] - s.phi2_mean]
        return pin, gear, start

    def summary(self) -> dict:
        """Plain dict for reports: angles deg, TE arcsec, lengths mm."""
        d = self.offset_increments
        return {
            "interpolation": self.law.kind,
            "control_points_deg": np.degrees(self.control_points).tolist(),
            "target_te_arcsec": (self.target / ARCSEC).tolist(),
            "blank_offset_mean_mm": self.law.base,
            "blank_offset_mm": self.offsets.tolist(),
            "blank_offset_increment_mm": d.tolist(),
            "blank_offset_increment_range_mm": [float(d.min()), float(d.max())],
            "cradle_angle_nodes_deg": np.degrees(self.psi_c1).tolist(),
            "control_point_errors_rad": self.control_point_errors.tolist(),
            "max_control_point_error_rad": float(np.max(self.control_point_errors)),
            "tol_abs_rad": self.tol_abs,
            "outer_iterations": self.outer_iterations,
            "elapsed_s": self.elapsed,
            "straight_blades": self.straight_blades,
        }


def _validate(synthesis, cmc, control_points, tol_abs, interpolation, max_outer):
    p = []
    for name in ("pinion_flank", "gear_flank", "mean", "pinion_settings", "phi1_mean", "phi2_mean"):
        if not hasattr(synthesis, name):
            p.append(Problem("synthesis", type(synthesis).__name__, "a SynthesisResult", "-"))
            break
    if not callable(cmc):
        p.append(Problem("cmc", type(cmc).__name__, "a callable Delta phi2(x), rad of rad", "-"))
    try:
        x = np.asarray(control_points, float).reshape(-1)
    except (TypeError, ValueError):
        x = None
    if x is None or x.size < 1 or not np.all(np.isfinite(x)) or not np.any(x != 0):
        p.append(Problem("control_points", control_points, "finite pinion rotations from phi10, at least one != 0",
                         "rad"))
    elif x.size and np.max(np.abs(x)) >= math.pi:
        p.append(Problem("control_points", control_points, "|value| < pi", "rad"))
    if not (isinstance(tol_abs, numbers.Real) and 0 < tol_abs < 1e-3):
        p.append(Problem("tol_abs", tol_abs, "0 < value < 1e-3", "rad"))
    if interpolation not in INTERPOLATIONS:
        p.append(Problem("interpolation", interpolation, " or ".join(repr(k) for k in INTERPOLATIONS), "-"))
    if isinstance(max_outer, bool) or not isinstance(max_outer, numbers.Integral) or max_outer < 1:
        p.append(Problem("max_outer", max_outer, "integer >= 1", "-"))
    if p:
        raise DesignError(p)
    return x


def _stations(x, step):
    """Continuation stations from 0 out to every control point (sub-steps <= step): {+1: [...], -1: [...]}."""
    out = {}
    for d in (1, -1):
        pts = np.sort(np.abs(x[np.sign(x) == d]))
        st, cur = [], 0.0
        for p in pts:
            k = max(1, int(math.ceil((p - cur) / step - 1e-9)))
            st.extend(cur + (p - cur) * np.arange(1, k + 1) / k)
            st[-1] = p              # the control point itself, not its rounded sum (a key of the path)
            cur = p
        out[d] = d * np.array(st)
    return out


def _continuation(system, x, target_fn, step):
    """First pass (constant offset rate 0): from M out along both sides, both sides batched at each level."""
    y_mean = system.start()
    phi2_ref = y_mean[4]
    st = _stations(x, step)
    path = {0.0: y_mean}
    prev = {d: [y_mean] for d in (1, -1)}
    levels = max(len(st[1]), len(st[-1]))
    for lev in range(levels):
        sides = [d for d in (1, -1) if lev < len(st[d])]
        xs = np.array([st[d][lev] for d in sides])
        guess = []
        for d in sides:
            h = prev[d]
            guess.append(h[-1] if len(h) < 2 else 2 * h[-1] - h[-2])   # secant predictor (equal sub-steps mostly)
        res = system.solve(np.array(guess), xs, target_fn(xs), np.zeros(len(xs)), phi2_ref, np.zeros(len(xs), bool))
        if not np.all(res.converged):
            bad = xs[~res.converged]
            raise ConvergenceError(f"multi-point control: no contact with the predesigned TE at phi1 - phi10 = "
                                   f"{bad.tolist()} rad (continuation from the mean point)", res.iterations,
                                   float(np.max(res.residual)), res.x)
        for d, xv, yv in zip(sides, xs, res.x):
            prev[d].append(yv)
            path[float(xv)] = yv
    return np.array([path[float(v)] for v in x])


def _law(kind, y, base):
    order = np.argsort(y[:, 1])
    return OffsetLaw(kind, y[order, 1], y[order, 5] - base, base)


def multipoint_control(synthesis, cmc, control_points, *, tol_abs: float = 1e-9, interpolation: str = "linear",
                       max_outer: int = 30, step: float | None = None,
                       straight_blades: bool = False) -> MultiPointResult:
    """Blank-offset law of the pinion that makes the TE pass through a predesigned motion curve at control points.

    Parameters
    ----------
    synthesis : SynthesisResult
        Local synthesis of the pinion (its blank offset E_m10 is kept at the mean contact point).
    cmc : callable
        Predesigned Delta phi2(x) (rad) of x = phi1 - phi10 (rad), e.g. a
        :class:`~spiralbevel.meshing.motion_curves.CombinedMotionCurve`; only differences CMC(x) - CMC(0) matter.
    control_points : (k,) float, rad
        Pinion rotations from phi10 at which the TE is controlled; 0 (the mean point) is added when absent.
    tol_abs : float, rad
        Absolute tolerance of Eq. (17), |Delta phi2^t - Delta phi2| < tol_abs (docs/theory/tca.md, Eq. (T8)), checked on
        the regenerated flank.
    interpolation : {"linear", "spline", "polynomial"}
        Law between the nodes: piecewise linear (seed 001 §4.3.1 step 3), natural cubic spline, or the interpolating
        polynomial (see :class:`~.offset_law.OffsetLaw`); "spline" gives a smooth flank for TCA.
    max_outer : int
        Cap on the fixed-point iterations on the offset rates.
    step : float, rad, optional
        Largest continuation step of the first pass (default pi / (4 z1)).
    straight_blades : bool
        Solve (and verify) on flanks generated with the straight blades continued down to the tip plane, as seed 001
        Eq. (16) (part (a) of the cutter only), so that control points may lie where the real contact has reached a
        fillet; the returned flank has the real edge radius (see ``multipoint_tca``).

    Returns
    -------
    MultiPointResult

    Raises
    ------
    DesignError
        Invalid arguments, or control points generated at coinciding cradle angles.
    ConvergenceError
        No contact with the predesigned TE at some control point, or the fixed point or the tolerance not reached.
    """
    t0 = time.perf_counter()
    xs = _validate(synthesis, cmc, control_points, tol_abs, interpolation, max_outer)
    x = np.unique(np.concatenate([xs, [0.0]]))
    i0 = int(np.nonzero(x == 0.0)[0][0])
    mean = x == 0.0
    sharp = (_sharp(synthesis.pinion_flank), _sharp(synthesis.gear_flank)) if straight_blades else (None, None)
    system = MultiPointSystem(synthesis, *sharp)
    z1 = system.kin.z1
    c0 = float(cmc(0.0))

    def target_fn(v):
        return np.asarray(cmc(np.asarray(v, float)), float) - c0

    target = target_fn(x)
    if not np.all(np.isfinite(target)):
        raise DesignError.single("cmc", "non-finite values", "finite Delta phi2 at the control points", "rad")
    y = _continuation(system, x, target_fn, step if step is not None else math.pi / (4 * z1))
    base = system.offset0
    # ---- fixed point on the offset rates (step 3): the contact at node k is generated with E'(psi_k) of the law
    for it in range(1, max_outer + 1):  # noqa: B007 - it is reported after the loop
        law = _law(interpolation, y, base)
        res = system.solve(y, x, target, law.rate(y[:, 1]), y[i0, 4], mean)
        if not np.all(res.converged):
            raise ConvergenceError("multi-point control: a control-point system diverged in the fixed-point iteration",
                                   res.iterations, float(np.max(res.residual)), res.x)
        change = max(np.max(np.abs(res.x[:, 1] - y[:, 1])) / 1e-11, np.max(np.abs(res.x[:, 5] - y[:, 5])) / 1e-12)
        y, (p1, p2) = res.x, res.params
        if change < 1.0:        # nodes fixed to 1e-11 rad and 1e-12 mm
            break
    else:
        raise ConvergenceError(f"multi-point control: offset rates not consistent after {max_outer} iterations "
                               f"(last scaled change {change:.3g})", max_outer, float(change), y)
    law = _law(interpolation, y, base)
    y = np.concatenate([p1, p2, y[:, 4:6]], -1)    # (u1, psi_c1, u2, psi_c2, phi2, E_m1)
    below = (y[:, 0] < system.gen.cp["u_j"]) | (y[:, 2] < system.gear.generator.cp["u_j"])
    if np.any(below):       # the systems are solved on the blades (continued past the fillet junction)
        raise DesignError.single("control_points", x[below].tolist(), "pinion rotations whose controlled contact "
                                 "lies on the blades of both members (see active_range)", "rad",
                                 "the contact there is below a fillet junction")
    settings = law.settings(synthesis.pinion_settings)
    flank = generate_flank(synthesis.pinion_cutter, settings, _blank_of(synthesis), Member.PINION,
                           synthesis.pinion_flank.side)
    errors = _verify(synthesis, _sharp(flank) if straight_blades else flank, law, x, target, y, i0,
                     sharp[1] or synthesis.gear_flank, straight_blades)
    result = MultiPointResult(
        synthesis=synthesis, cmc=cmc, control_points=x, mean_index=i0, target=target, offsets=y[:, 5],
        psi_c1=y[:, 1], pinion_params=y[:, 0:2].copy(), gear_params=y[:, 2:4].copy(), phi2=y[:, 4].copy(), law=law,
        pinion_settings=settings, pinion_flank=flank, control_point_errors=errors, tol_abs=float(tol_abs),
        outer_iterations=it, elapsed=time.perf_counter() - t0, straight_blades=bool(straight_blades))
    if np.max(errors) >= tol_abs:
        raise ConvergenceError(f"multi-point control: TE at the control points off the predesigned curve by up to "
                               f"{np.max(errors):.3g} rad (tol_abs {tol_abs:g} rad)", it, float(np.max(errors)),
                               result)
    return result


def _blank_of(synthesis):
    """The pinion's blank data (hand and axial outline) as ``generate_flank`` reads it, from the synthesized flank."""
    return _outline_blank(synthesis.pinion_flank)


def _outline_blank(flank):
    """Blank data (hand and axial outline) of a generated flank, as ``generate_flank`` reads them."""
    ol, i = flank.outline, flank.member.index
    return SimpleNamespace(**{f"hand{i}": flank.hand, f"delta{i}": ol.delta, f"delta_a{i}": ol.delta_a,
                              f"delta_f{i}": ol.delta_f, "Rm": ol.Rm, f"Re{i}": ol.Re, f"Ri{i}": ol.Ri,
                              f"ham{i}": ol.ham, f"hfm{i}": ol.hfm, "Re2": ol.Re, "Ri2": ol.Ri})


def _verify(synthesis, flank, law, x, target, y, i0, gear_flank, straight_blades):
    """|TE - target| at the control points on the regenerated pinion, by the TCA contact solver (``ContactProblem``).

    Smooth laws: the regenerated flank itself, all points in one batch. Linear law: at each node, the flank of the
    law's segment on the side of psi_c = 0 (``OffsetLaw.local``), which is the regenerated flank on that segment."""
    kin = synthesis.mean.kinematics
    gear = _Surface(gear_flank, synthesis.phi2_mean, y[i0, 2:4])
    x0 = np.concatenate([y[:, 0:4], (y[:, 4] - synthesis.phi2_mean)[:, None]], -1)
    if law.kind != "linear":
        prob = ContactProblem(_Surface(flank, synthesis.phi1_mean, y[i0, 0:2]), gear, kin)
        sol, conv, res, _, _ = prob.solve(x, x0, tol=1e-11)
    else:
        sol, conv, res = np.empty_like(x0), np.zeros(x.size, bool), np.zeros(x.size)
        blank = _blank_of(synthesis)
        for k in range(x.size):
            fl = generate_flank(flank.cutter, law.local(y[k, 1], synthesis.pinion_settings), blank,
                                Member.PINION, synthesis.pinion_flank.side)
            prob = ContactProblem(_Surface(fl, synthesis.phi1_mean, y[k, 0:2]), gear, kin)
            a, b, c, _, _ = prob.solve(x[k:k + 1], x0[k:k + 1], tol=1e-11)
            sol[k], conv[k], res[k] = a[0], b[0], c[0]
    if not np.all(conv):
        raise ConvergenceError("multi-point control: no contact on the regenerated pinion at phi1 - phi10 = "
                               f"{x[~conv].tolist()} rad", 30, float(np.max(res)), sol)
    drive = synthesis.mean.drive_sign
    te = drive * (-(sol[:, 4] - sol[i0, 4]) - kin.z1 / kin.z2 * x)
    return np.abs(te - target)


def multipoint_tca(result: MultiPointResult, *, n_positions: int = 61, pairs=(-1, 0, 1), misalignment=None,
                   straight_blades: bool = False, **kw):
    """TCA of the final pair over one mesh cycle centred on M (phi1 = 0 at phi10), see
    :func:`~spiralbevel.meshing.tca.solve_tca` (keywords pass through).

    Parameters
    ----------
    result : MultiPointResult
        With a smooth law ("spline" or "polynomial"): the flank generated with the linear law jumps along the cutter
        at every node (see :mod:`~spiralbevel.meshing.synthesis.offset_law`), which the TCA surface model does not
        cover.
    straight_blades : bool
        Generate both flanks with the straight blade continued down to the tip plane (edge radius 1e-4 mm) instead of
        the real edge radius: the surfaces of seed 001 Eq. (16), which uses the straight-edge part (a) only. The
        flanks are identical above the fillet junctions; below them the contact is the idealized one of the paper,
        whose surfaces have no edges (``flank_bounds=False`` of solve_tca unless given).
    """
    if result.law.kind == "linear":
        raise DesignError.single("interpolation", "linear", "'spline' or 'polynomial' for TCA of the whole cycle", "-",
                                 "the pinion generated with a piecewise-linear blank offset is not one smooth surface "
                                 "(the offset rate, hence the generated point, jumps at every node)")
    pin, gear, start = result.tca_surfaces()
    if straight_blades:
        pin = _Surface(_sharp(pin.flank), pin.rotation, pin.reference_params)
        gear = _Surface(_sharp(gear.flank), gear.rotation, gear.reference_params)
        kw.setdefault("flank_bounds", False)
    return solve_tca(pin, gear, result.synthesis.mean.kinematics, misalignment=misalignment, phi1_mean=0.0,
                     n_positions=n_positions, pairs=pairs, start=start, **kw)


def _sharp(flank):
    """The same flank generated by a cutter with a 1e-4 mm edge radius (straight blade down to the tip plane)."""
    from dataclasses import replace

    return generate_flank(replace(flank.cutter, edge_radius=1e-4), flank.settings, _outline_blank(flank),
                          flank.member, flank.side)
