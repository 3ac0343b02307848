"""Ball-end tool paths along the lines of curvature: scallop measured in 3-D, line-of-curvature property, CL data."""

from __future__ import annotations

import math

import numpy as np
import pytest

from spiralbevel._core import logspiral
from spiralbevel.conventions import Side
from spiralbevel.errors import DesignError, DesignWarning, GeometryError
from spiralbevel.manufacturing.toolpath import plan_toolpath

from ._cases import make

R_TOOL, H = 3.0, 0.01


def _cl(p_flank, psi_sign, vphi, phi, R):
    """Ball centres r + R n_out straight from the docs/theory/logspiral.md, Eqs. (S4), (S9) kernel (n_out = sign(psi)
    n); vphi, phi broadcast."""
    g = logspiral.geometry(vphi, phi, p_flank.rho0, p_flank.base_cone_angle, p_flank.spiral_angle)
    return g["r"] + R * psi_sign * g["n"]


def _entry(P, N, C, R):
    """Distance along N from P to the first point inside a ball of radius R centred at C; inf if the line misses."""
    d = C - P[:, None, :]
    a = np.einsum("mkj,mj->mk", d, N)
    disc = R * R - np.einsum("mkj,mkj->mk", d, d) + a * a
    return np.where(disc >= 0, a - np.sqrt(np.maximum(disc, 0.0)), np.inf)


def _residual(P, N, phiP, flank, psi_sign, vphi, lo_range, hi_range, R, K=161):
    """Residual material height above surface points P (m, 3) left by the swept ball of one pass each (vphi (m,)).

    Sampled union of balls along the pass within +-0.05 R (arc) of the point's phi, restricted to the pass's phi
    range, then a parabola through the three best samples (the entry distance is smooth in phi). The best ball
    sits within about 0.01 R of the point's phi (checked: the argmin never touches the window ends).
    """
    s = math.sin(flank.base_cone_angle)
    ds_dphi = flank.rho0 * np.exp(phiP * s / math.tan(flank.spiral_angle)) * s / abs(math.sin(flank.spiral_angle))
    half = 0.05 * R / ds_dphi
    lo = np.maximum(phiP - half, lo_range)
    hi = np.minimum(phiP + half, hi_range)
    t = np.linspace(0.0, 1.0, K)
    ph = lo[:, None] + (hi - lo)[:, None] * t[None, :]
    C = _cl(flank, psi_sign, vphi[:, None], ph, R)
    e = _entry(P, N, C, R)
    j = np.argmin(e, axis=1)
    interior = (j > 0) & (j < K - 1)
    at_window_end = ~interior & (((j == 0) & (lo > lo_range)) | ((j == K - 1) & (hi < hi_range)))
    assert not at_window_end.any()
    i = np.clip(j, 1, K - 2)
    rows = np.arange(len(P))
    y0, y1, y2 = e[rows, i - 1], e[rows, i], e[rows, i + 1]
    den = y0 - 2 * y1 + y2
    with np.errstate(invalid="ignore", divide="ignore"):
        vertex = np.where(interior & (den > 0) & np.isfinite(den), y1 - 0.125 * (y2 - y0) ** 2 / den, y1)
    return np.minimum(e.min(axis=1), vertex)


def _measure(flank, domain, tp, n_phi=9, n_across=41):
    """Scallop height at surface points of the real domain, each against the two passes bracketing it."""
    sign = 1 if domain.psi_min > 0 else -1
    vph = np.array([q.varphi for q in tp.paths])
    lo_r = np.array([q.phi.min() for q in tp.paths])
    hi_r = np.array([q.phi.max() for q in tp.paths])
    out = []
    frac = np.linspace(0.0, 1.0, n_across)
    for phi in np.linspace(domain.phi_min, domain.phi_max, n_phi):
        vlo, vhi = domain.to_varphi(domain.psi_min, phi), domain.to_varphi(domain.psi_max, phi)
        idx = np.nonzero((vph[1:] >= vlo) & (vph[:-1] <= vhi))[0]
        a, b = vph[idx], vph[idx + 1]
        v = (np.maximum(a, vlo)[:, None] + (np.minimum(b, vhi) - np.maximum(a, vlo))[:, None] * frac).ravel()
        ia, ib = np.repeat(idx, n_across), np.repeat(idx + 1, n_across)
        # both bracketing passes reach this phi (the overrun carries them past the root and top edges)
        assert np.all((lo_r[ia] <= phi + 1e-12) & (phi - 1e-12 <= hi_r[ia]))
        assert np.all((lo_r[ib] <= phi + 1e-12) & (phi - 1e-12 <= hi_r[ib]))
        ph = np.full_like(v, phi)
        g = logspiral.geometry(v, ph, flank.rho0, flank.base_cone_angle, flank.spiral_angle)
        P, N = g["r"], sign * g["n"]
        hA = _residual(P, N, ph, flank, sign, vph[ia], lo_r[ia], hi_r[ia], tp.tool_radius)
        hB = _residual(P, N, ph, flank, sign, vph[ib], lo_r[ib], hi_r[ib], tp.tool_radius)
        out.append(np.minimum(hA, hB))
    return np.concatenate(out)


@pytest.mark.parametrize("beta_sign,psi_sign", [(1, 1), (1, -1), (-1, 1), (-1, -1)])
def test_measured_scallop_between_passes(beta_sign, psi_sign):
    flank, domain = make(beta_sign, psi_sign)
    tp = plan_toolpath(flank, domain, R_TOOL, H, max_segment=2.0)
    h = _measure(flank, domain, tp)
    # never above the request (sampling of the ball union can only overestimate the residual; 1e-9 mm slack for
    # rounding), and the stepover is not wastefully small: the worst scallop reaches >= 0.8 h
    assert h.max() <= H + 1e-9
    assert h.max() >= 0.8 * H
    assert h.min() >= -1e-9  # no gouge anywhere between the passes (the balls only touch the flank)
    assert np.all(tp.predicted_scallop <= H * (1 + 1e-9))


def test_left_hand_passes_are_mirror_images_of_right_hand_ones():
    # docs/conventions.md: left hand = mirror image of right hand in the xz-plane; (beta, varphi, phi) ->
    # (-beta, -varphi, -phi). The mirrored ball centres of a left-hand pass are right-hand ball centres.
    fr, dr = make(1, 1)
    fl, dl = make(-1, -1)
    tl = plan_toolpath(fl, dl, R_TOOL, H)
    tr = plan_toolpath(fr, dr, R_TOOL, H)
    assert tr.side is tl.side is Side.CONVEX
    assert abs(len(tr) - len(tl)) <= 1  # the march starts from opposite corners
    mirror = np.array([1.0, -1.0, 1.0])
    for path in tl.paths[::7]:
        np.testing.assert_allclose(path.center * mirror, _cl(fr, 1, -path.varphi, -path.phi, R_TOOL), atol=1e-11)


@pytest.mark.parametrize("beta_sign,psi_sign", [(1, 1), (-1, 1)])
def test_passes_are_lines_of_curvature(beta_sign, psi_sign):
    flank, domain = make(beta_sign, psi_sign)
    tp = plan_toolpath(flank, domain, R_TOOL, H, max_segment=0.05)
    for path in tp.paths[5:-5:10]:
        g = logspiral.geometry(path.varphi, path.phi, flank.rho0, flank.base_cone_angle, flank.spiral_angle)
        np.testing.assert_allclose(path.surface, g["r"], atol=1e-12)  # varphi = const on the flank
        # numerical tangent (central differences of the points) is orthogonal to e1 and parallel to e2 and feed
        tan = path.surface[2:] - path.surface[:-2]
        tan /= np.linalg.norm(tan, axis=1, keepdims=True)
        assert np.abs(np.einsum("ij,ij->i", tan, g["e1"][1:-1])).max() < 1e-9
        assert np.abs(np.abs(np.einsum("ij,ij->i", tan, g["e2"][1:-1])) - 1).max() < 1e-6
        assert np.einsum("ij,ij->i", tan, path.feed[1:-1]).min() > 1 - 1e-6
        # Rodrigues: along a line of curvature dn_out is parallel to dr (no twist of the normal)
        dn = path.normal[2:] - path.normal[:-2]
        dr = path.surface[2:] - path.surface[:-2]
        cross = np.linalg.norm(np.cross(dn, dr), axis=1) / (np.linalg.norm(dn, axis=1) * np.linalg.norm(dr, axis=1))
        assert cross.max() < 1e-6


def test_cl_points_axis_and_arc_length():
    flank, domain = make(1, 1)
    lead, tilt = math.radians(10), math.radians(-5)
    tp = plan_toolpath(flank, domain, R_TOOL, H, lead=lead, tilt=tilt, max_segment=0.5)
    for path in tp.paths[1:-1:15]:
        np.testing.assert_allclose(path.center, path.surface + R_TOOL * path.normal, atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(path.axis, axis=1), 1.0, atol=1e-14)
        np.testing.assert_allclose(path.tip, path.center - R_TOOL * path.axis, atol=1e-12)
        # axis = normal turned by lead toward the feed, then tilt sideways: n.a = cos lead cos tilt
        np.testing.assert_allclose(np.einsum("ij,ij->i", path.axis, path.normal), math.cos(lead) * math.cos(tilt))
        np.testing.assert_allclose(np.einsum("ij,ij->i", path.axis, path.feed), math.sin(lead) * math.cos(tilt),
                                   atol=1e-14)
        # closed-form arc length |rho - rho_0| / cos(beta) against the sum of chords (error O(seg^2 k^2) ~ 1e-7)
        chords = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(path.surface, axis=0), axis=1))])
        np.testing.assert_allclose(path.arc_length, chords, rtol=1e-6, atol=1e-9)
        assert np.diff(path.arc_length).max() <= 0.5 + 1e-12
    # the outward normal of a convex flank points away from the tooth: every normal meets n.r_hat = sign(psi) sin(beta)
    n = tp.stacked("normal")
    r = tp.stacked("surface")
    np.testing.assert_allclose(np.einsum("ij,ij->i", n, r / np.linalg.norm(r, axis=1, keepdims=True)),
                               math.sin(flank.spiral_angle), atol=1e-12)
    assert tp.path_index.shape == tp.point_index.shape == (len(n),)


def test_zigzag_reverses_every_other_pass():
    flank, domain = make(1, 1)
    one, zig = plan_toolpath(flank, domain, R_TOOL, H), plan_toolpath(flank, domain, R_TOOL, H, zigzag=True)
    assert len(one) == len(zig)
    for i, (a, b) in enumerate(zip(one.paths, zig.paths)):
        np.testing.assert_allclose(a.center, b.center if i % 2 == 0 else b.center[::-1], atol=1e-12)
        assert np.all(np.diff(b.arc_length) > 0)


def test_gouge_check_names_the_concave_limit():
    flank, domain = make(1, -1)  # concave: lengthwise kappa2 = -sin(beta)/rho
    rho_min = flank.rho0 * math.exp(domain.phi_min * math.sin(domain.base_cone_angle) / math.tan(flank.spiral_angle))
    limit = rho_min / math.sin(flank.spiral_angle)
    with pytest.raises(GeometryError, match=f"< {limit:.6g}"):
        plan_toolpath(flank, domain, 1.01 * limit, H)
    plan_toolpath(flank, domain, 0.99 * limit, 0.5, max_segment=50.0, overrun=False)  # just below: fine
    convex, cdom = make(1, 1)
    plan_toolpath(convex, cdom, 1.5 * limit, 0.5, max_segment=50.0, overrun=False)  # no concave curvature


def test_overrun_clamped_near_the_singular_edge_warns():
    flank, domain = make(1, 1, psi=(0.05, 0.5))
    with pytest.warns(DesignWarning, match="singular edge"):
        tp = plan_toolpath(flank, domain, 10.0, 0.5, max_segment=50.0)
    assert tp.overrun[0] == pytest.approx(0.025)  # half the distance to psi = 0


@pytest.mark.parametrize("kw,field", [
    (dict(tool_radius=0.0), "tool_radius"), (dict(tool_radius=float("nan")), "tool_radius"),
    (dict(scallop_height=-1e-3), "scallop_height"), (dict(scallop_height=3.0), "scallop_height"),
    (dict(lead=2.0), "lead"), (dict(tilt="x"), "tilt"), (dict(max_segment=0), "max_segment"),
    (dict(max_paths=3), "scallop_height"),
])
def test_bad_input_is_a_design_error(kw, field):
    flank, domain = make(1, 1)
    args = dict(tool_radius=R_TOOL, scallop_height=H) | kw
    with pytest.raises(DesignError, match=field):
        plan_toolpath(flank, domain, **args)


def test_flank_and_domain_checks():
    flank, domain = make(1, 1)
    from spiralbevel.geometry.domain import ParallelogramDomain
    bad = ParallelogramDomain(0.0, 0.6, -0.1, 0.3, domain.base_cone_angle)
    with pytest.raises(DesignError, match="singular"):
        plan_toolpath(flank, bad, R_TOOL, H)
    other = ParallelogramDomain(0.0, 0.6, 0.3, 0.5, 0.5)
    with pytest.raises(DesignError, match="base_cone_angle"):
        plan_toolpath(flank, other, R_TOOL, H)


def test_march_samples_are_linspace_bit_for_bit():
    """The march's phi samples (``_samples``, linspace's arithmetic without its argument handling) are the floats of
    ``np.linspace`` itself: random ends over the flank parameters' scales, equal ends and denormally close ends."""
    from spiralbevel.manufacturing.toolpath import _N_OVERLAP, _samples

    rng = np.random.default_rng(7)
    lo = rng.uniform(-1.0, 1.0, 400) * 10.0 ** rng.integers(-6, 2, 400)
    hi = lo + rng.uniform(0.0, 1.0, 400) * 10.0 ** rng.integers(-12, 1, 400)
    cases = list(zip(lo, hi)) + [(0.3, 0.3), (0.0, 5e-324), (-0.2, 0.0)]
    for a, b in cases:
        assert np.array_equal(_samples(float(a), float(b)), np.linspace(a, b, _N_OVERLAP)), (a, b)
