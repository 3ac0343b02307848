"""Corrective machine settings from a CMM measurement of one flank of a face-milled design (``spiralbevel correct``).

A hypoid design (``gear_set.hypoid_offset`` != 0) takes its four flanks from the hypoid branch (basic settings at each
member's mean cone distance, the pinion by hypoid local synthesis), and each member is generated, measured and
corrected in its own view of the blank (``design.hypoid_member.member_blank``): the pinion's settings are those of the
universal generator with the blank offset that the synthesis chose."""

from __future__ import annotations

import math

from ..conventions import Member, Side
from ..errors import DesignError
from ..gearset.blank import blank_from_design
from ..gearset.facemilled import setup_flanks


def flank_setups(spec, blank):
    """The four flanks of a face-milled design and the blank each member is generated in.

    Returns
    -------
    (dict, callable)
        ``{(Member, Side): FlankSetup}`` and ``member -> blank``: the ISO 23509 blank itself for a spiral bevel pair,
        the member's view (``member_blank``) for a hypoid pair.
    """
    if float(blank.a) != 0.0:
        from ..design.hypoid_member import member_blank
        from ..gearset.hypoid import setup_hypoid_flanks

        return setup_hypoid_flanks(spec, blank), lambda m: member_blank(blank, m)
    return setup_flanks(spec, blank), lambda m: blank


def correct_from_measurement(spec, member: str, side: str, measured_csv, parameters=None, regularization=0.0,
                             with_setups: bool = False):
    """Read measured deviations on the nominal 9 x 5 grid of one flank and solve for corrected settings.

    Returns (FlankSetup, CorrectionResult), and with ``with_setups`` also the setups of all four flanks.
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
    setups, member_view = flank_setups(spec, blank)
    st = setups[(m, s)]
    grid = measurement_grid(st.flank)
    measured = read_measured_deviation(measured_csv, grid)
    res = correct_settings(st.cutter, st.settings, member_view(m), m, s, grid, measured,
                           parameters=tuple(parameters) if parameters else DEFAULT_PARAMETERS,
                           regularization=regularization)
    return (st, res, setups) if with_setups else (st, res)


#: first line of a design file written by ``spiralbevel correct --write``: only such a file is ever replaced
WRITTEN_MARK = "Corrected design written by 'spiralbevel correct --write'"


def check_write_target(path, design_path) -> None:
    """Refuse (:class:`DesignError`, before any work) an output of ``correct --write`` that would replace the input
    design or a file that ``correct --write`` did not write; the path must also pass the output-safety rules of
    :func:`~spiralbevel.io.atomic.check_output_file`."""
    from pathlib import Path

    from ..io.atomic import check_output_file

    target = check_output_file(path)
    if design_path is not None and target.exists() and Path(design_path).exists() and \
            target.resolve() == Path(design_path).resolve():
        raise DesignError.single("--write", str(path), "a new file, not the design file being corrected", "-")
    if target.is_file():
        with open(target, encoding="utf-8", errors="replace") as fh:
            first = fh.readline()
        if WRITTEN_MARK not in first:
            raise DesignError.single("--write", str(path), "a new file, or one written by 'spiralbevel correct "
                                     "--write'", "-", "it exists and spiralbevel did not write it; it is left as it is")


def _flank_tables(st, settings=None, cutter=None) -> dict:
    """``{"cutter": ..., "machine": ...}`` design-file tables (degrees) of a flank's cutter and settings."""
    settings = st.settings if settings is None else settings
    cutter = st.cutter if cutter is None else cutter
    d = settings.to_dict(degrees=True)
    if d.get("blank_offset_table"):
        raise DesignError.single("--write", "settings with a blank-offset table", "settings a design file can give",
                                 "-", "the blank-offset table of multi-point control has no design-file key")
    if getattr(cutter, "profile_ref", 0.0):
        raise DesignError.single("--write", "a cutter with a profile reference height", "settings a design file can "
                                 "give", "-", "the blade's profile reference height has no design-file key")
    machine: dict[str, object] = {k: float(d[k]) for k in ("radial_setting", "cradle_angle", "machine_root_angle",
                                          "machine_centre_to_back", "sliding_base", "blank_offset", "ratio_of_roll")}
    if d["modified_roll"]:
        machine["modified_roll"] = [float(c) for c in d["modified_roll"]]
    if d["blank_offset_poly"]:
        machine["blank_offset_poly"] = [float(c) for c in d["blank_offset_poly"]]
    tool = {"point_radius": float(cutter.point_radius), "blade_angle": math.degrees(cutter.blade_angle),
            "point_width": float(cutter.point_width), "edge_radius": float(cutter.edge_radius)}
    if math.isfinite(cutter.profile_radius):
        tool["profile_radius"] = float(cutter.profile_radius)
    return {"cutter": tool, "machine": machine}


def corrected_design_text(text: str, setups, member: str, side: str, res, source: str = "") -> str:
    """A design file that cuts every flank as ``setups`` does, the flank (``member``, ``side``) with the corrected
    settings and cutter of ``res``.

    Every flank's cutter and machine settings are written explicitly (degrees) and the ``[synthesis]`` section is
    dropped, so the file does not depend on derivation or synthesis. Raises :class:`DesignError` for settings that
    a design file cannot hold (a blank-offset table of multi-point control).
    """
    import tomllib

    from ..io.toml_write import dumps_toml

    data = tomllib.loads(text)
    data.pop("synthesis", None)
    fm = data.setdefault("face_milling", {})
    m, s = Member(member), Side(side)
    for (mm, ss), st in setups.items():
        tables = (_flank_tables(st, res.settings, res.cutter) if (mm, ss) == (m, s) else _flank_tables(st))
        fm[f"{mm.value}_{ss.value}"] = tables
    header = (f"{WRITTEN_MARK}\nfrom {source or 'a design file'}: the {m.value} {s.value} flank's settings corrected "
              f"from a measurement (rms {1000 * res.rms_before:.2f} -> {1000 * res.rms_after:.2f} um);\nevery flank's "
              "cutter and machine settings are given explicitly (angles in degrees).")
    return dumps_toml(data, header)


def verify_corrected_design(text: str, setups, member: str, side: str, res) -> None:
    """Read a corrected design back and check that it cuts the corrected flank with ``res``'s settings and every
    other flank with the settings it had (relative 1e-12: the floats are written exactly, angles pass through degrees).
    Raises :class:`DesignError` otherwise."""
    from ..io.design_file import parse_design

    spec = parse_design(text, source="<corrected design>")
    new, _ = flank_setups(spec, blank_from_design(spec))
    m, s = Member(member), Side(side)
    for key, st in setups.items():
        want = res.settings if key == (m, s) else st.settings
        a, b = want.to_dict(degrees=False), new[key].settings.to_dict(degrees=False)
        for k in ("radial_setting", "cradle_angle", "machine_root_angle", "machine_centre_to_back", "sliding_base",
                  "blank_offset", "ratio_of_roll"):
            if not math.isclose(a[k], b[k], rel_tol=1e-12, abs_tol=1e-12):
                raise DesignError.single("--write", f"{key[0].value} {key[1].value} {k}", "the settings it was written "
                                         "with", "-", f"the written design gives {b[k]!r} instead of {a[k]!r}")


def correction_rows(st, res):
    """Rows (setting, nominal, corrected, change, unit) in shop units (angles in degrees); each setting is named as
    ``spiralbevel correct --parameters`` spells it (``modified_roll_2C``)."""
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
            rows.append((f"modified_roll_{name}", a, b, b - a, "-"))
    for key, attr, unit in (("blade_angle", "blade_angle", "deg"), ("point_radius", "point_radius", "mm")):
        a, b = getattr(st.cutter, attr), getattr(res.cutter, attr)
        if unit == "deg":
            a, b = math.degrees(a), math.degrees(b)
        if a != b:
            rows.append((key, a, b, b - a, unit))
    return rows
