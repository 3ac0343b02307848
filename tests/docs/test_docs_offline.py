"""The documentation site loads nothing from the network: MathJax is bundled (docs/javascripts/mathjax) and typesets
the TeX of the pages in a real headless Chromium, served over the loopback interface."""

import functools
import http.server
import os
import re
import sys
import threading
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MATHJAX = ROOT / "docs" / "javascripts" / "mathjax"
sys.path.insert(0, str(ROOT / "tests" / "io"))
from _chromium import Browser, chromium_path  # noqa: E402


def test_site_config_names_no_remote_resource():
    config = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    block = config.split("extra_javascript:", 1)[1].split("\n\n", 1)[0]
    assert not re.search(r"https?:", block.split("plugins:")[0]), block
    assert re.search(r"^\s*font:\s*false", config, re.M)  # the theme's web fonts come from a CDN otherwise
    for name in ("tex-chtml.js", "LICENSE", "output/chtml/fonts/woff-v2/MathJax_Main-Regular.woff"):
        assert (MATHJAX / name).is_file(), name


_PAGE = """<!DOCTYPE html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<script src="mathjax.js"></script><script src="mathjax/tex-chtml.js"></script></head><body>
<p><span class="arithmatex">\\(\\psi = (\\varphi - \\phi)\\sin\\delta\\)</span></p>
<div class="arithmatex">\\[ \\rho(\\phi) = \\rho_0\\, e^{\\phi \\sin\\delta \\cot\\beta} \\tag{S2} \\]</div>
</body></html>"""


def test_bundled_mathjax_typesets_offline(tmp_path):
    pytest.importorskip("websocket")
    if chromium_path() is None:
        if os.environ.get("CI"):
            pytest.fail("CI installs Chromium (.ci/run): it is missing")
        pytest.skip("no Chromium on this machine")
    # the site's layout: the page beside javascripts/ (mathjax.js configures, the bundle typesets); the config
    # script calls mkdocs-material's document$, which this bare page stands in for
    site = tmp_path / "site"
    (site / "javascripts").mkdir(parents=True)
    (site / "javascripts" / "mathjax").symlink_to(MATHJAX, target_is_directory=True)
    config = (ROOT / "docs" / "javascripts" / "mathjax.js").read_text(encoding="utf-8")
    stub = "window.document$ = {subscribe: function (f) { window.addEventListener('load', f); }};\n"
    (site / "javascripts" / "mathjax.js").write_text(stub + config, encoding="utf-8")
    (site / "javascripts" / "index.html").write_text(_PAGE, encoding="utf-8")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        with Browser(width=800, height=400) as b:
            b.call("Network.enable")
            b.load(f"http://127.0.0.1:{server.server_address[1]}/javascripts/index.html")
            deadline = time.monotonic() + 15
            n = 0
            while time.monotonic() < deadline:
                n = b.evaluate("document.querySelectorAll('mjx-container').length")
                if n == 2 and b.evaluate("document.fonts.status") == "loaded":
                    break
                time.sleep(0.1)
            assert n == 2
            assert b.evaluate("document.body.innerText.includes('(S2)')")  # \tag (AMS) is in the bundle
            assert b.errors == [], b.errors
            remote = [u for u in b.requests if not u.startswith("http://127.0.0.1:")]
            assert remote == [], remote
    finally:
        server.shutdown()
        server.server_close()
