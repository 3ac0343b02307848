"""Tutorial: from basic data to TCA, loaded TCA and a STEP file, with the public Python API.

Run it as a script: ``python docs/tutorials/basic_data.py OUT`` (STEP needs the ``cad`` extra).
The test suite runs it (tests/docs/test_tutorials.py) and checks what it prints.
"""

import math
import sys
from pathlib import Path

import numpy as np

import spiralbevel as sb
from spiralbevel import Member, Side

ARCSEC = math.pi / 648000.0  # rad per arcsecond


def main(out: Path, n_positions: int = 21, cache_dir=None) -> dict:
    """Run the tutorial, writing into ``out``; ``cache_dir`` holds the FE cache (default: the user cache)."""
    # --8<-- [start:blank]
    # 1. Basic data (the aviation set of Liu, Chen and Li 2024, Table 1) -> ISO 23509 blank. Inside: mm and rad.
    r = math.radians
    blank = sb.compute_blank(sb.BlankInput(
        z1=23, z2=65, met=3.9, b=37.0, beta_m=r(30.0), rc0=114.3, hand1=sb.Hand.RIGHT,
        alpha_dD=r(20.0), alpha_dC=r(20.0), taper="given",
        theta_f1=r(1 + 5 / 60 + 50 / 3600), theta_f2=r(2 + 29 / 60 + 20 / 3600)))
    print(f"pitch angles {math.degrees(blank.delta1):.4f} / {math.degrees(blank.delta2):.4f} deg, "
          f"Rm {blank.Rm:.4f} mm")
    # --8<-- [end:blank]

    # --8<-- [start:gear]
    # 2. Gear convex flank: a head cutter on the inner blade, basic machine settings from the blank
    #    (crown-gear generation), and the generated flank.
    gear_cutter = sb.HeadCutter(point_radius=114.3 - 2.29 / 2, blade_angle=r(22.5), point_width=2.29,
                                edge_radius=1.31, blade=sb.Blade.INNER)
    gear_settings = sb.MachineSettings.from_blank(blank, Member.GEAR, Side.CONVEX, gear_cutter)
    gear = sb.generate_flank(gear_cutter, gear_settings, blank, Member.GEAR, Side.CONVEX)
    print(f"gear settings: S_r {gear_settings.radial_setting:.3f} mm, "
          f"q {math.degrees(gear_settings.cradle_angle):.4f} deg, ratio of roll {gear_settings.ratio_of_roll:.4f}")
    # --8<-- [end:gear]

    # --8<-- [start:synthesis]
    # 3. Pinion concave flank by local synthesis: path direction 6 deg, ellipse 3.7 mm, 3 arcsec parabolic TE.
    syn = sb.synthesize_pinion(gear_cutter, gear_settings, blank, side=Side.CONCAVE, eta=r(6.0),
                               semi_major_axis=3.7, te_magnitude=3.0 * ARCSEC)
    print(f"synthesized ellipse semi-major axis {syn.semi_axes[0]:.3f} mm")
    # --8<-- [end:synthesis]

    # --8<-- [start:tca]
    # 4. TCA of the drive side. Each flank is turned about its axis so that its mean point lies on the pitch line
    #    at zero roll (docs/conventions.md, gear-pair frame): the pinion's at azimuth 0, the gear's at azimuth pi.
    def phased(flank, azimuth):
        p = flank.mean_point().point
        return sb.GeneratedSurface(flank, azimuth - math.atan2(p[1], p[0]))

    pinion_surface, gear_surface = phased(syn.pinion_flank, 0.0), phased(gear, math.pi)
    kin = sb.BevelPairKinematics(shaft_angle=blank.Sigma, z1=blank.z1, z2=blank.z2)
    tca = sb.solve_tca(pinion_surface, gear_surface, kin, n_positions=n_positions,
                       start=np.r_[pinion_surface.reference_params, gear_surface.reference_params, 0.0])
    te = tca.te_arcsec   # TE of the pair in contact at each position, arcsec (NaN: no contact)
    print(f"unloaded TE peak to peak {np.nanmax(te) - np.nanmin(te):.2f} arcsec")
    # --8<-- [end:tca]

    # --8<-- [start:tooth]
    # 5. Whole teeth. Each member's other flank comes from a cutter on the other blade with basic settings from the
    #    blank; it is turned about the member axis so that the tooth has the mean normal thickness smn at the mean
    #    point (transverse angle smn / cos(beta_m) / r_m), on the side away from the convex outward normal.
    def other_flank(member, side, blade):
        cutter = sb.HeadCutter(point_radius=114.3 + blade.sign * 2.29 / 2, blade_angle=r(22.5), point_width=2.29,
                               edge_radius=1.31, blade=blade)
        settings = sb.MachineSettings.from_blank(blank, member, side, cutter)
        return sb.generate_flank(cutter, settings, blank, member, side)

    def rot_z(angle):
        c, s = math.cos(angle), math.sin(angle)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def concave_turn(convex, concave, smn, beta_m):
        """Rotation (rad about +z) of the concave flank that closes one tooth with the convex flank."""
        mc, mk = convex.mean_point(), concave.mean_point()
        r_m = math.hypot(mc.point[0], mc.point[1])
        away = -np.sign(mc.normal @ np.array([-mc.point[1], mc.point[0], 0.0]))   # material side of the convex flank
        return (math.atan2(mc.point[1], mc.point[0]) + away * smn / math.cos(beta_m) / r_m
                - math.atan2(mk.point[1], mk.point[0]))

    pinion_convex = other_flank(Member.PINION, Side.CONVEX, sb.Blade.INNER)
    gear_concave = other_flank(Member.GEAR, Side.CONCAVE, sb.Blade.OUTER)
    turn1 = concave_turn(pinion_convex, syn.pinion_flank, blank.smn1, blank.beta_m1)
    turn2 = concave_turn(gear, gear_concave, blank.smn2, blank.beta_m2)
    grid = lambda flank: flank.grid(9, 5, curvature=False).points   # noqa: E731  (face x profile)
    # (convex, concave) grids of one tooth in the frames of the TCA surfaces (their phasing rotation applied)
    rot1, rot2 = pinion_surface.rotation, gear_surface.rotation
    pinion_tooth = (grid(pinion_convex) @ rot_z(rot1 - turn1).T, grid(syn.pinion_flank) @ rot_z(rot1).T)
    gear_tooth = (grid(gear) @ rot_z(rot2).T, grid(gear_concave) @ rot_z(rot2 + turn2).T)
    # --8<-- [end:tooth]

    # --8<-- [start:ltca]
    # 6. Loaded TCA at 50 N m gear torque: finite-element compliance of three-tooth segments (linear elements here to
    #    keep it quick; cached on disk) plus the contact flattening.
    from spiralbevel.meshing.ltca.from_tca import loaded_tca

    loaded = None
    try:
        loaded = loaded_tca(pinion_surface, gear_surface, kin, tca, 50e3, pinion_grids=pinion_tooth,  # torque N mm
                            gear_grids=gear_tooth, fe_options={"order": 1}, cache_dir=cache_dir)
    except sb.MissingDependencyError:
        print("loaded TCA skipped: pip install 'spiralbevel[fem]'")
    else:
        m = len(loaded.te_loaded) // 2   # the mean contact position
        print(f"at the mean contact position: TE {loaded.te_unloaded[m]:.2f} arcsec unloaded, "
              f"{loaded.te_loaded[m]:.2f} arcsec loaded, peak contact pressure {loaded.max_pressure[m]:.0f} N/mm^2")
    # --8<-- [end:ltca]

    # --8<-- [start:step]
    # 7. STEP: one gear tooth with exact B-spline flanks and a sewn solid (needs the 'cad' extra).
    written = None
    try:
        from spiralbevel.io.step import write_step

        written = write_step(Path(out) / "gear_tooth.step", *gear_tooth, solid=True)
        print(f"STEP written: {written.path.name}, {written.n_faces} faces, solid {written.solid_volume:.0f} mm^3")
    except (ImportError, sb.MissingDependencyError):
        print("STEP skipped: pip install 'spiralbevel[cad]'")
    # --8<-- [end:step]
    return {"blank": blank, "gear_settings": gear_settings, "synthesis": syn, "tca": tca, "ltca": loaded,
            "gear_tooth": gear_tooth, "step": written}


if __name__ == "__main__":
    out_dir = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    out_dir.mkdir(parents=True, exist_ok=True)
    main(out_dir)
