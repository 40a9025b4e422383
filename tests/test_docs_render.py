"""The built documentation renders offline in a real browser: formulas typeset, images loaded.

Headless Chromium (Debian's ``chromium``) opens pages of the built site
(``docs/_build/html``, or the directory in ``MICROIMPACT_DOCS_HTML``) from
``file://`` with background networking disabled, lets the page's scripts run
for a budget of virtual time, and prints the DOM as it then stands
(``--dump-dom``). The theory page must come out with its math typeset by the
MathJax copy served from ``_static/mathjax`` (no CDN): no raw ``\\(`` or
``\\[`` delimiters left, one ``mjx-container`` per formula, and no MathJax
error nodes. The gallery page must show its figure: every ``<img>`` whose file
exists, with a nonzero natural size once loaded (checked by a small script
injected before the DOM is dumped).

Skipped, with the reason, when Chromium or a built site is missing (CI builds
the site first and installs Chromium: see ``.ci/run``).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = Path(os.environ.get("MICROIMPACT_DOCS_HTML", ROOT / "docs" / "_build" / "html"))
CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)

pytestmark = [
    pytest.mark.skipif(CHROMIUM is None, reason="no chromium on PATH (apt-get install -y chromium)"),
    pytest.mark.skipif(
        not (SITE / "theory.html").is_file(),
        reason=f"no built site at {SITE} (sphinx-build -b html docs docs/_build/html first)",
    ),
]

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-extensions",
    "--allow-file-access-from-files",
]


def dump_dom(page: Path, budget_ms: int = 20000) -> str:
    """The DOM of ``page`` after its scripts ran for ``budget_ms`` of virtual time."""
    with tempfile.TemporaryDirectory() as profile:
        proc = subprocess.run(
            [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", f"--virtual-time-budget={budget_ms}", "--dump-dom"]
            + [page.as_uri()],
            capture_output=True,
            text=True,
            timeout=180,
        )
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout


@pytest.fixture(scope="module")
def theory_dom() -> str:
    return dump_dom(SITE / "theory.html")


def test_theory_math_is_typeset(theory_dom):
    source = (SITE / "theory.html").read_text()
    # what the page asks MathJax to do: inline \( ... \) and display \[ ... \] / math blocks
    n_inline = source.count("\\(")
    n_display = source.count("\\[")
    assert n_inline + n_display >= 250, "the theory page holds 261 formulas"
    # served from the site itself, not a CDN
    assert re.search(r'<script[^>]+src="_static/mathjax/tex-chtml\.js[?"]', source)
    assert not re.search(r'<script[^>]+src="https?://', source)

    # after rendering: every formula became an mjx-container and no TeX source is left
    assert "\\(" not in theory_dom, "raw \\( left in the rendered page: MathJax did not run"
    assert "\\[" not in theory_dom
    containers = theory_dom.count("<mjx-container")
    assert containers >= n_inline + n_display, (containers, n_inline, n_display)
    assert "<mjx-merror" not in theory_dom, "MathJax reported a TeX error"
    assert theory_dom.count("<mjx-math") >= containers  # typeset output (CommonHTML), not just the wrappers


_IMAGE_PROBE = """
<script>
window.addEventListener("load", () => {
  const bad = [...document.images].filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.src);
  const out = document.createElement("pre");
  out.id = "image-probe";
  out.textContent = JSON.stringify({n: document.images.length, bad: bad});
  document.body.appendChild(out);
});
</script>
"""


def _probe(page: Path) -> dict:
    """Load ``page`` (a copy beside it with the probe script) and return what the probe saw."""
    import json

    html = page.read_text().replace("</body>", _IMAGE_PROBE + "</body>")
    copy = page.with_name(f".probe-{os.getpid()}-{page.name}")
    tmp = copy.with_name(copy.name + ".tmp")
    tmp.write_text(html)
    tmp.rename(copy)
    try:
        dom = dump_dom(copy, budget_ms=10000)
    finally:
        copy.unlink()
    m = re.search(r'<pre id="image-probe">(.*?)</pre>', dom, re.S)
    assert m, "the page did not finish loading"
    return json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))


@pytest.mark.parametrize(
    "page, at_least",
    [("gallery/paper/plot_fig02_restitution.html", 1), ("gallery/index.html", 13), ("theory.html", 0)],
)
def test_images_load(page, at_least):
    seen = _probe(SITE / page)
    assert seen["bad"] == [], f"images that did not load: {seen['bad']}"
    assert seen["n"] >= at_least, seen
