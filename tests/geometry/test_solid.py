"""Closed tooth and gear meshes from flank grids (spiralbevel.geometry.solid).

Flank grids come from the closed-form log-spiral kernel (seed 000 Eq. (16), docs/theory/logspiral.md, Eq. (S2)
(#surface)): rho0 = 100 mm, delta = 20°,
beta = 35°; convex flank psi in [0.05, 0.3], phi in [0, 0.3]; the concave flank is the other branch (psi < 0) turned
by Delta about +z. Its outward normal is -n (the docs/theory/logspiral.md, Eqs. (S4), (S9) normal n is outward on the
convex branch; checked below).

Independent reference: in spherical coordinates (rho, theta, alpha) about the apex this tooth is the set
rho0 <= rho <= rho_heel, theta_root <= theta <= theta_face, alpha_convex <= alpha <= alpha_convex + w(psi) with
cos(theta) = cos(psi) cos(delta) and w(psi) = Delta - 2 (psi / sin(delta) - atan(tan(psi) / sin(delta))) (the
azimuth of r(varphi, phi) is varphi - atan(tan(psi)/sin(delta)), the toe/heel are spheres, root/face are cones), so
V = (rho_heel^3 - rho0^3) / 3 * cos(delta) * integral of sin(psi) w(psi) dpsi, a 1-D quadrature.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from spiralbevel._core import logspiral as ls
from spiralbevel._core.rotations import apply, rot_z
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.geometry.solid import GearBody, gear_body_mesh, gear_mesh, tooth_mesh
from spiralbevel.geometry.surface_mesh import TriangleMesh, triangulate_grid

RHO0, DELTA, BETA = 100.0, np.radians(20.0), np.radians(35.0)
PSI, PHI = (0.05, 0.3), (0.0, 0.3)
SD = np.sin(DELTA)


def flank(sign, n, m, delta_rot=0.0):
    """(points, outward normals) of the convex (sign=+1) or concave (sign=-1, turned by delta_rot) flank."""
    psi = sign * np.linspace(*PSI, m)
    phi, psi = np.meshgrid(np.linspace(*PHI, n), psi, indexing="ij")
    g = ls.geometry(phi + psi / SD, phi, RHO0, DELTA, BETA)
    R = rot_z(delta_rot)
    return apply(R, g["r"]), sign * apply(R, g["n"])


def tooth(n=21, m=11, delta_rot=0.35, m_concave=None, n_concave=None):
    return flank(1, n, m), flank(-1, n_concave or n, m_concave or m, delta_rot)


def f(psi):
    return psi / SD - np.arctan(np.tan(psi) / SD)


def analytic_tooth_volume(delta_rot):
    rho_heel = RHO0 * np.exp(PHI[1] * SD / np.tan(BETA))
    integral = quad(lambda p: np.sin(p) * (delta_rot - 2.0 * f(p)), *PSI, epsabs=1e-13, epsrel=1e-13)[0]
    return (rho_heel**3 - RHO0**3) / 3.0 * np.cos(DELTA) * integral


def test_outward_normals_of_the_test_tooth():
    """The material lies at larger azimuth than the convex flank: its outward normal has a negative azimuthal part."""
    (pa, na), (pb, nb) = tooth()
    e_az = np.cross([0.0, 0.0, 1.0], pa)
    assert np.all(np.einsum("...i,...i->...", na, e_az) < 0)
    e_az = np.cross([0.0, 0.0, 1.0], pb)
    assert np.all(np.einsum("...i,...i->...", nb, e_az) > 0)


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    faces = [f for a, b, c, d in quads for f in ((a, b, c), (a, c, d))]
    return TriangleMesh(v, np.array(faces))


def test_mesh_measures_on_a_cube():
    c = cube()
    assert c.is_watertight() and c.euler_characteristic() == 2
    assert c.volume() == pytest.approx(1.0, abs=1e-14) and c.area() == pytest.approx(6.0, abs=1e-14)
    moved = TriangleMesh(c.vertices * [2.0, 3.0, 5.0] + [100.0, -50.0, 7.0], c.faces)
    assert moved.volume() == pytest.approx(30.0, rel=1e-13)
    flipped = TriangleMesh(c.vertices, c.faces[:, ::-1])
    assert flipped.is_watertight() and flipped.volume() == pytest.approx(-1.0, abs=1e-14)
    one_flipped = c.faces.copy()
    one_flipped[0] = one_flipped[0, ::-1]
    assert not TriangleMesh(c.vertices, one_flipped).is_watertight()
    assert not TriangleMesh(c.vertices, c.faces[1:]).is_watertight()


def test_triangulate_grid_follows_the_normals():
    (pa, na), _ = tooth()
    for normals in (na, -na):
        mesh = triangulate_grid(pa, normals)
        fn = mesh.face_normals()
        vn = normals.reshape(-1, 3)[mesh.faces].mean(axis=1)
        assert np.all(np.einsum("ij,ij->i", fn, vn) > 0.99)


def test_tooth_is_closed_and_outward():
    (pa, na), (pb, nb) = tooth()
    mesh = tooth_mesh((pa, na), (pb, nb))
    assert mesh.is_watertight()
    assert mesh.euler_characteristic() == 2
    assert mesh.volume() > 0
    # every face whose corners are all convex-flank nodes points along the given outward normal
    from scipy.spatial import cKDTree

    for pts, nrm in ((pa, na), (pb, nb)):
        dist, node = cKDTree(pts.reshape(-1, 3)).query(mesh.vertices)
        on = dist < 1e-12
        flank_faces = np.all(on[mesh.faces], axis=1)
        vn = nrm.reshape(-1, 3)[node[mesh.faces[flank_faces]]].mean(axis=1)
        assert flank_faces.sum() >= 2 * 20 * 10
        assert np.all(np.einsum("ij,ij->i", mesh.face_normals()[flank_faces], vn) > 0.99)


def test_tooth_without_normals_has_the_same_volume():
    (pa, na), (pb, nb) = tooth()
    with_normals = tooth_mesh((pa, na), (pb, nb))
    without = tooth_mesh(pa, {"points": pb})
    assert without.is_watertight()
    assert without.volume() == pytest.approx(with_normals.volume(), rel=1e-12)


def test_tooth_volume_converges_to_the_quadrature_at_second_order():
    exact = analytic_tooth_volume(0.35)
    errors = []
    for m in (6, 11, 21, 41):
        (pa, na), (pb, nb) = tooth(n=2 * m - 1, m=m)
        errors.append(abs(tooth_mesh((pa, na), (pb, nb)).volume() / exact - 1.0))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios  # O(h^2): halving h divides the error by 4
    assert errors[-1] < 2e-4


def test_pointed_tooth_welds_the_top_edges():
    delta_rot = 2.0 * f(PSI[1])  # zero top land: both top edges coincide
    (pa, na), (pb, nb) = tooth(delta_rot=delta_rot)
    assert np.abs(pa[:, -1] - pb[:, -1]).max() < 1e-12
    mesh = tooth_mesh((pa, na), (pb, nb))
    assert mesh.is_watertight() and mesh.euler_characteristic() == 2
    assert mesh.volume() == pytest.approx(analytic_tooth_volume(delta_rot), rel=3e-3)


def test_flanks_of_different_sizes():
    (pa, na), (pb, nb) = tooth(n=21, m=11, n_concave=15, m_concave=8)
    mesh = tooth_mesh((pa, na), (pb, nb))
    assert mesh.is_watertight() and mesh.euler_characteristic() == 2
    assert mesh.volume() == pytest.approx(analytic_tooth_volume(0.35), rel=3e-3)


def test_inward_normal_on_one_flank_is_refused():
    (pa, na), (pb, nb) = tooth()
    with pytest.raises(GeometryError, match="outward"):
        tooth_mesh((pa, na), (pb, -nb))


@pytest.mark.parametrize("bad, field", [(np.zeros((1, 5, 3)), "convex.points"), (np.zeros((4, 5)), "convex.points"),
                                        (np.full((3, 3, 3), np.nan), "convex.points")])
def test_bad_grids_are_named(bad, field):
    (_, _), (pb, nb) = tooth()
    with pytest.raises(DesignError, match=field):
        tooth_mesh(bad, (pb, nb))


def test_gear_is_closed_ring_and_adds_up():
    z = 12
    a, b = tooth()
    gear, body, one = gear_mesh(a, b, z), gear_body_mesh(a, b, z), tooth_mesh(a, b)
    assert gear.is_watertight() and body.is_watertight()
    assert gear.euler_characteristic() == 0 and body.euler_characteristic() == 0  # genus 1: the bore
    assert gear.volume() > body.volume() > 0
    # the root strips under the teeth are the same triangles in body and tooth: exact up to rounding
    assert gear.volume() == pytest.approx(body.volume() + z * one.volume(), rel=1e-12)


def test_body_volume_converges_to_the_frustum():
    """Default body: flat annuli at the toe and heel root circles, the root cone, a bore prism of n_bore sides.

    Reference: V = integral over z_toe..z_heel of pi ((z tan theta_root)^2 - r_bore^2) dz, minus the polygon defect
    of the bore (n sides inscribed: area n/2 r^2 sin(2 pi / n) instead of pi r^2), both closed forms.
    """
    theta_root = np.arccos(np.cos(PSI[0]) * np.cos(DELTA))
    rho_heel = RHO0 * np.exp(PHI[1] * SD / np.tan(BETA))
    z0, z1 = RHO0 * np.cos(theta_root), rho_heel * np.cos(theta_root)
    t, r_bore, n_bore = np.tan(theta_root), 20.0, 64
    bore_area = 0.5 * n_bore * r_bore**2 * np.sin(2 * np.pi / n_bore)
    exact = np.pi * t**2 * (z1**3 - z0**3) / 3.0 - bore_area * (z1 - z0)
    errors = []
    for m in (6, 11, 21):
        a, b = tooth(n=2 * m - 1, m=m)
        body = gear_body_mesh(a, b, 12, GearBody(bore_radius=r_bore, n_bore=n_bore))
        errors.append(abs(body.volume() / exact - 1.0))
    assert errors[0] / errors[1] > 3.0 and errors[1] / errors[2] > 3.0, errors
    assert errors[-1] < 1e-4


def test_left_hand_gear_mirrors_the_right_hand_one():
    M = np.array([1.0, -1.0, 1.0])
    (pa, na), (pb, nb) = tooth(n=31, m=16)
    rh = gear_mesh((pa, na), (pb, nb), 12)
    lh = gear_mesh((pa * M, na * M), (pb * M, nb * M), 12)
    assert lh.is_watertight() and lh.euler_characteristic() == 0
    # mirrored geometry; only the quad diagonals differ, an O(h^2) triangulation effect
    assert lh.volume() == pytest.approx(rh.volume(), rel=1e-4)


def test_gear_without_root_lands_welds_neighbouring_teeth():
    z = 12
    delta_rot = 2 * np.pi / z + 2.0 * f(PSI[0])  # root edges of neighbouring teeth coincide
    a, b = tooth(delta_rot=delta_rot)
    gear = gear_mesh(a, b, z)
    assert gear.is_watertight() and gear.euler_characteristic() == 0
    body, one = gear_body_mesh(a, b, z), tooth_mesh(a, b)
    assert gear.volume() == pytest.approx(body.volume() + z * one.volume(), rel=1e-12)


def test_gear_with_a_hub_body():
    a, b = tooth()
    gear = gear_mesh(a, b, 9, GearBody(bore_radius=15.0, front_z=60.0, back_z=130.0, n_bore=40))
    assert gear.is_watertight() and gear.euler_characteristic() == 0 and gear.volume() > 0
    assert gear.vertices[:, 2].min() == pytest.approx(60.0) and gear.vertices[:, 2].max() == pytest.approx(130.0)


@pytest.mark.parametrize("kwargs, exc, field", [
    (dict(z=2), DesignError, "z"),
    (dict(z=30), GeometryError, "z"),  # 30 teeth of 0.35 rad root width overlap
    (dict(z=12, body=GearBody(bore_radius=80.0)), DesignError, "body.bore_radius"),
    (dict(z=12, body=GearBody(front_z=200.0)), DesignError, "body.front_z"),
    (dict(z=12, body=GearBody(back_z=0.0)), DesignError, "body.back_z"),
    (dict(z=12, body=GearBody(n_bore=2)), DesignError, "body.n_bore"),
])
def test_gear_input_errors(kwargs, exc, field):
    a, b = tooth(n=5, m=4)
    with pytest.raises(exc, match=field):
        gear_mesh(a, b, **kwargs)


def test_root_slot_width_closed_form():
    """Root edge of the test tooth at psi = 0.05: convex azimuth phi + f(psi), concave phi - f(psi) + Delta (seed 000
    Eq. (16)), so the tooth space at the root spans 2 pi / z - (Delta - 2 f(psi)) radians, on the root circle of the
    leading (concave) edge; negative when the teeth overlap."""
    from spiralbevel.geometry.solid import root_slot_width

    (pa, _), (pb, _) = tooth(n=9, m=5)
    r = np.hypot(pb[:, 0, 0], pb[:, 0, 1])
    for z in (12, 17, 30):
        expected = (2.0 * np.pi / z - (0.35 - 2.0 * f(PSI[0]))) * r
        assert np.allclose(root_slot_width(pa, pb, z), expected, rtol=0, atol=1e-12)
    assert np.all(root_slot_width(pa, pb, 30) < 0)  # 30 teeth of 0.3 rad at the root cannot fit
    with pytest.raises(DesignError, match="z"):
        root_slot_width(pa, pb, 0)


def test_open_edges_check_is_the_full_orientation_check():
    """``MeshBuilder.add_patch(..., open_edges=...)`` (used for the copies of a gear's sector) checks only a patch's
    open boundary: it must accept and refuse exactly what the check of every edge does. Reference: the full check on
    the same patches; and the open boundary of an n x m grid patch is its perimeter, 2 (n - 1) + 2 (m - 1) edges."""
    from spiralbevel.geometry.surface_mesh import MeshBuilder, OrientationError, grid_faces, open_edges

    n, m = 5, 4
    idx = np.arange(n * m).reshape(n, m)
    faces = grid_faces(idx)
    rim = open_edges(faces)
    assert len(rim) == 2 * (n - 1) + 2 * (m - 1)
    undirected = {tuple(sorted(e)) for e in rim.tolist()}
    perimeter = {tuple(sorted(e)) for e in zip(idx[0, :-1], idx[0, 1:])} | \
        {tuple(sorted(e)) for e in zip(idx[-1, :-1], idx[-1, 1:])} | \
        {tuple(sorted(e)) for e in zip(idx[:-1, 0], idx[1:, 0])} | \
        {tuple(sorted(e)) for e in zip(idx[:-1, -1], idx[1:, -1])}
    assert undirected == perimeter
    # a neighbouring patch on the next grid rows, sharing the last row of the first: accepted when it continues the
    # orientation, refused when it is flipped, by both checks
    nxt = grid_faces(np.arange((n - 1) * m, (2 * n - 1) * m).reshape(n, m))
    for flipped in (False, True):
        second = nxt[:, ::-1] if flipped else nxt
        verdicts = []
        for use_open in (False, True):
            b = MeshBuilder()
            b.add_vertices(np.zeros(((2 * n - 1) * m, 3)))
            b.add_patch(faces, fixed=True, open_edges=rim if use_open else None)
            try:
                b.add_patch(second, fixed=True, open_edges=open_edges(second) if use_open else None)
                verdicts.append("accepted")
            except OrientationError:
                verdicts.append("refused")
        assert verdicts == (["refused", "refused"] if flipped else ["accepted", "accepted"])
