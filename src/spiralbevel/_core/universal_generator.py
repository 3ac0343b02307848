"""Kernels of the universal generator: a cradle-type hypoid generator with cutter tilt and swivel and the universal
motions (docs/theory/universal.md; signs in docs/conventions.md "Universal generator").

A second, independent parametrization of face-milling generation: the whole chain cutter -> cradle -> machine ->
work is a product of 4x4 homogeneous matrices M(psi_c), its derivative by psi_c is taken by the complex step
(exact to round-off, no closed-form derivative needed), and the equation of meshing n . dr/dpsi_c = 0 is written
in the member frame. Because the cutter is a surface of revolution and M is a rigid motion, the equation is
exactly P cos(theta) + Q sin(theta) + R = 0 in the cutter angle theta; P, Q and R are read off three evaluations.

Frames (canonical machine = the one that cuts a LEFT-hand member; a right-hand member is its mirror image y -> -y):

* S_m: Z_m = cradle axis, cradle plane z = 0, root line = -X_m, machine centre at the origin.
* Cradle frame S_c turns by psi_c about +Z_m. In it the cutter centre is at S_r(psi_c) e(pi - q), e(a) =
  (cos a, sin a, 0).
* Cutter frame S_h: axis z_h, blade tips in z_h = 0, body toward -z_h, x_h along the ray machine centre -> cutter
  centre at zero tilt. The cutter axis is turned by the tilt i about the swivel line d = e(pi - q + j) of the cradle
  plane through the cutter centre (right-hand rule about d).
* Work axis a = (-cos g, 0, sin g) through A(psi_c) = (0, E(psi_c), -X_B(psi_c)), member apex at A + X_D a; the
  work turns by psi_i(psi_c) about +a; a member point is r_i = R_z(-psi_i) B^T (r_m - A - X_D a) with the member
  basis e_x = (sin g, 0, cos g), e_y = Y_m, e_z = a.

Parameters arrive as one plain dict ``up`` (see ``UniversalSettings.kernel_params``): ``S, q, g, XD, XB, E, m, roll,
tilt, swivel, radial, helical, vertical`` (E and the vertical motion already in the kernel's sign, i.e. minus the
blank offset of docs/conventions.md). Everything works on float64 (or complex128 for the step) arrays, mm and rad.
"""

from __future__ import annotations

import numpy as np

_STEP = 1e-30          # complex step: the derivative is Im(M(psi + i h))/h, exact to round-off for analytic M


def _poly(psi, c0, coeffs):
    """c0 + c1 psi + c2 psi^2 + ... (psi real or complex)."""
    out = c0 + 0.0 * psi
    p = 1.0 + 0.0 * psi
    for c in coeffs:
        p = p * psi
        out = out + c * p
    return out


def work_rotation(psi, up):
    """psi_i = m (psi - (2C) psi^2/2! - (6D) psi^3/3! - (24E) psi^4/4! - (120F) psi^5/5!) (Taylor modified roll)."""
    fact = (2.0, 6.0, 24.0, 120.0)
    out = psi + 0.0
    p = psi + 0.0
    for k, ck in enumerate(up["roll"]):
        p = p * psi
        out = out - ck * p / fact[k]
    return up["m"] * out


def positions(psi, up):
    """Machine-frame positions at cradle angle psi (real or complex): cutter centre, cutter axis, tilt rotation.

    Returns
    -------
    centre : (..., 3), mm; axis : (..., 3); R : (..., 3, 3) cutter frame -> machine frame rotation;
    apex : (..., 3), mm, the member apex; work_axis : (3,).
    """
    psi = np.asarray(psi)
    b = np.pi - up["q"] + psi
    S = _poly(psi, up["S"], up["radial"])
    centre = np.stack([S * np.cos(b), S * np.sin(b), 0.0 * b], -1)
    R = cutter_rotation(psi, up)
    E = _poly(psi, up["E"], up["vertical"])
    XB = _poly(psi, up["XB"], up["helical"])
    g = up["g"]
    a = np.array([-np.cos(g), 0.0, np.sin(g)])
    apex = np.stack([0.0 * E, E, -XB], -1) + up["XD"] * a
    return centre, R[..., :, 2], R, apex, a


def cutter_rotation(psi, up):
    """Cutter frame -> machine frame: R_z(psi) . Rot(e(pi - q + j), i) . R_z(pi - q), shape (..., 3, 3)."""
    psi = np.asarray(psi)
    q, i, j = up["q"], up["tilt"], up["swivel"]
    Rz0 = _rz(np.pi - q + 0.0 * psi)
    dx, dy = np.cos(np.pi - q + j), np.sin(np.pi - q + j)
    ci, si = np.cos(i), np.sin(i)
    # Rodrigues about the unit vector d = (dx, dy, 0)
    T = np.array([[ci + dx * dx * (1 - ci), dx * dy * (1 - ci), dy * si],
                  [dx * dy * (1 - ci), ci + dy * dy * (1 - ci), -dx * si],
                  [-dy * si, dx * si, ci]])
    return _rz(psi) @ T @ Rz0


def _rz(a):
    a = np.asarray(a)
    c, s = np.cos(a), np.sin(a)
    z, o = 0.0 * a, 1.0 + 0.0 * a
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def chain(psi, up):
    """Homogeneous matrix cutter frame -> member frame (canonical left-hand machine), shape (..., 4, 4)."""
    psi = np.asarray(psi)
    centre, _, R, apex, a = positions(psi, up)
    g = up["g"]
    Bt = np.array([[np.sin(g), 0.0, np.cos(g)], [0.0, 1.0, 0.0], [-np.cos(g), 0.0, np.sin(g)]])   # rows e_x, e_y, a
    W = _rz(-work_rotation(psi, up)) @ Bt                        # machine -> member rotation
    L = W @ R
    t = np.einsum("...ij,...j->...i", W, centre - apex)
    M = np.zeros(psi.shape + (4, 4), dtype=L.dtype)
    M[..., :3, :3] = L
    M[..., :3, 3] = t
    M[..., 3, 3] = 1.0
    return M


def chain_and_rate(psi, up):
    """M(psi) and dM/dpsi by the complex step, both (..., 4, 4) float."""
    psi = np.asarray(psi, dtype=float)
    Mc = chain(psi + 1j * _STEP, up)
    return Mc.real, Mc.imag / _STEP


def cutter_point(rho, z, nr, nz, theta):
    """Homogeneous cutter point (..., 4) and unit normal (..., 3) in S_h at cutter angle theta."""
    c, s = np.cos(theta), np.sin(theta)
    r = np.stack([rho * c, rho * s, z, np.ones_like(c)], -1)
    n = np.stack([nr * c, nr * s, nz + 0.0 * c], -1)
    return r, n


def meshing(M, dM, rho, z, nr, nz, theta):
    """f = n_i . dr_i/dpsi_c at cutter angle theta (mm/rad), n_i = L n_h, dr_i/dpsi_c = dM r_h."""
    r, n = cutter_point(rho, z, nr, nz, theta)
    ni = np.einsum("...ij,...j->...i", M[..., :3, :3], n)
    v = np.einsum("...ij,...j->...i", dM[..., :3, :], r)
    return np.einsum("...i,...i->...", ni, v)


def solve_theta(M, dM, rho, z, nr, nz, theta_ref):
    """Cutter angle on the branch nearest ``theta_ref`` and the discriminant -R/sqrt(P^2 + Q^2) (|.| <= 1: contact).

    f(theta) = P cos theta + Q sin theta + R exactly (rigid motion of a surface of revolution), so P, Q, R follow
    from f(0), f(pi/2), f(pi).
    """
    f0 = meshing(M, dM, rho, z, nr, nz, 0.0 * rho)
    f1 = meshing(M, dM, rho, z, nr, nz, 0.5 * np.pi + 0.0 * rho)
    f2 = meshing(M, dM, rho, z, nr, nz, np.pi + 0.0 * rho)
    R = 0.5 * (f0 + f2)
    P = 0.5 * (f0 - f2)
    Q = f1 - R
    disc = -R / np.hypot(P, Q)
    half = np.arccos(np.clip(disc, -1.0, 1.0))
    base = np.arctan2(Q, P)
    c1, c2 = base + half, base - half
    d1 = np.abs(np.angle(np.exp(1j * (c1 - theta_ref))))
    d2 = np.abs(np.angle(np.exp(1j * (c2 - theta_ref))))
    return np.where(d1 <= d2, c1, c2), disc


def reference_theta(psi, up, Rc):
    """Branch-choosing cutter angle: toward the point where the nominal cutter circle (radius Rc, untilted, in the
    cradle plane) crosses the member's root line far from the machine centre (the line y = E parallel to the root
    line -X_m through the work axis displaced by the blank offset E at psi_c = 0, kernel sign); the cutter angle is
    measured from the ray machine centre -> cutter centre."""
    psi = np.asarray(psi, float)
    S, q, E = up["S"], up["q"], np.asarray(up["E"], float)
    b0 = np.pi - q + psi
    d2 = Rc**2 - (S * np.sin(q) - E) ** 2
    xr = -S * np.cos(q) - np.sqrt(np.maximum(d2, 0.0))
    return np.where(d2 > 0.0, np.arctan2(E - S * np.sin(b0), xr - S * np.cos(b0)), -0.5 * np.pi + psi) - b0


def member_state(M, rho, z, nr, nz, theta):
    """Member-frame points (..., 3) and unit cutter normals n_h mapped to the member frame (..., 3)."""
    r, n = cutter_point(rho, z, nr, nz, theta)
    p = np.einsum("...ij,...j->...i", M[..., :3, :], r)
    ni = np.einsum("...ij,...j->...i", M[..., :3, :3], n)
    return p, ni
