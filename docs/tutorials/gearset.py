"""Tutorial: one GearSet object, from basic data to contact analysis, with result objects.

Run it as a script: ``python docs/tutorials/gearset.py OUT``. The test suite runs it (tests/docs/test_tutorials.py)
and checks what it computes.
"""

import sys
from pathlib import Path

import spiralbevel as sb


def main(out: Path) -> dict:
    """Run the tutorial, writing its figures into ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    # --8<-- [start:build]
    # 1. Basic data of the aviation set of Liu, Chen and Li (2024), Table 1 (degrees and mm, as in a design file).
    #    The face-milled pair is assembled once: ISO 23509 blank, default cutters, basic machine settings solved for
    #    the design angles, and the pinion developed by local synthesis on both sides.
    gs = sb.GearSet.from_basic_data(pinion_teeth=23, gear_teeth=65, module=3.9, face_width=37.0,
                                    mean_spiral_angle=30.0, normal_pressure_angle=20.0, pinion_hand="RH",
                                    title="Aviation set 23/65 from basic data")
    print(gs)
    # --8<-- [end:build]

    # --8<-- [start:machine]
    # 2. Machine summary: cutters and settings of the four flanks, and the achieved mean-point angles.
    machine = gs.machine_summary()
    for label, value, unit in machine.rows("gear", "convex")[1:4]:
        print(f"gear convex  {label}: {value} {unit}")
    flanks = machine.to_dict()["flanks"]
    print(f"gear convex mean spiral angle {flanks['gear']['convex']['spiral_angle_deg']:.4f} deg, "
          f"pressure angle {flanks['gear']['convex']['pressure_angle_deg']:.4f} deg")
    # --8<-- [end:machine]

    # --8<-- [start:tca]
    # 3. TCA of the drive side: a result object in arcsec and degrees; .plot() returns a matplotlib Figure.
    drive = gs.tca("drive", positions=21)            # 21 pinion positions over one mesh cycle
    print(drive)
    drive.plot().savefig(out / "gearset_tca_drive.png", dpi=80)
    # the same under a misalignment given in mm and degrees
    tilted = gs.tca("drive", misalignment={"shaft_angle": 0.05}, positions=21)
    print(f"TE peak to peak {drive.peak_to_peak_arcsec:.2f} arcsec aligned, "
          f"{tilted.peak_to_peak_arcsec:.2f} arcsec with the shaft angle 0.05 deg larger")
    # --8<-- [end:tca]

    # --8<-- [start:more]
    # 4. The main job's misalignment study and the ease-off; to_dict() is the matching report.json section.
    sensitivity = gs.sensitivity(positions=21)
    print(sensitivity)
    easeoff = gs.easeoff()
    print(easeoff)
    easeoff.plot("drive").savefig(out / "gearset_easeoff_drive.png", dpi=80)
    # --8<-- [end:more]
    return {"gearset": gs, "machine": machine, "drive": drive, "tilted": tilted, "sensitivity": sensitivity,
            "easeoff": easeoff}


if __name__ == "__main__":
    import warnings

    warnings.simplefilter("ignore")   # the design checks print their warnings in the results
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("tutorial_out"))
