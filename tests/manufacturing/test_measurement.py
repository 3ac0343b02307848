"""CMM measurement grids, simulated measurements and their CSV files."""

import numpy as np
import pytest
from scipy.optimize import brentq

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.design.logspiral_pair import BlankBoundaries, design_logspiral_pair
from spiralbevel.errors import DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.io.measurement_csv import read_measured_deviation, write_measurement_grid
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.manufacturing.measurement import (measure_deviation, measurement_grid,
                                                   measurement_grid_logspiral)

D = np.radians
KEYS = [(Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)]


@pytest.fixture(scope="module")
def flanks():
    b, table = seed001_blank(), seed001_settings()
    return {k: generate_flank(*table[k], b, *k) for k in KEYS}


@pytest.fixture(scope="module")
def logspiral():
    z1, z2, S, an, bm = 23, 65, D(90), D(20), D(35)
    g1 = np.arctan2(np.sin(S), z2 / z1 + np.cos(S))
    m, at = 2 * 100.0 * np.sin(g1) / z1, np.arctan(np.tan(an) / np.cos(bm))
    bounds = []
    for g in (g1, S - g1):
        d = np.arcsin(np.sin(g) * np.cos(at))
        bounds.append(BlankBoundaries(85.0, 115.0, max(g - 1.1 * m / 100, d + D(0.15)), g + m / 100))
    return design_logspiral_pair(z1, z2, S, an, bm, Hand.RIGHT, tuple(bounds))


def _Rh(delta, p):
    rho, z = np.hypot(p[..., 0], p[..., 1]), p[..., 2]
    return rho * np.sin(delta) + z * np.cos(delta), rho * np.cos(delta) - z * np.sin(delta)


@pytest.mark.parametrize("key", KEYS)
def test_grid_layout_on_generated_flank(flanks, key):
    f = flanks[key]
    g = measurement_grid(f)
    ol = f.outline
    assert g.shape == (9, 5) and g.size == 45 and g.member is key[0] and g.side is key[1]
    assert g.labels[0, 0] == "F1P1" and g.labels[4, 2] == "F5P3" and g.labels[-1, -1] == "F9P5"
    assert g.index_of("f5p3") == (4, 2) and g.row[8, 0] == 9 and g.column[0, 4] == 5
    # R and h recomputed from the located points (independent of the stored targets)
    R, h = _Rh(ol.delta, g.points)
    b = ol.Re - ol.Ri
    np.testing.assert_allclose(R, np.linspace(ol.Ri + 0.1 * b, ol.Re - 0.1 * b, 9)[:, None] * np.ones(5), atol=1e-8)
    np.testing.assert_allclose(h, g.h, atol=1e-8)
    np.testing.assert_allclose(np.diff(h, 2, axis=1), 0.0, atol=1e-9)  # even in height
    # top: the last column sits 10 % of the active depth below the face cone; lower limit: the junction line u = u_j,
    # found here per station by a scalar root solve on the generated surface (second method)
    h_low = g.h[:, 0] - (g.h[:, -1] - g.h[:, 0]) * 0.1 / 0.8
    h_top = g.h[:, -1] + (g.h[:, -1] - g.h[:, 0]) * 0.1 / 0.8
    np.testing.assert_allclose(h_top, ol.h_face(R[:, 0]), atol=1e-9)
    uj = f.cutter.fillet_range[1]
    for i in (0, 4, 8):
        def dR(psi, i=i):
            p = f.evaluate(uj, psi, curvature=False).points
            return _Rh(ol.delta, p)[0] - R[i, 0]
        psi = brentq(dR, g.v[i, 0] - 0.05, g.v[i, 0] + 0.05, xtol=1e-14)
        hj = _Rh(ol.delta, f.evaluate(uj, psi, curvature=False).points)[1]
        assert abs(hj - h_low[i]) < 1e-6  # cubic-spline interpolation of the junction line, 41 stations
    assert np.all(g.u > uj)  # every point on the blade, none on the fillet
    # unit normals perpendicular to the surface tangents (finite differences on the generating parameters)
    np.testing.assert_allclose(np.linalg.norm(g.normals, axis=-1), 1.0, atol=1e-12)
    e = 1e-5
    for du, dp in ((e, 0.0), (0.0, e)):
        t = (f.evaluate(g.u + du, g.v + dp, curvature=False).points
             - f.evaluate(g.u - du, g.v - dp, curvature=False).points)
        t /= np.linalg.norm(t, axis=-1, keepdims=True)
        assert np.max(np.abs(np.einsum("...i,...i", t, g.normals))) < 1e-7


def test_logspiral_grid_closed_form(logspiral):
    fl = logspiral.flank(Member.PINION, Side.CONCAVE)
    gamma = logspiral.pinion.pitch_angle
    g = measurement_grid_logspiral(fl, 7, 4, 0.1, 0.2, pitch_angle=gamma)
    rho = np.linalg.norm(g.points, axis=-1)
    nu = np.arctan2(np.hypot(g.points[..., 0], g.points[..., 1]), g.points[..., 2])
    np.testing.assert_allclose(rho, np.linspace(88.0, 112.0, 7)[:, None] * np.ones(4), atol=1e-9)  # 85..115, 10 %
    b = fl.domain  # root and face cone angles: cos nu = cos psi cos delta (docs/theory/logspiral.md, Eq. (S10))
    d = fl.surface.base_cone_angle
    nu_root, nu_face = sorted(np.arccos(np.cos([b.psi_min, b.psi_max]) * np.cos(d)))
    np.testing.assert_allclose(nu, np.ones((7, 1)) * (nu_root + (nu_face - nu_root) * np.linspace(0.2, 0.8, 4)),
                               atol=1e-12)
    R, h = _Rh(gamma, g.points)
    np.testing.assert_allclose(R, g.R, atol=1e-9)
    np.testing.assert_allclose(h, g.h, atol=1e-9)
    assert g.member is Member.PINION and g.side is Side.CONCAVE


def test_bad_grid_input(flanks, logspiral):
    f = flanks[KEYS[0]]
    for kw in (dict(n_face=1), dict(n_profile=2.5), dict(face_margin=0.5), dict(profile_margin=-0.1)):
        with pytest.raises(DesignError):
            measurement_grid(f, **kw)
    with pytest.raises(DesignError, match="flank"):
        measurement_grid(logspiral.flank(Member.GEAR, Side.CONVEX))
    with pytest.raises(DesignError, match="flank"):
        measurement_grid_logspiral(f)
    with pytest.raises(DesignError, match="label"):
        measurement_grid(f).index_of("F10P1")


def test_measure_deviation_sign_and_offset(logspiral):
    """An offset surface p + c n (material added for c > 0) measures exactly +c along the nominal normal."""
    fl = logspiral.flank(Member.GEAR, Side.CONVEX)
    g = measurement_grid_logspiral(fl)
    np.testing.assert_allclose(measure_deviation(fl, g), 0.0, atol=1e-12)
    dom = fl.domain
    box = ((dom.to_varphi(dom.psi_min, dom.phi_min) - 0.2, dom.to_varphi(dom.psi_max, dom.phi_max) + 0.2),
           (dom.phi_min - 0.05, dom.phi_max + 0.05))
    for c in (0.02, -0.015):
        def offset(u, v, c=c):
            geo = fl.evaluate(u, v)
            return geo.point + c * geo.normal, geo.normal
        np.testing.assert_allclose(measure_deviation(offset, g, bounds=box), c, atol=1e-10)


def test_measure_deviation_converges(flanks):
    c, s = seed001_settings()[KEYS[1]]
    f = flanks[KEYS[1]]
    g = measurement_grid(f)
    np.testing.assert_allclose(measure_deviation(f, g), 0.0, atol=1e-10)
    moved = generate_flank(c, s.replace(radial_setting=s.radial_setting + 0.05), seed001_blank(), *KEYS[1])
    d = [measure_deviation(moved, g, iterations=k) for k in (1, 2, 3, 4)]
    assert np.max(np.abs(d[3])) > 0.01  # a real deviation of tens of um
    # Newton-type convergence of the line/surface intersection: errors fall much faster than linearly
    e = [np.max(np.abs(x - d[3])) for x in d[:3]]
    assert e[1] < 1e-2 * e[0] and e[2] < 1e-9


def test_csv_round_trip(tmp_path, flanks):
    g = measurement_grid(flanks[KEYS[0]])
    dev = np.random.default_rng(1).normal(0, 0.01, g.shape)
    path = write_measurement_grid(tmp_path / "grid.csv", g, dev)
    text = path.read_text()
    header = [ln for ln in text.splitlines() if not ln.startswith("#")][0]
    assert header == ("label,row,column,R_mm,h_mm,axial_mm,radius_mm,x_mm,y_mm,z_mm,nx,ny,nz,deviation_mm")
    assert "positive = material added" in text
    np.testing.assert_allclose(read_measured_deviation(path, g), dev, atol=5e-10)
    # a minimal measurement file addressed by row/column, in any order
    order = reversed(list(np.ndindex(9, 5)))
    lines = ["row,column,deviation_mm"] + [f"{i + 1},{j + 1},{dev[i, j]:.6f}" for i, j in order]
    (tmp_path / "m.csv").write_text("\n".join(lines))
    np.testing.assert_allclose(read_measured_deviation(tmp_path / "m.csv", g), dev, atol=5e-7)


def test_csv_errors(tmp_path, flanks):
    g = measurement_grid(flanks[KEYS[0]], 3, 2)
    p = tmp_path / "bad.csv"
    p.write_text("label,value\nF1P1,0.1\n")
    with pytest.raises(DesignError, match="columns"):
        read_measured_deviation(p, g)
    p.write_text("label,deviation_mm\nF1P1,0.1\nF1P2,0.0\n")
    with pytest.raises(DesignError, match="missing"):
        read_measured_deviation(p, g)
    p.write_text("label,deviation_mm\nF1P1,0.1\nF1P1,0.0\n")
    with pytest.raises(DesignError, match="once"):
        read_measured_deviation(p, g)
    p.write_text("label,deviation_mm\nF7P1,0.1\n")
    with pytest.raises(DesignError, match="line 2"):
        read_measured_deviation(p, g)
    p.write_text("label,deviation_mm\nF1P1,abc\n")
    with pytest.raises(DesignError, match="line 2"):
        read_measured_deviation(p, g)
    with pytest.raises(DesignError, match="deviation"):
        write_measurement_grid(tmp_path / "x.csv", g, np.zeros((2, 2)))
    assert not (tmp_path / "x.csv").exists()
