"""The face-milled flank as a TCA contact surface."""

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings
from spiralbevel.meshing.generated_surface import GeneratedSurface, phased_for_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics


@pytest.fixture(scope="module")
def flanks():
    b = seed001_blank()
    st = seed001_settings()
    g = generate_flank(*st[(Member.GEAR, Side.CONVEX)], b, Member.GEAR, Side.CONVEX)
    p = generate_flank(*st[(Member.PINION, Side.CONCAVE)], b, Member.PINION, Side.CONCAVE)
    return p, g


def test_evaluate_matches_flank_and_rotation(flanks):
    _, g = flanks
    s = GeneratedSurface(g, rotation=0.3)
    q = s.reference_params + np.array([[0.5, 0.01], [-0.3, -0.02]])
    r, n = s.evaluate(q)
    fp = g.evaluate(q[:, 0], q[:, 1], curvature=False)
    c, sn = np.cos(0.3), np.sin(0.3)
    R = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1]])
    assert np.allclose(r, fp.points @ R.T, atol=1e-12) and np.allclose(n, fp.normals @ R.T, atol=1e-14)
    assert s.contains(s.reference_params)


def test_off_surface_is_nan_not_an_exception(flanks):
    _, g = flanks
    s = GeneratedSurface(g)
    r, n = s.evaluate(np.array([[50.0, 0.5]]))  # u = 50 mm, psi_c = 0.5 rad: no root of the equation of meshing
    assert np.all(np.isnan(r)) and np.all(np.isnan(n))
    assert not s.contains(np.array([50.0, 0.5]))


def test_phased_mean_points_meet_on_the_pitch_line(flanks):
    p, g = flanks
    s1, s2 = phased_for_pair(p, g)
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    r1, n1 = s1.evaluate(s1.reference_params)
    r2, n2 = s2.evaluate(s2.reference_params)
    r2f = kin.gear_to_fixed(0.0) @ r2
    assert np.allclose(r1, r2f, atol=1e-6)          # both at the mean pitch point, A_m from the apex
    assert np.linalg.norm(r1) == pytest.approx(115.9511, abs=1e-3)
    assert abs(r1[1]) < 1e-9                         # on the pitch line in the xz-plane
