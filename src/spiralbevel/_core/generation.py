"""Kernels of face-milling generation on a cradle-type machine (seed 001 §3, seed 003, docs/theory/generation.md, Eqs.
(G5)-(G8) (and (G13)-(G15) for curvatures)).

Everything here works on float64 arrays (xyz on the trailing axis), mm and rad, and trusts its input. Parameters come
as two plain dicts built by the user layer: ``cp`` (head cutter, see :func:`cutter_params`) and ``mp`` (machine
settings, see ``MachineSettings.kernel_params``).

Frames (canonical machine = the one that cuts a LEFT-hand member; a right-hand member is its mirror image y -> -y):

* S_m, machine frame: Z_m = cradle axis k = (0, 0, 1), cradle plane z = 0, root line = -x axis. The cradle turns by
  psi_c about +Z_m; the cutter centre sits at C = S_r e(pi - q + psi_c), e(a) = (cos a, sin a, 0), i.e. at
  S_r(-cos q, sin q, 0) for psi_c = 0 (docs/theory/generation.md, Eq. (G5): q measured from the root line).
* Cutter: blade tips in the plane z = 0, cutter body toward -z; a cutter point is C + rho(u) e(phi) + z(u) k with the
  absolute angle phi = pi - q + psi_c + theta (theta measured from the ray O->C, as in seed 001 Eq. (15)).
* Work axis a = (-cos g, 0, sin g), g = machine root angle, through A = (0, E_m(psi_c), -X_B); the member apex sits at
  A + X_D a. Member frame basis at psi_i = 0: e_x = (sin g, 0, cos g), e_y = (0, 1, 0), e_z = a.
* The work turns by psi_i(psi_c) about +a; a member point is r_i = R_z(-psi_i) B^T (r_m - A - X_D a).

Blade profile (meridian of the cutter surface of revolution), one parameter u in mm (docs/theory/generation.md, Eqs.
(G1)-(G3)): the
in-plane cutter normal is n_h = (sin chi, s cos chi) in (radial, axial) components; chi = pi/2 - alpha on the straight
blade, chi = lambda on the fillet, and varies linearly with u on a circular-arc blade. s = +1 outer blade, -1 inner.
The straight-blade u is exactly the u of Eq. (7); the fillet continues it by arc length below the junction u_j.
"""

from __future__ import annotations

import numpy as np

HALF_PI = 0.5 * np.pi


# ----------------------------------------------------------------------------------------------------------------
# head cutter
# ----------------------------------------------------------------------------------------------------------------
def cutter_params(s, alpha, Rh, rho_f, profile_radius=np.inf, profile_ref=0.0):
    """Derived constants of a blade: fillet junction, fillet centre radius T, arc centre. docs/theory/generation.md,
    Eqs. (G1)-(G3).

    Returns a dict with keys ``s, alpha, Rh, rho_f, rp, up, chi0, chi_j, u_j, u_min, T, rc, zc``.
    """
    chi0 = HALF_PI - alpha
    ca, sa = np.cos(alpha), np.sin(alpha)
    if np.isinf(profile_radius):
        chi_j = chi0
        u_j = rho_f * (1.0 - sa) / ca
        T = Rh - s * rho_f * (1.0 - sa) / ca
        rc = zc = np.nan
    else:
        rp, up = profile_radius, profile_ref
        rc = Rh + s * up * sa + s * rp * ca          # arc centre = line point at u_p + rp * n_in
        zc = -up * ca + rp * sa
        chi_j = np.arccos(np.clip((zc + rho_f) / (rho_f + rp), -1.0, 1.0))
        u_j = up + rp * (chi0 - chi_j)
        T = rc - s * (rho_f + rp) * np.sin(chi_j)
    return dict(s=float(s), alpha=float(alpha), Rh=float(Rh), rho_f=float(rho_f), rp=float(profile_radius),
                up=float(profile_ref), chi0=chi0, chi_j=float(chi_j), u_j=float(u_j),
                u_min=float(u_j - rho_f * chi_j), T=float(T), rc=float(rc), zc=float(zc))


def profile(u, cp):
    """Blade meridian at parameter u: radius rho, axial z (<= 0), normal angle chi and d(chi)/du.

    Fillet for u < u_j (torus, Eq. (8)), straight blade (cone, Eq. (7)) or circular arc above.
    """
    u = np.asarray(u, dtype=float)
    s, rf = cp["s"], cp["rho_f"]
    fil = u < cp["u_j"]
    chi_f = cp["chi_j"] - (cp["u_j"] - u) / rf
    rho_f = cp["T"] + s * rf * np.sin(chi_f)
    z_f = -rf * (1.0 - np.cos(chi_f))
    if np.isinf(cp["rp"]):
        chi_b = np.full_like(u, cp["chi0"])
        rho_b = cp["Rh"] + s * u * np.cos(cp["chi0"])
        z_b = -u * np.sin(cp["chi0"])
        d_b = 0.0
    else:
        chi_b = cp["chi0"] - (u - cp["up"]) / cp["rp"]
        rho_b = cp["rc"] - cp["rp"] * s * np.sin(chi_b)
        z_b = cp["zc"] - cp["rp"] * np.cos(chi_b)
        d_b = -1.0 / cp["rp"]
    rho = np.where(fil, rho_f, rho_b)
    z = np.where(fil, z_f, z_b)
    chi = np.where(fil, chi_f, chi_b)
    dchi = np.where(fil, 1.0 / rf, d_b)
    return rho, z, chi, dchi


# ----------------------------------------------------------------------------------------------------------------
# machine motions
# ----------------------------------------------------------------------------------------------------------------
def roll(psi, mp):
    """Work rotation psi_i, its rate omega_i = d psi_i/d psi_c and d omega_i/d psi_c (Taylor modified roll).

    psi_i = m (psi - (2C) psi^2/2! - (6D) psi^3/3! - (24E) psi^4/4! - (120F) psi^5/5!).
    """
    m, c = mp["m"], mp["roll"]                      # c = (2C, 6D, 24E, 120F)
    p = np.asarray(psi, dtype=float)
    fact = (2.0, 6.0, 24.0, 120.0)
    psi_i, w, dw = p.copy(), np.ones_like(p), np.zeros_like(p)
    for k, ck in enumerate(c):                      # term -ck psi^(k+2)/(k+2)!
        n = k + 2
        psi_i = psi_i - ck * p**n / fact[k]
        w = w - ck * p ** (n - 1) / fact[k] * n
        dw = dw - ck * p ** (n - 2) / fact[k] * n * (n - 1)
    return m * psi_i, m * w, m * dw


def offset(psi, mp):
    """Blank offset E_m(psi_c) and its first two derivatives w.r.t. psi_c (polynomial in psi_c).

    Optional additive terms (absent keys change nothing): ``mp["E_table"] = (nodes, values[, second])``, a
    piecewise-linear or cubic-spline law (see :func:`table_offset`), and ``mp["E_rate"]``, a linear term E_rate psi_c
    whose value may be an array that
    broadcasts with ``psi`` (batched solvers give every system its own offset rate; ``mp["E"]`` may then be an array
    too).
    """
    p = np.asarray(psi, dtype=float)
    c = mp["E_poly"]
    if not c:
        z = np.zeros_like(p)
        E, dE, ddE = z + mp["E"], z, z
    else:
        c = np.concatenate([[mp["E"]], np.asarray(c, float)])
        P = np.polynomial.polynomial
        E, dE, ddE = P.polyval(p, c), P.polyval(p, P.polyder(c)), P.polyval(p, P.polyder(c, 2))
    table = mp.get("E_table")
    if table is not None and len(table[0]):
        t, dt, ddt = table_offset(p, *table)
        E, dE, ddE = E + t, dE + dt, ddE + ddt
    rate = mp.get("E_rate")
    if rate is not None:
        E, dE = E + rate * p, dE + rate
    return E, dE, ddE


def table_offset(psi, nodes, values, second=None):
    """Offset law through (nodes, values): piecewise linear, or a cubic spline with the given second derivatives.

    Linear (``second`` None): at a node the slope of the segment on the side of psi_c = 0 is used (the side the law
    is built from, outward from the mean contact point, seed 001 §4.3.1 steps 2-3); at psi_c = 0 itself, the segment
    below; the second derivative is reported as zero. Cubic: on [x_i, x_i+1] with t = psi - x_i, h = x_i+1 - x_i,
    E = y_i + b_i t + M_i t^2/2 + (M_i+1 - M_i) t^3/(6 h), b_i = (y_i+1 - y_i)/h - h (2 M_i + M_i+1)/6 (C2 when M are
    the spline's moments). Both continue linearly beyond the end nodes with the end value and slope.

    Parameters
    ----------
    psi : (...) float, rad
    nodes : (m,) float, rad, strictly increasing, m >= 2
    values : (m,) float, mm
    second : (m,) float, mm/rad^2, optional

    Returns
    -------
    E, dE, ddE : (...) float, mm, mm/rad and mm/rad^2
    """
    psi = np.asarray(psi, dtype=float)
    x, y = np.asarray(nodes, float), np.asarray(values, float)
    if second is None:
        hi = np.where(psi >= 0.0, np.searchsorted(x, psi, side="left"), np.searchsorted(x, psi, side="right"))
        i = np.clip(hi - 1, 0, x.size - 2)
        slope = (y[i + 1] - y[i]) / (x[i + 1] - x[i])
        return y[i] + slope * (psi - x[i]), slope, np.zeros_like(slope)
    M = np.asarray(second, float)
    h = np.diff(x)
    b = np.diff(y) / h - h * (2 * M[:-1] + M[1:]) / 6
    i = np.clip(np.searchsorted(x, psi, side="right") - 1, 0, x.size - 2)
    t = np.clip(psi, x[0], x[-1]) - x[i]
    k = (M[i + 1] - M[i]) / h[i]
    E = y[i] + t * (b[i] + t * (M[i] / 2 + t * k / 6))
    dE = b[i] + t * (M[i] + t * k / 2)
    ddE = M[i] + t * k
    out = (psi < x[0]) | (psi > x[-1])          # linear continuation with the end value and slope
    E = E + np.where(out, dE * (psi - np.clip(psi, x[0], x[-1])), 0.0)
    ddE = np.where(out, 0.0, ddE)
    return E, dE, ddE


def cross(a, b):
    """Cross product over the trailing axis (faster than numpy.cross for small stacks)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], -1)


def work_axis(mp):
    g = mp["gamma"]
    return np.array([-np.cos(g), 0.0, np.sin(g)])


# ----------------------------------------------------------------------------------------------------------------
# equation of meshing, solved in closed form for the cutter angle
# ----------------------------------------------------------------------------------------------------------------
def reference_angle(psi, mp, Rc):
    """Absolute cutter angle phi that points from the cutter centre to the wanted contact zone (branch choice).

    The zone is where the nominal cutter circle (radius Rc) crosses the member's root line far from the apex: the
    line y = E of the cradle plane parallel to -x, through the work axis displaced by the blank offset E at
    psi_c = 0 (``mp["E"]``, kernel sign; the root line -x itself at zero offset). Where the circle does not reach
    that line, the cutter angle square to the root line, -pi/2 + psi_c.
    """
    S, q, E = mp["S"], mp["q"], np.asarray(mp["E"], float)
    psi = np.asarray(psi, float)
    b0 = np.pi - q + psi
    d2 = Rc**2 - (S * np.sin(q) - E) ** 2
    xr = -S * np.cos(q) - np.sqrt(np.maximum(d2, 0.0))
    return np.where(d2 > 0.0, np.arctan2(E - S * np.sin(b0), xr - S * np.cos(b0)), psi - HALF_PI)


def solve_contact(u, psi, cp, mp, phi_ref):
    """Solve f = n . v = 0 for the cutter angle at given (u, psi_c): P cos phi + Q sin phi + R = 0.

    Because r and n are linear in e(phi) and e(phi).(Omega x e(phi)) = 0, the equation of meshing of a surface of
    revolution is first order in (cos phi, sin phi) for every blade shape, roll law and offset law
    (docs/theory/generation.md, Eq. (G6); seed 001
    Eq. (15), written as v = Omega x r + w with Omega = k - omega_i a and w = omega_i a x A - E' j).

    Returns
    -------
    phi : absolute cutter angle (rad); disc : cos of the half-gap, |disc| <= 1 where a contact exists; and the
    profile quantities ``rho, z, chi, dchi``.
    """
    u, psi = np.broadcast_arrays(np.asarray(u, float), np.asarray(psi, float))
    rho, z, chi, dchi = profile(u, cp)
    s, S, g = cp["s"], mp["S"], mp["gamma"]
    _, w_i, _ = roll(psi, mp)
    E, dE, _ = offset(psi, mp)
    b0 = np.pi - mp["q"] + psi
    Ox, Oz = w_i * np.cos(g), 1.0 - w_i * np.sin(g)
    # w = omega_i a x A - E' j with A = (0, E, -XB): a x A = (-sin g E, -cos g XB, -cos g E)
    wx, wy, wz = -w_i * np.sin(g) * E, -w_i * np.cos(g) * mp["XB"] - dE, -w_i * np.cos(g) * E
    nr, nz = np.sin(chi), s * np.cos(chi)
    sb, cb = np.sin(b0), np.cos(b0)
    P = -nr * S * Oz * sb + nr * wx
    Q = nr * S * Oz * cb - (z * nr - rho * nz) * Ox + nr * wy
    R = nz * S * Ox * sb + nz * wz
    amp = np.hypot(P, Q)
    disc = -R / amp
    half = np.arccos(np.clip(disc, -1.0, 1.0))
    base = np.arctan2(Q, P)
    c1, c2 = base + half, base - half
    d1 = np.abs(np.angle(np.exp(1j * (c1 - phi_ref))))
    d2 = np.abs(np.angle(np.exp(1j * (c2 - phi_ref))))
    phi = np.where(d1 <= d2, c1, c2)
    return dict(phi=phi, disc=disc, rho=rho, z=z, chi=chi, dchi=dchi, u=u, psi=psi, theta=phi - b0)


def machine_state(sol, cp, mp):
    """Cutter point r_m, cutter normal n_h (Eqs. (9)-(10)) and meridian tangent t_h in S_m."""
    phi, psi = sol["phi"], sol["psi"]
    S, q, s = mp["S"], mp["q"], cp["s"]
    e = np.stack([np.cos(phi), np.sin(phi), np.zeros_like(phi)], -1)
    k = np.array([0.0, 0.0, 1.0])
    C = S * np.stack([np.cos(np.pi - q + psi), np.sin(np.pi - q + psi), np.zeros_like(psi)], -1)
    chi = sol["chi"]
    r = C + sol["rho"][..., None] * e + sol["z"][..., None] * k
    n_h = np.sin(chi)[..., None] * e + (s * np.cos(chi))[..., None] * k
    t_h = (s * np.cos(chi))[..., None] * e - np.sin(chi)[..., None] * k
    return r, n_h, t_h, e


def relative_velocity(r, psi, mp):
    """v^(h,i) = k x r - omega_i a x (r - A) - E' j (docs/theory/generation.md, Eqs. (G5)-(G6)), unit cradle rate; also
    pieces for the curvature transfer."""
    a = work_axis(mp)
    _, w_i, dw_i = roll(psi, mp)
    E, dE, ddE = offset(psi, mp)
    A = np.stack([np.zeros_like(E), E, np.full_like(E, -mp["XB"])], -1)
    k = np.array([0.0, 0.0, 1.0])
    j = np.array([0.0, 1.0, 0.0])
    v1 = cross(k, r)
    v2 = w_i[..., None] * cross(a, r - A) + dE[..., None] * j
    dtv = -dw_i[..., None] * cross(a, r - A) + (w_i * dE)[..., None] * cross(a, j) - ddE[..., None] * j
    return dict(v1=v1, v2=v2, v12=v1 - v2, w1=np.broadcast_to(k, r.shape), w2=w_i[..., None] * a, dtv12=dtv)


def to_member(vec, psi, mp, point=True):
    """Map machine-frame vectors (points if ``point``) to the member frame of the canonical (left-hand) machine."""
    g = mp["gamma"]
    a = work_axis(mp)
    psi_i, _, _ = roll(psi, mp)
    if point:
        E, _, _ = offset(psi, mp)
        A = np.stack([np.zeros_like(E), E, np.full_like(E, -mp["XB"])], -1)
        vec = vec - A - mp["XD"] * a
    xb = vec[..., 0] * np.sin(g) + vec[..., 2] * np.cos(g)
    yb = vec[..., 1]
    zb = vec[..., :] @ a
    c, s = np.cos(psi_i), np.sin(psi_i)
    return np.stack([c * xb + s * yb, -s * xb + c * yb, zb], -1)


def axial_radial(r, psi, mp):
    """Axial position z and radius about the work axis of machine points (independent of the work rotation)."""
    g = mp["gamma"]
    E, _, _ = offset(psi, mp)
    dx, dy, dz = r[..., 0], r[..., 1] - E, r[..., 2] + mp["XB"]
    ax = -dx * np.cos(g) + dz * np.sin(g)
    xb = dx * np.sin(g) + dz * np.cos(g)
    return ax - mp["XD"], np.hypot(xb, dy)


def contact_point(sol, mp):
    """Machine-frame point only (lean version of :func:`machine_state`)."""
    phi, psi, S = sol["phi"], sol["psi"], mp["S"]
    b0 = np.pi - mp["q"] + psi
    rho = sol["rho"]
    return np.stack([S * np.cos(b0) + rho * np.cos(phi), S * np.sin(b0) + rho * np.sin(phi), sol["z"]], -1)


# ----------------------------------------------------------------------------------------------------------------
# curvature transfer, docs/theory/generation.md, Eqs. (G13)-(G15) (#curvature-transfer) (exactly that form; the time
# derivative of v12 at fixed r is added to the
# constant-velocity term for modified roll and a variable blank offset, and is zero otherwise). Flank points are
# evaluated per point by the compiled kernel of _core/generation_points.py; these array forms are the reference the
# tests compare it with (tests/generation/test_flank_points_compiled.py) and serve meshing_residual
# ----------------------------------------------------------------------------------------------------------------
def transfer_curvature(n, eI, eII, kI, kII, vel):
    """Principal curvatures/directions of the generated surface from those of the generating surface.

    Parameters
    ----------
    n, eI, eII : (..., 3) unit vectors with eI x eII = n (common normal, generating surface's principal directions).
    kI, kII : (...) principal curvatures of the generating surface, kappa(v) = v.W v with W = -dn/dr.
    vel : dict from :func:`relative_velocity`.

    Returns
    -------
    k_a, k_b : (...) eigenvalues of W2 (k_a >= k_b); d_a, d_b : (..., 3) unit eigenvectors; a33 : (...).
    """
    v12, w12 = vel["v12"], vel["w1"] - vel["w2"]
    vI, vII = np.einsum("...i,...i", v12, eI), np.einsum("...i,...i", v12, eII)
    a13 = -kI * vI - np.einsum("...i,...i", w12, eII)
    a23 = -kII * vII + np.einsum("...i,...i", w12, eI)
    b = np.einsum("...i,...i", n, cross(vel["w1"], vel["v2"]) - cross(vel["w2"], vel["v1"]))
    b = b + np.einsum("...i,...i", n, vel["dtv12"])
    a33 = kI * vI**2 + kII * vII**2 - np.einsum("...i,...i", n, cross(w12, v12)) + b
    W11 = kI - a13 * a13 / a33
    W22 = kII - a23 * a23 / a33
    W12 = -a13 * a23 / a33
    mean, half = 0.5 * (W11 + W22), np.hypot(0.5 * (W11 - W22), W12)
    k_a, k_b = mean + half, mean - half
    ang = 0.5 * np.arctan2(2.0 * W12, W11 - W22)          # eigenvector of k_a at angle ang from eI
    ca, sa = np.cos(ang)[..., None], np.sin(ang)[..., None]
    d_a = ca * eI + sa * eII
    d_b = -sa * eI + ca * eII
    return k_a, k_b, d_a, d_b, a33
