"""Kernels of the bevel-pair kinematics and of the meshing (envelope) equation for intersecting axes.

Fixed frame with the common apex O (docs/conventions.md, "Gear-pair frame"): pinion axis a1 = (0, 0, 1), gear axis
a2 = (sin S, 0, cos S), pitch line p = (sin g1, 0, cos g1). Angular velocities w(1) = w1 a1, w(2) = -w2 a2 with
w2/w1 = z1/z2, so w(12) = w1 a1 + w2 a2 = (w1 cos g1 + w2 cos g2) p (docs/theory/gearing.md, Eqs. (M1)-(M2)).

Meshing equation (Willis form): n . v(12) = 0  <=>  det[r, n, p] = 0. In pinion member coordinates, pinion turned
by phi1: f = (r1 x n1) . R(a1, -phi1) p. Because R(a1, -phi1) p = (sin g1 cos phi1, -sin g1 sin phi1, cos g1),
f = A cos(phi1) + B sin(phi1) + C exactly (any surface, constant ratio), which gives both roots in closed form.

All functions are pure, float64, mm and rad, xyz on the trailing axis; inputs are trusted.
"""

from __future__ import annotations

import numpy as np

from .rotations import rot_axis, rot_y, rot_z


# --------------------------------------------------------------------------------------------- pair geometry
def pitch_angles(shaft_angle, z1, z2):
    """Pitch angles (g1, g2) in rad: tan g1 = sin S / (z2/z1 + cos S), g2 = S - g1 (docs/theory/logspiral.md, Eq.
    (S12))."""
    g1 = np.arctan2(np.sin(shaft_angle), z2 / z1 + np.cos(shaft_angle))
    return g1, shaft_angle - g1


def gear_axis(shaft_angle):
    """Gear axis a2 = (sin S, 0, cos S) in the fixed frame."""
    return np.array([np.sin(shaft_angle), 0.0, np.cos(shaft_angle)])


def pitch_line(gamma1):
    """Unit pitch line p = (sin g1, 0, cos g1) in the fixed frame."""
    return np.array([np.sin(gamma1), 0.0, np.cos(gamma1)])


def pinion_to_fixed(phi1):
    """R(a1, phi1) = R_z(phi1): pinion member frame -> fixed frame, shape phi1.shape + (3, 3)."""
    return rot_z(phi1)


def gear_to_fixed(phi2, shaft_angle):
    """R(a2, phi2) R_y(S): gear member frame -> fixed frame, shape phi2.shape + (3, 3) (docs/conventions.md)."""
    return rot_axis(gear_axis(shaft_angle), phi2) @ rot_y(shaft_angle)


def pinion_to_gear(phi1, shaft_angle, ratio):
    """Pinion member frame -> gear member frame with the pinion at phi1 and the gear at phi2 = -ratio phi1.

    M = R_y(-S) R(a2, ratio phi1) R(a1, phi1) = gear_to_fixed(phi2)^T pinion_to_fixed(phi1) (docs/theory/gearing.md, Eq.
    (M6)).
    """
    phi1 = np.asarray(phi1, float)
    return rot_y(-shaft_angle) @ rot_axis(gear_axis(shaft_angle), ratio * phi1) @ rot_z(phi1)


def pinion_to_fixed_and_gear(vectors, phi1, shaft_angle, ratio):
    """Pinion member vectors seen in the fixed frame and in the gear member frame, elementwise (no 3 x 3 stacks).

    M = R_y(-S) R(a2, ratio phi1) R_z(phi1) = R_z(ratio phi1) R_y(-S) R_z(phi1), because R_y(-S) a2 = e_z
    (R_y(-S) R(a2, t) R_y(S) = R(R_y(-S) a2, t)); the same map as :func:`pinion_to_gear` to round-off.

    Parameters
    ----------
    vectors : sequence of (..., 3) float
        Vectors in the pinion member frame (points in mm or unit normals).
    phi1 : (...) float, rad
        Pinion rotation (broadcast with the vectors' leading axes).

    Returns
    -------
    fixed, gear : lists of (..., 3) float
        R_z(phi1) v (fixed frame) and M v (gear member frame) for each vector.
    """
    phi1 = np.asarray(phi1, float)
    c1, s1 = np.cos(phi1), np.sin(phi1)
    ck, sk = np.cos(ratio * phi1), np.sin(ratio * phi1)
    cS, sS = np.cos(shaft_angle), np.sin(shaft_angle)
    fixed, gear = [], []
    for v in vectors:
        x, y, z = v[..., 0], v[..., 1], v[..., 2]
        xf, yf = c1 * x - s1 * y, s1 * x + c1 * y
        xa, za = cS * xf - sS * z, sS * xf + cS * z
        fixed.append(np.stack([xf, yf, z * np.ones_like(xf)], -1))
        gear.append(np.stack([ck * xa - sk * yf, sk * xa + ck * yf, za], -1))
    return fixed, gear


# --------------------------------------------------------------------------------------------- meshing equation
def willis(r, n, p):
    """det[r, n, p] = (r x n) . p (mm for unit n), broadcasting over the leading axes."""
    return np.einsum("...i,...i->...", np.cross(r, n), p)


def meshing_function(r1, n1, phi1, gamma1):
    """f(phi1) = (r1 x n1) . R(a1, -phi1) p, in pinion member coordinates (docs/theory/gearing.md, Eq. (M5)), mm."""
    phi1 = np.asarray(phi1, float)
    p_rot = np.stack([np.sin(gamma1) * np.cos(phi1), -np.sin(gamma1) * np.sin(phi1),
                      np.cos(gamma1) * np.ones_like(phi1)], -1)
    return willis(r1, n1, p_rot)


def meshing_coefficients(r1, n1, gamma1):
    """(A, B, C) with f(phi1) = A cos phi1 + B sin phi1 + C, from q = r1 x n1 (mm)."""
    q = np.cross(r1, n1)
    s, c = np.sin(gamma1), np.cos(gamma1)
    return s * q[..., 0], -s * q[..., 1], c * q[..., 2]


def meshing_roots(A, B, C):
    """Both roots of A cos x + B sin x + C = 0.

    Returns
    -------
    plus, minus : (...) float, rad
        ``theta + acos(-C/R)`` (where df/dx <= 0, "branch +1") and ``theta - acos(-C/R)`` ("branch -1"),
        theta = atan2(B, A), R = hypot(A, B). NaN where there is no root.
    exists : (...) bool
        |C| <= R (a contact exists).
    """
    R = np.hypot(A, B)
    theta = np.arctan2(B, A)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = -C / R
    exists = np.isfinite(ratio) & (np.abs(ratio) <= 1.0)
    a = np.arccos(np.where(exists, ratio, 0.0))
    nan = np.where(exists, 0.0, np.nan)
    return theta + a + nan, theta - a + nan, exists


def wrap_near(x, ref):
    """x shifted by a multiple of 2 pi to lie within pi of ref."""
    return x - 2.0 * np.pi * np.round((x - ref) / (2.0 * np.pi))


def polish_phi1(A, B, C, phi1, iterations=2):
    """Newton steps on A cos x + B sin x + C (analytic derivative), vectorized."""
    for _ in range(iterations):
        c, s = np.cos(phi1), np.sin(phi1)
        f = A * c + B * s + C
        df = B * c - A * s
        safe = np.abs(df) > 1e-300
        phi1 = phi1 - np.where(safe, f / np.where(safe, df, 1.0), 0.0)
    return phi1


# --------------------------------------------------------------------------------------------- scalar roots
def bracket_scan(fvals, grid, v0=None, return_index=False):
    """Choose a sign-change bracket per row of ``fvals (n, m)`` sampled at ``grid (m,)``.

    The bracket nearest to ``v0 (n,)`` is taken when given, the first from grid[0] otherwise.
    Returns ``lo, hi, flo, fhi (n,)`` and ``found (n,) bool`` (and the grid index of ``lo`` when ``return_index``).
    """
    sgn = np.sign(fvals)
    change = (sgn[:, :-1] * sgn[:, 1:] <= 0) & np.isfinite(fvals[:, :-1]) & np.isfinite(fvals[:, 1:])
    found = change.any(axis=1)
    if v0 is None:
        idx = np.argmax(change, axis=1)
    else:
        mid = 0.5 * (grid[:-1] + grid[1:])
        dist = np.where(change, np.abs(mid[None, :] - np.asarray(v0, float).reshape(-1, 1)), np.inf)
        idx = np.argmin(dist, axis=1)
    rows = np.arange(fvals.shape[0])
    out = grid[idx], grid[idx + 1], fvals[rows, idx], fvals[rows, idx + 1], found
    return (*out, idx) if return_index else out


def angle_secant_start(f_lo, f_hi, roots_lo, roots_hi, lo, hi, phi1):
    """Start point inside each bracket from the closed-form contact rotations at its ends.

    At fixed phi1 the meshing function f(v) changes sign between ``lo`` and ``hi``. The contact rotation of the
    point at v, phi1*(v) (Eq. (M5b), ``roots_* = (plus, minus)`` at the ends), passes through phi1 there, and near its
    root f has the sign of d+(v) = wrap(plus(v) - phi1) (branch +1, f' < 0) or of -d-(v) (branch -1). The branch whose
    signed angle agrees with the signs of f at both ends is followed and the secant of that angle, which varies
    slowly along a flank (linearly in v for a log-spiral flank), gives the start; NaN where no branch agrees or the
    secant leaves the open bracket (the caller then starts at the midpoint).
    """
    best = np.full(np.shape(lo), np.nan)
    width = np.full(np.shape(lo), np.inf)
    for sgn, r_lo, r_hi in ((1.0, roots_lo[0], roots_hi[0]), (-1.0, roots_lo[1], roots_hi[1])):
        g_lo = sgn * wrap_near(r_lo - phi1, 0.0)
        g_hi = sgn * wrap_near(r_hi - phi1, 0.0)
        agree = (np.sign(g_lo) == np.sign(f_lo)) & (np.sign(g_hi) == np.sign(f_hi)) & (g_lo != g_hi)
        agree &= np.abs(g_hi - g_lo) < np.pi  # the angle does not wrap across the bracket
        with np.errstate(divide="ignore", invalid="ignore"):
            x = lo - g_lo * (hi - lo) / (g_hi - g_lo)
        agree &= np.isfinite(x) & (x > np.minimum(lo, hi)) & (x < np.maximum(lo, hi))
        take = agree & (np.abs(g_hi - g_lo) < width)
        best = np.where(take, x, best)
        width = np.where(take, np.abs(g_hi - g_lo), width)
    return best


def bracketed_newton(fun, lo, hi, flo, fhi, scale, tol, max_iter=60, rel_step=1e-7, x0=None, fx0=None):
    """Safeguarded Newton (rtsafe) on many scalar equations at once, each with a sign-change bracket.

    Parameters
    ----------
    fun : callable
        ``fun(x (n,)) -> (n,)`` residuals.
    lo, hi, flo, fhi : (n,) float
        Brackets and the residuals there (flo * fhi <= 0).
    scale : (n,) float
        Residual scale; convergence when |f| / scale <= tol or the bracket is narrower than 4 eps |x|.
    tol : float
        Relative residual tolerance.
    x0, fx0 : (n,) float, optional
        A start inside the bracket and its residual (NaN entries: the midpoint); the bracket is shrunk to the side of
        the start that keeps the sign change.

    Returns
    -------
    x, residual (|f| / scale), converged, iterations
    """
    lo, hi, flo, fhi = (np.array(a, float) for a in (lo, hi, flo, fhi))
    if x0 is None:
        x = np.where(flo == 0, lo, np.where(fhi == 0, hi, 0.5 * (lo + hi)))
        fx = fun(x)
    else:
        x, fx = np.array(x0, float), np.array(fx0, float)
        same_lo = np.sign(fx) == np.sign(flo)
        lo, flo = np.where(same_lo, x, lo), np.where(same_lo, fx, flo)
        hi, fhi = np.where(~same_lo, x, hi), np.where(~same_lo, fx, fhi)
    it = 0
    width_tol = 4 * np.finfo(float).eps * np.maximum(1.0, np.abs(x))
    done = (np.abs(fx) <= tol * scale) | (np.abs(hi - lo) <= width_tol)
    dx_old = np.abs(hi - lo)
    while not done.all() and it < max_iter:
        it += 1
        # Newton from the bracket end with the smaller residual (never from the far side of a curved f)
        near_lo = np.abs(flo) <= np.abs(fhi)
        xb, fb = np.where(near_lo, lo, hi), np.where(near_lo, flo, fhi)
        h = rel_step * np.maximum(1.0, np.abs(xb))
        h = np.where(near_lo == (lo <= hi), h, -h)  # step into the bracket
        df = (fun(xb + h) - fb) / h
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = xb - fb / df
        bad = ~np.isfinite(xn) | (xn <= np.minimum(lo, hi)) | (xn >= np.maximum(lo, hi))
        bad |= np.abs(xn - xb) > 0.5 * dx_old  # steps not halving: bisect (rtsafe rule)
        xn = np.where(bad, 0.5 * (lo + hi), xn)
        dx_old = np.where(done, dx_old, np.abs(xn - xb))
        xn = np.where(done, x, xn)
        fn = fun(xn)
        # keep the bracket: replace the end whose residual has the sign of fn
        same_lo = np.sign(fn) == np.sign(flo)
        lo, flo = np.where(same_lo & ~done, xn, lo), np.where(same_lo & ~done, fn, flo)
        hi, fhi = np.where(~same_lo & ~done, xn, hi), np.where(~same_lo & ~done, fn, fhi)
        x, fx = xn, fn
        width_tol = 4 * np.finfo(float).eps * np.maximum(1.0, np.abs(x))
        done = done | (np.abs(fx) <= tol * scale) | (np.abs(hi - lo) <= width_tol)
    res = np.abs(fx) / scale
    return x, res, done, it


# --------------------------------------------------------------------------------------------- numerical normals
def fd_normals(points_fun, u, v, step, orientation=1.0):
    """Unit normals orientation * (r_u x r_v) / |r_u x r_v| by 4th-order central differences.

    ``points_fun(u, v) -> (..., 3)``; ``step`` in parameter units (error ~ step^4, rounding ~ eps / step).
    """
    def d(fun_shift):
        return (-fun_shift(2) + 8 * fun_shift(1) - 8 * fun_shift(-1) + fun_shift(-2)) / (12 * step)

    ru = d(lambda k: points_fun(u + k * step, v))
    rv = d(lambda k: points_fun(u, v + k * step))
    nvec = np.cross(ru, rv)
    return orientation * nvec / np.linalg.norm(nvec, axis=-1, keepdims=True)


# --------------------------------------------------------------------------------------------- log-spiral invariant
def logspiral_invariant(points, delta, beta, psi_sign=1.0):
    """ln rho0 of the seed-000 flank (delta, beta) through each point: ln rho - phi sin(delta) cot(beta).

    The point is put on the tangent plane Pi(varphi) of the base cone (r . m(varphi) = 0, the root giving
    sign(psi) = psi_sign), psi = atan2(r . w, r . t), phi = varphi - psi / sin(delta) (docs/theory/logspiral.md, Eq.
    (S2)). The value is
    defined modulo 2 pi sin(delta) |cot(beta)| (the spiral's turns); callers reduce it.

    Returns
    -------
    inv : (...) float
        ln(rho0 / 1 mm).
    psi, phi, varphi : (...) float, rad
        Coordinates of the point on that flank (valid when the point is on it).
    """
    x, y, z = points[..., 0], points[..., 1], points[..., 2]
    rho_h = np.hypot(x, y)
    sd, cd = np.sin(delta), np.cos(delta)
    az = np.arctan2(y, x)
    c = np.clip(z * sd / (cd * rho_h), -1.0, 1.0)
    out = []
    for sgn in (1.0, -1.0):
        varphi = az + sgn * np.arccos(c)
        t = np.stack([sd * np.cos(varphi), sd * np.sin(varphi), cd * np.ones_like(varphi)], -1)
        w = np.stack([np.sin(varphi), -np.cos(varphi), np.zeros_like(varphi)], -1)
        psi = np.arctan2(np.einsum("...i,...i->...", points, w), np.einsum("...i,...i->...", points, t))
        out.append((varphi, psi))
    pick = np.sign(out[0][1]) == np.sign(psi_sign)
    varphi = np.where(pick, out[0][0], out[1][0])
    psi = np.where(pick, out[0][1], out[1][1])
    phi = varphi - psi / sd
    rho = np.linalg.norm(points, axis=-1)
    return np.log(rho) - phi * sd / np.tan(beta), psi, phi, varphi


def reduce_periodic(values, period, ref=None):
    """values shifted by multiples of ``period`` to lie within period/2 of ``ref`` (median when omitted)."""
    if ref is None:
        ref = np.median(values)
    return values - period * np.round((values - ref) / period)


__all__ = [
    "pitch_angles", "gear_axis", "pitch_line", "pinion_to_fixed", "gear_to_fixed", "pinion_to_gear",
    "pinion_to_fixed_and_gear",
    "willis", "meshing_function", "meshing_coefficients", "meshing_roots", "wrap_near", "polish_phi1",
    "bracket_scan", "angle_secant_start", "bracketed_newton", "fd_normals", "logspiral_invariant", "reduce_periodic",
]
