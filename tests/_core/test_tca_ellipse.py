"""Compiled contact geometry (spiralbevel._core.tca_ellipse, behind spiralbevel._core.tca) against plain numpy and
LAPACK on many random inputs: poses (Rodrigues vs rot_z, rot_axis), Weingarten tensors (np.linalg.inv), relative
curvatures (np.linalg.eigh) and their composition in TCA's contact ellipses."""

import numpy as np

from spiralbevel._core import tca as K
from spiralbevel._core import tca_ellipse as E
from spiralbevel._core.rotations import rot_axis, rot_y, rot_z


def _rotations(rng, m):
    q, _ = np.linalg.qr(rng.standard_normal((m, 3, 3)))
    return q * np.sign(np.linalg.det(q))[:, None, None]


def _weingarten_numpy(dr, dn):
    G = np.swapaxes(dr, -1, -2) @ dr
    W = dn @ np.linalg.inv(G) @ np.swapaxes(dr, -1, -2)
    return 0.5 * (W + np.swapaxes(W, -1, -2))


def _relative_numpy(W1, W2, n):
    e1, e2 = K.tangent_basis(n)
    T = np.stack([e1, e2], -1)
    Km = np.swapaxes(T, -1, -2) @ (W1 + W2) @ T
    lam, vec = np.linalg.eigh(0.5 * (Km + np.swapaxes(Km, -1, -2)))
    return lam, np.swapaxes(T @ vec, -1, -2)


def test_pose_matches_rotation_matrices():
    rng = np.random.default_rng(1)
    axes = K.assembly_axes(1.3, 0.02, -0.01, 0.03, 2e-3)
    p1, p2 = rng.uniform(-4, 4, 300), rng.uniform(-4, 4, 300)
    R1, R2 = K._pose(p1, p2, axes)
    # same formulas in other arithmetic: round-off only
    assert np.max(np.abs(R1 - rot_z(p1))) < 1e-15
    assert np.max(np.abs(R2 - rot_axis(axes[2], p2) @ rot_y(1.3 + 2e-3))) < 1e-14
    # broadcasting: scalar phi1 against an array of phi2
    R1b, R2b = K._pose(0.3, p2[:5], axes)
    assert R1b.shape == R2b.shape == (5, 3, 3) and np.array_equal(R2b, R2[:5])


def test_weingarten_matches_numpy_inverse():
    rng = np.random.default_rng(2)
    dr, dn = rng.standard_normal((500, 3, 2)), rng.standard_normal((500, 3, 2))
    W, ref = K.weingarten(dr, dn), _weingarten_numpy(dr, dn)
    # explicit 2 x 2 inverse vs LAPACK: relative round-off times the condition of the random G (2e-13 here)
    assert np.max(np.abs(W - ref) / np.max(np.abs(ref), axis=(-1, -2), keepdims=True)) < 1e-12
    assert np.array_equal(W, np.swapaxes(W, -1, -2))
    assert K.weingarten(dr[0], dn[0]).shape == (3, 3)


def test_relative_curvature_matches_eigh():
    rng = np.random.default_rng(3)
    m = 2000
    A, B = rng.standard_normal((m, 3, 3)), rng.standard_normal((m, 3, 3))
    W1, W2 = A + np.swapaxes(A, -1, -2), 0.1 * (B + np.swapaxes(B, -1, -2))
    W2[:50] = -W1[:50]  # K = 0: the degenerate (umbilic) case
    W2[50:100] = np.eye(3) - W1[50:100]  # K = identity on every tangent plane: a double eigenvalue
    n = rng.standard_normal((m, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    lam, dirs = K.relative_curvature(W1, W2, n)
    lam_r, dirs_r = _relative_numpy(W1, W2, n)
    scale = np.max(np.abs(lam_r), axis=-1, keepdims=True) + 1e-300
    # one Jacobi rotation vs LAPACK's dsyevd: both backward stable, eigenvalues to a few ulp of the norm
    assert np.max(np.abs(lam - lam_r)[100:] / scale[100:]) < 1e-14
    assert np.max(np.abs(lam[:100] - lam_r[:100])) < 1e-14
    # unit, orthogonal, tangent, right-handed with n; they diagonalize K
    assert np.allclose(np.linalg.norm(dirs, axis=-1), 1.0, atol=1e-15, rtol=0)
    assert np.max(np.abs(np.einsum("mi,mi->m", dirs[:, 0], dirs[:, 1]))) < 1e-15
    assert np.max(np.abs(np.einsum("mki,mi->mk", dirs, n))) < 1e-15
    assert np.max(np.abs(dirs[:, 1] - np.cross(n, dirs[:, 0]))) < 1e-15
    Wt = W1 + W2
    for k in (0, 1):
        Wd = np.einsum("mij,mj->mi", Wt, dirs[:, k])
        tang = Wd - np.einsum("mi,mi->m", Wd, n)[:, None] * n  # the tangent-plane part
        assert np.max(np.abs(tang - lam[:, k, None] * dirs[:, k]) / scale) < 1e-13
    # the same axes as LAPACK's vectors up to sign where the eigenvalues are well separated
    sep = (lam_r[:, 1] - lam_r[:, 0]) > 1e-3 * scale[:, 0]
    dots = np.abs(np.einsum("mki,mki->mk", dirs, dirs_r))[sep]
    # eigenvector error ~ round-off / relative gap (gap >= 1e-3)
    assert np.min(dots) > 1.0 - 1e-12


def test_rotated_curvatures_of_tca_match_numpy():
    # TCA's ellipses: Weingarten tensors turned into the fixed frame in the kernel, then the relative curvature,
    # against the same composition in numpy (np.linalg.inv, matrix products, eigh)
    rng = np.random.default_rng(4)
    m = 300
    dr1, dn1, dr2, dn2 = (rng.standard_normal((m, 3, 2)) for _ in range(4))
    R1, R2 = _rotations(rng, m), _rotations(rng, m)
    n = rng.standard_normal((m, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    W1, W2 = np.empty((m, 3, 3)), np.empty((m, 3, 3))
    E.weingarten_batch(dr1, dn1, R1, True, W1)
    E.weingarten_batch(dr2, dn2, R2, True, W2)
    lam, dirs = np.empty((m, 2)), np.empty((m, 2, 3))
    E.relative_curvature_batch(W1, W2, n, lam, dirs)
    W1r = R1 @ _weingarten_numpy(dr1, dn1) @ np.swapaxes(R1, -1, -2)
    W2r = R2 @ _weingarten_numpy(dr2, dn2) @ np.swapaxes(R2, -1, -2)
    # round-off times the condition of the random G (explicit 2 x 2 inverse vs LAPACK): about 1e-12 here
    assert np.max(np.abs(W1 - W1r) / np.max(np.abs(W1r), axis=(-1, -2), keepdims=True)) < 5e-12
    lam_r, dirs_r = _relative_numpy(W1r, W2r, n)
    scale = np.max(np.abs(lam_r), axis=-1, keepdims=True)
    assert np.max(np.abs(lam - lam_r) / scale) < 5e-12  # inherited from the tensors
    sep = (lam_r[:, 1] - lam_r[:, 0]) > 1e-3 * scale[:, 0]
    # direction error ~ perturbation / relative gap (5e-12 / 1e-3): |cos| off 1 by its square
    assert np.min(np.abs(np.einsum("mki,mki->mk", dirs, dirs_r))[sep]) > 1.0 - 1e-12
