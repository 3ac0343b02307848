import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

from spiralbevel.conventions import Member, Side  # noqa: E402
from spiralbevel.machine import seed001_blank, seed001_settings  # noqa: E402
from spiralbevel.meshing.synthesis import FREE_MODIFIED_ROLL, synthesize_pinion  # noqa: E402
from _synth_common import A, ETA, TE  # noqa: E402


@pytest.fixture(scope="session")
def blank():
    return seed001_blank()


@pytest.fixture(scope="session")
def gear_table4():
    return seed001_settings()[(Member.GEAR, Side.CONVEX)]


def _synth(blank, gear, eta, **kw):
    c, s = gear
    return synthesize_pinion(c, s, blank, side=Side.CONCAVE, eta=eta, semi_major_axis=A, te_magnitude=TE, **kw)


@pytest.fixture(scope="session")
def synth_pos(blank, gear_table4):
    return _synth(blank, gear_table4, ETA)


@pytest.fixture(scope="session")
def synth_neg(blank, gear_table4):
    return _synth(blank, gear_table4, -ETA)


@pytest.fixture(scope="session")
def synth_roll(blank, gear_table4):
    return _synth(blank, gear_table4, ETA, free=FREE_MODIFIED_ROLL)


@pytest.fixture(scope="session", params=["pos", "neg", "roll"])
def synth(request, synth_pos, synth_neg, synth_roll):
    return {"pos": synth_pos, "neg": synth_neg, "roll": synth_roll}[request.param]
