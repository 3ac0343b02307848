"""One unit convention for report.json: every dimensional name carries its unit as a suffix.

Lengths ``_mm``, angles and rotations ``_deg`` (never rad), transmission errors ``_arcsec``, pressures and stresses
``_N_per_mm2``, torques ``_N_m``, forces ``_N``, curvatures ``_per_mm``; dimensionless names carry no suffix. No
section holds a ``units`` mapping or a unit written in prose.
"""

from __future__ import annotations

import math

__all__ = ["SUFFIX", "suffix", "suffixed", "rad_to_deg", "MACHINE_SETTING_UNITS"]

#: unit text (as the library's unit tables write it) -> name suffix
SUFFIX = {
    "-": "", "": "", "mm": "_mm", "deg": "_deg", "arcsec": "_arcsec", "um": "_um", "mm^2": "_mm2", "mm^3": "_mm3",
    "N/mm^2": "_N_per_mm2", "N/mm2": "_N_per_mm2", "N m": "_N_m", "N mm": "_N_mm", "N": "_N", "1/mm": "_per_mm",
    "m/s": "_m_per_s", "1/min": "_per_min", "kW": "_kW", "kg/mm^3": "_kg_per_mm3", "mm^2/s": "_mm2_per_s",
    "N/(mm um)": "_N_per_mm_um", "N/mm/um": "_N_per_mm_um", "1/s": "_per_s", "s": "_s", "rad": "_deg",
    "1/rad": "_per_rad", "mm/rad": "_mm_per_rad",
}

#: units of :meth:`MachineSettings.to_dict(degrees=True) <spiralbevel.machine.settings.MachineSettings.to_dict>`
MACHINE_SETTING_UNITS = {
    "radial_setting": "mm", "cradle_angle": "deg", "machine_root_angle": "deg", "machine_centre_to_back": "mm",
    "sliding_base": "mm", "blank_offset": "mm", "ratio_of_roll": "-", "modified_roll": "-",
    "blank_offset_poly": "mm", "blank_offset_table": "mm",
    # UniversalSettings.to_dict (a Formate gear)
    "tilt": "deg", "swivel": "deg", "helical_motion": "mm", "vertical_motion": "mm", "radial_motion": "mm",
}


def suffix(unit: str) -> str:
    """The name suffix of a unit (``"N/mm^2"`` -> ``"_N_per_mm2"``; ``"-"`` -> ``""``)."""
    if unit in SUFFIX:
        return SUFFIX[unit]
    text = unit.replace("^", "").replace("/", "_per_").replace(" ", "_")
    return "_" + "".join(c for c in text if c.isalnum() or c == "_")


def rad_to_deg(value):
    """Degrees of a value (or nested list) in rad; None stays None."""
    if value is None:
        return None
    if isinstance(value, (list, tuple)):
        return [rad_to_deg(v) for v in value]
    try:
        import numpy as np

        if isinstance(value, np.ndarray):
            return np.degrees(value)
    except ImportError:  # pragma: no cover
        pass
    return math.degrees(value)


def suffixed(values: dict, units: dict) -> dict:
    """``values`` with each name given the suffix of its unit in ``units`` (names without a unit unchanged; a name
    that already ends with its suffix is kept); values in rad become degrees."""
    out = {}
    for k, v in values.items():
        unit = units.get(k)
        if unit is None:
            out[k] = v
            continue
        s = suffix(unit)
        if unit == "rad":
            v = rad_to_deg(v)
        out[k if not s or k.endswith(s) else k + s] = v
    return out


#: units of the names in the synthesis summaries (``SynthesisResult.summary``, ``CMCDesign.summary``); values there
#: are already in mm and degrees
SYNTHESIS_UNITS = {
    "point_radius": "mm", "blade_angle": "deg", "point_width": "mm", "edge_radius": "mm", "mean_point": "mm",
    "phi1_mean": "deg", "phi2_mean": "deg", "pinion_k": "1/mm", "gear_k": "1/mm", "semi_axes": "mm",
    "ellipse_angle": "deg", "eta": "deg", "eta_from_principal": "deg", "path_speed": "mm/rad", "m21_prime": "1/rad",
    "approach": "mm",
}

#: transmission-error figures the library gives in rad: reported in arcsec
_TE_RAD = ("control_point_errors_rad", "max_control_point_error_rad", "tol_abs_rad")
_ARCSEC = math.pi / 648000.0


def _arcsec(v):
    if isinstance(v, (list, tuple)):
        return [_arcsec(x) for x in v]
    return None if v is None else float(v) / _ARCSEC


def synthesis_units(d: dict, parent: str | None = None) -> dict:
    """A synthesis summary (nested dict) with the report's unit convention: unit suffixes on every dimensional name,
    TE figures in arcsec, the CMC coefficients as ``a2_per_rad``, ``a3_per_rad2``, ``a4_per_rad3``; no prose
    ``units`` entry."""
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            v = synthesis_units(v, k)
        if k == "units" and isinstance(v, str):
            continue
        if k in _TE_RAD:
            out[k[:-4] + "_arcsec"] = _arcsec(v)
        elif k == "a" and parent == "cmc":
            for i, c in enumerate(v, start=2):
                out[f"a{i}_per_rad" + ("" if i == 2 else str(i - 1))] = c
        else:
            table = MACHINE_SETTING_UNITS if parent in ("pinion_settings", "pinion_settings_final") else \
                SYNTHESIS_UNITS
            unit = table.get(k)
            s = suffix(unit) if unit else ""
            out[k + s if s and not k.endswith(s) else k] = v
    return out
