import json
import math

import numpy as np

from spiralbevel.io.report import dumps_report, to_jsonable, write_report


def test_numpy_and_missing_values(tmp_path):
    rep = {"a": np.float64(1.5), "b": np.arange(3), "c": [np.nan, 2.0, np.inf], "d": (np.int64(4), np.bool_(True))}
    out = json.loads(dumps_report(rep))
    assert out == {"a": 1.5, "b": [0, 1, 2], "c": [None, 2.0, None], "d": [4, True]}
    write_report(tmp_path / "r.json", rep)
    assert json.loads((tmp_path / "r.json").read_text()) == out


def test_plain_values_untouched():
    assert to_jsonable({"x": 1, "y": "s", "z": math.pi}) == {"x": 1, "y": "s", "z": math.pi}
