"""Fused TCA kernels (spiralbevel._core.tca_batch) against the reference kernels of spiralbevel._core.tca and plain
SVD, and the batched Newton driver's handling of systems without a solution."""

import numpy as np
import pytest

from spiralbevel._core import tca as K
from spiralbevel._core import tca_batch as B
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair


@pytest.fixture(scope="module")
def pair():
    return conjugate_logspiral_pair()


@pytest.mark.parametrize("mis", [None, Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04,
                                                    shaft_angle=1e-3)])
def test_stacked_system_matches_reference_kernel(pair, mis):
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    prob = ContactProblem(pair.pinion, pair.gear, kin, mis)
    rng = np.random.default_rng(1)
    m = 7
    x = np.concatenate([np.array(pair.pinion.reference_params) + 0.02 * rng.standard_normal((m, 2)),
                        np.array(pair.gear.reference_params) + 0.02 * rng.standard_normal((m, 2)),
                        0.1 * rng.standard_normal((m, 1))], -1)
    phi1 = 0.1 * rng.standard_normal(m)
    e1, e2 = prob.basis(x, phi1)
    F_ref, J_ref = prob.system(x, phi1, (e1, e2))
    st = prob.state(x)
    S1, S2 = B.stack_state(*st[:4]), B.stack_state(*st[4:])
    c = lambda a: np.cos(a)[:, None]  # noqa: E731
    s = lambda a: np.sin(a)[:, None]  # noqa: E731
    F, J, S1f, Q = B.system_stacked(S1, S2, c(phi1), s(phi1), c(x[:, 4]), s(x[:, 4]), prob._const,
                                    np.stack([e1, e2], -2))
    np.testing.assert_allclose(F, F_ref, atol=1e-11)
    np.testing.assert_allclose(J, J_ref, atol=1e-10)
    # dF/dphi1 against the reference kernel
    Fp = B.dF_dphi1_stacked(S1f, np.stack([e1, e2], -2), prob.scale)
    np.testing.assert_allclose(Fp, K.dF_dphi1(st[0], st[1], phi1, prob.axes, (e1, e2), prob.scale), atol=1e-10)


def _matrices(rng, m, rank=5):
    A = rng.standard_normal((m, 5, rank)) @ rng.standard_normal((m, rank, 5))
    return A * np.array([1.0, 100.0, 0.01, 10.0, 1e3])  # badly scaled columns: equilibration matters


def test_newton_step_equals_minimum_norm_svd_step():
    rng = np.random.default_rng(2)
    for rank in (5, 4):
        J = _matrices(rng, 50, rank)
        F = rng.standard_normal((50, 5))
        dx = B.newton_step(J, F)
        ref, _ = K.minnorm_step(J, F)
        np.testing.assert_allclose(dx, ref, rtol=1e-7, atol=1e-9 * np.abs(ref).max())


def test_is_singular_agrees_with_svd_ratio():
    rng = np.random.default_rng(3)
    J = np.concatenate([_matrices(rng, 40, 5), _matrices(rng, 40, 4), _matrices(rng, 10, 3)])
    # near the threshold: s_min / s_max set exactly by an SVD with prescribed singular values
    U, _, Vt = np.linalg.svd(rng.standard_normal((6, 5, 5)))
    s = np.array([[1.0, 0.9, 0.7, 0.5, r] for r in (1e-6, 3e-7, 1.1e-7, 0.9e-7, 3e-8, 1e-9)])
    J = np.concatenate([J, U @ (s[..., None] * Vt)])
    cn = np.linalg.norm(J, axis=-2)
    sv = np.linalg.svd(J / cn[:, None, :], compute_uv=False)
    tol = 1e-7
    np.testing.assert_array_equal(B.is_singular(J, tol), sv[:, -1] < tol * sv[:, 0])


def test_newton_batched_gives_up_on_systems_without_solution():
    # system 0: x_i^2 = 2 (solution), system 1: x_0^2 = -1 (none; Newton wanders), system 2: sqrt(x) = 1 from
    # x = 4, whose first full step lands on x = 0 (infinite Jacobian) and is halved
    def fun(x, idx):
        F = x**2 - 2.0
        F[idx == 1, 0] = x[idx == 1, 0] ** 2 + 1.0
        J = np.zeros((len(idx), 5, 5))
        J[:, range(5), range(5)] = 2 * x
        k = idx == 2
        with np.errstate(invalid="ignore"):
            F[k] = np.sqrt(x[k]) - 1.0
            J[k][:, range(5), range(5)] = 0.0
            Jk = np.zeros((k.sum(), 5, 5))
            Jk[:, range(5), range(5)] = 0.5 / np.sqrt(x[k])
            J[k] = Jk
        return F, J, (x.copy(),)

    x0 = np.array([np.full(5, 1.0), np.full(5, 0.5), np.full(5, 4.0)])  # system 2: first full step to x = 0
    x, conv, res, J, aux, it = B.newton_batched(fun, x0, 1e-12, max_iter=30, patience=3)
    assert conv[0] and not conv[1] and conv[2]
    np.testing.assert_allclose(x[0], np.sqrt(2.0), rtol=1e-12)
    np.testing.assert_allclose(x[2], 1.0, rtol=1e-11)
    np.testing.assert_array_equal(aux[0], x)
    assert it < 30  # the hopeless system is dropped, not iterated to max_iter
