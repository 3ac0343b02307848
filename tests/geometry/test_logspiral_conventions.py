"""Pins the hand convention of docs/conventions.md: beta > 0 is right hand.

Rule: in the member frame, walking along a right-hand tooth from toe to heel turns positively about +z; seen by an
observer at the apex looking along +z, the outer half of the tooth turns clockwise from the axial plane through the
mean point. We walk along the tooth trace (psi = const curve) from small to large |r| and measure the azimuth.
"""

import numpy as np
import pytest

from spiralbevel import Hand, LogSpiralFlank, Side


@pytest.mark.parametrize("beta_deg", [10.0, 35.0, 60.0, -10.0, -35.0, -60.0])
@pytest.mark.parametrize("side", list(Side))
def test_tooth_trace_turns_positively_about_z_for_right_hand(beta_deg, side):
    flank = LogSpiralFlank(100.0, np.radians(25.0), np.radians(beta_deg))
    psi = flank.psi_sign(side) * 0.2
    phi = np.linspace(-0.3, 0.3, 21)
    p = flank.point(flank.varphi_of(psi, phi), phi)
    radius = np.linalg.norm(p, axis=-1)
    order = np.argsort(radius)  # toe -> heel
    azimuth = np.unwrap(np.arctan2(p[order, 1], p[order, 0]))
    turn = np.sign(np.diff(azimuth))
    expected = 1 if beta_deg > 0 else -1
    assert np.all(turn == expected)
    assert flank.hand is (Hand.RIGHT if beta_deg > 0 else Hand.LEFT)
    # observer at the apex looking along +z sees the xy-plane mirrored: positive turn about +z appears clockwise
    v_obs = np.diff(np.stack([p[order, 0], -p[order, 1]], -1), axis=0)  # (x, -y) is the observer's picture
    r_obs = np.stack([p[order, 0], -p[order, 1]], -1)[:-1]
    cw = np.sign(r_obs[:, 0] * v_obs[:, 1] - r_obs[:, 1] * v_obs[:, 0]) < 0
    assert np.all(cw == (beta_deg > 0))


def test_convex_branch_is_sign_psi_equal_sign_beta():
    for beta in (0.6, -0.6):
        flank = LogSpiralFlank(100.0, 0.4, beta)
        assert flank.side_of(0.5 * np.sign(beta), 0.0) is Side.CONVEX
        assert flank.side_of(-0.5 * np.sign(beta), 0.0) is Side.CONCAVE
