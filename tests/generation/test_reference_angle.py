"""Branch and window centre of the generated flank (``_core.generation.reference_angle``): the cutter angle toward
the crossing of the nominal cutter circle with the member's root line, which a blank offset displaces (the line of the
cradle plane parallel to -X_m through the offset work axis). Checked by the crossing point itself (on the circle, on
the line, the far one of the two) and against the universal generator's own reference."""

import math

import numpy as np
import pytest

from spiralbevel._core.generation import reference_angle
from spiralbevel._core.universal_generator import reference_theta
from spiralbevel.machine.settings import MachineSettings
from spiralbevel.machine.universal import UniversalSettings

RC = 58.0          # mm, nominal cutter radius
PSI = np.array([-0.4, 0.0, 0.3])


@pytest.mark.parametrize("offset", [0.0, -19.66, 1.5])     # mm; the last moves the line away from the cutter
def test_reference_points_at_the_far_crossing_with_the_offset_root_line(offset):
    s = MachineSettings(radial_setting=61.5, cradle_angle=1.15, machine_root_angle=0.354, blank_offset=offset,
                        ratio_of_roll=3.4)
    mp = s.kernel_params()
    phi = reference_angle(PSI, mp, RC)
    # the crossing point at psi_c = 0, fixed in the machine frame, seen from the cutter centre at every psi_c
    c0 = mp["S"] * np.array([math.cos(math.pi - mp["q"]), math.sin(math.pi - mp["q"])])
    x0 = c0 + RC * np.array([math.cos(phi[1]), math.sin(phi[1])])
    assert x0[1] == pytest.approx(mp["E"], abs=1e-12)                   # on the member's root line y = E (kernel)
    # the far crossing: the other root of |c0 + (x, E) - c0| = RC has the larger x (nearer the apex)
    x_other = 2.0 * c0[0] - x0[0]
    assert x0[0] < x_other
    for p, ph in zip(PSI, phi):
        c = mp["S"] * np.array([math.cos(math.pi - mp["q"] + p), math.sin(math.pi - mp["q"] + p)])
        d = x0 - c
        assert math.atan2(d[1], d[0]) == pytest.approx(ph, abs=1e-12)
    # the universal generator's reference (measured from the ray machine centre -> cutter centre) is the same angle
    up = UniversalSettings.from_machine_settings(s).kernel_params()
    th = reference_theta(PSI, up, RC)
    np.testing.assert_allclose(np.angle(np.exp(1j * (th + math.pi - mp["q"] + PSI - phi))), 0.0, atol=1e-12)


def test_offset_turns_the_reference_as_the_crossing_moves():
    """A 19.66 mm offset toward the cutter centre moves the crossing out along the root line: the reference turns by
    the angle between the two crossings seen from the cutter centre (0.6 rad here, most of the 0.75 rad window)."""
    base = dict(radial_setting=61.5, cradle_angle=1.15, machine_root_angle=0.354, ratio_of_roll=3.4)
    a = reference_angle(0.0, MachineSettings(**base).kernel_params(), RC)
    b = reference_angle(0.0, MachineSettings(**base, blank_offset=-19.66).kernel_params(), RC)
    ys = 61.5 * math.sin(1.15)                       # cutter centre's distance from the root line, mm
    turn = math.asin(ys / RC) - math.asin((ys - 19.66) / RC)
    assert abs(float(np.angle(np.exp(1j * (b - a))))) == pytest.approx(turn, abs=1e-12)
    assert turn > 0.5
