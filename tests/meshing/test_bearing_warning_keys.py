"""The bearing warning names the key the user can change: given pinion settings, a synthesized side, or a side that a
``[synthesis]`` section leaves out (its pinion flank then has the basic settings from the blank, which the design file
does not give: the warning once told the user to remove settings they never wrote)."""

import re
from types import SimpleNamespace

import numpy as np

from spiralbevel.gearset.run_facemilled import pinion_settings_given
from spiralbevel.io.design_file import parse_design
from spiralbevel.io.design_schema import BaseModel, DesignFile, SynthesisSpec
from spiralbevel.meshing.tca_checks import bearing_warnings

BASE = """
[gear_set]
pinion_teeth = 12
gear_teeth = 41
module = 5
face_width = 30
mean_spiral_angle = 35
[flank]
kind = "face-milled"
"""
PARTIAL = BASE + "[synthesis]\nte_magnitude = 12\n"
GIVEN = BASE + """[face_milling.pinion_convex.machine]
radial_setting = 90.0
cradle_angle = 60.0
machine_root_angle = 15.0
ratio_of_roll = 3.5
"""


def _res_with_one_edge_contact():
    te = np.zeros(41)
    edge = np.zeros(41, bool)
    edge[3] = True
    return SimpleNamespace(te=te, edge_contact=edge, edges=[(3, 0, "gear", "top")])


def test_settings_given_is_read_from_the_design_file():
    assert not pinion_settings_given(parse_design(PARTIAL), "coast")
    assert not pinion_settings_given(parse_design(PARTIAL), "drive")
    assert pinion_settings_given(parse_design(GIVEN), "coast")
    assert not pinion_settings_given(parse_design(GIVEN), "drive")


def test_warning_names_the_key_of_each_case():
    res = _res_with_one_edge_contact()
    (given,) = bearing_warnings(res, "coast", synthesized=False, given=True)
    assert "face_milling.pinion_convex.machine" in given and "at 1 of 41" in given
    (left_out,) = bearing_warnings(res, "coast", synthesized=False, given=False)
    assert "synthesis.sides" in left_out and '"coast"' in left_out
    assert "face_milling" not in left_out and "given settings" not in left_out
    (synth,) = bearing_warnings(res, "coast", synthesized=True)
    assert "synthesis.path_direction" in synth


def _schema_key(path: str) -> bool:
    """True when the dotted design-file key ``path`` (``synthesis.sides``, ``face_milling.pinion_convex.machine``)
    is a field of the design-file schema."""
    model = DesignFile
    for part in path.split("."):
        if model is None or part not in model.model_fields:
            return False
        ann = model.model_fields[part].annotation
        model = next((a for a in (ann, *getattr(ann, "__args__", ())) if isinstance(a, type) and
                      issubclass(a, BaseModel)), None)
    return True


def _keys(text: str) -> list[str]:
    return re.findall(r"\b(?:synthesis|face_milling|gear_set)(?:\.[a-z_0-9]+)+", text)


def test_every_warning_names_keys_of_the_schema():
    res = _res_with_one_edge_contact()
    cases = [dict(synthesized=False, given=True), dict(synthesized=False, given=False), dict(synthesized=True),
             dict(synthesized=True, default=True)]
    for case in cases:
        for side in ("drive", "coast"):
            (text,) = bearing_warnings(res, side, **case)
            keys = _keys(text)
            assert keys, (case, text)
            for key in keys:
                assert _schema_key(key), (case, key)
    assert not _schema_key("synthesis.drive.te_magnitude") and _schema_key("synthesis.te_magnitude")


def test_default_search_warning_gives_true_advice():
    """A default-synthesized side that keeps an edge contact: the warning says to give synthesis.path_direction in the
    [synthesis] section, with the range the schema allows, and that it applies to both sides unless synthesis.sides
    says otherwise (a section that leaves ``sides`` out develops both sides, tests/gearset/test_effective_synthesis.py;
    the warning once said to write sides = ["drive", "coast"], as if a section without it synthesized one side)."""
    res = _res_with_one_edge_contact()
    (text,) = bearing_warnings(res, "drive", synthesized=True, default=True)
    assert "default synthesis" in text and "[synthesis] section" in text
    assert "synthesis.path_direction" in text and "synthesis.semi_major_axis" in text
    assert "sides = [" not in text and "both when left out" in text
    eta = SynthesisSpec.model_json_schema()["properties"]["path_direction"]
    assert f"{eta['exclusiveMinimum']:g} to {eta['exclusiveMaximum']:g} deg" in text and eta["unit"] == "deg"
