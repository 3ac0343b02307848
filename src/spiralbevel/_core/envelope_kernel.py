"""Compiled envelope kernel: contact rotation of every member-1 point in closed form, and its conjugate image.

For intersecting axes the meshing function of a fixed member-1 point r1 with unit normal n1 is, with q = r1 x n1,

    f(phi1) = (r1 x n1) . R_z(-phi1) p = A cos phi1 + B sin phi1 + C,
    A = sin(g1) q_x,  B = -sin(g1) q_y,  C = cos(g1) q_z

(docs/theory/gearing.md, Eqs. (M5a)-(M5b)), so its roots are theta +- arccos(-C / hypot(A, B)), theta = atan2(B, A),
and exist iff |C| <= hypot(A, B). One pass over the points does the roots, the branch choice, two Newton steps with
the analytic derivative (the arccos loses digits near a tangent root), the residual and the maps to the fixed frame
and the gear frame, M = R_z((z1/z2) phi1) R_y(-S) R_z(phi1) (Eq. (M6)). Same arithmetic as the numpy functions of
``_core/meshing.py`` (``meshing_coefficients``, ``meshing_roots``, ``polish_phi1``, ``pinion_to_fixed_and_gear``),
which the tests use as the reference.

Pure, float64, mm and rad; inputs are trusted (contiguous (n, 3) arrays).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["envelope_points"]

_TWO_PI = 2.0 * math.pi


@kernel
def _envelope_loop(r, nrm, guess, branch, sg, cg, cS, sS, ratio, tol, phi, res, exists, conv, pts, nrs, fix):
    tiny = np.finfo(np.float64).tiny
    for i in range(r.shape[0]):
        rx, ry, rz = r[i, 0], r[i, 1], r[i, 2]
        nx, ny, nz = nrm[i, 0], nrm[i, 1], nrm[i, 2]
        A = sg * (ry * nz - rz * ny)
        B = -sg * (rz * nx - rx * nz)
        C = cg * (rx * ny - ry * nx)
        R = math.hypot(A, B)
        g = guess[i]
        ratio_c = -C / R if R > 0.0 else (math.nan if C == 0.0 else -math.copysign(math.inf, C))
        ok = math.isfinite(ratio_c) and abs(ratio_c) <= 1.0
        if ok:
            theta = math.atan2(B, A)
            a = math.acos(ratio_c)
            plus, minus = theta + a, theta - a
            if branch == 1:
                x = plus
            elif branch == -1:
                x = minus
            else:
                dp = abs(plus - _TWO_PI * np.rint((plus - g) / _TWO_PI) - g)
                dm = abs(minus - _TWO_PI * np.rint((minus - g) / _TWO_PI) - g)
                x = plus if dp <= dm else minus
        else:
            x = g
        for _ in range(2):
            c, s = math.cos(x), math.sin(x)
            f = A * c + B * s + C
            df = B * c - A * s
            if abs(df) > 1e-300:
                x = x - f / df
        x = x - _TWO_PI * np.rint((x - g) / _TWO_PI)
        c, s = math.cos(x), math.sin(x)
        scale = max(math.sqrt(rx * rx + ry * ry + rz * rz), tiny)
        rs = abs(A * c + B * s + C) / scale
        cv = ok and rs <= tol
        phi[i], res[i], exists[i], conv[i] = x, rs, ok, cv
        if not cv:
            c, s = math.nan, math.nan
        ck, sk = math.cos(ratio * x), math.sin(ratio * x)
        if not cv:
            ck, sk = math.nan, math.nan
        for j in range(2):
            if j == 0:
                vx, vy, vz = rx, ry, rz
            else:
                vx, vy, vz = nx, ny, nz
            xf, yf = c * vx - s * vy, s * vx + c * vy
            xa, za = cS * xf - sS * vz, sS * xf + cS * vz
            gx, gy = ck * xa - sk * yf, sk * xa + ck * yf
            if j == 0:
                fix[i, 0], fix[i, 1], fix[i, 2] = xf, yf, vz
                pts[i, 0], pts[i, 1], pts[i, 2] = gx, gy, za
            else:
                nrs[i, 0], nrs[i, 1], nrs[i, 2] = -gx, -gy, -za


def envelope_points(r1, n1, guess, branch, gamma1, shaft_angle, ratio, tol):
    """Contact rotation, residual and conjugate data of member-1 points, all in one compiled pass.

    Parameters
    ----------
    r1, n1 : (..., 3) float, mm and -
        Member-1 points and unit normals (member-1 frame).
    guess : (...) float, rad
        Start value; the root is returned within pi of it (and is the root nearest to it when ``branch`` is 0).
    branch : {1, -1, 0}
        +1: the root theta + arccos (df/dphi1 <= 0); -1: theta - arccos; 0: the one nearest to ``guess``.
    gamma1, shaft_angle : float, rad
        Pinion pitch angle and shaft angle.
    ratio : float
        z1/z2.
    tol : float
        Accepted |f| / |r1|.

    Returns
    -------
    phi1 : (...) float, rad
        Polished root (the guess, polished, where none exists; not masked).
    residual : (...) float
        |f(phi1)| / |r1|.
    exists, converged : (...) bool
        |C| <= hypot(A, B); exists and residual <= tol.
    points, normals, fixed : (..., 3) float
        Conjugate points and member-2 outward normals (-M n1) in the gear frame, and R_z(phi1) r1 in the fixed frame;
        NaN where not converged (except the z component of ``fixed``, which R_z leaves unchanged).
    """
    shape = r1.shape[:-1]
    r = np.ascontiguousarray(r1, dtype=np.float64).reshape(-1, 3)
    nrm = np.ascontiguousarray(n1, dtype=np.float64).reshape(-1, 3)
    # a copy: a read-only broadcast view would compile the kernel a second time (_core/jit.py, one signature)
    g = np.array(np.broadcast_to(np.asarray(guess, np.float64), shape)).reshape(-1)
    n = r.shape[0]
    phi, res = np.empty(n), np.empty(n)
    exists, conv = np.empty(n, np.bool_), np.empty(n, np.bool_)
    pts, nrs, fix = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
    _envelope_loop(r, nrm, g, int(branch), math.sin(gamma1), math.cos(gamma1), math.cos(shaft_angle),
                   math.sin(shaft_angle), float(ratio), float(tol), phi, res, exists, conv, pts, nrs, fix)
    return (phi.reshape(shape), res.reshape(shape), exists.reshape(shape), conv.reshape(shape),
            pts.reshape(shape + (3,)), nrs.reshape(shape + (3,)), fix.reshape(shape + (3,)))
