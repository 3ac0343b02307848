"""Kernels of local synthesis: Litvin's three relations at the mean contact point, in one fixed frame.

Derivation (Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., §9.4 "Local synthesis", rewritten in the
convex = positive convention of docs/conventions.md). Time is the pinion rotation phi1 (unit pinion rate). Both axes
pass through the origin. n is the pinion's outward unit normal at the contact point r; the gear's outward normal is
-n. K1, K2 are the curvature tensors (3 x 3, acting on the tangent plane) of pinion and gear, each w.r.t. its own
outward normal (K = dn_out/dr, a convex flank has positive curvatures).

* Contact point: dr/dt = w1 x r + v_r1 = w2 x r + v_r2, so v_r2 = v_r1 + v12 with v12 = w12 x r, w12 = w1 - w2.
* Common normal: dn/dt = w1 x n + K1 v_r1 = w2 x n - K2 v_r2, i.e. K1 v_r1 + K2 v_r2 = -w12 x n.
* Meshing n . v12 = 0 along the motion, with the gear's angular acceleration eps2 a2 (d w12/dt = -eps2 a2):
  v_r2 . b + c = 0 with

      b = -K2 v12 - w12 x n,
      c = (w2 x n) . v12 + n . (w12 x (w2 x r)) - eps2 n . (a2 x r).

Hence, for a prescribed direction t of the contact path on the gear, v_r2 = s t with s = -c / (t . b) (relation 1:
the path direction and the derivative of the gear ratio m21' fix the speed of the contact point), and the relative
curvature tensor K = K1 + K2 obeys (K1 + K2) v_r1 = b with v_r1 = v_r2 - v12 (relation 2: two linear conditions on
K). The contact ellipse of an elastic approach delta has semi-axes sqrt(2 delta / lam) for the eigenvalues lam of K
(``spiralbevel.meshing.ellipse``), so the semi-major axis a fixes lam_min = 2 delta / a^2 (relation 3). In the basis
e = v_r1/|v_r1|, f = n x e: K11 = b.e/|v_r1|, K12 = b.f/|v_r1|, and det(K - lam_min I) = 0 gives
K22 = lam_min + K12^2 / (K11 - lam_min), which requires K11 > lam_min. Then K1 = K - K2.
"""

from __future__ import annotations

import numpy as np

__all__ = ["curvature_tensor", "path_speed_terms", "relative_curvature_from_path", "tangent_components"]


def curvature_tensor(k, dirs):
    """K = k_1 d_1 d_1^T + k_2 d_2 d_2^T, shape (..., 3, 3), from ``k (..., 2)`` and unit ``dirs (..., 2, 3)``."""
    k, d = np.asarray(k, float), np.asarray(dirs, float)
    return np.einsum("...a,...ai,...aj->...ij", k, d, d)


def path_speed_terms(r, n, K2, w1, w2, a2, eps2):
    """Vectors v12, b and scalar c of the module docstring (fixed frame, per unit pinion rotation).

    Parameters
    ----------
    r, n : (3,) float, mm and -
        Contact point and pinion outward normal.
    K2 : (3, 3) float, 1/mm
        Gear curvature tensor w.r.t. the gear's outward normal (-n).
    w1, w2 : (3,) float, rad/rad
        Angular velocities per unit pinion rotation.
    a2 : (3,) float
        Unit gear axis.
    eps2 : float, rad/rad^2
        Angular acceleration of the gear about +a2 per unit pinion rotation squared, d^2 phi2 / d phi1^2.
    """
    w12 = w1 - w2
    v12 = np.cross(w12, r)
    b = -K2 @ v12 - np.cross(w12, n)
    c = (np.cross(w2, n) @ v12 + n @ np.cross(w12, np.cross(w2, r)) - eps2 * (n @ np.cross(a2, r)))
    return v12, b, float(c)


def relative_curvature_from_path(n, t_path, v12, b, c, lam_min):
    """Relative curvature tensor K = K1 + K2 realising a contact path direction and a TE curvature.

    Parameters
    ----------
    n : (3,) float
        Common unit normal.
    t_path : (3,) float
        Unit tangent of the contact path on the gear (tangent plane).
    v12, b : (3,) float; c : float
        From :func:`path_speed_terms`.
    lam_min : float, 1/mm
        Smaller principal relative curvature, 2 delta / a^2.

    Returns
    -------
    K : (3, 3) float, 1/mm
    v_r2, v_r1 : (3,) float, mm/rad
        Velocities of the contact point over the gear and the pinion per unit pinion rotation.
    ok : str
        "" if the relations have a solution, else the reason.
    """
    tb = float(t_path @ b)
    if abs(tb) < 1e-14 * (np.linalg.norm(b) + 1e-300):
        return None, None, None, "the path direction is perpendicular to b: the contact cannot move along it"
    v_r2 = (-c / tb) * t_path
    v_r1 = v_r2 - v12
    speed = float(np.linalg.norm(v_r1))
    e = v_r1 / speed
    f = np.cross(n, e)
    K11, K12 = float(b @ e) / speed, float(b @ f) / speed
    if not K11 > lam_min:
        return None, v_r2, v_r1, (f"the relative normal curvature along the pinion path, {K11:.4g} 1/mm, is not above "
                                  f"lam_min = {lam_min:.4g} 1/mm")
    K22 = lam_min + K12 * K12 / (K11 - lam_min)
    K = K11 * np.outer(e, e) + K12 * (np.outer(e, f) + np.outer(f, e)) + K22 * np.outer(f, f)
    return K, v_r2, v_r1, ""


def tangent_components(p, n, K, axis=(0.0, 0.0, 1.0)):
    """Rotation-invariant description of a surface point about ``axis`` (through the origin).

    Returns (..., 7): axial position, radius, normal components along the axis and along the radial unit vector,
    and the tangent-plane tensor components K_aa, K_ab, K_bb in the basis t_a = unit(axis - (axis.n) n), t_b = n x t_a.
    The 8th value, returned separately, is the tangential normal component (its sign picks the branch).
    """
    p, n, K, axis = (np.asarray(x, float) for x in (p, n, K, axis))
    ax = p @ axis
    radial = p - ax[..., None] * axis
    rad = np.linalg.norm(radial, axis=-1)
    rhat = radial / rad[..., None]
    nz = n @ axis
    ta = axis - nz[..., None] * n
    ta /= np.linalg.norm(ta, axis=-1, keepdims=True)
    tb = np.cross(n, ta)
    kaa = np.einsum("...i,...ij,...j", ta, K, ta)
    kab = np.einsum("...i,...ij,...j", ta, K, tb)
    kbb = np.einsum("...i,...ij,...j", tb, K, tb)
    nt = np.einsum("...i,...i", n, np.cross(axis, rhat))
    out = np.stack([ax, rad, nz, np.einsum("...i,...i", n, rhat), kaa, kab, kbb], -1)
    return out, nt
