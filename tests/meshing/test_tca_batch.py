"""Compiled TCA kernels (spiralbevel._core.tca_newton, called through tca_solve; spiralbevel._core.logspiral_jet)
against the reference numpy kernels of spiralbevel._core.tca, plain SVD, the closed forms of
spiralbevel._core.logspiral and a plain per-point Newton; the give-up rule of the batched iteration; and the numba
cache fallback."""

import numpy as np
import pytest

from spiralbevel._core import logspiral as LS
from spiralbevel._core import tca as K
from spiralbevel._core import tca_batch as B
from spiralbevel._core import tca_solve as N
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair

MIS = Misalignment(pinion_axial=0.05, gear_axial=-0.03, offset=0.04, shaft_angle=1e-3)


@pytest.fixture(scope="module")
def pair():
    return conjugate_logspiral_pair()


def _random_x(pair, rng, m, spread=0.02):
    return np.concatenate([np.array(pair.pinion.reference_params) + spread * rng.standard_normal((m, 2)),
                           np.array(pair.gear.reference_params) + spread * rng.standard_normal((m, 2)),
                           0.1 * rng.standard_normal((m, 1))], -1)


class _NoJet:
    """The same flank without a compiled jet: TCA evaluates it by numpy between the compiled steps."""

    def __init__(self, surface):
        self.s = surface
        self.reference_params = surface.reference_params

    def evaluate(self, params):
        return self.s.evaluate(params)

    def derivatives(self, params):
        return self.s.derivatives(params)


def test_logspiral_jet_matches_closed_forms(pair):
    # points, normals and first derivatives against seed 000 Eqs. (16), (21) as coded in _core.logspiral (r_varphi,
    # r_phi, n closed form) and central differences of those normals (dn); both flank signs and a phased flank
    rng = np.random.default_rng(5)
    for surf in (pair.pinion, pair.gear):
        q = np.array(surf.reference_params) + 0.05 * rng.standard_normal((40, 2))
        r, n, dr, dn = surf.derivatives(q)
        g = LS.geometry(q[:, 0], q[:, 1], surf.rho0, surf.delta, surf.beta)
        sg = np.sign(g["psi"])[:, None]
        R = np.array([[np.cos(surf.azimuth), -np.sin(surf.azimuth), 0], [np.sin(surf.azimuth),
                      np.cos(surf.azimuth), 0], [0, 0, 1.0]])
        np.testing.assert_allclose(r, g["r"] @ R.T, atol=1e-12 * surf.rho0)
        np.testing.assert_allclose(n, sg * g["n"] @ R.T, atol=1e-14)
        np.testing.assert_allclose(dr[..., 0], g["r_varphi"] @ R.T, atol=1e-12 * surf.rho0)
        np.testing.assert_allclose(dr[..., 1], g["r_phi"] @ R.T, atol=1e-12 * surf.rho0)
        h = 1e-6  # central difference: truncation ~h^2 |n'''| ~ 1e-12, rounding ~1e-16 / h = 1e-10
        for j in range(2):
            e = np.zeros(2)
            e[j] = h
            gp = LS.geometry(*(q + e).T, surf.rho0, surf.delta, surf.beta)
            gm = LS.geometry(*(q - e).T, surf.rho0, surf.delta, surf.beta)
            fd = sg * (gp["n"] - gm["n"]) / (2 * h) @ R.T
            np.testing.assert_allclose(dn[..., j], fd, atol=1e-9)


@pytest.mark.parametrize("mis", [None, MIS])
def test_compiled_assembly_matches_reference_kernel(pair, mis):
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    prob = ContactProblem(pair.pinion, pair.gear, kin, mis)
    rng = np.random.default_rng(1)
    m = 7
    x = _random_x(pair, rng, m)
    phi1 = 0.1 * rng.standard_normal(m)
    e1, e2 = prob.basis(x, phi1)
    F_ref, J_ref = prob.system(x, phi1, (e1, e2))
    st = prob.state(x)
    S1, S2 = (np.ascontiguousarray(B.stack_state(*s)) for s in (st[:4], st[4:]))
    d, M2, L = prob._const
    E = np.empty((m, 2, 3))
    # assembly at x alone (no iteration: max_iter = 0), the basis rows from the gear normal
    run = N.Iteration(m, 5, np.cos(phi1), np.sin(phi1), E, d, M2, L, -1, np.zeros(m), 0.0, 0, 1e-10, 0, 8)
    assert run.begin(x, S1, S2) == 0
    np.testing.assert_allclose(E, np.stack([e1, e2], -2), atol=1e-14)
    F, J, S1f = run.F, run.J, run.S1f
    # rounding of products of ~100 mm terms: 1e-13 relative
    np.testing.assert_allclose(F, F_ref, atol=1e-11)
    np.testing.assert_allclose(J, J_ref, atol=1e-10)
    # path tangent: -J^-1 dF/dphi1 with the reference dF/dphi1
    Fp = K.dF_dphi1(st[0], st[1], phi1, prob.axes, (e1, e2), prob.scale)
    ref = np.linalg.solve(J_ref, -Fp[..., None])[..., 0]
    np.testing.assert_allclose(prob.path_tangent(J, S1f, E), ref, rtol=1e-9, atol=1e-12)


def _matrices(rng, m, rank=5, rows=5):
    A = rng.standard_normal((m, rows, rank)) @ rng.standard_normal((m, rank, 5))
    return A * np.array([1.0, 100.0, 0.01, 10.0, 1e3])  # badly scaled columns: equilibration matters


@pytest.mark.parametrize("rank, rows", [(5, 5), (4, 5), (5, 6), (4, 6)])
def test_step_equals_minimum_norm_svd_step(rank, rows):
    rng = np.random.default_rng(2)
    J = _matrices(rng, 50, rank, rows)
    F = rng.standard_normal((50, rows))
    dx = N.step_batch(J, F, 1e-10)
    ref, _ = K.minnorm_step(J, F)
    # LU vs SVD on equilibrated matrices with condition up to ~1e4: agreement to ~1e-12 relative; rank-deficient
    # systems: the discarded direction is decided by the same threshold in both
    np.testing.assert_allclose(dx, ref, rtol=1e-7, atol=1e-9 * np.abs(ref).max())
    J[3, 2, 1] = np.nan
    assert np.isnan(N.step_batch(J, F, 1e-10)[3]).all()


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


def test_iteration_gives_up_on_systems_without_solution():
    # the rules of start/propose/accept on toy systems: system 0: x_i^2 = 2 (solution), system 1: x_0^2 = -1 (none;
    # Newton wanders), system 2: sqrt(x) = 1 from x = 4, whose first full step lands on x = 0 (infinite Jacobian)
    # and is halved
    def fun(x, idx):
        with np.errstate(all="ignore"):
            F = x**2 - 2.0
            F[idx == 1, 0] = x[idx == 1, 0] ** 2 + 1.0
            J = np.zeros((len(idx), 5, 5))
            J[:, range(5), range(5)] = 2 * x
            k = idx == 2
            F[k] = np.sqrt(x[k]) - 1.0
            Jk = np.zeros((k.sum(), 5, 5))
            Jk[:, range(5), range(5)] = 0.5 / np.sqrt(x[k])
            J[k] = Jk
        return F, J

    x = np.array([np.full(5, 1.0), np.full(5, 0.5), np.full(5, 4.0)])
    m, tol, patience = 3, 1e-12, 3
    F, J = fun(x, np.arange(m))
    # the systems are given, not assembled: the surface arguments are unused
    run = N.Iteration(m, 5, np.zeros(m), np.zeros(m), np.zeros((m, 2, 3)), np.zeros(3), np.zeros((6, 3)), 1.0, -1,
                      np.zeros(m), tol, 30, 1e-10, patience, 8)
    c, halvings_seen = run.begin(x, F=F, J=J), 0
    while c:
        Fn, Jn = fun(run.xn[:c], run.idx[:c])
        c_taken = c
        c = run.advance(Fn=Fn, Jn=Jn)
        halvings_seen += int(np.sum(~run.accepted[:c_taken]))
    x, res, it = run.x, run.res, run.iterations
    conv = res < tol
    assert conv[0] and not conv[1] and conv[2]
    np.testing.assert_allclose(x[0], np.sqrt(2.0), rtol=1e-12)
    np.testing.assert_allclose(x[2], 1.0, rtol=1e-11)
    assert halvings_seen >= 1  # the step to x = 0 was halved, not taken
    assert it < 30  # the hopeless system is dropped, not iterated to max_iter


def _plain_newton(prob, phi1, x, basis, tol=1e-10, max_iter=30):
    """One system at a time: numpy solve of the reference system (spiralbevel._core.tca.contact_system)."""
    for _ in range(max_iter):
        F, J = prob.system(x, phi1, basis)
        if np.max(np.abs(F)) < tol:
            return x, True
        x = x + np.linalg.solve(J, -F)
    F, _ = prob.system(x, phi1, basis)
    return x, bool(np.max(np.abs(F)) < tol)


@pytest.mark.parametrize("mis", [MIS, Misalignment(offset=0.2, shaft_angle=3e-3)])
def test_compiled_newton_matches_plain_per_point_solve(pair, mis):
    # point contact (condition number of the equilibrated J about 2.5e3): a misaligned assembly and a pinion of a
    # 0.3 % larger spiral parameter; 60 random starts around the mean point. The
    # compiled iteration (both flanks with compiled jets), the numpy-evaluated flanks with the compiled step, and a
    # plain per-point numpy Newton of the reference kernels find the same roots
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    pin = pair.pinion.with_changes(beta=pair.pinion.beta * 1.003)
    prob = ContactProblem(pin, pair.gear, kin, mis)
    slow = ContactProblem(_NoJet(pin), _NoJet(pair.gear), kin, mis)
    assert prob._jets is not None and slow._jets is None
    rng = np.random.default_rng(7)
    m = 60
    x0 = _random_x(pair, rng, m, spread=0.01)
    phi1 = 0.01 * rng.standard_normal(m)
    x, conv, res, J, data, it, E = prob.newton(phi1, x0, tol=1e-10)
    xs, convs, ress, Js, datas, its, Es = slow.newton(phi1, x0, tol=1e-10)
    assert conv.sum() > 0.8 * m
    np.testing.assert_array_equal(conv, convs)
    assert it == its
    # same arithmetic on the same data: identical up to rounding of the surface evaluation (1e-15 relative)
    np.testing.assert_allclose(x[conv], xs[conv], rtol=0, atol=1e-12)
    for a, b in zip(data, datas):
        np.testing.assert_allclose(a[conv], b[conv], atol=1e-11)
    for i in np.nonzero(conv)[0]:
        basis = (E[i, 0], E[i, 1])
        xp, ok = _plain_newton(prob, phi1[i], x0[i], basis)
        assert ok
        # both iterate the same map to |F| < 1e-10 mm from the same start; the last quadratic step leaves both far
        # below that, and the different rounding of LU vs LAPACK and of the two assemblies, amplified by the
        # condition number, stays below 1e-12 rad (5e-13 observed)
        np.testing.assert_allclose(x[i], xp, rtol=0, atol=1e-12)
    # the stored data is the data at the final iterate
    st = prob.state(x[conv])
    np.testing.assert_allclose(data[0][conv][..., 0], st[0], atol=1e-12)


def test_cache_fallback_compiles_in_memory(monkeypatch):
    import numba

    from spiralbevel._core import jit

    calls = []
    real = numba.njit

    def njit(*args, cache=False, **kw):
        if args:  # numba's own functions (its modules imported at the process's first compile), not our kernel
            return real(*args, cache=cache, **kw)
        calls.append(cache)
        if cache:
            raise RuntimeError("cannot cache function 'f': no locator available for file '<test>'")
        return real(*args, cache=cache, **kw)

    monkeypatch.setattr(jit.numba, "njit", njit)

    @jit.kernel
    def f(a):
        return 2.0 * a

    assert f(1.5) == 3.0 and calls == [True, False]


def test_unknown_jet_kind_gives_nan_and_no_convergence(pair):
    # a surface claiming an unregistered jet: NaN data, every system reported as not converged (never a silent root)
    from spiralbevel._core import jets

    out = np.zeros((3, 6))
    jets.surface_jet(99, np.zeros(5), 0.1, 0.2, out)
    assert np.isnan(out).all()

    class _Bogus(_NoJet):
        jet = (99, np.zeros(5))

    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    prob = ContactProblem(_Bogus(pair.pinion), _Bogus(pair.gear), kin)
    x0 = _random_x(pair, np.random.default_rng(0), 4)
    x, conv, res, *_ = prob.newton(np.zeros(4), x0)
    assert not conv.any() and np.all(res == np.inf)


def test_every_operation_shares_one_compiled_signature(pair):
    # the TCA Newton's operations are values of one kernel's integer argument, not kernels of their own: after the
    # jets' whole Newton, the numpy-evaluated iteration with an anchor row, the step, the tangent and the line test,
    # the kernel holds one compiled signature (a second one would compile its whole call tree again: _core/jit.py)
    from spiralbevel._core import tca_newton

    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    rng = np.random.default_rng(11)
    x0 = _random_x(pair, rng, 3, spread=0.005)
    phi1 = np.zeros(3)
    anchor = (0, x0[:, 0])
    x, conv, res, J, data, it, E = ContactProblem(pair.pinion, pair.gear, kin, MIS).newton(phi1, x0, anchor=anchor)
    xs, convs, *_ = ContactProblem(_NoJet(pair.pinion), _NoJet(pair.gear), kin, MIS).newton(phi1, x0, anchor=anchor)
    np.testing.assert_array_equal(conv, convs)
    N.step_batch(J, rng.standard_normal((3, 6)), 1e-10)
    N.tangent_batch(J, data[2], E, 100.0, 1e-10)
    B.is_singular(J[:, :5], 1e-7)
    assert len(tca_newton.newton_batch.signatures) == 1
