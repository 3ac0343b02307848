"""The fold of generation: where the two cutter angles that solve the equation of meshing merge inside the face (low
spiral angles), the (u, psi_c) chart of the generated flank folds, but the flank itself is regular and really cut.
The (phi, psi_c) chart of the blade generates it through the fold; checked here against the equation of meshing,
numerical tangents and a brute-force test of the cutter's swept material."""


import numpy as np
import pytest

from _blade_sweep import penetration as blade_penetration
from _designs import basic_design, basic_setups

from spiralbevel.conventions import Member, Side

# a low-spiral-angle design of the robustness bench (11/41, beta 8.1 deg) whose gear convex flank folds on the blade
DESIGN = basic_design(11, 41, shaft_angle=76.6, module=11.67, face_width=61.2, mean_spiral_angle=8.1, hand="RH",
                      cutter_radius=235)


@pytest.fixture(scope="module")
def flank():
    _, _, setups = basic_setups(DESIGN)
    return setups[(Member.GEAR, Side.CONVEX)].flank


def test_fold_lies_inside_the_face_and_the_flank_is_generated_through_it(flank):
    g = flank.grid(9, 5, curvature=False)
    gen = flank.generator
    # the fold is inside this face: part of the grid lies on the second root of the equation of meshing at its own
    # (u, psi_c), which the (u, psi_c) chart does not reach
    kernel_root = gen.contact(g.u, g.psi_c)
    phi = g.theta + np.pi - gen.mp["q"] + g.psi_c
    other = np.abs(np.angle(np.exp(1j * (kernel_root["phi"] - phi)))) > 1e-8
    assert 0 < other.sum() < other.size
    # every point is on the equation of meshing (relative velocity from its own code, seed 001 Eq. (13))
    assert np.max(np.abs(flank.meshing_residual(g.u, g.theta, g.psi_c))) < 1e-12
    # and on the blade, from the fillet junction up to the face cone, toe to heel
    ol = flank.outline
    R, h = ol.Rh(g.points[..., 2], np.hypot(g.points[..., 0], g.points[..., 1]))
    assert np.allclose(R[:, 0], np.linspace(ol.Ri, ol.Re, 9), atol=1e-8)
    assert np.allclose(h[:, -1], ol.h_face(R[:, -1]), atol=1e-8)
    assert np.all(g.u >= gen.cp["u_j"] - 1e-12)


def test_flank_is_regular_across_the_fold(flank):
    """Numerical tangents of the (phi, psi_c) chart (central differences) span the tangent plane of the flank normal
    at every grid point, on both roots: no cusp, no singular point where the (u, psi_c) chart folds."""
    g = flank.grid(9, 5, curvature=False)
    gen = flank.generator
    phi = g.theta + np.pi - gen.mp["q"] + g.psi_c
    h = 1e-6

    def pts(dphi, dpsi):
        return gen.evaluate_blade(phi + dphi, g.psi_c + dpsi, curvature=False).points

    t1 = (pts(h, 0) - pts(-h, 0)) / (2 * h)
    t2 = (pts(0, h) - pts(0, -h)) / (2 * h)
    c = np.cross(t1, t2)
    area = np.linalg.norm(c, axis=-1)
    assert np.all(area > 1e-3 * np.linalg.norm(t1, axis=-1) * np.linalg.norm(t2, axis=-1))
    # central differences with h = 1e-6 rad on points of size 1e2 mm: about 1e-8 relative
    assert np.all(np.abs(np.einsum("...i,...i", c / area[..., None], g.normals)) > 1 - 1e-8)


def test_no_point_of_the_flank_is_cut_away(flank):
    """Brute force on the swept material: a point of the true generated flank is touched by the blade at its own
    cradle angle and lies outside the blade's cutting side at every other one. For the straight blade the cutter's
    material side is s (rho_blade(z) - rho) > 0 (rho the distance from the cutter axis at height z); sampled over
    the whole roll, both roots' points stay outside (to round-off), so the part beyond the fold is real flank, not
    undercut or secondary cutting."""
    g = flank.grid(9, 5, curvature=False)
    gen = flank.generator
    psis = np.linspace(g.psi_c.min() - 0.3, g.psi_c.max() + 0.3, 1201)

    def penetration(points):
        return blade_penetration(gen, points, psis).reshape(-1)

    pen = penetration(g.points)
    # the largest penetration is the touch at the generating cradle angle (0 to round-off of 1e2 mm coordinates)
    assert np.all(np.isfinite(pen)) and np.max(pen) < 1e-10
    # the test sees a cut: the same points moved 0.01 mm into the tooth space (along the outward normal) lie in the
    # swept material by about 0.01 mm times the blade's radial normal component
    moved = penetration(g.points + 0.01 * g.normals)
    assert np.all(moved > 0.005)
