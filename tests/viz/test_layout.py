"""The drawing shortcuts of ``viz.layout`` give the picture of the slow way: the thinned Gouraud grid against the
full grid (rendered), the fixed panel title against matplotlib's measured placement; and the lazy old module paths
of ``spiralbevel.job``."""

import subprocess
import sys

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from spiralbevel.viz.layout import display_subgrid, panel_title  # noqa: E402


def _parallelogram(n):
    s, t = np.meshgrid(np.linspace(0.0, 1.0, n), np.linspace(0.0, 1.0, n), indexing="ij")
    x, y = 40.0 * s + 25.0 * t, 30.0 * t
    return x, y, np.sin(2.0 * s + 0.5) * np.cos(1.5 * t)  # a smooth field, like a draft angle


def test_subgrid_keeps_the_edges_and_thins_evenly():
    x, y, v = _parallelogram(101)
    xs, ys, vs = display_subgrid(x, y, v)
    assert xs.shape == ys.shape == vs.shape == (41, 41)
    for full, sub in ((x, xs), (y, ys), (v, vs)):   # same outline: first and last rows and columns kept
        for a, b in ((full[0], sub[0]), (full[-1], sub[-1]), (full[:, 0], sub[:, 0]), (full[:, -1], sub[:, -1])):
            assert set(b.tolist()) <= set(a.tolist()) and b[0] == a[0] and b[-1] == a[-1]
    assert display_subgrid(x[:7, :9])[0].shape == (7, 9)   # a small grid is left whole


def _render(x, y, v):
    fig, ax = plt.subplots(figsize=(4.0, 3.0), dpi=100)
    ax.pcolormesh(x, y, v, shading="gouraud", cmap="RdYlGn", vmin=-1.0, vmax=1.0)
    ax.set_axis_off()
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    plt.close(fig)
    return img


def test_subgrid_draws_the_colours_of_the_full_grid():
    x, y, v = _parallelogram(101)
    full, thin = _render(x, y, v), _render(*display_subgrid(x, y, v))
    d = np.abs(full - thin).max(-1)
    # inside the map the linear interpolation over the coarser cells moves a colour by a few levels (8 of 255 on the
    # draft maps of the bundled example); the larger differences are anti-aliased pixels on the outline (0.11 % here)
    assert np.mean(d > 8) < 0.002, f"{100 * np.mean(d > 8):.2f} % of the pixels differ by more than 8 levels"
    assert np.mean(d > 0) < 0.35  # 29 % of the pixels move by a level or more (measured)


def test_fixed_title_sits_where_matplotlib_places_it():
    boxes = []
    for fixed in (False, True):
        fig, axes = plt.subplots(1, 2, figsize=(8.0, 3.0))
        for ax in axes:
            ax.pcolormesh(*_parallelogram(11), shading="gouraud")
            ax.set_xlabel("axial position z [mm]")
            fig.colorbar(ax.collections[0], ax=ax)
            (panel_title if fixed else type(ax).set_title)(ax, "pinion convex: k1 (profile)", fontsize=9)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        boxes.append([ax.title.get_window_extent(renderer).bounds for ax in axes])
        plt.close(fig)
    np.testing.assert_allclose(boxes[0], boxes[1], atol=1e-9)


def test_old_job_paths_are_the_gearset_modules_imported_on_first_use():
    code = ("import sys, spiralbevel.job\n"
            "assert 'spiralbevel.gearset.facemilled' not in sys.modules\n"
            "import spiralbevel.job.facemilled as a\n"
            "from spiralbevel.job import blank\n"
            "import spiralbevel.gearset.facemilled as b, spiralbevel.gearset.blank as c\n"
            "assert a is b and blank is c and b.__spec__.name == 'spiralbevel.gearset.facemilled'\n")
    subprocess.run([sys.executable, "-c", code], check=True)
