"""Reference values P1-P4 of docs/theory/logspiral.md#reference-values (rho0 = 100 mm, delta = 20 deg, beta = 35 deg),
both branches.

Oracle: column (B) of docs/theory/logspiral.md#reference-values -- the raw seed 000 Eq. (16) differentiated by mpmath at
50 digits, n oriented
like the corrected Eq. (21), curvatures 'bend toward n' (papers' convention). Tolerance: 1e-11 relative for the
closed forms (docs/theory/logspiral.md#reference-values recommends rtol ~ 1e-11 against (B)); the generic numerical
module (Richardson central
differences) is held to 1e-8 relative on curvatures (task requirement; measured ~1e-10).
"""

import numpy as np
import pytest

from spiralbevel import LogSpiralFlank
from spiralbevel._core import logspiral as core
from spiralbevel.geometry.diffgeom import surface_geometry

RHO0, DELTA, BETA = 100.0, np.radians(20.0), np.radians(35.0)

# docs/theory/logspiral.md#reference-values column (B); (varphi, phi): r, n, E, G, L, N, k1, k2
REF = {
    "P1": ((0.5, 0.1), (38.0888936179341, 4.4895117484889, 97.7512227081296),
           (0.56357500736832, -0.705952111174161, 0.42896949518415),
           181.096686981289, 3920.55420151025, -11.2511298626197, -21.4153617935416,
           -0.0621277509277801, -0.00546233024537503),
    "P2": ((1.2, 0.3), (46.3703091830943, 22.4622937318498, 103.685338183272),
           (0.926553031275627, -0.250713367102517, 0.280432323012283),
           1086.62518312735, 4766.51379034682, -29.5644971686677, -23.6130513509125,
           -0.0272076311388073, -0.0049539458794253),
    "P3": ((2.2, 0.25), (38.6390636699024, 65.6807526174137, 83.4230859925147),
           (0.818506286420744, 0.572078563488653, -0.052664753739888),
           4313.55926936144, 4539.28557589378, -61.6198401747378, -23.0433405211812,
           -0.0142851497630771, -0.00507642450247118),
    "P4": ((0.1, 0.6), (42.6771996682741, 27.2095727602487, 124.132172889299),
           (0.310628463160478, -0.681989427567339, 0.662118100161091),
           459.554987466261, 6389.70695692652, 14.2943410301569, -27.3395999368525,
           0.0311047457214385, -0.00427869386204261),
}
RTOL = 1e-11


def _rel(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b)) / np.maximum(np.abs(b), 1e-300))


@pytest.mark.parametrize("name", sorted(REF))
def test_core_kernel_matches_reference(name):
    (vp, ph), r, n, E, G, L, N, k1, k2 = REF[name]
    g = core.geometry(vp, ph, RHO0, DELTA, BETA)
    assert _rel(g["r"], r) < RTOL
    assert np.max(np.abs(g["n"] - n)) < RTOL
    for key, ref in (("E", E), ("G", G), ("L", L), ("N", N), ("k1", k1), ("k2", k2)):
        assert _rel(g[key], ref) < RTOL, key


@pytest.mark.parametrize("name", sorted(REF))
def test_public_flank_matches_reference_converted(name):
    """Public conventions: n_out = sign(psi) n, L_out = -sign(psi) L, k_reported = -sign(psi) k
    (docs/conventions.md)."""
    (vp, ph), r, n, E, G, L, N, k1, k2 = REF[name]
    g = LogSpiralFlank(RHO0, DELTA, BETA).evaluate(vp, ph)
    s = np.sign(g.psi)
    assert s == (1 if name != "P4" else -1)  # P1-P3 convex, P4 concave (docs/theory/logspiral.md#reference-values)
    assert _rel(g.point, r) < RTOL
    assert np.max(np.abs(g.normal - s * np.asarray(n))) < RTOL
    assert _rel(g.E, E) < RTOL and _rel(g.G, G) < RTOL
    assert _rel(g.L, -s * L) < RTOL and _rel(g.N, -s * N) < RTOL
    assert _rel(g.k1, -s * k1) < RTOL and _rel(g.k2, -s * k2) < RTOL
    assert g.F == 0.0 and g.M == 0.0


@pytest.mark.parametrize("name", sorted(REF))
def test_generic_numerical_module_matches_reference(name):
    (vp, ph), r, n, E, G, L, N, k1, k2 = REF[name]
    flank = LogSpiralFlank(RHO0, DELTA, BETA)
    s = -1.0 if name == "P4" else 1.0
    # orientation of the normal n of docs/theory/logspiral.md, Eqs. (S4), (S9): n = sign(sin psi sin beta) unit(r_varphi
    # x r_phi) (docs/theory/logspiral.md, Eq. (S4))
    g = surface_geometry(flank.point, vp, ph, normal_sign=s)
    assert np.max(np.abs(g.normal - n)) < 1e-10
    assert _rel(g.E, E) < 1e-10 and _rel(g.G, G) < 1e-10
    # generic module: L = -r_uu . n, so L_generic = -L_reference; curvatures likewise change sign
    assert _rel(-g.L, L) < 1e-8 and _rel(-g.N, N) < 1e-8
    assert _rel(-g.k1, k1) < 1e-8 and _rel(-g.k2, k2) < 1e-8
    assert abs(g.F) < 1e-9 * np.sqrt(E * G) and abs(g.M) < 1e-9 * abs(N)
