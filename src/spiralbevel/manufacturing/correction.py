"""Corrective machine settings from measured flank deviations (sensitivity matrix + regularized least squares).

The sensitivity matrix J (n_points x n_parameters) holds the normal deviation at each grid point per unit change of
each chosen setting: the flank is regenerated with the setting changed by +-h, re-located on the same circles
(axial, radius) as the nominal grid points, and the displacement is projected on the nominal outward normal,

    J[:, k] = ((r(+h_k) - r(-h_k)) . n0) / (2 h_k)          (central differences, error O(h^2)),

which is the first-order change of the distance along the nominal normal line (the measured CMM quantity). Units:
mm of deviation per mm (lengths), per rad (angles), per unit (ratio of roll, 2C, 6D).

:func:`correct_settings` solves J x ~ d for the setting change x that explains the measured deviation d (positive =
material added) by a truncated, Tikhonov-regularized SVD of the column-scaled matrix, optionally refined by chord
Gauss-Newton steps on the exact (regenerated) deviation, and returns the corrected settings = settings - x: cutting
with them is predicted to bring the flank back to nominal (to first order, up to the unexplained residual).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError, DesignError, GeometryError
from ..generation.flank import generate_flank
from .measurement import MeasurementGrid, measure_deviation

__all__ = ["PARAMETERS", "DEFAULT_PARAMETERS", "CorrectionResult", "sensitivity_matrix", "apply_changes",
           "correct_settings"]

#: name -> (owner, field, index, default step, unit)
PARAMETERS = {
    "radial_setting": ("settings", "radial_setting", None, 1e-3, "mm"),
    "cradle_angle": ("settings", "cradle_angle", None, 1e-5, "rad"),
    "machine_root_angle": ("settings", "machine_root_angle", None, 1e-5, "rad"),
    "sliding_base": ("settings", "sliding_base", None, 1e-3, "mm"),
    "machine_centre_to_back": ("settings", "machine_centre_to_back", None, 1e-3, "mm"),
    "blank_offset": ("settings", "blank_offset", None, 1e-3, "mm"),
    "ratio_of_roll": ("settings", "ratio_of_roll", None, 1e-5, "-"),
    "modified_roll_2C": ("settings", "modified_roll", 0, 1e-4, "-"),
    "modified_roll_6D": ("settings", "modified_roll", 1, 1e-3, "-"),
    "blade_angle": ("cutter", "blade_angle", None, 1e-5, "rad"),
    "point_radius": ("cutter", "point_radius", None, 1e-3, "mm"),
}
#: machine settings only (no cutter change); condition number about 620 on the seed 001 flanks (9 x 5 grid)
DEFAULT_PARAMETERS = ("radial_setting", "cradle_angle", "machine_root_angle", "ratio_of_roll", "modified_roll_2C",
                      "modified_roll_6D")


def _check_parameters(parameters) -> tuple:
    if isinstance(parameters, str):
        parameters = (parameters,)
    parameters = tuple(parameters)
    bad = [p for p in parameters if p not in PARAMETERS]
    if bad or not parameters or len(set(parameters)) != len(parameters):
        raise DesignError.single("parameters", parameters, f"distinct names from {sorted(PARAMETERS)}", "-")
    return parameters


def apply_changes(cutter, settings, changes: dict) -> tuple[Any, Any]:
    """(cutter, settings) with the named parameters changed by the given amounts (see ``PARAMETERS``)."""
    s_changes, c_changes = {}, {}
    for name, delta in changes.items():
        owner, field, index, _, _ = PARAMETERS[name]
        if owner == "cutter":
            c_changes[field] = getattr(cutter, field) + float(delta)
        elif index is None:
            s_changes[field] = getattr(settings, field) + float(delta)
        else:
            coeffs = list(s_changes.get(field, settings.modified_roll))
            coeffs += [0.0] * (index + 1 - len(coeffs))
            coeffs[index] += float(delta)
            s_changes[field] = tuple(coeffs)
    return (dataclasses.replace(cutter, **c_changes) if c_changes else cutter,
            settings.replace(**s_changes) if s_changes else settings)


def _located_shift(cutter, settings, blank, member, side, grid):
    fp = generate_flank(cutter, settings, blank, member, side).locate(grid.axial, grid.radius, curvature=False)
    return np.einsum("...i,...i->...", fp.points - grid.points, grid.normals)


def sensitivity_matrix(cutter, settings, blank, member, side, grid: MeasurementGrid,
                       parameters=DEFAULT_PARAMETERS, steps: dict | None = None) -> np.ndarray:
    """Normal deviation at each grid point per unit change of each setting (central differences).

    Parameters
    ----------
    cutter : HeadCutter
    settings : MachineSettings
    blank, member, side
        As for ``generate_flank``; the nominal flank of ``grid``.
    grid : MeasurementGrid
        Nominal grid of that flank.
    parameters : sequence of str
        Names from ``PARAMETERS``: radial_setting, cradle_angle, machine_root_angle, sliding_base,
        machine_centre_to_back, blank_offset, ratio_of_roll, modified_roll_2C, modified_roll_6D, blade_angle,
        point_radius.
    steps : dict, optional
        Finite-difference steps per name (units of the parameter); defaults in ``PARAMETERS``.

    Returns
    -------
    (n_face * n_profile, n_parameters) float
        mm per unit of each parameter (mm/mm, mm/rad, mm per unit ratio); rows in the grid's C order.
    """
    parameters = _check_parameters(parameters)
    steps = dict(steps or {})
    J = np.empty((grid.size, len(parameters)))
    for k, name in enumerate(parameters):
        h = float(steps.get(name, PARAMETERS[name][3]))
        if not (np.isfinite(h) and h > 0):
            raise DesignError.single(f"steps[{name}]", h, "> 0", PARAMETERS[name][4])
        plus = _located_shift(*apply_changes(cutter, settings, {name: h}), blank, member, side, grid)
        minus = _located_shift(*apply_changes(cutter, settings, {name: -h}), blank, member, side, grid)
        J[:, k] = ((plus - minus) / (2.0 * h)).ravel()
    return J


@dataclass(frozen=True)
class CorrectionResult:
    """Outcome of :func:`correct_settings`.

    Attributes
    ----------
    parameters : tuple of str
        Parameters solved for.
    identified : dict
        name -> estimated change of that setting that explains the measured deviation (the part behaves as if cut
        with settings + identified); 0 for parameters flagged not identifiable.
    settings, cutter : MachineSettings, HeadCutter
        Corrected settings and cutter = nominal - identified.
    identifiable, not_identifiable : tuple of str
        Split of ``parameters`` by the rank test (pivoted QR on the column-scaled sensitivity matrix).
    singular_values : (n_parameters,) float
        Of the column-scaled sensitivity matrix (columns of unit norm), descending.
    condition_number : float
        sigma_max / sigma_min of the column-scaled matrix of all ``parameters`` (inf when singular).
    condition_number_used : float
        The same for the identifiable subset that was solved.
    rank : int
        Number of singular values above ``rcond * sigma_max``.
    residual : (n_face, n_profile) float, mm
        Deviation left unexplained after the correction (measured - model(identified)): the predicted deviation of
        a flank cut with the corrected settings.
    rms_before, rms_after : float, mm
        RMS of the measured deviation and of ``residual``.
    sensitivity : (n_points, n_parameters) float
        The sensitivity matrix used.
    """

    parameters: tuple
    identified: dict
    settings: object
    cutter: object
    identifiable: tuple
    not_identifiable: tuple
    singular_values: np.ndarray
    condition_number: float
    condition_number_used: float
    rank: int
    residual: np.ndarray
    rms_before: float
    rms_after: float
    sensitivity: np.ndarray


def _cond(s):
    return float(s[0] / s[-1]) if s[-1] > 0 else float("inf")


def correct_settings(cutter, settings, blank, member, side, grid: MeasurementGrid, measured_deviation,
                     parameters=DEFAULT_PARAMETERS, regularization: float = 0.0, rcond: float = 1e-3,
                     iterations: int = 2, sensitivity: np.ndarray | None = None) -> CorrectionResult:
    """Least-squares corrective machine settings from a measured normal deviation.

    Parameters
    ----------
    cutter, settings, blank, member, side
        Cutter and settings the measured flank was cut with (the nominal ones), blank, member and side.
    grid : MeasurementGrid
        Nominal grid the measurement refers to.
    measured_deviation : (n_face, n_profile) array_like, mm
        Normal deviation, positive = material added (``read_measured_deviation`` or ``measure_deviation``).
    parameters : sequence of str
        Settings to correct (see ``sensitivity_matrix``).
    regularization : float, -
        Tikhonov parameter lambda relative to the largest singular value of the column-scaled matrix: the solution
        minimizes |J x - d|^2 + (lambda sigma_max)^2 |S x|^2, S the column norms (0: plain least squares).
    rcond : float, -
        Singular values below ``rcond * sigma_max`` count as zero; that many parameters (the last ones chosen by
        QR with column pivoting) are flagged not identifiable and left unchanged.
    iterations : int
        Solves: 1 = one linear least-squares step; each further one a chord Gauss-Newton step on the exact
        deviation of a flank regenerated with the current estimate (same matrix).
    sensitivity : (n_points, n_parameters) array, optional
        Precomputed ``sensitivity_matrix`` for the same parameters.

    Returns
    -------
    CorrectionResult
    """
    from scipy.linalg import qr

    parameters = _check_parameters(parameters)
    d = np.asarray(measured_deviation, float)
    if d.shape != grid.shape or not np.all(np.isfinite(d)):
        raise DesignError.single("measured_deviation", f"shape {d.shape}", f"finite values of shape {grid.shape}",
                                 "mm")
    for name, val, ok, allowed in (("regularization", regularization, lambda v: v >= 0, ">= 0"),
                                   ("rcond", rcond, lambda v: 0 < v < 1, "0 < value < 1")):
        if not (isinstance(val, (int, float)) and np.isfinite(val) and ok(val)):
            raise DesignError.single(name, val, allowed, "-")
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)) or iterations < 1:
        raise DesignError.single("iterations", iterations, "integer >= 1", "-")
    J = sensitivity if sensitivity is not None else sensitivity_matrix(cutter, settings, blank, member, side, grid,
                                                                       parameters)
    J = np.asarray(J, float)
    if J.shape != (grid.size, len(parameters)):
        raise DesignError.single("sensitivity", f"shape {J.shape}", f"({grid.size}, {len(parameters)})", "mm/unit")
    scale = np.linalg.norm(J, axis=0)
    scale = np.where(scale > 0, scale, 1.0)
    Js = J / scale
    sv = np.linalg.svd(Js, compute_uv=False)
    rank = int(np.sum(sv > rcond * sv[0]))
    _, _, piv = qr(Js, mode="economic", pivoting=True)
    keep = np.sort(piv[:rank])
    drop = np.sort(piv[rank:])
    U, s, Vt = np.linalg.svd(Js[:, keep], full_matrices=False)
    lam = regularization * sv[0]
    filt = s / (s ** 2 + lam ** 2)

    def solve(rhs):
        return Vt.T @ (filt * (U.T @ rhs)) / scale[keep]

    x = np.zeros(len(parameters))
    x[keep] = solve(d.ravel())
    r = d
    for it in range(iterations):
        changes = {p: x[k] for k, p in enumerate(parameters)}
        try:
            model = measure_deviation(generate_flank(*apply_changes(cutter, settings, changes), blank, member, side),
                                      grid)
        except (DesignError, GeometryError) as err:
            shown = {k: round(float(v), 9) for k, v in changes.items()}
            raise ConvergenceError(
                f"correct_settings: the flank cannot be regenerated with the identified setting changes {shown} "
                f"({err}); the problem is ill-conditioned (condition number {_cond(sv):.3g}): use "
                "regularization > 0, a larger rcond or fewer parameters", iterations=it,
                residual=float(np.sqrt(np.mean(np.square(r)))), last=x.copy()) from err
        r = d - model
        if it + 1 < iterations:
            x[keep] += solve(r.ravel())
    identified = {p: float(x[k]) for k, p in enumerate(parameters)}
    c_new, s_new = apply_changes(cutter, settings, {p: -v for p, v in identified.items()})
    rms = lambda a: float(np.sqrt(np.mean(np.square(a))))  # noqa: E731
    return CorrectionResult(
        parameters=parameters, identified=identified, settings=s_new, cutter=c_new,
        identifiable=tuple(parameters[k] for k in keep), not_identifiable=tuple(parameters[k] for k in drop),
        singular_values=sv, condition_number=_cond(sv), condition_number_used=_cond(s), rank=rank,
        residual=r, rms_before=rms(d), rms_after=rms(r), sensitivity=J)
