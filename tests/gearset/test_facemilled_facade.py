"""``gearset.facemilled`` is a facade over the small modules that hold its names (flank setup, default synthesis and
its candidate search, tooth assembly, checks, report): every old name is the same object, and a name set on the facade
(a monkeypatch) reaches the module whose code calls it, and is undone with it."""

from spiralbevel.gearset import default_candidates, default_synthesis, facemilled, flank_report, flank_setup


def test_old_names_are_the_moved_objects():
    assert facemilled.bearing_off_flank is default_candidates.bearing_off_flank
    assert facemilled._candidates is default_candidates._candidates is default_synthesis._candidates
    assert facemilled.synthesize_sides is default_synthesis.synthesize_sides
    assert facemilled.setup_flanks is flank_setup.setup_flanks
    assert facemilled.flank_report is flank_report.flank_report
    assert facemilled.FlankSetup is default_synthesis.FlankSetup is flank_setup.FlankSetup


def test_a_patch_of_the_facade_reaches_the_callers(monkeypatch):
    original = facemilled.tooth_rotation
    with monkeypatch.context() as m:
        m.setattr(facemilled, "tooth_rotation", "patched")
        m.setattr(facemilled, "bearing_off_flank", "patched")
        assert flank_report.tooth_rotation == "patched"                # flank_report calls it
        assert default_candidates.bearing_off_flank == "patched"       # _candidates' judge calls it
    assert flank_report.tooth_rotation is original and facemilled.tooth_rotation is original
    assert default_candidates.bearing_off_flank is facemilled.bearing_off_flank
