"""The parabolic TE level of a TCA (``meshing.tca_checks.parabolic_level``) is taken at the mean contact M, the TE's
stationary point, also when M is not the TCA's mean position (the default synthesis' depth candidates put M below
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


@pytest.mark.parametrize("offset", [0.23, 0.25, 0.3])
def test_level_is_taken_at_the_stationary_point(offset):
    # as the 10/19 coast pair of the bench: M about a quarter of a half cycle off phi = 0, 9.3 arcsec of curvature
    # at phi = 0; the cubic fit reproduces a cubic TE to round-off
    phi0 = offset * HALF
    te = _cubic(8.0, 9.3, phi0)
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-9)
    # a parabola fitted around phi = 0 sees the curvature away from M (the fit the check used before)
    near = np.abs(PHI) <= 0.4 * HALF * (1 + 1e-9)     # both ends of the symmetric window (round-off of linspace)
    assert -np.polyfit(PHI[near], te[near], 2)[0] * HALF**2 == pytest.approx(9.3, rel=1e-9)


def test_window_with_one_more_position_on_one_side():
    # M at phi = 0 and positions that put one more into the window on the left than on the right: a parabola
    # through them bends with the cubic term, the level at the stationary point does not
    phi = np.linspace(-HALF, HALF, 21) - 0.04 * HALF
    te = -8.0 * (phi / HALF) ** 2 + 3.0 * (phi / HALF) ** 3
    assert parabolic_level(phi, te, Z1) == pytest.approx(8.0, rel=1e-9)
    near = np.abs(phi) <= 0.4 * HALF
    assert abs(-np.polyfit(phi[near], te[near], 2)[0] * HALF**2 - 8.0) > 0.05   # 0.09 arcsec here


def test_no_stationary_point_near_the_mean_position_keeps_the_parabola_at_phi_0():
    # a TE with no stationary point near the mean position (an edge-distorted curve): the parabola around phi = 0
    te = -8.0 * (PHI / HALF) ** 2 + 40.0 * PHI / HALF
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-12)
    assert parabolic_level(PHI[:2], te[:2], Z1) is None
