"""Corner contacts of TCA (spiralbevel._core.tca_corner through meshing.tca_edge.solve_edge_contacts) against a
per-point ``scipy.optimize.root`` of the same five equations written plainly here with numpy: the two points
coincide (3, mm) and each lies on its boundary (the surfaces' own ``boundary_margins``). Cases: the corners TCA
finds on the drive side of the bundled face-milled example (the pinion's heel edge meeting the gear's top edge,
and the vertex of the pinion's heel and fillet junction against the gear flank), solved by the compiled kernel and
by the numpy-evaluated path (the same flanks behind a wrapper without compiled jets and margins)."""

import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import root

from spiralbevel.conventions import Member
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.generated_surface import phased_for_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_edge import corner_split, solve_edge_contacts


class _Plain:
    """A flank without compiled jet or margins: ``evaluate``, ``derivatives``, ``boundary_margins`` and ``contains``
    of the wrapped surface only (TCA then evaluates it by numpy and differences its margins)."""

    def __init__(self, s):
        self._s = s
        self.boundary_names = s.boundary_names
        self.reference_params = s.reference_params

    def evaluate(self, q):
        return self._s.evaluate(q)

    def derivatives(self, q):
        return self._s.derivatives(q)

    def boundary_margins(self, q):
        return self._s.boundary_margins(q)

    def contains(self, q):
        return self._s.contains(q)


@pytest.fixture(scope="module")
def drive_pair():
    from spiralbevel.gearset.blank import blank_from_design
    from spiralbevel.gearset.facemilled import PAIR_SIDES, _basic_setups
    from spiralbevel.io.design_file import load_design

    spec = load_design(str(Path(__file__).parents[2] / "src" / "spiralbevel" / "data"
                           / "aviation_23x65_facemilled.toml"))
    blank = blank_from_design(spec)
    setups = _basic_setups(spec, blank)  # the drive flanks of the example: given settings, not synthesized
    s1, s2 = PAIR_SIDES["drive"]
    c1, c2 = phased_for_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank)
    kin = BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
    res = solve_tca(c1, c2, kin, n_positions=41, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    return c1, c2, kin, res


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _reference_residual(prob, phi1_eff, a, b):
    """The corner equations at one system as a plain function of x (5,): the points coincide (fixed frame, mm) and
    margin a[1] of member a[0] and margin b[1] of member b[0] vanish (the surfaces' numpy ``boundary_margins``)."""
    _, o1, a2, o2, B2 = prob.axes
    K = np.array([[0, -a2[2], a2[1]], [a2[2], 0, -a2[0]], [-a2[1], a2[0], 0]])
    surfs = (prob.pinion, prob.gear)

    def fun(x):
        q = (x[0:2], x[2:4])
        R2 = (np.eye(3) + np.sin(x[4]) * K + (1 - np.cos(x[4])) * K @ K) @ B2
        r1, r2 = surfs[0].evaluate(q[0])[0], surfs[1].evaluate(q[1])[0]
        ga = surfs[a[0]].boundary_margins(q[a[0]][None])[0, a[1]]
        gb = surfs[b[0]].boundary_margins(q[b[0]][None])[0, b[1]]
        return np.r_[o1 + _rz(phi1_eff) @ r1 - o2 - R2 @ r2, ga, gb]

    return fun


@pytest.mark.parametrize("path", ["compiled", "numpy"])
def test_corner_newton_matches_per_point_scipy(drive_pair, path):
    """Random starts around every corner contact TCA found (pinion rotations within a tenth of the position spacing,
    starts perturbed by 1e-3 in every unknown): the solver and a per-point scipy root of the reference equations
    reach the same root. Measured: 9e-16 (compiled) and 8e-16 (numpy path: the equations hold no derivative, only
    their Jacobian does); the bound 1e-12 leaves room for the round-off of other starts."""
    c1, c2, kin, res = drive_pair
    corners = [(i, list(res.pairs).index(k)) for i, k, m, e in res.edges if e.endswith(" corner")]
    assert len(corners) >= 8, res.edges
    if path == "numpy":
        c1, c2 = _Plain(c1), _Plain(c2)
    prob = ContactProblem(c1, c2, kin)
    assert (prob._jets is None) == (path == "numpy")
    # the corner's code: the label's boundaries, read back from the margins that vanish at the reported points
    from spiralbevel.meshing.tca_edge import corner_index

    rng = np.random.default_rng(3)
    dphi = np.diff(res.phi1[:2])[0]
    phi, x0, code = [], [], []
    for a in rng.integers(0, len(corners), 16):
        i, j = corners[a]
        g = [np.abs(c1.boundary_margins(res.params1[i, j][None])[0]),
             np.abs(c2.boundary_margins(res.params2[i, j][None])[0])]
        zero = [(m, int(e)) for m in (0, 1) for e in np.flatnonzero(g[m] < 1e-9)]
        assert len(zero) == 2, (i, zero)
        p = res.phi1[i] + res.pairs[j] * 2 * np.pi / prob.z1
        d = rng.uniform(-0.1, 0.1) * dphi
        x = np.r_[res.params1[i, j], res.params2[i, j], res.phi2_pairs[i, j] - res.pairs[j] * 2 * np.pi / prob.z2]
        x[4] -= prob.ratio * d
        phi.append(p + d), x0.append(x + rng.normal(0.0, 1e-3, 5)), code.append(corner_index(prob, *zero))
    phi, x0, code = np.array(phi), np.array(x0), np.array(code)
    assert corner_split(prob, np.zeros(len(code), int), code)[0].all()
    xs, conv, ndot = solve_edge_contacts(prob, phi, x0, np.zeros(len(code), int), code, tol=1e-11)
    assert conv.all() and np.all(ndot < -0.5)
    _, ma, ea, mb, eb = corner_split(prob, np.zeros(len(code), int), code)
    worst = 0.0
    for k in range(len(phi)):
        fun = _reference_residual(prob, phi[k], (ma[k], ea[k]), (mb[k], eb[k]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            # y = x + 1: see test_tca_engine
            sol = root(lambda y, f=fun: f(y - 1.0), x0[k] + 1.0, method="hybr", tol=1e-14)
        xr = sol.x - 1.0
        assert np.max(np.abs(fun(xr))) < 1e-9
        worst = max(worst, np.max(np.abs(xr - xs[k])))
    assert worst < 1e-12, f"{path}: corner roots differ from scipy's by {worst:.2e}"
