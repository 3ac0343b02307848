"""Contact lines in the sheared zone of action of a hypoid pair's virtual gear, checked by plain plane geometry: the
parallelogram (tip and root boundaries inclined at gamma to the face) sampled and intersected numerically,
independent of the closed forms in rating/contact_lines.py."""

import math

import numpy as np
import pytest

from spiralbevel.rating.contact_lines import contact_line_layout, contact_line_length

# the virtual gear of ISO/TR 10300-30 Sample 2 (hypoid), rounded; gamma from the offset angles of its blank
V = {"g_valpha": 10.435, "b_veff": 24.88, "b_v": 29.271, "beta_vb": math.radians(41.0), "p_vet": 10.329,
     "eps_valpha": 1.010, "eps_vbeta": 2.096, "gamma": math.radians(4.68)}


# x across the face from the centre, y along the path: the tip (+) and root (-) boundaries y = +-g/2 + x tan(gamma);
# the contact lines y = -x tan(beta_vb) + c fall across the face where the boundaries rise (ISO 10300-1's sense,
# tan(gamma) + tan(beta_vb) in its formulas)
T = np.array([math.cos(V["beta_vb"]), -math.sin(V["beta_vb"])])   # direction of the contact lines
N = np.array([math.sin(V["beta_vb"]), math.cos(V["beta_vb"])])    # their unit normal


def _boundary(x, sign):
    return sign * V["g_valpha"] / 2 + x * math.tan(V["gamma"])


def test_f_max_is_the_farthest_point_of_the_sheared_zone():
    x, s = np.meshgrid(np.linspace(-V["b_veff"] / 2, V["b_veff"] / 2, 401), np.linspace(-1.0, 1.0, 401))
    y = s * V["g_valpha"] / 2 + x * math.tan(V["gamma"])
    # the lines x n_x + y n_y = f: the zone reaches |f| = f_max, at a corner contained in the grid
    dist = np.abs(x * N[0] + y * N[1])
    assert contact_line_layout(V)["f_max"] == pytest.approx(dist.max(), rel=1e-12)


def test_unshortened_line_spans_the_sheared_zone():
    # l_b0 (C_lb -> 0 when b_veff = b_v): the line through the centre at beta_vb, between the two inclined
    # boundaries, found by bisection on each boundary independently of the closed form
    v = dict(V, b_v=V["b_veff"])

    def crossing(sign):
        lo, hi = -100.0, 100.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if (mid * T[1] - _boundary(mid * T[0], sign)) < 0.0:
                hi = mid
            else:
                lo = mid
        return 0.5 * (lo + hi)

    expected = abs(crossing(+1) - crossing(-1))
    assert contact_line_length(0.0, v, contact_line_layout(v)["f_max"]) == pytest.approx(expected, rel=1e-12)
    # the shear shortens the line against the rectangle's g/sin(beta_vb)
    assert expected < V["g_valpha"] / math.sin(V["beta_vb"])


def test_zero_gamma_is_the_spiral_bevel_zone():
    v0 = {k: x for k, x in V.items() if k != "gamma"}
    lay0, lay = contact_line_layout(v0), contact_line_layout(dict(V, gamma=0.0))
    assert lay == lay0
    assert contact_line_length(2.0, dict(V, gamma=0.0), lay["f_max"]) == contact_line_length(2.0, v0, lay0["f_max"])
