"""Mismatched log-spiral pair: TCA against the targets and misalignment sensitivity beside the line-contact pair.

Prints the figures of the README section "Log-spiral gears for production" for a bundled design (default: the
default pair, aviation_23x65_logspiral, crowned with a = 6 mm, eta = 20 deg, 8 arcsec; the forged example uses its
own [crowning] and forging relief).

    python examples/logspiral_mismatch.py [aviation_23x65_logspiral | aviation_23x65_logspiral_forged]
"""

import math
import sys

import numpy as np

from spiralbevel.conventions import Member, Side
from spiralbevel.io.design_file import bundled_designs, load_design
from spiralbevel.io.design_schema import CrowningSpec
from spiralbevel.job import logspiral_production as lp
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.logspiral import design_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.synthesis.logspiral_sensitivity import misalignment_sensitivity
from spiralbevel.meshing.synthesis.mean_contact import path_reference
from spiralbevel.meshing.tca import solve_tca

ARCSEC = math.pi / (180 * 3600)

name = sys.argv[1] if len(sys.argv) > 1 else "aviation_23x65_logspiral"
spec = load_design(bundled_designs()[name])
if spec.crowning is None:
    spec = spec.model_copy(update={"crowning": CrowningSpec()})
pair = design_pair(spec, blank_from_design(spec))
cr = lp.design_crowning(spec, pair)
reliefs = lp.design_reliefs(spec, pair, cr) if spec.manufacturing.forging_relief else None
kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
c1 = lp.contact_surface(pair, Member.PINION, Side.CONVEX, cr, reliefs)
c0 = lp.contact_surface(pair, Member.PINION, Side.CONVEX)
c2 = lp.contact_surface(pair, Member.GEAR, Side.CONCAVE, None, reliefs)
p1 = pair.mean_point(Member.PINION, Side.CONVEX).point
phi1m = -math.atan2(p1[1], p1[0])
start = np.r_[c1.reference_params, c2.reference_params, -kin.ratio * phi1m]
res = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=21, start=start)
c = spec.crowning
level = -float(np.nanmin(res.te))
r = res.point1[np.arange(21), res.pair]
t_p, t_l = path_reference(r[10], res.normal1[10, res.pair[10]], (0.0, 0.0, 1.0), pair.pinion.pitch_angle)
d = r[11] - r[9]
eta = (math.degrees(math.atan2(d @ t_l, d @ t_p)) + 90.0) % 180.0 - 90.0  # a direction, not an orientation
print(f"{name}: TE level {level / ARCSEC:.3f} arcsec (target {c.te_level}, {level / (c.te_level * ARCSEC) - 1:+.2%}),"
      f" a = {np.max(res.semi_axes[10]):.6f} mm (target {c.semi_major_axis}), eta = {eta:.3f} deg (target "
      f"{c.path_direction}), statuses {sorted(set(res.status.tolist()))} (0 = point contact inside)")
m = c.misalignment
mis = {"pinion_axial": Misalignment(pinion_axial=m.pinion_axial), "gear_axial": Misalignment(gear_axial=m.gear_axial),
       "offset": Misalignment(offset=m.offset), "shaft_angle": Misalignment(shaft_angle=math.radians(m.shaft_angle))}
study = misalignment_sensitivity(c0, c1, c2, kin, phi1_mean=phi1m, phi2_mean=res.phi2_mean, drive_sign=res.drive_sign,
                                 misalignments=mis)
print(f"first touch vs surface TCA, aligned: {np.nanmax(np.abs(study.aligned_mismatched_te - res.te)) / ARCSEC:.4f}"
      " arcsec")
for row in study.rows:
    rm = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=21, start=start, misalignment=mis[row.name])
    print(f"{row.name:13s} TE growth: line {row.line_growth / ARCSEC:+.4f}  mismatched "
          f"{row.mismatched_growth / ARCSEC:+.4f} arcsec  "
          f"(mismatched ptp: first touch {row.mismatched_ptp / ARCSEC:.3f},"
          f" surface TCA {rm.peak_to_peak / ARCSEC:.3f})")
