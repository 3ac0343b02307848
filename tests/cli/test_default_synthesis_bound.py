"""The default synthesis search is bounded: when no local synthesis succeeds, at most DEFAULT_MAX_SYNTHESES are tried
per side, and the error names the cause and the [synthesis] keys to give."""


import pytest

from spiralbevel.errors import ConvergenceError
from spiralbevel.job import facemilled as fm
from spiralbevel.meshing import synthesis as syn
from _design_12x41 import design_12x41
from _designs import basic_setups

DESIGN = design_12x41()


def test_failing_syntheses_are_bounded_and_named(monkeypatch):
    spec, blank, setups = basic_setups(DESIGN)
    calls = []

    def fail(*args, **kw):
        calls.append(kw["eta"])
        raise ConvergenceError("pinion machine settings: Newton did not reach the synthesized geometry", 7, 1.0)

    monkeypatch.setattr(syn, "synthesize_pinion", fail)
    with pytest.raises(ConvergenceError) as info:
        fm.synthesize_sides(spec, blank, setups, fm.effective_synthesis(spec, blank))
    assert len(calls) == fm.DEFAULT_MAX_SYNTHESES        # the first side stops at the bound
    msg = str(info.value)
    assert "drive side" in msg and "synthesis.path_direction" in msg and "Newton did not reach" in msg
