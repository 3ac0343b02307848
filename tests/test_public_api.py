"""Every name of the curated public API resolves."""

import spiralbevel


def test_all_names_resolve():
    for name in spiralbevel.__all__:
        assert getattr(spiralbevel, name) is not None, name


def test_unknown_name():
    import pytest

    with pytest.raises(AttributeError):
        spiralbevel.no_such_thing  # noqa: B018


def test_gearset_is_public():
    # the user-facing gear pair and its result objects (issue 12)
    from spiralbevel.gearset import LTCA, TCA, EaseOff, MachineSummary, MeasurementGrids, Rating, Sensitivity

    assert "GearSet" in spiralbevel.__all__ and spiralbevel.GearSet.__module__ == "spiralbevel.gearset.gearset"
    for cls in (TCA, LTCA, EaseOff, Sensitivity, MachineSummary, MeasurementGrids, Rating):
        assert callable(cls.plot) and callable(cls.to_dict) and callable(cls._repr_html_)
