"""Corrective machine settings from a CMM measurement of one flank of a face-milled design (``spiralbevel correct``)."""

from __future__ import annotations

import math

from ..conventions import Member, Side
from ..errors import DesignError
from ..gearset.blank import blank_from_design
from ..gearset.facemilled import setup_flanks


def correct_from_measurement(spec, member: str, side: str, measured_csv, parameters=None, regularization=0.0):
    """Read measured deviations on the nominal 9 x 5 grid of one flank and solve for corrected settings.

    Returns (FlankSetup, CorrectionResult).
    """
    from ..io.measurement_csv import read_measured_deviation
    from ..manufacturing.correction import DEFAULT_PARAMETERS, correct_settings
    from ..manufacturing.measurement import measurement_grid

    if spec.flank.kind != "face-milled":
        raise DesignError.single("flank.kind", spec.flank.kind, "'face-milled' for corrective settings", "-")
    try:
        m, s = Member(member), Side(side)
    except ValueError as err:
        raise DesignError.single("member/side", f"{member}/{side}", "pinion|gear / convex|concave", "-") from err
    blank = blank_from_design(spec)
    st = setup_flanks(spec, blank)[(m, s)]
    grid = measurement_grid(st.flank)
    measured = read_measured_deviation(measured_csv, grid)
    res = correct_settings(st.cutter, st.settings, blank, m, s, grid, measured,
                           parameters=tuple(parameters) if parameters else DEFAULT_PARAMETERS,
                           regularization=regularization)
    return st, res


def correction_rows(st, res):
    """Rows (setting, nominal, corrected, change, unit) in shop units (angles in degrees)."""
    nom, cor = st.settings.to_dict(degrees=True), res.settings.to_dict(degrees=True)
    rows = []
    for key in ("radial_setting", "cradle_angle", "machine_root_angle", "sliding_base", "machine_centre_to_back",
                "blank_offset", "ratio_of_roll"):
        unit = "deg" if key in ("cradle_angle", "machine_root_angle") else ("-" if key == "ratio_of_roll" else "mm")
        rows.append((key, nom[key], cor[key], cor[key] - nom[key], unit))
    for i, name in enumerate(("2C", "6D", "24E", "120F")):
        a = nom["modified_roll"][i] if i < len(nom["modified_roll"]) else 0.0
        b = cor["modified_roll"][i] if i < len(cor["modified_roll"]) else 0.0
        if a or b:
            rows.append((f"modified roll {name}", a, b, b - a, "-"))
    for key, attr, unit in (("blade angle", "blade_angle", "deg"), ("point radius", "point_radius", "mm")):
        a, b = getattr(st.cutter, attr), getattr(res.cutter, attr)
        if unit == "deg":
            a, b = math.degrees(a), math.degrees(b)
        if a != b:
            rows.append((key, a, b, b - a, unit))
    return rows
