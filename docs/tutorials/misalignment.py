"""Tutorial: sensitivity of a face-milled pair to misalignment (TE level and shift of the contact).

Run it as a script: ``python docs/tutorials/misalignment.py``. The CLI does the same with
``spiralbevel sweep aviation_23x65_synthesized --gear-axial -0.05:0.05:3``. The test suite runs it.
"""

import sys

from spiralbevel import load_design
from spiralbevel.io.design_file import bundled_designs
from spiralbevel.job.sweep import misalignment_sweep


def main(values=(-0.05, 0.0, 0.05), scheduler="sequential", n_positions=21) -> list:
    # --8<-- [start:sweep]
    # The synthesized aviation pair (pinion by local synthesis), drive side. Misalignments in the pair frame
    # (docs/conventions.md): axial displacements of pinion and gear, offset (mm), shaft-angle error (deg).
    spec = load_design(bundled_designs()["aviation_23x65_synthesized"])
    records = misalignment_sweep(spec, {"gear_axial": list(values)}, side="drive", scheduler=scheduler,
                                 n_positions=n_positions)
    print(f"{'gear axial (mm)':>16} {'TE p-p (arcsec)':>16} {'mean contact R (mm)':>20} {'h (mm)':>8}")
    for rec in records:
        print(f"{rec['gear_axial']:16.3f} {rec['peak_to_peak_arcsec']:16.2f} {rec['mean_contact_R_mm']:20.3f} "
              f"{rec['mean_contact_h_mm']:8.3f}")
    # --8<-- [end:sweep]
    return records


if __name__ == "__main__":
    # dask's local processes when dask is installed (extra 'dist'); 'sequential' runs in this process
    main(scheduler=sys.argv[1] if len(sys.argv) > 1 else None)
