"""Contact lines in the zone of action of the virtual gear, checked by plain plane geometry: the rectangle
g_valpha x b_veff sampled and intersected numerically, independent of the closed forms in rating/contact_lines.py."""

import math

import numpy as np
import pytest

from spiralbevel.rating.contact_lines import contact_line_layout, contact_line_length
from spiralbevel.rating.pitting import load_sharing_factor
from spiralbevel.rating.root import bevel_spiral_angle_factor

# the virtual gear of ISO/TR 10300-30 Sample 1, rounded
V = {"g_valpha": 13.12, "b_veff": 21.59, "b_v": 25.4, "beta_vb": math.radians(32.615), "p_vet": 11.262,
     "eps_valpha": 1.165, "eps_vbeta": 1.227}


def _unit_normal(beta):
    # zone of action: x across the face (b), y along the transverse path (g); lines run at beta to the x axis
    return np.array([-math.sin(beta), math.cos(beta)])


def test_f_max_is_the_farthest_point_of_the_zone_of_action():
    n = _unit_normal(V["beta_vb"])
    x, y = np.meshgrid(np.linspace(-V["b_veff"] / 2, V["b_veff"] / 2, 401),
                       np.linspace(-V["g_valpha"] / 2, V["g_valpha"] / 2, 401))
    dist = np.abs(x * n[0] + y * n[1])
    # the grid contains the corners, where the maximum lies: agreement to rounding
    assert contact_line_layout(V)["f_max"] == pytest.approx(dist.max(), rel=1e-12)


def test_neighbouring_lines_one_base_pitch_apart_along_the_path():
    lay = contact_line_layout(V)
    n = _unit_normal(V["beta_vb"])
    # moving one transverse base pitch along the path (y) changes the normal distance by p_vet * n_y
    assert lay["f_t"] - lay["f_m"] == pytest.approx(V["p_vet"] * n[1], rel=1e-12)
    assert lay["f_m"] - lay["f_r"] == pytest.approx(V["p_vet"] * n[1], rel=1e-12)


def test_unshortened_line_spans_tip_to_root_of_the_zone():
    # l_b0: the line through the centre, between the boundaries y = -g/2 and y = +g/2 (C_lb -> 0 when b_veff = b_v)
    v = dict(V, b_v=V["b_veff"])
    lay = contact_line_layout(v)
    t = np.array([math.cos(V["beta_vb"]), math.sin(V["beta_vb"])])
    s_hi, s_lo = (V["g_valpha"] / 2) / t[1], (-V["g_valpha"] / 2) / t[1]
    assert contact_line_length(0.0, v, lay["f_max"]) == pytest.approx(s_hi - s_lo, rel=1e-12)


def test_lines_vanish_at_the_corner_and_shrink_monotonically():
    lay = contact_line_layout(V)
    f = np.linspace(0.0, lay["f_max"], 50)
    lengths = [contact_line_length(x, V, lay["f_max"]) for x in f]
    assert lengths[-1] == pytest.approx(0.0, abs=1e-12)
    assert all(a > b for a, b in zip(lengths[:-1], lengths[1:]))


def test_load_sharing_limits():
    lay = contact_line_layout(V)
    v = dict(V, **lay)
    for key in ("m", "t", "r"):
        v[f"l_b{key}"] = contact_line_length(lay[f"f_{key}"], V, lay["f_max"])
    low, high = load_sharing_factor(v, "low")["Z_LS"], load_sharing_factor(v, "high")["Z_LS"]
    # a sharper peak-load fall-off (high crowning) leaves more load on the middle line
    assert 0.0 < low < high < 1.0
    # neighbours beyond the zone of action carry nothing: the middle line takes all the load
    far = dict(v, f_t=2 * lay["f_max"], f_r=-2 * lay["f_max"])
    assert load_sharing_factor(far)["Z_LS"] == 1.0


def test_bevel_spiral_angle_factor_minimum_is_one():
    # Y_BS = 1 exactly where the projected contact line is 1.05 b_BS of the developed face width, above 1 elsewhere
    v = {"b_v": 25.4, "beta_v": math.radians(35.0), "beta_vb": math.radians(32.615), "l_bm": 22.442}
    ref = bevel_spiral_angle_factor(v, 7.23, 7.23)
    l_at_min = 1.05 * ref["b_BS"] * ref["b_a"] * math.cos(v["beta_v"]) / math.cos(v["beta_vb"])
    assert bevel_spiral_angle_factor(dict(v, l_bm=l_at_min), 7.23, 7.23)["Y_BS"] == pytest.approx(1.0, abs=1e-14)
    assert bevel_spiral_angle_factor(dict(v, l_bm=0.8 * l_at_min), 7.23, 7.23)["Y_BS"] > 1.0
    assert bevel_spiral_angle_factor(dict(v, beta_v=0.0), 7.23, 7.23)["Y_BS"] == 1.0
