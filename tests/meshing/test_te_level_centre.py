"""The parabolic TE level of a TCA (``meshing.tca_checks.parabolic_level``) is fitted around the mean contact M, the
TE's stationary point, also when M is not the TCA's mean position (the default synthesis' depth candidates put M below
the pitch line, bench/bench_robustness.py).

Checked against the closed form of a cubic TE: TE(phi) = -A (phi - phi0)^2 + C (phi - phi0)^3 has its stationary
point at phi0 with TE'' = -2A there, so the level at M is A (pi/z1)^2, while its curvature at phi = 0 gives
(A + 3 C phi0) (pi/z1)^2.
"""

import math

import numpy as np
import pytest

from spiralbevel.meshing.tca_checks import parabolic_level

Z1 = 10
HALF = math.pi / Z1
#: the TCA's 21 positions over one mesh cycle
PHI = np.linspace(-HALF, HALF, 21)


def _cubic(level_at_m, level_at_0, phi0):
    A = level_at_m / HALF**2
    C = (level_at_0 - level_at_m) / (3.0 * phi0 * HALF**2)
    return -A * (PHI - phi0) ** 2 + C * (PHI - phi0) ** 3


def test_level_of_a_pure_parabola_about_the_mean_position_is_exact():
    te = -8.0 * (PHI / HALF) ** 2 + 0.3
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-12)


@pytest.mark.parametrize("offset", [0.25, 0.3])
def test_level_is_fitted_around_the_stationary_point(offset):
    # as the 10/19 coast pair of the bench: M a quarter of a half cycle off phi = 0, 9.3 arcsec of curvature at 0
    phi0 = offset * HALF
    te = _cubic(8.0, 9.3, phi0)
    level = parabolic_level(PHI, te, Z1)
    # the samples in the window around M sit symmetric about it at 0.25 (exact to round-off) and up to half a step
    # (0.05 of half a cycle) off symmetric otherwise, where the cubic term leaks at most 3 C (0.05 pi/z1) (pi/z1)^2
    # = 0.22 arcsec (2.7 %) into the fitted level
    C = (9.3 - 8.0) / (3.0 * phi0 * HALF**2)
    assert abs(level - 8.0) <= 3.0 * C * 0.05 * HALF**3 * (1 + 1e-6)
    # a window centred on phi = 0 sees the curvature away from M (the fit the check used before)
    near = np.abs(PHI) <= 0.4 * HALF * (1 + 1e-9)     # both ends of the symmetric window (round-off of linspace)
    assert -np.polyfit(PHI[near], te[near], 2)[0] * HALF**2 == pytest.approx(9.3, rel=1e-9)


def test_vertex_outside_the_window_keeps_the_fit_at_the_mean_position():
    # a TE with no stationary point near the mean position (an edge-distorted curve): the fit stays around phi = 0
    te = -8.0 * (PHI / HALF) ** 2 + 40.0 * PHI / HALF
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-12)
    assert parabolic_level(PHI[:2], te[:2], Z1) is None
