"""The pinion flank exactly conjugate to a wheel flank in a hypoid pair (crossed axes; docs/theory/hypoid.md).

A wheel point p and outward normal m (wheel member frame) turned by phi2 about the wheel axis sit at
x = o2 + R(phi2) B2 p with the normal R(phi2) B2 n. The equation of meshing n . v12 = 0, with
v12 = w12 x x + b (``HypoidPairKinematics.relative_velocity``, b = v12 at the origin), reads

    f(phi2) = (w12 x o2 + b) . R q + w12 . R (P x Q) = A cos(phi2) + B sin(phi2) + C,

with P = B2 p, Q = B2 m (R is a rotation about an axis through the origin and o2 lies on it, so o2 x R Q =
R (o2 x Q)); every term is v . R(phi2) u, linear in (cos, sin). A, B, C follow from f at 0, pi/2 and pi, and of the
two roots the one nearer ``phi2_ref`` is taken. The conjugate pinion point is x carried back to the pinion member frame
at phi1 = -phi2 / (z1/z2): r1 = R_z(-phi1) (x - o1), with the pinion's outward normal -R_z(-phi1) R(phi2) Q. With
E = 0 this is the envelope of ``spiralbevel.meshing.envelope`` written for the wheel as the generating member.
"""

from __future__ import annotations

import numpy as np

from .._core.rotations import rot_axis, rot_z

__all__ = ["conjugate_pinion_points", "hypoid_easeoff"]


def conjugate_pinion_points(gear_points, gear_normals, kinematics, phi2_ref: float = 0.0):
    """Pinion points and outward normals conjugate to wheel points in a hypoid (or intersecting-axes) pair.

    Parameters
    ----------
    gear_points, gear_normals : (..., 3) float, mm and -
        Wheel flank points and outward unit normals in the wheel member frame (as phased for the pair).
    kinematics : HypoidPairKinematics
    phi2_ref : float, rad
        Wheel rotation near which the contact is sought (0: the phasing's mean contact).

    Returns
    -------
    points, normals : (..., 3) float
        Conjugate pinion points (mm) and outward normals in the pinion member frame; NaN where no wheel rotation
        satisfies the equation of meshing.
    phi2 : (...) float, rad
        Wheel rotation of the contact.
    """
    p = np.asarray(gear_points, float)
    m = np.asarray(gear_normals, float)
    a1, o1, a2, o2, B2 = kinematics.axes()
    P, Q = p @ B2.T, m @ B2.T
    w12 = kinematics.relative_angular_velocity()
    b = kinematics.relative_velocity(np.zeros(3))
    c = np.cross(w12, o2) + b
    PQ = np.cross(P, Q)

    def f(phi):
        R = rot_axis(a2, phi)
        return (Q @ R.T) @ c + (PQ @ R.T) @ w12

    f0, f1, f2 = f(0.0), f(0.5 * np.pi), f(np.pi)
    C = 0.5 * (f0 + f2)
    A = 0.5 * (f0 - f2)
    B = f1 - C
    with np.errstate(invalid="ignore", divide="ignore"):
        half = np.arccos(-C / np.hypot(A, B))
    base = np.arctan2(B, A)
    r1, r2 = base + half, base - half
    d1 = np.abs(np.angle(np.exp(1j * (r1 - phi2_ref))))
    d2 = np.abs(np.angle(np.exp(1j * (r2 - phi2_ref))))
    phi2 = np.where(d1 <= d2, r1, r2)
    R = rot_axis(a2, phi2)                                  # (..., 3, 3)
    x = o2 + np.einsum("...ij,...j->...i", R, P)
    n = np.einsum("...ij,...j->...i", R, Q)
    phi1 = -phi2 / kinematics.ratio
    Rb = np.swapaxes(rot_z(phi1), -1, -2)                   # fixed -> pinion member frame
    r = np.einsum("...ij,...j->...i", Rb, x - o1)
    nn = -np.einsum("...ij,...j->...i", Rb, n)
    return r, nn, phi2


def hypoid_easeoff(pinion, gear, kinematics, *, n_face: int = 15, n_profile: int = 9, face_margin: float = 0.05,
                   profile_margin: float = 0.05, iterations: int = 4):
    """Ease-off of a pinion flank against the flank conjugate to a wheel flank in a hypoid pair.

    The method of :func:`spiralbevel.meshing.easeoff.easeoff` (grid over the projected pinion tooth, rigid rotation
    about the pinion axis removed at the mean point, distance along the real pinion's outward normal; positive =
    material removed from the pinion), with the conjugate flank of :func:`conjugate_pinion_points` (crossed axes).

    Parameters
    ----------
    pinion : ToothFlank
        Real pinion flank (pinion member frame).
    gear : GeneratedSurface
        The mating wheel flank phased for the pair (``phased_for_hypoid_pair`` or ``tca_surfaces``), so that its
        contact with the pinion is near zero wheel rotation.
    kinematics : HypoidPairKinematics
    n_face, n_profile, face_margin, profile_margin, iterations
        As ``easeoff``.

    Returns
    -------
    EaseOff
        ``branch`` is 0 (the root nearest the phased mean contact); ``gear_u, gear_v`` are the wheel surface's own
        parameters (cutter angle phi and cradle angle psi_c, rad, for a ``GeneratedSurface``).
    """
    from .easeoff import EaseOff
    from .flank_access import FlankAccess, flank_access, normal_line_distance, tooth_grid

    pa = flank_access(pinion)
    tg = tooth_grid(pinion, n_face, n_profile, face_margin, profile_margin)
    d = tg["pitch_angle"]
    mR = float(tg["Rm"])
    ax_all = np.append(tg["axial"].ravel(), mR * np.cos(d))
    rad_all = np.append(tg["radius"].ravel(), mR * np.sin(d))
    P, N, pu, pv = pa.locate(ax_all, rad_all)

    def conj_surface(u, v):
        g, n = gear.evaluate(np.stack(np.broadcast_arrays(u, v), -1))
        r, nn, _ = conjugate_pinion_points(g, n, kinematics)
        return r, nn

    grid = gear.flank.grid(9, 5, curvature=False)         # start samples in the surface's (phi, psi_c) chart
    if hasattr(gear, "chart_params"):                      # a Formate wheel: its own (u, theta) chart
        start = tuple(v.ravel() for v in gear.chart_params(grid))
    else:
        start = (gear.cutter_angle(grid.theta, grid.psi_c).ravel(), grid.psi_c.ravel())
    conj = FlankAccess(conj_surface, start)
    C, _, _, _ = conj.locate(ax_all[-1:], rad_all[-1:])
    ang = float(np.angle(np.exp(1j * (np.arctan2(C[-1, 1], C[-1, 0]) - np.arctan2(P[-1, 1], P[-1, 0])))))
    back = rot_z(-ang)

    def turned(axial, radius):
        p, n, u, v = conj.locate(axial, radius)
        return p @ back.T, n @ back.T, u, v

    values = normal_line_distance(FlankAccess(conj_surface, conj.samples, turned), P, N, iterations)
    Cg, _, gu, gv = turned(ax_all, rad_all)
    shape, k = tg["R"].shape, -1
    return EaseOff(R=tg["R"], h=tg["h"], axial=tg["axial"], radius=tg["radius"], values=values[:k].reshape(shape),
                   points=P[:k].reshape(shape + (3,)), normals=N[:k].reshape(shape + (3,)),
                   conjugate_points=Cg[:k].reshape(shape + (3,)), pinion_u=pu[:k].reshape(shape),
                   pinion_v=pv[:k].reshape(shape), gear_u=gu[:k].reshape(shape), gear_v=gv[:k].reshape(shape),
                   mean_R=mR, mean_h=0.0, rigid_rotation=ang, branch=0)
