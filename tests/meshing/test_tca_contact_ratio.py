"""Contact ratio from the TCA (``meshing.tca_checks.contact_ratio``) on constructed status grids; against the ISO
10300-1 virtual cylindrical gears on the bundled synthesized example in tests/cli/test_run_synthesized.py."""

import math
import types

import numpy as np
import pytest

from spiralbevel.meshing.tca_checks import contact_ratio, contact_ratio_warnings
from spiralbevel.meshing.tca_result import ContactStatus


def _fake(span_lo, span_hi, n=41, z1=10):
    """A TCA result whose pair k is inside the flanks at offsets o in [span_lo, span_hi] (units of the pitch)."""
    T = 2 * math.pi / z1
    phi = np.linspace(-T / 2, T / 2, n)
    pairs = np.array([-1, 0, 1])
    off = (phi[:, None] + pairs * T) / T
    inside = (off >= span_lo - 1e-12) & (off <= span_hi + 1e-12)
    status = np.where(inside, int(ContactStatus.OK), int(ContactStatus.NO_CONTACT))
    return types.SimpleNamespace(phi1=phi, phi1_mean=0.0, pairs=pairs, status_pairs=status)


@pytest.mark.parametrize("lo, hi", [(-0.6, 0.6), (-0.3, 0.95), (-0.45, 0.2), (-1.1, 0.7)])
def test_span_of_a_constructed_grid(lo, hi):
    ratio, lower = contact_ratio(_fake(lo, hi))
    assert not lower
    # each end within half a grid step (1/80 of the pitch; the worst case, a boundary on a sample, is exact here)
    assert ratio == pytest.approx(hi - lo, abs=1 / 40 + 1e-12)


def test_contact_beyond_the_analysed_pairs_is_a_lower_bound():
    ratio, lower = contact_ratio(_fake(-2.0, 2.0))
    assert lower and ratio == pytest.approx(3.0 + 1 / 40)


def test_below_one_warns_with_the_keys():
    res = _fake(-0.3, 0.4)
    assert contact_ratio(res)[0] < 1
    (text,) = contact_ratio_warnings(res, "drive", True)
    assert "< 1" in text and "synthesis.semi_major_axis" in text
    (text,) = contact_ratio_warnings(res, "coast", False)
    assert "face_milling.pinion_convex.machine" in text
    assert contact_ratio_warnings(_fake(-0.6, 0.6), "drive", True) == []
