import numpy as np
import pytest
from scipy.optimize import fsolve

from spiralbevel._core.newton import fd_jacobian, solve_batched
from spiralbevel._core.rotations import apply, rot_axis, rot_x, rot_y, rot_z


def _fun(x):
    # intersection of a circle of radius c and a hyperbola x*y = d, per system
    c = np.linspace(2.0, 3.0, x.shape[0])
    return np.stack([x[:, 0] ** 2 + x[:, 1] ** 2 - c**2, x[:, 0] * x[:, 1] - 1.0], -1)


def test_batched_newton_matches_per_point_fsolve():
    x0 = np.tile([2.0, 0.5], (50, 1))
    res = solve_batched(_fun, x0, tol=1e-13)
    assert res.converged.all()
    for i in range(0, 50, 7):
        ref = fsolve(lambda y, i=i: _fun(np.tile(y, (50, 1)))[i], x0[i], xtol=1e-12)
        assert np.allclose(res.x[i], ref, atol=1e-11)


def test_newton_converges_quadratically():
    def f(x):
        return np.stack([np.exp(x[..., 0]) - 2.0], -1)
    def jac(x):
        return np.exp(x[..., 0])[..., None, None]
    errs = []
    x = np.array([[1.5]])
    for it in range(1, 5):
        x = solve_batched(f, np.array([[1.5]]), jac=jac, tol=0.0, max_iter=it).x
        errs.append(abs(x[0, 0] - np.log(2.0)))
    # e_{k+1} ≈ C e_k^2 with C = f''/(2 f') = 1/2
    assert errs[2] < 0.6 * errs[1] ** 2 + 1e-15
    assert errs[1] < 0.6 * errs[0] ** 2


def test_fd_jacobian_matches_analytic():
    x = np.array([[1.2, 0.7], [2.0, -0.3]])
    J = fd_jacobian(_fun, x)[:, :, :]
    exact = np.array([[[2 * 1.2, 2 * 0.7], [0.7, 1.2]], [[4.0, -0.6], [-0.3, 2.0]]])
    assert np.allclose(J, exact, atol=1e-5)


def test_unconverged_flagged_not_raised():
    def f(x):
        return x**2 + 1.0  # no real root
    res = solve_batched(f, np.array([[0.5]]), max_iter=5)
    assert not res.converged[0]


@pytest.mark.parametrize("R", [rot_x, rot_y, rot_z])
def test_rotations_are_proper_and_match_rodrigues(R):
    a = np.linspace(-3, 3, 7)
    M = R(a)
    assert np.allclose(M @ np.swapaxes(M, -1, -2), np.eye(3), atol=1e-14)
    assert np.allclose(np.linalg.det(M), 1.0)
    axis = {rot_x: [1, 0, 0], rot_y: [0, 1, 0], rot_z: [0, 0, 1]}[R]
    assert np.allclose(M, rot_axis(axis, a), atol=1e-14)


def test_positive_rotation_is_counterclockwise():
    # docs/conventions.md: a positive angle turns counterclockwise seen from the tip of the axis
    assert np.allclose(apply(rot_z(np.pi / 2), [1.0, 0, 0]), [0, 1.0, 0], atol=1e-15)
