"""The parabolic TE level of a TCA (``meshing.tca_checks.parabolic_level``) is fitted around the mean contact M, the
TE's stationary point, when a depth candidate of the default synthesis has moved M off the TCA's mean position
(bench/bench_robustness.py, 10/19 of sample ``100 2``).

Checked against the closed form of a cubic TE: TE(phi) = -A (phi - phi0)^2 + C (phi - phi0)^3 has its stationary
point at phi0 with TE'' = -2A there, so the level at M is A (pi/z1)^2, while its curvature at phi = 0 gives
(A + 3 C phi0) (pi/z1)^2.
"""

import math

import numpy as np
import pytest

from spiralbevel.meshing.tca_checks import STATIONARY_SHIFT, parabolic_level

Z1 = 10
HALF = math.pi / Z1
#: the bench's TCA: 21 positions over one mesh cycle, a step of 0.1 of half a cycle
PHI = np.linspace(-HALF, HALF, 21)


def _cubic(level_at_m, level_at_0, phi0):
    A = level_at_m / HALF**2
    C = (level_at_0 - level_at_m) / (3.0 * phi0 * HALF**2)
    return -A * (PHI - phi0) ** 2 + C * (PHI - phi0) ** 3, C


def _parabola_at_0(te):
    near = np.abs(PHI) <= 0.4 * HALF * (1 + 1e-9)     # both ends of the symmetric window (round-off of linspace)
    return -np.polyfit(PHI[near], te[near], 2)[0] * HALF**2


def test_level_of_a_pure_parabola_about_the_mean_position_is_exact():
    te = -8.0 * (PHI / HALF) ** 2 + 0.3
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-12)


@pytest.mark.parametrize("offset", [0.23, 0.25, 0.3])
def test_level_is_fitted_around_the_stationary_point(offset):
    # as the 10/19 coast pair of the bench: M about a quarter of a half cycle off phi = 0, 9.3 arcsec of curvature
    # at phi = 0
    phi0 = offset * HALF
    te, C = _cubic(8.0, 9.3, phi0)
    # the positions in the window around M lie symmetric about it to within half a step (0.05 of half a cycle); the
    # cubic term then bends the fitted parabola by at most 3 C (0.05 pi/z1) (pi/z1)^2 (0 at 0.25: symmetric)
    assert abs(parabolic_level(PHI, te, Z1) - 8.0) <= 3.0 * C * 0.05 * HALF**3 * (1 + 1e-9)
    # a parabola around phi = 0 sees the curvature away from M (the fit the check used before)
    assert _parabola_at_0(te) == pytest.approx(9.3, rel=1e-9)


def test_stationary_point_near_the_mean_position_keeps_the_parabola_at_phi_0():
    # M within STATIONARY_SHIFT of phi = 0 (a pitch-point pair whose sampled TE scatters): the fit stays at phi = 0
    te, _ = _cubic(8.0, 8.3, 0.5 * STATIONARY_SHIFT * HALF)
    near = np.abs(PHI) <= 0.4 * HALF      # the window as the check takes it (its round-off included)
    assert parabolic_level(PHI, te, Z1) == pytest.approx(-np.polyfit(PHI[near], te[near], 2)[0] * HALF**2, rel=1e-12)


def test_no_stationary_point_near_the_mean_position_keeps_the_parabola_at_phi_0():
    # a TE with no stationary point near the mean position (an edge-distorted curve): the parabola around phi = 0
    te = -8.0 * (PHI / HALF) ** 2 + 40.0 * PHI / HALF
    assert parabolic_level(PHI, te, Z1) == pytest.approx(8.0, rel=1e-12)
    assert parabolic_level(PHI[:2], te[:2], Z1) is None
