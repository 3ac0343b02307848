"""report.html: every value of report.json on the page, the meshing pair placed so the pitch cones roll, and the page
checked in a real headless Chromium (no console errors, no network request, every section rendered, screenshots of the
page and of the 3-D view not blank)."""

import json
import math
import os
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import default_design_text
from spiralbevel.io.report_html import HEADER_KEYS, SECTIONS, render_report_html
from spiralbevel.io.report_mesh import decimate, pair_placements, tooth_centre_angle, weld
from spiralbevel.io.report_tables import unit_of

sys.path.insert(0, str(Path(__file__).parent))
from _chromium import Browser, chromium_path  # noqa: E402

runner = CliRunner()


def _run(tmp_path_factory, name, text=None):
    d = tmp_path_factory.mktemp(name)
    args = ["run", "-o", str(d / "out"), "-q"]
    if text is not None:
        (d / "design.toml").write_text(text)
        args.insert(1, str(d / "design.toml"))
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    out = d / "out"
    return out, json.loads((out / "report.json").read_text())


@pytest.fixture(scope="module")
def logspiral_run(tmp_path_factory):
    """The default design (log-spiral), as the Quick start runs it."""
    return _run(tmp_path_factory, "ls")


@pytest.fixture(scope="module")
def facemilled_run(tmp_path_factory):
    """The face-milled example on a coarser grid and without STEP (the HTML report does not use them)."""
    text = default_design_text("aviation_23x65_facemilled.toml")
    return _run(tmp_path_factory, "fm", text.replace("grid = [31, 15]", "grid = [15, 9]")
                .replace("step = true", "step = false"))


def _leaves(node, key=""):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _leaves(v, k)
    elif not isinstance(node, list) or not node or not all(isinstance(x, dict) for x in node):
        yield key, node
    else:
        for x in node:
            yield from _leaves(x, key)


@pytest.mark.parametrize("which", ["logspiral_run", "facemilled_run"])
def test_every_report_key_is_on_the_page(which, request):
    out, report = request.getfixturevalue(which)
    assert "report.html" in report["files"]
    html = (out / "report.html").read_text(encoding="utf-8")
    # one file, no network: nothing loaded from elsewhere
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//|@import|url\(\s*["']?https?:""", html, re.I)
    size = len(html.encode())
    assert size < 5e6, size  # the bundled examples give 2.2-2.3 MB (PNG figures 2.0 MB as base64, meshes 0.1-0.2 MB)
    body = html.split("<main>", 1)[1]
    missing = set()
    header = html.split("<main>", 1)[0]
    assert report["design"]["title"] in header and report["spiralbevel_version"] in header
    for key, value in _leaves({k: v for k, v in report.items() if k not in HEADER_KEYS}):
        if key in ("units", "descriptions") or not key:
            continue
        label = unit_of(key)[0]
        label = re.sub(r"(?<=[A-Za-z_])[12]$", "", label)  # pinion/gear columns drop the member digit
        if label not in body and label.replace("_", " ") not in body.lower():
            missing.add(key)
        # every number with six significant digits (the page's rounding, chosen here on its own)
        if isinstance(value, float) and f"{value:.6g}" not in body:
            missing.add(f"{key} = {value}")
    assert not missing, sorted(missing)
    for s in SECTIONS:
        assert f'id="{s.id}"' in html


def test_units_from_names():
    assert unit_of("max_contact_pressure_N_per_mm2") == ("max_contact_pressure", "N/mm²")
    assert unit_of("k1_per_mm") == ("k1", "1/mm")
    assert unit_of("peak_to_peak_arcsec") == ("peak_to_peak", "″")
    assert unit_of("semi_major_axis_mm") == ("semi_major_axis", "mm")
    assert unit_of("R", {"R": "mm"}) == ("R", "mm")
    assert unit_of("teeth") == ("teeth", "")


def test_curves_over_the_rotation_are_plotted():
    rot = np.linspace(-0.1, 0.1, 11)
    report = {"ltca": {"pinion_rotation_rad": rot.tolist(), "loaded_transmission_error_arcsec": (rot * 100).tolist(),
                       "unloaded_transmission_error_arcsec": (rot * 50).tolist(),
                       "load_share": [[0.5, 0.5]] * 11, "pair_names": ["pair -1", "pair +0"]}}
    html = render_report_html(report)
    assert html.count("<svg") == 2  # TE (both curves in one chart), load share
    # each point carries its values in degrees: the last one at 0.1 rad = 5.72958 deg
    assert f"{math.degrees(0.1):.6g}, {10.0:.6g}" in html
    assert "pair +0" in html


def test_failures_and_warnings_are_listed_once():
    report = {"blank": {"warnings": ["w1"]}, "blank_warnings": ["w1"],
              "tca": {"drive": {"status": "failed", "reason": "no contact at the mean point"}},
              "draft": {"flanks": {"pinion_convex": {"passes": False}}},
              "failed_analyses": [{"analysis": "TCA, drive side", "reason": "no contact at the mean point"}]}
    html = render_report_html(report)
    warnings = html.split('id="warnings"', 1)[1].split("</section>", 1)[0]
    assert "Warnings (4)" in warnings and warnings.count("w1") == 1
    assert "tca.drive: failed (no contact at the mean point)" in warnings
    assert "draft.flanks.pinion_convex: does not pass" in warnings
    assert "failed: TCA, drive side" in warnings
    # the failed analysis keeps its place in its section, marked
    tca = html.split('id="tca"', 1)[1].split("</section>", 1)[0]
    assert 'class="bad">Failed: no contact at the mean point' in tca
    # without tooth meshes the 3-D section says why, and the page carries no viewer script
    assert "No 3-D view" in html and "pair-canvas" not in html and "getContext" not in html


def _cube():
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return corners[np.array(tris)]


def test_weld_and_decimate():
    m = weld(_cube())
    assert m.vertices.shape == (8, 3) and m.faces.shape == (12, 3)
    # vertex normals of a cube: unit, pointing away from the centre (the area-weighted mean of three face normals
    # along +-x, +-y, +-z: each component the same sign as the corner's offset)
    d = m.vertices - m.vertices.mean(0)
    np.testing.assert_allclose(np.linalg.norm(m.normals, axis=1), 1.0, rtol=1e-6)
    assert (np.sign(m.normals) == np.sign(d)).all()
    # a fine sphere decimated below a budget keeps its size
    u, v = np.meshgrid(np.linspace(0, np.pi, 60), np.linspace(0, 2 * np.pi, 120), indexing="ij")
    p = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)], -1)
    tris = np.concatenate([np.stack([p[:-1, :-1], p[1:, :-1], p[1:, 1:]], 2).reshape(-1, 3, 3),
                           np.stack([p[:-1, :-1], p[1:, 1:], p[:-1, 1:]], 2).reshape(-1, 3, 3)])
    fine = weld(tris)
    coarse = decimate(fine, 2000)
    assert len(coarse.faces) <= 2000 < len(fine.faces)
    # clustering moves vertices inward by less than the cell size (about 2 * pi / cells of the radius)
    assert np.abs(np.linalg.norm(coarse.vertices, axis=1) - 1.0).max() < 0.08


@pytest.mark.parametrize("sigma_deg, z1, z2", [(90.0, 23, 65), (75.0, 12, 41)])
def test_pair_placement_rolls_the_pitch_cones(sigma_deg, z1, z2):
    sigma = math.radians(sigma_deg)
    # pitch angles from the ratio (ISO 23509: tan delta1 = sin Sigma / (cos Sigma + u)), computed here on their own
    d1 = math.atan2(math.sin(sigma), math.cos(sigma) + z2 / z1)
    d2 = sigma - d1
    a1, a2 = 0.3, -1.1  # tooth centres of the two meshes
    Q1, Q2 = pair_placements(sigma, (z1, z2), (a1, a2))
    for Q in (Q1, Q2):
        np.testing.assert_allclose(Q @ Q.T, np.eye(3), atol=1e-14)
        assert np.linalg.det(Q) == pytest.approx(1.0)
    # the axes make the shaft angle
    assert math.acos(Q1[:, 2] @ Q2[:, 2]) == pytest.approx(sigma, abs=1e-12)
    # the pinion tooth centre at the pitch cone lands on the pitch point P (y = 0, x < 0) ...
    t1 = np.array([math.sin(d1) * math.cos(a1), math.sin(d1) * math.sin(a1), math.cos(d1)])
    P = Q1 @ t1
    assert P[1] == pytest.approx(0.0, abs=1e-14) and P[0] < 0
    # ... on the gear's pitch cone, in the middle of the space after the gear tooth a2 (angle pi / z2 past it)
    g = Q2.T @ P
    assert math.acos(g[2]) == pytest.approx(d2, abs=1e-12)
    assert math.atan2(g[1], g[0]) == pytest.approx(a2 + math.pi / z2, abs=1e-12)
    # rolling: a pinion turn phi and a gear turn -phi z1/z2 move P at the same velocity (finite difference)
    h = 1e-6

    def rz(a):
        return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])

    v1 = (Q1 @ rz(h) @ Q1.T @ P - P) / h
    v2 = (Q2 @ rz(-h * z1 / z2) @ Q2.T @ P - P) / h
    np.testing.assert_allclose(v1, v2, atol=1e-6)


def test_tooth_centre_of_a_symmetric_tooth():
    # a wedge symmetric about the azimuth 0.7 rad: its centre is found there
    r = np.linspace(90, 130, 9)
    a = np.linspace(-0.05, 0.05, 5)
    R, A = np.meshgrid(r, a)
    pts = np.stack([R * np.cos(A + 0.7) * 0.4, R * np.sin(A + 0.7) * 0.4, R * 0.9], -1).reshape(-1, 3)
    assert tooth_centre_angle(pts) == pytest.approx(0.7, abs=1e-12)


# -- the page in a real browser --------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def browser():
    """One headless Chromium for the pages of this module (about 1 s to start)."""
    pytest.importorskip("websocket")  # websocket-client, extra 'test'
    if chromium_path() is None:
        if os.environ.get("CI"):
            pytest.fail("CI installs Chromium (.ci/run): it is missing")
        pytest.skip("no Chromium on this machine")
    with Browser(width=1280, height=900) as b:
        b.call("Network.enable")
        yield b


def _pixels(png: bytes) -> np.ndarray:
    import io

    import matplotlib.image as mpimg

    return mpimg.imread(io.BytesIO(png), format="png")[..., :3]


@pytest.mark.parametrize("which", ["logspiral_run", "facemilled_run"])
def test_page_in_headless_chromium(which, request, browser):
    out, report = request.getfixturevalue(which)
    with browser.fresh() as b:
        b.load((out / "report.html").as_uri())
        # every section is there with content, and the nav links to each
        sections = b.evaluate("Array.from(document.querySelectorAll('main > section')).map("
                              "s => [s.id, s.innerText.trim().length, s.getBoundingClientRect().height])")
        ids = [s[0] for s in sections]
        assert ids == [s.id for s in SECTIONS] + ["warnings", "view3d", "other", "design"]
        assert all(n > 20 and h > 30 for _, n, h in sections), sections
        assert b.evaluate("document.querySelectorAll('nav a').length") == len(ids)
        # figures decoded (a broken data URI has naturalWidth 0)
        assert b.evaluate("Array.from(document.images).every(i => i.complete && i.naturalWidth > 100)")
        # the viewer drew: both members' colours on the canvas
        assert b.evaluate("document.getElementById('pair-canvas').getAttribute('data-rendered')") == "1"
        # (page coordinates for the clip: the viewport's plus the scroll offset; centred below the sticky header)
        b.evaluate("document.getElementById('pair-canvas').scrollIntoView({block: 'center'})")
        rect = b.evaluate("(() => { const r = document.getElementById('pair-canvas').getBoundingClientRect();"
                          " return {x: r.x, y: r.y + window.scrollY, width: r.width, height: r.height}; })()")
        view = _pixels(b.screenshot(clip=rect))
        blue = (view[..., 2] > view[..., 0] + 0.2).mean()  # pinion (0.23, 0.47, 0.78) shaded
        orange = (view[..., 0] > view[..., 2] + 0.2).mean()  # gear (0.80, 0.42, 0.22) shaded
        assert blue > 0.01 and orange > 0.01, (blue, orange)
        # rolling the pair changes the picture
        b.evaluate("window.spiralbevelView.set(-0.9, -1.0, 2.0, 0.3)")
        assert np.abs(_pixels(b.screenshot(clip=rect)) - view).max() > 0.1
        b.evaluate("window.scrollTo(0, 0)")
        page = _pixels(b.screenshot())
        assert page.std() > 0.05 and len(np.unique((page * 255).astype(np.uint8).reshape(-1, 3), axis=0)) > 50
        assert b.errors == [], b.errors
        assert b.requests == [], b.requests


# keys the page treats specially, mixed with arbitrary ones
_keys = st.sampled_from(["pinion_rotation_rad", "pinion_rotation_deg", "transmission_error_arcsec", "load_share",
                         "pair_names", "status", "reason", "passes", "warnings", "checks", "failed_analyses", "units",
                         "descriptions", "z1", "z2"]) | st.text(max_size=10)
_json = st.recursive(
    st.none() | st.booleans() | st.integers(-10**6, 10**6) | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=12),
    lambda inner: st.lists(inner, min_size=3, max_size=4) | st.lists(inner, max_size=3)
    | st.dictionaries(_keys, inner, max_size=6),
    max_leaves=40)


@settings(max_examples=80, deadline=None, derandomize=True)
@given(st.dictionaries(st.sampled_from(["blank", "tca", "ltca", "flanks", "files", "title", "x_mm", "other"]) |
                       st.text(max_size=8), _json, max_size=6))
def test_any_json_report_renders(report):
    # whatever the report's shape (keys renamed, lists of lists, odd types), the page is written, all sections closed
    html = render_report_html(report)
    assert html.count("<section") == html.count("</section>") == len(SECTIONS) + 4
