"""Kernels of tooth contact analysis (TCA): assembly transforms, the 5 x 5 contact system and its Jacobian, a batched
minimum-norm Newton solver, and the relative curvature at a contact point.

Pure functions on float64 arrays (mm, rad, xyz on the trailing axis). Seed 001 Eq. (16) (docs/theory/tca.md, Eq. (T5))
in
the pair frame of docs/conventions.md (docs/theory/gearing.md, Eq. (M1)) with the misalignments of docs/conventions.md
"Misalignments".

Unknowns per system: x = (q1_0, q1_1, q2_0, q2_1, phi2) with q1, q2 the surface parameters of pinion and gear;
the pinion rotation phi1 is prescribed. Equations (all in mm):

    F[0:3] = r1f - r2f                      r1f = d1 + R_z(phi1) r1(q1),  r2f = d2 + R(a2, phi2) R_y(S) r2(q2)
    F[3:5] = L * (n1f + n2f) . e_j          e_1, e_2: a fixed basis orthogonal to the start normal of the system

Outward normals are opposite at the contact (n1f = -n2f), so ``n1f + n2f = 0``; two projections are independent.
L (mm) is a length scale that gives the normal equations the unit of the position equations.
"""

from __future__ import annotations

import numpy as np

from .rotations import rot_z

__all__ = [
    "assembly_axes",
    "tangent_basis",
    "contact_system",
    "dF_dphi1",
    "minnorm_step",
    "weingarten",
    "relative_curvature",
    "ellipse_axes",
]


def assembly_axes(shaft_angle, d_a1=0.0, d_a2=0.0, d_offset=0.0, d_shaft=0.0):
    """Pinion and gear axes and origins of the (misaligned) assembly in the fixed frame.

    Returns
    -------
    a1, o1, a2, o2 : (3,) float
        Unit axes (-) and member-frame origins (apexes, mm). a1 = +z, o1 = d_a1 a1 + d_offset e_y;
        a2 = (sin(S + dS), 0, cos(S + dS)), o2 = d_a2 a2.
    B2 : (3, 3) float
        R_y(S + dS): gear member frame -> fixed frame at phi2 = 0.
    """
    s = shaft_angle + d_shaft
    c, sn = float(np.cos(s)), float(np.sin(s))  # the values of rot_y(s); built from floats: called once per TCA
    a1 = np.array([0.0, 0.0, 1.0])
    a2 = np.array([sn, 0.0, c])
    o1 = np.array([0.0, d_offset, d_a1])
    o2 = np.array([d_a2 * sn, 0.0 * d_a2, d_a2 * c])
    return a1, o1, a2, o2, np.array([[c, 0.0, sn], [0.0, 1.0, 0.0], [-sn, 0.0, c]])


def tangent_basis(n):
    """Two unit vectors (..., 3) orthogonal to the unit vectors ``n (..., 3)`` and to each other."""
    n = np.asarray(n, float)
    helper = np.where((np.abs(n[..., 0]) < 0.6)[..., None], np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
    e1 = cross(n, helper)
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = cross(n, e1)
    return e1, e2


def _flat(a, shape, tail):
    """``a`` broadcast to ``shape + tail`` as a contiguous, writable float64 array of rows ``(-1,) + tail``.

    Writable: a read-only array (``broadcast_to`` returns one) is another numba type and would compile every kernel it
    reaches a second time. An array of that shape is passed as it is when it already is such an array (the kernels
    only read it), else copied once (no broadcast)."""
    if type(a) is np.ndarray and a.dtype == np.float64 and a.shape == shape + tail:
        f = a.flags
        if not (f.c_contiguous and f.writeable and f.aligned):
            a = np.array(a, float, order="C")
        return a.reshape((-1,) + tail)
    return np.require(np.broadcast_to(np.asarray(a, float), shape + tail), float, "CW").reshape((-1,) + tail)


def _pose(phi1, phi2, axes):
    """Member -> fixed rotations R1 = R_z(phi1), R2 = R(a2, phi2) B2 (..., 3, 3), compiled
    (:func:`spiralbevel._core.tca_ellipse.pose_batch`)."""
    from .tca_ellipse import pose_batch  # numba stays off the import path of the numpy-only users of this module

    a1, o1, a2, o2, B2 = axes
    shape = np.shape(phi1)
    if np.shape(phi2) != shape:
        shape = np.broadcast_shapes(shape, np.shape(phi2))
    p1, p2 = _flat(phi1, shape, ()), _flat(phi2, shape, ())
    R1, R2 = np.empty((p1.size, 3, 3)), np.empty((p1.size, 3, 3))
    pose_batch(p1, p2, np.ascontiguousarray(a2, float), np.ascontiguousarray(B2, float), R1, R2)
    return R1.reshape(shape + (3, 3)), R2.reshape(shape + (3, 3))


def _mv(R, v):
    return np.einsum("...ij,...j->...i", R, v)


def cross(a, b):
    """Cross product over the trailing axis (broadcasting), faster than numpy.cross for small batches."""
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def contact_system(r1, n1, dr1, dn1, r2, n2, dr2, dn2, phi1, phi2, axes, basis, scale, jac=True):
    """Residual F (..., 5) mm and Jacobian dF/dx (..., 5, 5) of the contact system (see module docstring).

    Parameters
    ----------
    r1, n1, r2, n2 : (..., 3) float
        Member-frame points (mm) and outward unit normals of pinion (1) and gear (2).
    dr1, dn1, dr2, dn2 : (..., 3, 2) float
        Their derivatives with respect to the surface parameters (columns); unused when ``jac`` is False.
    phi1, phi2 : (...) float, rad
        Pinion rotation about a1 and gear rotation about a2.
    axes : tuple
        Output of :func:`assembly_axes`.
    basis : ((..., 3), (..., 3))
        Fixed unit vectors e_1, e_2 for the two normal equations.
    scale : float, mm
        Length scale L of the normal equations.

    Notes
    -----
    d/dphi2 [R(a2, phi2) v] = a2 x (R(a2, phi2) v); the pinion parameters enter through R_z(phi1) dr1, R_z(phi1) dn1.
    """
    a1, o1, a2, o2, B2 = axes
    R1, R2 = _pose(phi1, phi2, axes)
    r2r = _mv(R2, r2)
    n2f = _mv(R2, n2)
    ns = _mv(R1, n1) + n2f
    e1, e2 = basis
    shape = ns.shape[:-1]
    F = np.empty(shape + (5,))
    F[..., :3] = o1 + _mv(R1, r1) - o2 - r2r
    F[..., 3] = scale * np.einsum("...i,...i->...", ns, e1)
    F[..., 4] = scale * np.einsum("...i,...i->...", ns, e2)
    if not jac:
        return F, None
    J = np.empty(shape + (5, 5))
    J[..., :3, 0:2] = R1 @ dr1
    J[..., :3, 2:4] = -(R2 @ dr2)
    J[..., :3, 4] = -cross(a2, r2r)
    N1 = R1 @ dn1
    N2 = R2 @ dn2
    c = cross(a2, n2f)
    for k, e in enumerate((e1, e2)):
        J[..., 3 + k, 0:2] = scale * np.einsum("...ij,...i->...j", N1, e)
        J[..., 3 + k, 2:4] = scale * np.einsum("...ij,...i->...j", N2, e)
        J[..., 3 + k, 4] = scale * np.einsum("...i,...i->...", c, e)
    return F, J


def dF_dphi1(r1, n1, phi1, axes, basis, scale):
    """Partial derivative of F with respect to the prescribed pinion rotation phi1, (..., 5) mm/rad."""
    a1 = axes[0]
    R1 = rot_z(phi1)
    r1f = _mv(R1, r1)
    n1f = _mv(R1, n1)
    out = np.empty(r1f.shape[:-1] + (5,))
    out[..., :3] = cross(a1, r1f)
    dn = cross(a1, n1f)
    out[..., 3] = scale * np.einsum("...i,...i->...", dn, basis[0])
    out[..., 4] = scale * np.einsum("...i,...i->...", dn, basis[1])
    return out


def minnorm_step(J, F, rcond=1e-10):
    """Minimum-norm least-squares Newton step dx = -pinv(J) F with column equilibration, batched.

    ``J (..., m, 5)`` with m >= 5 (extra rows, e.g. an anchor equation on a contact line, give a Gauss-Newton step).

    Singular values below ``rcond * s_max`` are discarded: along a contact line (exact conjugate pair) the 5 x 5
    system is singular and the step has no component along the line.

    Returns
    -------
    dx : (..., 5) float
    sratio : (...) float
        s_min / s_max of the column-equilibrated Jacobian (about 1e-16 on a contact line).
    """
    cn = np.linalg.norm(J, axis=-2)
    cn = np.where(cn > 0, cn, 1.0)
    Js = J / cn[..., None, :]
    U, s, Vt = np.linalg.svd(Js, full_matrices=False)
    smax = s[..., :1]
    inv = np.where(s > rcond * smax, 1.0 / np.where(s > 0, s, 1.0), 0.0)
    y = np.einsum("...ji,...j->...i", U, -F) * inv
    dxs = np.einsum("...ji,...j->...i", Vt, y)
    return dxs / cn, s[..., -1] / s[..., 0]


def weingarten(dr, dn):
    """Weingarten (shape) tensor W (..., 3, 3) with W dr_i = dn_i on the tangent plane and W n = 0.

    With outward normals, v . W v = v . (dn/dr) v is the normal curvature in the convex = positive convention of
    docs/conventions.md. W = dn (dr^T dr)^-1 dr^T, symmetrized (exactly symmetric for a smooth surface).
    Compiled: :func:`spiralbevel._core.tca_ellipse.weingarten_batch`.
    """
    from .tca_ellipse import weingarten_batch

    shape = np.broadcast_shapes(np.shape(dr), np.shape(dn))[:-2]
    W = np.empty((int(np.prod(shape)), 3, 3))
    weingarten_batch(_flat(dr, shape, (3, 2)), _flat(dn, shape, (3, 2)), W, False, W)
    return W.reshape(shape + (3, 3))


def relative_curvature(W1, W2, n):
    """Principal relative curvatures and directions at contact points.

    Parameters
    ----------
    W1, W2 : (..., 3, 3) float, 1/mm
        Weingarten tensors of both surfaces in a common frame, each w.r.t. its own outward normal.
    n : (..., 3) float
        Common unit normal (either sign).

    Returns
    -------
    lam : (..., 2) float, 1/mm
        Eigenvalues lam_1 <= lam_2 of K = W1 + W2 restricted to the tangent plane. The separation of the two
        surfaces at a tangent-plane offset xi from the contact point is s(xi) = 1/2 xi^T K xi + O(|xi|^3).
    dirs : (..., 2, 3) float
        Matching unit eigenvectors (tangent plane, fixed frame); dirs[..., 0] is the long axis of the ellipse,
        dirs[..., 1] = n x dirs[..., 0].

    Notes
    -----
    Compiled: :func:`spiralbevel._core.tca_ellipse.relative_curvature_batch` (K = T^T (W1 + W2) T on the basis T of
    :func:`tangent_basis`, its 2 x 2 eigenproblem in closed form).
    """
    from .tca_ellipse import relative_curvature_batch

    shape = np.broadcast_shapes(np.shape(W1)[:-2], np.shape(W2)[:-2], np.shape(n)[:-1])
    m = int(np.prod(shape))
    lam, dirs = np.empty((m, 2)), np.empty((m, 2, 3))
    relative_curvature_batch(_flat(W1, shape, (3, 3)), _flat(W2, shape, (3, 3)), _flat(n, shape, (3,)), lam, dirs)
    return lam.reshape(shape + (2,)), dirs.reshape(shape + (2, 3))


def ellipse_axes(lam, approach):
    """Semi-axes (..., 2) mm of the instantaneous contact ellipse for an elastic approach ``approach`` mm.

    The ellipse is the locus s(xi) = approach with s = 1/2 (lam_1 xi_1^2 + lam_2 xi_2^2), hence
    a_i = sqrt(2 approach / lam_i) = sqrt(approach / A_i) with Litvin's A_i = lam_i / 2. Non-positive lam gives inf
    (line contact or no proper ellipse).
    """
    lam = np.asarray(lam, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.sqrt(2.0 * approach / lam)
    return np.where(lam > 0, out, np.inf)
