"""The hypoid job's flank checks name the design-file keys as the face-milled job's do: ``run_hypoid`` passes the design
to ``flank_report``, so a synthesized pinion flank of a design without a ``[synthesis]`` section is said to come from
the default synthesis, with the section's keys to give (it once read "the local synthesis of the [synthesis] section
produced this flank" for a file that has no such section).

The hypoid flanks are the ISO 23509 Sample 2 basic settings (under a second); one pinion flank is labelled as the
hypoid synthesis labels its flanks and its achieved pressure angle moved 0.2 deg off the design, past the 0.05 deg
check, so that the check warns. The job stops after its flank step (the TCA and what follows are not under test)."""

import contextlib
import dataclasses
import math
import warnings
from types import SimpleNamespace

import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignWarning
from spiralbevel.gearset.flank_checks import flank_checks
from spiralbevel.gearset.hypoid import _basic
from spiralbevel.gearset.run_hypoid import run_hypoid
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from _hypoid_sample2 import SAMPLE2_TOML

#: the source line of a flank of the hypoid synthesis (gearset/hypoid.py), which marks it as synthesized
SOURCE = "hypoid local synthesis (drive side, path 0 deg, free = offset)"


class _Stop(Exception):
    pass


class _FlankStepOnly:
    """Progress steps of the job that stop it when the TCA step begins."""

    @contextlib.contextmanager
    def step(self, description):
        if description.startswith("tooth contact analysis"):
            raise _Stop
        yield


def _job_warnings(spec):
    """The flank-check warnings of the hypoid job on Sample 2 with a synthesized pinion concave flank whose pressure
    angle misses the design by 0.2 deg, and the face-milled checks of that flank for the same design."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the sample's own blank warnings (face width) are not under test
        blank = blank_from_design(spec)
    setups = _basic(spec, blank)
    key = (Member.PINION, Side.CONCAVE)
    st = setups[key]
    fit = dataclasses.replace(st.fit, pressure_angle=st.fit.pressure_angle_design + math.radians(0.2))
    setups[key] = dataclasses.replace(st, source=SOURCE, fit=fit)
    gs = SimpleNamespace(design=spec, blank=blank, setups=setups, synthesis={})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(_Stop):
            run_hypoid(gs, None, _FlankStepOnly(), {}, SimpleNamespace(partial=[], files=[], highlights=[]))
    found = [str(w.message) for w in caught
             if issubclass(w.category, DesignWarning) and str(w.message).startswith("pinion concave:")]
    return found, flank_checks(fit, Member.PINION, Side.CONCAVE, SOURCE, spec)


def test_default_synthesized_hypoid_flank_names_the_synthesis_keys():
    found, facemilled = _job_warnings(parse_design(SAMPLE2_TOML))
    (angle,) = [t for t in found if "pressure angle" in t]
    assert angle == f"pinion concave: {facemilled[0]}"       # worded as the face-milled job words it
    assert "the default synthesis (no [synthesis] section) produced this flank" in angle
    assert "give a [synthesis] section (synthesis.path_direction" in angle


def test_hypoid_flank_of_a_given_section_names_the_keys_to_change():
    found, facemilled = _job_warnings(parse_design(SAMPLE2_TOML + "[synthesis]\npath_direction = 10\n"))
    (angle,) = [t for t in found if "pressure angle" in t]
    assert angle == f"pinion concave: {facemilled[0]}"
    assert "the local synthesis of the [synthesis] section" in angle and "change synthesis.path_direction" in angle
