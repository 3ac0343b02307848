"""The compiled flank points (``_core.generation_points``: point, normal, principal curvatures and directions) against
two independent computations, on many random points of the four seed 001 basic flanks (both members, sides and
hands; straight and arc blades; with modified roll and a variable blank offset):

* the numpy kernels of ``_core.generation`` (``machine_state``, ``relative_velocity``, ``transfer_curvature``),
  evaluated on whole arrays and ordered here as ``FlankPoints`` states (the same formulas in array form);
* the fundamental forms of the compiled first-order jet in the (phi, psi_c) chart (``_core.generation_blade_jet``:
  r, n and their analytic derivatives by implicit differentiation of the equation of meshing), a method that does not
  use the curvature transfer at all: the shape operator from I = r_i . r_j and the second form r_i . n_j.
"""

import math

import numpy as np
import pytest
from conftest import CASES, basic_flank

from spiralbevel._core import generation as _g
from spiralbevel._core import generation_blade_jet as _gbj
from spiralbevel.conventions import Hand

MIRROR = np.array([1.0, -1.0, 1.0])
VARIANTS = [(math.inf, {}), (300.0, {"modified_roll": (0.05, -0.3, 0.2)}),
            (math.inf, {"blank_offset_poly": (0.5, 2.0, -1.0), "blank_offset": 0.8})]


def _numpy_reference(gen, u, phi, psi):
    """Points, normals, k1, k2, e1, e2 by the numpy kernels on whole arrays (member frame of the generator's hand)."""
    cp, mp = gen.cp, gen.mp
    m = MIRROR if gen.hand is Hand.RIGHT else np.ones(3)
    rho, z, chi, dchi = _g.profile(u, cp)
    sol = dict(phi=phi, psi=psi, rho=rho, z=z, chi=chi, dchi=dchi, u=u)
    r, n_h, t_h, _ = _g.machine_state(sol, cp, mp)
    n_in = cp["s"] * n_h
    pts = m * _g.to_member(r, psi, mp)
    nrm = m * _g.to_member(-n_in, psi, mp, point=False)
    kI, kII = -dchi, -cp["s"] * np.sin(chi) / rho
    vel = _g.relative_velocity(r, psi, mp)
    k_a, k_b, d_a, d_b, _ = _g.transfer_curvature(n_in, t_h, np.cross(n_in, t_h), kI, kII, vel)
    d_a, d_b = m * _g.to_member(d_a, psi, mp, point=False), m * _g.to_member(d_b, psi, mp, point=False)
    rhat = pts / np.linalg.norm(pts, axis=-1, keepdims=True)
    prof = np.abs(np.sum(d_a * rhat, -1)) <= np.abs(np.sum(d_b * rhat, -1))
    k1, k2 = np.where(prof, k_a, k_b), np.where(prof, k_b, k_a)
    e1 = np.where(prof[:, None], d_a, d_b)
    radial = pts * np.array([1.0, 1.0, 0.0])
    radial /= np.linalg.norm(radial, axis=-1, keepdims=True)
    up = radial - np.sum(radial * rhat, -1)[:, None] * rhat
    e1 *= np.where(np.sum(e1 * up, -1) < 0, -1.0, 1.0)[:, None]
    return pts, nrm, k1, k2, e1, np.cross(nrm, e1)


def _random_points(flank, n, seed):
    """(u, phi, psi_c) of n random points of the flank: blade points of a random (phi, psi_c) window around the mean
    point, and fillet points from the (u, psi_c) chart."""
    gen = flank.generator
    mp = flank.mean_point()
    rng = np.random.default_rng(seed)
    phi_m = mp.theta + math.pi - gen.mp["q"] + mp.psi_c
    phi = phi_m + rng.uniform(-0.1, 0.1, n)
    psi = mp.psi_c + rng.uniform(-0.15, 0.15, n)
    _, _, u = gen.blade_axial_radial(phi, psi)
    ok = np.isfinite(u) & (u >= gen.cp["u_j"])
    u0, uj = flank.cutter.fillet_range
    uf = rng.uniform(u0 + 0.05 * (uj - u0), uj - 0.05 * (uj - u0), n // 4)
    pf = mp.psi_c + rng.uniform(-0.15, 0.15, n // 4)
    phif = gen.contact(uf, pf)["phi"]
    return np.concatenate([u[ok], uf]), np.concatenate([phi[ok], phif]), np.concatenate([psi[ok], pf]), ok.sum()


@pytest.mark.parametrize("rp, extra", VARIANTS)
@pytest.mark.parametrize("member, side", CASES)
def test_compiled_flank_points_match_numpy_kernels(member, side, rp, extra):
    flank = basic_flank(member, side, rp=rp, **extra)
    u, phi, psi, n_blade = _random_points(flank, 400, 11)
    assert n_blade > 200
    fp = flank.generator.evaluate_at(u, phi, psi)
    P, N, k1, k2, e1, e2 = _numpy_reference(flank.generator, u, phi, psi)
    assert fp.fillet.sum() == len(u) - n_blade
    # same formulas, a different evaluation order (scalar vs array, Horner vs polyval, sqrt vs hypot) and libm (numba's
    # vs numpy's sin/cos): a few ulp. Measured over the 12 cases: points 1.4e-14 mm (1 ulp of |r| ~ 100 mm), unit
    # vectors 7.8e-16, curvatures 3e-16 of the largest; the bounds leave a factor 7-30 for other platforms' libm
    np.testing.assert_allclose(fp.points, P, rtol=0, atol=1e-13)
    for a, b in ((fp.normals, N), (fp.e1, e1), (fp.e2, e2)):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    kmax = np.maximum(np.abs(k1), np.abs(k2)).max()
    assert np.abs(fp.k1 - k1).max() <= 1e-14 * kmax
    assert np.abs(fp.k2 - k2).max() <= 1e-14 * kmax
    # without curvatures: the same points and normals, NaN curvature data
    fq = flank.generator.evaluate_at(u, phi, psi, curvature=False)
    assert np.array_equal(fq.points, fp.points) and np.array_equal(fq.normals, fp.normals)
    assert np.all(np.isnan(fq.k1)) and np.all(np.isnan(fq.e2))


@pytest.mark.parametrize("rp, extra", VARIANTS)
@pytest.mark.parametrize("member, side", CASES)
def test_compiled_curvatures_match_fundamental_forms_of_the_jet(member, side, rp, extra):
    """Shape operator from the analytic first-order jet (r, n, dr, dn in the (phi, psi_c) chart) on blade points."""
    flank = basic_flank(member, side, rp=rp, **extra)
    gen = flank.generator
    u, phi, psi, n_blade = _random_points(flank, 400, 12)
    u, phi, psi = u[:n_blade], phi[:n_blade], psi[:n_blade]
    fp = gen.evaluate_at(u, phi, psi)
    prm = _gbj.parameters(gen.cp, gen.mp, gen.hand is Hand.RIGHT, 0.0)
    S, uj = np.empty((n_blade, 3, 6)), np.empty(n_blade)
    _gbj.jet_batch(prm, np.ascontiguousarray(np.stack([phi, psi], -1)), S, uj)
    # the jet solves u from the equation of meshing again (measured 1.2e-14 mm from the given u, points 1.5e-14 mm)
    np.testing.assert_allclose(uj, u, rtol=0, atol=1e-13)
    np.testing.assert_allclose(S[:, :, 0], fp.points, rtol=0, atol=1e-13)
    np.testing.assert_allclose(S[:, :, 1], fp.normals, rtol=0, atol=1e-14)
    r_q, n_q = S[:, :, 2:4], S[:, :, 4:6]                                   # (m, 3, 2)
    I = np.einsum("mki,mkj->mij", r_q, r_q)
    # outward n, convex = positive: dn = +W dr (a sphere of radius a: n = r/a, W = I/a); II_ij = r_i . n_j
    II = np.einsum("mki,mkj->mij", r_q, n_q)
    II = 0.5 * (II + np.swapaxes(II, 1, 2))
    k = np.sort(np.linalg.eigvals(np.linalg.solve(I, II)).real, -1)
    kc = np.sort(np.stack([fp.k1, fp.k2], -1), -1)
    # the jet's derivatives are exact up to rounding (r_q ~ 100 mm/rad, u_q = -f_q / f_u); the eigenvalues of
    # I^-1 II then carry the rounding of the 2 x 2 solve: measured 1.2e-14 of the largest curvature over the 12
    # cases (II's asymmetry 1e-13 of |r_q|), bound 1e-13
    scale = np.abs(kc).max(-1)
    assert (np.abs(k - kc).max(-1) / scale).max() <= 1e-13
    # principal directions: the normal curvature of the second form along e1 (and e2) is k1 (k2)
    c1 = np.linalg.lstsq(r_q[0], fp.e1[0], rcond=None)[0]
    c2 = np.linalg.lstsq(r_q[0], fp.e2[0], rcond=None)[0]
    np.testing.assert_allclose(r_q[0] @ c1, fp.e1[0], atol=1e-12)
    assert c1 @ II[0] @ c1 == pytest.approx(fp.k1[0], rel=0, abs=1e-13 * scale[0])
    assert c2 @ II[0] @ c2 == pytest.approx(fp.k2[0], rel=0, abs=1e-13 * scale[0])
    assert c1 @ II[0] @ c2 == pytest.approx(0.0, abs=1e-13 * scale[0])
