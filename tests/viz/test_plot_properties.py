"""Plots an engineer would put in a review (issue 12 item 4), checked by their properties, not by pixels: a colour bar
where a map is drawn, degrees in the rotation and angle axes, no text outside the figure, a picture that is not
blank; and what each fix is about (teeth not overprinted, ordered curvatures, a filled pressure map)."""

from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402


def _check(fig, *, colorbar=True):
    """Common properties of a review plot; returns the rendered RGBA image."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    # every drawn artist (matplotlib's tight box counts only the ticks inside the view) lies inside the figure
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    assert tight.x0 >= -1 and tight.y0 >= -1 and tight.x1 <= box.x1 + 1 and tight.y1 <= box.y1 + 1, \
        f"something is drawn outside the figure: {tight} vs {box}"
    # and each title, label and annotation explicitly (one pixel of slack: anti-aliased glyph edges)
    texts = list(fig.texts)
    for ax in fig.axes:
        if ax.get_visible():
            texts += [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label, *ax.texts]
    for t in texts:
        if not t.get_visible() or not t.get_text().strip():
            continue
        bb = t.get_window_extent(renderer)
        assert bb.x0 >= box.x0 - 1 and bb.x1 <= box.x1 + 1 and bb.y0 >= box.y0 - 1 and bb.y1 <= box.y1 + 1, \
            f"text {t.get_text()!r} is clipped by the figure edge: {bb} outside {box}"
    if colorbar:
        assert any(getattr(ax, "_colorbar", None) is not None for ax in fig.axes), "no colour bar"
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    ink = np.any(img < 240, axis=-1).mean()
    assert ink > 0.03, f"nearly blank figure ({100 * ink:.1f}% of the pixels drawn)"
    assert len(np.unique(img.reshape(-1, 3) // 16, axis=0)) > 20, "too few colours: a blank or flat image"
    plt.close(fig)
    return img


def _sheet(n=15, m=7, x0=0.0, tilt=0.0):
    """A curved (n, m, 3) flank-like grid, mm."""
    s, t = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, m), indexing="ij")
    return np.stack([30 + 10 * t + x0, 20 * s - 10 + 3 * (t - 0.5) ** 2 + tilt * t, 90 + 35 * s + 2 * t], -1)


def test_tca_plot_degrees_and_labels_outside_the_flank():
    from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
    from spiralbevel.meshing.kinematics import BevelPairKinematics
    from spiralbevel.meshing.tca import solve_tca
    from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair
    from spiralbevel.viz.tca_plot import project_axial_radial

    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    res = solve_tca(crowned, pair.gear, kin)
    outline = pair.pinion.grid()
    fig = res.plot(outline1=outline, outline2=pair.gear.grid())
    ax_te, ax1 = fig.axes[:2]
    assert "deg" in ax_te.get_xlabel() and "rad" not in ax_te.get_xlabel()
    np.testing.assert_allclose(ax_te.lines[0].get_xdata(), np.degrees(res.phi1 - res.phi1_mean))
    # toe / heel / root / top labels sit outside the projected flank: not on the contact path or the ellipses
    from matplotlib.path import Path

    q = project_axial_radial(outline)
    ring = np.concatenate([q[:, 0], q[-1], q[::-1, -1], q[0, ::-1]])
    flank = Path(ax1.transData.transform(ring))
    fig.canvas.draw()
    labels = [t for t in ax1.texts if t.get_text() in ("toe", "heel", "root", "top")]
    assert len(labels) == 4
    for t in labels:
        bb = t.get_window_extent(fig.canvas.get_renderer())
        corners = [(bb.x0, bb.y0), (bb.x1, bb.y0), (bb.x0, bb.y1), (bb.x1, bb.y1)]
        assert not any(flank.contains_point(c) for c in corners), t.get_text()
    _check(fig, colorbar=False)


def _fake_ltca():
    """A loaded-TCA-like result: three contact lines per position on a gear flank with an elliptic pressure."""
    rng = np.linspace(-1, 1, 25)
    points, pressure = [], []
    for c in np.linspace(-3, 3, 9):
        z = 40 + c * 0.8 + 2.0 * rng
        r = 108 + c + 0.6 * rng
        pts = np.stack([r * np.cos(0.1), r * np.sin(0.1), z], -1)
        points.append(pts)
        pressure.append(1000 * np.sqrt(np.clip(1 - rng**2, 0, None)) * (1 - (c / 4) ** 2))
    x = np.linspace(-8, 8, 9)
    return SimpleNamespace(pinion_angles=np.radians(x), te_pairs=np.zeros((9, 2)), pair_names=("-1", "+0"),
                           te_unloaded=-x**2 / 20, te_loaded=-15 - x**2 / 20, torque=87950.0,
                           load_share=np.c_[np.linspace(1, 0, 9), np.linspace(0, 1, 9)], points2=points,
                           points1=points, pressure=pressure, peak_pressure=1000.0)


def test_ltca_pressure_is_a_filled_map_on_the_flank_outline():
    from matplotlib.tri import TriContourSet

    from spiralbevel.viz.ltca_plot import plot_ltca

    res = _fake_ltca()
    outline = np.stack([np.stack([100 * np.cos(0.1) * np.ones(7), 100 * np.sin(0.1) * np.ones(7),
                                  np.linspace(30, 50, 7)], -1) + np.array([0.0, 0.0, 0.0])] * 3, 0)
    outline[1, :, :2] *= 1.1
    outline[2, :, :2] *= 1.2
    fig = plot_ltca(res, outline=outline)
    ax3 = fig.axes[2]
    filled = [c for c in ax3.collections if isinstance(c, TriContourSet)]
    assert filled, "the pressure is not a filled map"
    assert filled[0].levels[-1] == pytest.approx(1000.0)          # the colour scale reaches the peak pressure
    assert not [c for c in ax3.collections if type(c).__name__ == "PathCollection"]   # no scatter of dots
    assert {t.get_text() for t in ax3.texts} == {"toe", "heel", "root", "top"}
    for ax in fig.axes[:2]:
        assert "deg" in ax.get_xlabel()
    _check(fig)


def test_easeoff_both_panels_colour_bar_and_sign():
    from spiralbevel.viz.easeoff_plot import SIGN, plot_easeoff

    R, h = np.meshgrid(np.linspace(100, 130, 15), np.linspace(0, 5, 9), indexing="ij")
    eo = SimpleNamespace(R=R, h=h, values=1e-4 * ((R - 115) ** 2 / 10 + (h - 2.5) ** 2), axial=R * 0.94,
                         radius=R * 0.33 + h)
    title = "Ease-off of the pinion concave flank against the conjugate of the gear convex flank (drive side), " \
            "a title long enough to have been clipped before"
    fig = plot_easeoff(eo, kind="both", title=title)
    cbars = [ax for ax in fig.axes if getattr(ax, "_colorbar", None) is not None]
    assert len(cbars) == 1 and SIGN in cbars[0].get_ylabel()
    _check(fig)
    fig = plot_easeoff(eo, kind="surface", title=title)
    _check(fig)


def test_draft_map_shows_draft_angles_with_the_limit():
    from spiralbevel.io.design_file import load_design
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.logspiral import design_pair
    from spiralbevel.manufacturing.draft import draft_map
    from spiralbevel.viz.draft_plot import draft_angle, plot_draft_maps

    spec = load_design(None)
    pair = design_pair(spec, blank_from_design(spec))
    results = []
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):
            f = pair.flank(m, s)
            results.append((f"{m} {s}", draft_map(f.surface, f.domain, die_direction=(0, 0, 1), n_phi=21, n_psi=21)))
    results.append(("pinion concave at 5 deg", results[1][1], np.radians(5.0)))
    fig = plot_draft_maps(results)
    axes = [ax for ax in fig.axes if ax.get_visible() and getattr(ax, "_colorbar", None) is None]
    cbars = [ax for ax in fig.axes if getattr(ax, "_colorbar", None) is not None]
    assert len(cbars) == len(results)
    for ax, cb, (_, r, *lim) in zip(axes, cbars, results):
        assert "draft angle [deg]" in cb.get_ylabel()
        mesh = ax.collections[0]
        np.testing.assert_allclose(np.asarray(mesh.get_array()).ravel(), np.degrees(draft_angle(r)).ravel())
        # the limit is the centre of the colour scale and marked on the colour bar
        assert mesh.norm.vcenter == pytest.approx(np.degrees(lim[0]) if lim else 0.0)
        assert any(abs(ln.get_ydata()[0] - mesh.norm.vcenter) < 1e-9 for ln in cb.lines)
        assert "n_out" not in ax.get_title() and "v_d" not in ax.get_title()     # words, not pseudo-code
        assert "deg" in ax.get_xlabel() and "deg" in ax.get_ylabel()
    # the failing flank (pinion convex) has negative draft angles, the others positive
    assert np.all(draft_angle(results[0][1]) < 0) and np.all(draft_angle(results[1][1]) > 0)
    _check(fig)


def test_pair_3d_equal_scales_and_opaque_lit_faces():
    from spiralbevel.viz.pair3d import plot_surfaces_3d

    surfaces = [("pinion convex", _sheet(), "tab:blue"), ("gear convex", _sheet(x0=2.0, tilt=1.0), "tab:red"),
                ("_", _sheet(x0=4.0), "tab:red")]
    fig = plot_surfaces_3d(surfaces, title="pair")
    allpts = np.concatenate([s[1].reshape(-1, 3) for s in surfaces])
    span = np.ptp(allpts, axis=0)
    for ax in fig.axes:
        # one millimetre is as long on every axis: the box aspect is the data span plus equal relative padding
        box = np.array(ax.get_box_aspect())
        np.testing.assert_allclose(box / box.max(), span / span.max(), rtol=1e-9)
        coll = ax.collections[0]
        assert coll.get_alpha() in (None, 1.0)
        faces = coll.get_facecolor()
        assert np.all(faces[:, 3] == 1.0)                                  # opaque
        assert len(np.unique(np.round(faces[:, :3], 3), axis=0)) > 10      # shaded, not flat colours
    _check(fig, colorbar=False)


def test_axial_section_sides_in_separate_panels():
    from spiralbevel.viz.axial_section import plot_axial_section

    members = [{"name": "pinion", "grids": {"convex": _sheet(), "concave": _sheet(x0=1.0)}, "outline": None,
                "profile": [np.c_[np.linspace(-3, -1, 5), np.linspace(37, 43, 5)],
                            np.c_[np.linspace(1, 3, 5), np.linspace(43, 37, 5)]], "radius": 115.0},
               {"name": "gear", "grids": {"convex": _sheet(), "concave": _sheet(x0=1.0)}, "outline": None,
                "profile": None, "radius": None}]
    fig = plot_axial_section(members, title="t")
    grid_axes = [ax for ax in fig.axes if "flank: grid" in ax.get_title()]
    assert len(grid_axes) == 4
    for ax in grid_axes:
        colours = {matplotlib.colors.to_hex(ln.get_color()) for ln in ax.lines if ln.get_xydata().size}
        assert len(colours) == 1, ax.get_title()   # one side per panel: nothing overprinted
    _check(fig, colorbar=False)


def test_ordered_curvatures_have_no_step_where_labels_swap():
    from spiralbevel.viz.flank_maps import ordered_curvatures, plot_flank_fields

    # two smooth principal curvatures whose "nearer the profile" labels swap along the face (a step band in k1, k2)
    s = np.linspace(0, 1, 41)[:, None] * np.ones((1, 9))
    a, b = 0.010 + 0.002 * s, 0.004 + 0.001 * s
    swap = s > 0.5
    k1, k2 = np.where(swap, b, a), np.where(swap, a, b)
    assert np.max(np.abs(np.diff(k1, axis=0))) > 0.005                  # the labelled field jumps
    kmax, kmin = ordered_curvatures(k1, k2)
    np.testing.assert_array_equal(kmax, a)
    np.testing.assert_array_equal(kmin, b)
    assert np.max(np.abs(np.diff(kmax, axis=0))) < 1e-4                 # the ordered one does not
    pts = _sheet(41, 9)
    fig = plot_flank_fields([("κ_max", pts, kmax, "1/mm"), ("κ_min", pts, kmin, "1/mm")] * 2, title="curvatures")
    _check(fig)


def test_pressure_map_of_a_single_contact_line_falls_back_to_dots():
    from spiralbevel.viz.ltca_plot import pressure_map

    fig, ax = plt.subplots()
    x = np.linspace(0, 4, 9)
    art = pressure_map(ax, x, 2 * x + 1, 100 * np.sin(np.pi * x / 4), fig=fig)   # collinear: no triangle
    assert type(art).__name__ == "PathCollection"
    _check(fig)
