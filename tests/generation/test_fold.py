"""A flank whose contact region of generation ends inside the blank (the two cutter angles of the equation of meshing
merge there) gives a clear error naming the design-file key, not a bare locate failure."""

import re
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import GeometryError
from spiralbevel.io.design_file import parse_design
from spiralbevel.job import facemilled as fm
from spiralbevel.job.blank import blank_from_design

# a low-spiral-angle design of the robustness bench (11/41, beta 8.1 deg) whose gear convex flank folds on the blade
DESIGN = """
[gear_set]
pinion_teeth = 11
gear_teeth = 41
shaft_angle = 76.6
module = 11.67
face_width = 61.2
normal_pressure_angle = 20
mean_spiral_angle = 8.1
pinion_hand = "RH"
cutter_radius = 235
[flank]
kind = "face-milled"
"""


def test_fold_inside_the_face_is_named():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(DESIGN)
        blank = blank_from_design(spec)
        flank = fm._basic_setups(spec, blank)[(Member.GEAR, Side.CONVEX)].flank
    with pytest.raises(GeometryError) as info:
        flank.grid(9, 5, curvature=False)
    msg = str(info.value)
    assert "gear_set.mean_spiral_angle" in msg and "gear_set.cutter_radius" in msg
    R_fold = float(re.search(r"at R = ([0-9.]+) mm", msg).group(1))
    ol, gen = flank.outline, flank.generator
    assert ol.Ri < R_fold < ol.Re
    # independently: on the blade row u = u_j, the cradle angle where |disc| = 1 (brentq on the closed-form
    # discriminant) maps inside the face, and there the two roots of the equation of meshing coincide
    u = gen.cp["u_j"]
    P = np.linspace(-1.2, 1.2, 241)
    d = gen.axial_radial(np.full_like(P, u), P)[2]
    k = np.nonzero(np.diff(np.sign(np.abs(d) - 1.0)))[0]
    psi = [brentq(lambda p: abs(gen.axial_radial(np.array(u), np.array(p))[2]) - 1.0, P[i], P[i + 1], xtol=1e-13)
           for i in k]
    R = np.array([ol.Rh(*gen.axial_radial(np.array(u), np.array(p))[:2])[0] for p in psi])
    assert np.any((R > ol.Ri) & (R < ol.Re))
