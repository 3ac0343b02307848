"""The blade part of a face-milled generated flank in the (phi, psi_c) chart: cutter angle and cradle angle as the
surface parameters, the blade parameter u solved from the equation of meshing of generation.

Why a second chart. In the (u, psi_c) chart of :mod:`spiralbevel._core.generation` the cutter angle phi is the root
of ``f = P cos(phi) + Q sin(phi) + R = 0`` (seed 001 Eqs. (13)-(15), docs/theory/generation.md, Eq. (G6)); the chart
folds where the two roots merge (``f_phi = 0``: the contact line of generation on the cutter is tangent to the blade
circle u = const). The generated surface itself is regular there: only its projection onto (u, psi_c) folds.
On the blade, f is *linear* in u for a straight blade (the cone normal is constant along a generatrix and the point
moves linearly with u): ``P`` and ``R`` do not depend on u and ``Q = Q_0 + u Omega_x``, so

    u(phi, psi_c) = -(P cos(phi) + Q_0 sin(phi) + R) / (Omega_x sin(phi)),

regular wherever ``Omega_x sin(phi) != 0`` (Omega_x = omega_i cos(gamma), the roll rate times the cosine of the
machine root angle; ``sin(phi) = 0`` only for a contact zone on the cutter-centre line parallel to the root line, a
spiral angle near 90 deg); docs/theory/generation.md, Eq. (G9), the explicit form of the dual spiral article. A
circular-arc blade is solved by Newton's method in u from the straight-blade value.

The meridian used here is the blade (straight line or arc) *extended* below the fillet junction: points with
u < u_j are not on the flank (the fillet is generated in the (u, psi_c) chart).

Same frames and conventions as :mod:`spiralbevel._core.generation`; results in the member frame of the canonical
(left-hand) machine, outward normal n = -s n_h. Pure functions on float64 arrays, mm and rad.
"""

from __future__ import annotations

import numpy as np

from .generation import profile
from .generation_jet import _to_member_stack, meshing_coefficients

__all__ = ["blade_profile", "blade_u", "blade_points", "blade_jet", "meshing_function"]


def blade_profile(u, cp):
    """Blade meridian (straight or arc) extended past the fillet junction: rho, z, chi, d(chi)/du."""
    u = np.asarray(u, float)
    s = cp["s"]
    if np.isinf(cp["rp"]):
        chi = np.full_like(u, cp["chi0"])
        return cp["Rh"] + s * u * np.cos(cp["chi0"]), -u * np.sin(cp["chi0"]), chi, np.zeros_like(u)
    chi = cp["chi0"] - (u - cp["up"]) / cp["rp"]
    return (cp["rc"] - cp["rp"] * s * np.sin(chi), cp["zc"] - cp["rp"] * np.cos(chi), chi,
            np.full_like(u, -1.0 / cp["rp"]))


def meshing_function(u, phi, psi, cp, mp):
    """f = P cos(phi) + Q sin(phi) + R (mm/rad, = n_h . v at unit cradle rate) of the equation of meshing at
    (u, phi, psi_c) on the whole blade profile (fillet included); zero on the generated surface."""
    return _terms(u, phi, psi, cp, mp, profile)["f"]


def _terms(u, phi, psi, cp, mp, meridian=None):
    """f = P cos phi + Q sin phi + R at (u, phi, psi_c) and its partial derivatives f_u, f_phi, f_psi, with the
    pieces the jet needs (coefficients of :func:`~spiralbevel._core.generation_jet.meshing_coefficients`)."""
    C = meshing_coefficients(u, psi, cp, mp, meridian or blade_profile)
    P, Q, R = C["P"], C["Q"], C["R"]
    c, sn = np.cos(phi), np.sin(phi)
    return dict(f=P * c + Q * sn + R, f_u=C["P_u"] * c + C["Q_u"] * sn + C["R_u"], f_phi=Q * c - P * sn,
                f_psi=C["P_p"] * c + C["Q_p"] * sn + C["R_p"], rho=C["rho"], z=C["z"], chi=C["chi"],
                dchi=C["dchi"], psi_i=C["psi_i"], w=C["w"], E=C["E"], dE=C["dE"], sb=C["sb"], cb=C["cb"], c=c, sn=sn)


def blade_u(phi, psi, cp, mp, max_iter=8):
    """Blade parameter u (mm) of the generated point at cutter angle ``phi`` and cradle angle ``psi`` (rad).

    Exact in one step for a straight blade (f linear in u); Newton's method for an arc blade (stops at a relative
    change below 1e-14 of the blade length scale). Returns (u, terms) with the terms of the equation of meshing at
    the solution; ``terms["f_u"] == 0`` marks the chart's singular set (u is then non-finite).
    """
    phi, psi = np.broadcast_arrays(np.asarray(phi, float), np.asarray(psi, float))
    u = np.full(phi.shape, cp["u_j"])
    n = 1 if np.isinf(cp["rp"]) else max_iter
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(n):
            T = _terms(u, phi, psi, cp, mp)
            du = -T["f"] / T["f_u"]
            u = u + du
            if np.all(~(np.abs(du) > 1e-14 * (1.0 + abs(cp["Rh"])))):
                break
        T = _terms(u, phi, psi, cp, mp)
    return u, T


def blade_points(phi, psi, cp, mp):
    """Machine-frame points (..., 3) mm and blade parameters u (...) mm at (phi, psi_c)."""
    u, T = blade_u(phi, psi, cp, mp)
    S, b0 = mp["S"], np.pi - mp["q"] + np.asarray(psi, float)
    rho = T["rho"]
    r = np.stack([S * np.cos(b0) + rho * T["c"], S * np.sin(b0) + rho * T["sn"], T["z"]], -1)
    return r, u


def blade_jet(phi, psi, cp, mp):
    """Points, outward normals and their derivatives w.r.t. (phi, psi_c) of the blade part of a generated flank.

    Parameters
    ----------
    phi : (...) float, rad
        Absolute cutter angle (as ``solve_contact``'s ``phi``).
    psi : (...) float, rad
        Cradle angle (broadcast with ``phi``).
    cp, mp : dict
        Cutter and machine parameters (see :mod:`spiralbevel._core.generation`).

    Returns
    -------
    S : (..., 3, 6) float
        Columns r (mm), n (-), dr/dphi (mm/rad), dr/dpsi_c (mm/rad), dn/dphi (1/rad), dn/dpsi_c (1/rad), member frame
        of the canonical machine (no mirror, no phasing turn).
    u : (...) float, mm
        Blade parameter (on the flank where u >= u_j).
    f_u : (...) float
        d f / d u of the equation of meshing; the chart is regular where it is non-zero.

    Notes
    -----
    Implicit differentiation of f(u, phi, psi_c) = 0: u_phi = -f_phi / f_u, u_psi = -f_psi / f_u; the total
    derivatives are D_phi = d_phi + u_phi d_u and D_psi = d_psi + u_psi d_u with the partials d_u r = t_h (the
    meridian tangent, u being the meridian's arc length), d_phi r = rho k x e(phi), d_psi r = d(C - A)/d psi_c, and
    the work rotation psi_i(psi_c) as in ``generation_jet``. The compiled per-point form that TCA and
    ``GeneratedSurface`` run is :mod:`spiralbevel._core.generation_blade_jet`; this array form is its reference
    (``tests/meshing/test_generated_jet.py``) and serves per-system offset laws.
    """
    phi, psi = np.broadcast_arrays(np.asarray(phi, float), np.asarray(psi, float))
    shape = phi.shape
    phi, psi = phi.reshape(-1), psi.reshape(-1)
    u, T = blade_u(phi, psi, cp, mp)
    s, S, g, XB, XD = cp["s"], mp["S"], mp["gamma"], mp["XB"], mp["XD"]
    sg, cg = np.sin(g), np.cos(g)
    with np.errstate(divide="ignore", invalid="ignore"):
        u_phi, u_psi = -T["f_phi"] / T["f_u"], -T["f_psi"] / T["f_u"]
    rho, z, chi, dchi, c, sn = T["rho"], T["z"], T["chi"], T["dchi"], T["c"], T["sn"]
    nr, nc = np.sin(chi), np.cos(chi)
    snr, snc = s * nr, s * nc
    V = np.empty(phi.shape + (3, 6))
    V[:, 0, 0] = S * T["cb"] + rho * c + XD * cg
    V[:, 1, 0] = S * T["sb"] + rho * sn - T["E"]
    V[:, 2, 0] = z + (XB - XD * sg)
    V[:, 0, 1] = -snr * c
    V[:, 1, 1] = -snr * sn
    V[:, 2, 1] = -nc
    # partials in u: meridian tangent t_h, and dn/du = -s dchi t_h ... written out as in generation_jet
    ru = (snc * c, snc * sn, -nr)
    nu = (-dchi * snc * c, -dchi * snc * sn, dchi * nr)
    V[:, 0, 2] = -rho * sn + u_phi * ru[0]
    V[:, 1, 2] = rho * c + u_phi * ru[1]
    V[:, 2, 2] = u_phi * ru[2]
    V[:, 0, 3] = -S * T["sb"] + u_psi * ru[0]
    V[:, 1, 3] = S * T["cb"] - T["dE"] + u_psi * ru[1]
    V[:, 2, 3] = u_psi * ru[2]
    V[:, 0, 4] = snr * sn + u_phi * nu[0]
    V[:, 1, 4] = -snr * c + u_phi * nu[1]
    V[:, 2, 4] = u_phi * nu[2]
    V[:, 0, 5] = u_psi * nu[0]
    V[:, 1, 5] = u_psi * nu[1]
    V[:, 2, 5] = u_psi * nu[2]
    M = _to_member_stack(V, T["psi_i"], g, np.array([-cg, 0.0, sg]))
    w = T["w"]
    M[:, 0, 3] += w * M[:, 1, 0]
    M[:, 1, 3] -= w * M[:, 0, 0]
    M[:, 0, 5] += w * M[:, 1, 1]
    M[:, 1, 5] -= w * M[:, 0, 1]
    return M.reshape(shape + (3, 6)), u.reshape(shape), T["f_u"].reshape(shape)
