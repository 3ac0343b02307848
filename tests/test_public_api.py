"""Every name of the curated public API resolves."""

import spiralbevel


def test_all_names_resolve():
    for name in spiralbevel.__all__:
        assert getattr(spiralbevel, name) is not None, name


def test_unknown_name():
    import pytest

    with pytest.raises(AttributeError):
        spiralbevel.no_such_thing  # noqa: B018
