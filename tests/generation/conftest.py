import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from spiralbevel.conventions import Member, Side  # noqa: E402
from spiralbevel.generation import generate_flank  # noqa: E402
from spiralbevel.machine import Blade, HeadCutter, MachineSettings, seed001_blank, seed001_settings  # noqa: E402

CASES = [(Member.PINION, Side.CONCAVE), (Member.PINION, Side.CONVEX), (Member.GEAR, Side.CONCAVE),
         (Member.GEAR, Side.CONVEX)]


def basic_flank(member, side, blank=None, alpha=22.5, rp=math.inf, **changes):
    blank = blank or seed001_blank()
    bl = Blade.for_side(side)
    c = HeadCutter(114.3 + bl.sign * -1.145, math.radians(alpha), 2.29, 1.31, bl, profile_radius=rp, profile_ref=3.0)
    s = MachineSettings.from_blank(blank, member, side, c).replace(**changes)
    return generate_flank(c, s, blank, member, side)


@pytest.fixture(scope="session")
def blank():
    return seed001_blank()


@pytest.fixture(scope="session")
def gear_t4(blank):
    c, s = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    return generate_flank(c, s, blank, Member.GEAR, Side.CONVEX)


@pytest.fixture(scope="session")
def pinion_t5(blank):
    c, s = seed001_settings()[(Member.PINION, Side.CONCAVE)]
    return generate_flank(c, s, blank, Member.PINION, Side.CONCAVE)
