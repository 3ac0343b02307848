"""Ease-off maps and CMM measurement grids of a face-milled pair and their report sections."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..conventions import Member
from ..errors import ConvergenceError, GeometryError, NoContactError
from ..meshing.pair import pair_kinematics
from .tca import SIDES


def easeoff_maps(blank, setups, out, plots: bool, return_maps: bool = False):
    """Ease-off of the drive and coast pinion flanks against the gear. Returns (report section, files), and with
    ``return_maps`` also {side: EaseOff or None}."""
    from ..meshing.easeoff import easeoff

    kin = pair_kinematics(blank)
    section: dict[str, Any] = {"sign": "positive = clearance (material removed from the pinion)"}
    files: list = []
    maps: dict[str, Any] = {}
    for name, (s1, s2) in SIDES.items():
        maps[name] = None
        try:
            eo = easeoff(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, kin)
        except (GeometryError, ConvergenceError, NoContactError) as err:
            section[name] = {"error": str(err)}
            continue
        maps[name] = eo
        v = eo.values[np.isfinite(eo.values)]
        section[name] = {"min_mm": float(v.min()), "max_mm": float(v.max()),
                         "rms_mm": float(np.sqrt(np.mean(v**2))), "grid": list(eo.values.shape)}
        if plots:
            from .outputs import save_figure

            fig = eo.plot(kind="both", title=f"Ease-off of the pinion {s1.value} flank against the conjugate of "
                                             f"the gear {s2.value} flank ({name} side), µm; + = clearance (material "
                                             "removed from the pinion)")
            files.append(save_figure(fig, out / f"easeoff_{name}.png"))
    return (section, files, maps) if return_maps else (section, files)


def measurement_grids(setups) -> dict:
    """9 x 5 nominal CMM grids with outward normals of every flank: {(member, side): MeasurementGrid}."""
    from ..manufacturing.measurement import measurement_grid

    return {k: measurement_grid(st.flank) for k, st in setups.items()}


def measurement_files(setups, out):
    """9 x 5 nominal CMM grids with outward normals, one CSV per flank. Returns (report section, files)."""
    from ..io.measurement_csv import write_measurement_grid

    section, files = {"grid": [9, 5], "deviation_sign": "positive = material added"}, []
    for (m, s), grid in measurement_grids(setups).items():
        name = f"measurement_{m.value}_{s.value}.csv"
        write_measurement_grid(out / name, grid)
        files.append(name)
        section[f"{m.value}_{s.value}"] = name
    return section, files
