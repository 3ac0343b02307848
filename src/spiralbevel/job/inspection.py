"""Ease-off maps and CMM measurement grids of a face-milled pair in the main job."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..conventions import Member
from ..errors import ConvergenceError, GeometryError, NoContactError
from ..meshing.kinematics import BevelPairKinematics
from .tca import SIDES


def easeoff_maps(blank, setups, out, plots: bool):
    """Ease-off of the drive and coast pinion flanks against the gear. Returns (report section, files)."""
    from ..meshing.easeoff import easeoff

    kin = BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
    section: dict[str, Any] = {"units": "mm; positive = clearance (material removed from the pinion)"}
    files: list = []
    for name, (s1, s2) in SIDES.items():
        try:
            eo = easeoff(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, kin)
        except (GeometryError, ConvergenceError, NoContactError) as err:
            section[name] = {"error": str(err)}
            continue
        v = eo.values[np.isfinite(eo.values)]
        section[name] = {"min_mm": float(v.min()), "max_mm": float(v.max()),
                         "rms_mm": float(np.sqrt(np.mean(v**2))), "grid": list(eo.values.shape)}
        if plots:
            from .outputs import save_figure

            fig = eo.plot(kind="both", title=f"Ease-off of the pinion {s1.value} flank against the conjugate of "
                                             f"the gear {s2.value} flank ({name} side), µm; + = clearance (material "
                                             "removed from the pinion)")
            files.append(save_figure(fig, out / f"easeoff_{name}.png"))
    return section, files


def measurement_files(setups, out):
    """9 x 5 nominal CMM grids with outward normals, one CSV per flank. Returns (report section, files)."""
    from ..io.measurement_csv import write_measurement_grid
    from ..manufacturing.measurement import measurement_grid

    section, files = {"grid": [9, 5], "deviation_sign": "positive = material added"}, []
    for (m, s), st in setups.items():
        grid = measurement_grid(st.flank)
        name = f"measurement_{m.value}_{s.value}.csv"
        write_measurement_grid(out / name, grid)
        files.append(name)
        section[f"{m.value}_{s.value}"] = name
    return section, files
