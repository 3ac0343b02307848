"""Input checks and outward-normal geometry of a log-spiral flank, shared by the manufacturing functions.

The manufacturing functions accept any object with the attributes ``rho0`` (mm), ``base_cone_angle`` (rad) and
``spiral_angle`` (rad) — such as ``spiralbevel.geometry.logspiral.LogSpiralFlank`` — together with a
:class:`~spiralbevel.geometry.domain.ParallelogramDomain`, and call the closed-form kernel
:func:`spiralbevel._core.logspiral.geometry` directly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, TypeGuard

import numpy as np

from .._core import logspiral
from ..conventions import Side
from ..errors import DesignError, Problem


class FlankLike(Protocol):
    """What the manufacturing functions need from a flank: the three log-spiral parameters."""

    rho0: float
    base_cone_angle: float
    spiral_angle: float


@dataclass(frozen=True)
class FlankParams:
    """Checked parameters of a log-spiral flank on its domain.

    Attributes
    ----------
    rho0 : float, mm
    delta : float, rad
        Base-cone half-angle.
    beta : float, rad
        Spiral angle in the rolling plane (beta > 0 right hand).
    psi_sign : int
        +1 or -1: the branch of the domain (sign of psi).
    side : Side
        CONVEX where sign(psi) = sign(beta), else CONCAVE (docs/theory/logspiral.md, Eq. (S9) (#flank-types)).
    """

    rho0: float
    delta: float
    beta: float
    psi_sign: int
    side: Side


def _finite(x) -> TypeGuard[float]:
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def check_flank(flank: FlankLike, domain) -> FlankParams:
    """Validate ``flank`` and ``domain`` together; raise :class:`DesignError` listing every problem.

    Parameters
    ----------
    flank : FlankLike
        Object with ``rho0`` (mm), ``base_cone_angle`` (rad), ``spiral_angle`` (rad).
    domain : ParallelogramDomain
        Rectangle in (psi, phi).

    Returns
    -------
    FlankParams
    """
    problems = []
    rho0 = getattr(flank, "rho0", None)
    delta = getattr(flank, "base_cone_angle", None)
    beta = getattr(flank, "spiral_angle", None)
    if not (_finite(rho0) and float(rho0) > 0):
        problems.append(Problem("flank.rho0", rho0, "0 < value < inf", "mm"))
    if not (_finite(delta) and 0 < float(delta) < math.pi / 2):
        problems.append(Problem("flank.base_cone_angle", delta, "0 < value < pi/2", "rad"))
    if not (_finite(beta) and 0 < abs(float(beta)) < math.pi / 2):
        problems.append(Problem("flank.spiral_angle", beta, "0 < |value| < pi/2", "rad"))
    for name in ("phi_min", "phi_max", "psi_min", "psi_max", "base_cone_angle"):
        if not _finite(getattr(domain, name, None)):
            problems.append(Problem(f"domain.{name}", getattr(domain, name, None), "a finite number", "rad"))
    if problems:
        raise DesignError(problems)
    rho0, delta, beta = float(rho0), float(delta), float(beta)  # type: ignore[arg-type]  # finite: checked above
    d = domain
    if not d.phi_min < d.phi_max:
        problems.append(Problem("domain.phi_max", d.phi_max, f"> phi_min = {d.phi_min!r}", "rad"))
    if not d.psi_min < d.psi_max:
        problems.append(Problem("domain.psi_max", d.psi_max, f"> psi_min = {d.psi_min!r}", "rad"))
    elif d.psi_min <= 0 <= d.psi_max:
        problems.append(Problem("domain.psi_min", d.psi_min, "psi_min > 0 or psi_max < 0", "rad",
                                "psi = 0 is the singular (cuspidal) edge of the flank, "
                                "docs/theory/logspiral.md#singular-edge"))
    if not math.isclose(float(d.base_cone_angle), delta, rel_tol=1e-12, abs_tol=0.0):
        problems.append(Problem("domain.base_cone_angle", d.base_cone_angle, f"= flank.base_cone_angle = {delta!r}",
                                "rad", "the domain belongs to another flank"))
    if not problems and max(abs(d.psi_min - beta), abs(d.psi_max - beta)) >= math.pi / 2:
        problems.append(Problem("domain.psi_min/psi_max", (d.psi_min, d.psi_max),
                                f"|psi - beta| < pi/2 with beta = {beta!r}", "rad",
                                "outside it n_out = sign(psi) n is not the outward normal, "
                                "docs/theory/logspiral.md, Eq. (S9)"))
    if problems:
        raise DesignError(problems)
    psi_sign = 1 if d.psi_min > 0 else -1
    side = Side.CONVEX if psi_sign == (1 if beta > 0 else -1) else Side.CONCAVE
    return FlankParams(rho0, delta, beta, psi_sign, side)


def outward_geometry(varphi, phi, p: FlankParams) -> dict:
    """Closed-form geometry with the outward normal and convex-positive curvatures.

    Parameters
    ----------
    varphi, phi : (...) float, rad
        Surface parameters (broadcast).
    p : FlankParams

    Returns
    -------
    dict of arrays
        ``r`` (..., 3) mm; ``n_out`` (..., 3) outward unit normal; ``kappa1``, ``kappa2`` (...) 1/mm principal
        curvatures along the profile (e1) and lengthwise (e2) directions, convex = positive; ``e1``, ``e2`` (..., 3)
        with e1 x e2 = n_out; ``r_phi`` (..., 3) mm/rad; ``dA`` (...) mm^2/rad^2 area element sqrt(EG - F^2);
        ``psi``, ``rho``.

    Notes
    -----
    n_out = sign(psi) n (docs/theory/logspiral.md, Eq. (S9) (#flank-types)). The kernel's k is positive when the surface
    bends toward n, so the
    convex-positive curvature of docs/conventions.md is kappa = -sign(psi) k. e1 is flipped with n (e1_out =
    sign(psi) m) so that e1 x e2 = n_out holds with the kernel's e2.
    """
    g = logspiral.geometry(varphi, phi, p.rho0, p.delta, p.beta)
    s = float(p.psi_sign)
    return dict(
        r=g["r"], n_out=s * g["n"], kappa1=-s * g["k1"], kappa2=-s * g["k2"], e1=s * g["e1"], e2=g["e2"],
        r_phi=g["r_phi"], dA=np.sqrt(g["E"] * g["G"] - g["F"] ** 2), psi=g["psi"], rho=g["rho"],
    )


def unit_vector(v, field: str) -> np.ndarray:
    """Unit-normalize a 3-vector given by the user; zero, non-finite or wrongly shaped input -> DesignError."""
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise DesignError.single(field, v, "a 3-vector of finite numbers, not zero", "-") from None
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise DesignError.single(field, v, "a 3-vector of finite numbers, not zero", "-")
    norm = float(np.linalg.norm(a))
    if norm == 0.0:
        raise DesignError.single(field, v, "a non-zero 3-vector", "-", "a direction cannot be the zero vector")
    return a / norm
