"""The compiled jet of a crowned flank (``_core.normal_deviation_jet``, kind NORMAL_QUADRATIC of ``_core.jets``) against
the numpy surface it replaces in TCA (``NormalDeviation.evaluate`` with central differences,
``surface_derivatives``) on many random points of a log-spiral flank; and the whole TCA of the crowned log-spiral pair
with the compiled jet against the same TCA evaluating the crowned flank by numpy."""

import numpy as np
import pytest
from _meshing_helpers import seed001_synthesized_pair

from spiralbevel._core.jets import NORMAL_QUADRATIC, surface_jet
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning, surface_derivatives
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.synthesis.logspiral_crowning import SumDeviation
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair


@pytest.mark.parametrize("sum_of_one", [False, True])
def test_compiled_crowned_jet_matches_numpy(sum_of_one):
    base, spread = conjugate_logspiral_pair().pinion, 0.05
    crown = quadratic_crowning(base.reference_params, (0.5, 0.1, 5.0))
    surf = NormalDeviation(base, SumDeviation(crown) if sum_of_one else crown)  # the job's crowned flank: a sum
    kind, prm = surf.jet
    assert kind == NORMAL_QUADRATIC
    rng = np.random.default_rng(7)
    q = base.reference_params + rng.normal(0.0, spread, (200, 2))
    r, n, dr, dn = surface_derivatives(surf, q)
    out = np.empty((200, 3, 6))
    for i in range(len(q)):
        surface_jet(kind, prm, q[i, 0], q[i, 1], out[i])
    ok = np.isfinite(r[:, 0])
    assert ok.sum() > 150
    scale = np.max(np.abs(r[ok]))
    # the same expressions in the same order; numpy's and libm's sin/cos may differ by an ulp of |r| (about 1e-14
    # mm here): r and n to that, their central differences (steps 1e-5 on both sides) to that / 2e-5
    assert np.max(np.abs(out[ok, :, 0] - r[ok])) < 1e-13 * scale
    assert np.max(np.abs(out[ok, :, 1] - n[ok])) < 1e-13
    assert np.max(np.abs(out[ok, :, 2:4] - dr[ok])) < 1e-13 * scale / 1e-5
    assert np.max(np.abs(out[ok, :, 4:6] - dn[ok])) < 1e-13 / 1e-5


def test_a_deviation_that_is_not_a_quadratic_crowning_has_no_compiled_jet():
    base = conjugate_logspiral_pair().pinion
    crown = quadratic_crowning(base.reference_params, (0.5, 0.0, 5.0))
    assert NormalDeviation(base, lambda q: crown(q)).jet is None
    assert NormalDeviation(base, SumDeviation(crown, crown)).jet is None
    assert NormalDeviation(NormalDeviation(base, crown), crown).jet is None  # a base without a plain compiled jet
    c1, _, _ = seed001_synthesized_pair()
    assert NormalDeviation(c1, quadratic_crowning(c1.reference_params, (0.5, 0.0, 5.0))).jet is None  # generated


def test_crowned_tca_compiled_equals_numpy(monkeypatch):
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    assert ContactProblem(crowned, pair.gear, kin)._jets is not None
    a = solve_tca(crowned, pair.gear, kin)
    monkeypatch.setattr(NormalDeviation, "jet", property(lambda self: None))
    assert ContactProblem(crowned, pair.gear, kin)._jets is None
    b = solve_tca(crowned, pair.gear, kin)
    assert np.array_equal(a.status_pairs, b.status_pairs) and a.edges == b.edges
    # Newton to |F| < 1e-10 mm from the same starts on flanks equal to an ulp: the roots agree to well below the
    # 1e-9 of the TCA benchmark's comparison with scipy
    for f in ("te_pairs", "phi2_pairs", "params1", "params2", "semi_axes", "transfer_phi1"):
        u, v = getattr(a, f), getattr(b, f)
        assert np.array_equal(np.isfinite(u), np.isfinite(v)), f
        fin = np.isfinite(u)
        assert np.max(np.abs(u[fin] - v[fin]), initial=0.0) < 1e-9, f
