"""The built HTML book as a reader meets it, in a real headless Chromium.

Runs after the book is built (``jupyter-book build .``); skips when there is no
``_build/html`` or no Chromium. Pages are served from 127.0.0.1 (MathJax and the theme load
their files by script, which ``file://`` pages may block). Screenshots of every page are kept in
``_build/screenshots/`` as test artifacts (never committed).
"""

from __future__ import annotations

import functools
import http.server
import re
import shutil
import subprocess
import tempfile
import threading
from html.parser import HTMLParser
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HTML = ROOT / "_build" / "html"
SHOTS = ROOT / "_build" / "screenshots"
CHROMIUM = next((shutil.which(c) for c in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(c)), None)

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(not (HTML / "index.html").is_file(), reason="book not built"),
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium (apt-get install chromium)"),
]


def _toc_pages():
    return re.findall(r"(?:root|file):\s*(\S+)", (ROOT / "_toc.yml").read_text())


@pytest.fixture(scope="module")
def server():
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(HTML))
    handler.log_message = lambda *a, **k: None
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    t = threading.Thread(target=httpd.serve_forever, daemon=True)
    t.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()


def _chromium(*args, timeout=120):
    profile = tempfile.mkdtemp(prefix="tb-chromium-")
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
           "--no-first-run", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", f"--user-data-dir={profile}", "--virtual-time-budget=20000", *args]
    try:
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    finally:
        shutil.rmtree(profile, ignore_errors=True)


class _Page(HTMLParser):
    """Collects what the checks need from a rendered DOM."""

    def __init__(self):
        super().__init__()
        self.mathjax = 0           # typeset formulas (MathJax 2 wraps each in span.MathJax)
        self.raw_math = 0          # math spans left untypeset
        self.images = 0
        self.nav = []              # hrefs of the left navigation, in order
        self.cells = []            # per code cell: (has_widget, has_image)
        self.tracebacks = 0
        self.raw_tables = 0        # markdown table rows shown as text (outside code)
        self._code = 0
        self._in_nav = 0
        self._cell_depth = None
        self._depth = 0
        self._cell = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        cls = a.get("class", "") or ""
        self._depth += 1
        if tag in ("pre", "code", "script"):
            self._code += 1
        if tag == "span" and re.search(r"\bMathJax\b", cls):
            self.mathjax += 1
        if tag == "img":
            self.images += 1
            if self._cell is not None:
                self._cell[1] = True
        if "bd-docs-nav" in cls or a.get("id") == "bd-docs-nav":
            self._in_nav = self._depth
        if self._in_nav and tag == "a" and a.get("href"):
            self.nav.append(a["href"])
        if tag == "div" and "cell_output" in cls:
            self._cell = [False, False]
            self._cell_depth = self._depth
            self.cells.append(self._cell)
        if self._cell is not None and ("jupyter-widgets" in cls or "widget-view" in cls
                                       or a.get("type") == "application/vnd.jupyter.widget-view+json"):
            self._cell[0] = True
        if "traceback" in cls or "ansi-red-intense" in cls or "output_error" in cls:
            self.tracebacks += 1

    def handle_endtag(self, tag):
        if tag in ("pre", "code", "script") and self._code:
            self._code -= 1
        if self._in_nav and self._depth == self._in_nav:
            self._in_nav = 0
        if self._cell is not None and self._depth == self._cell_depth:
            self._cell = None
        self._depth -= 1

    def handle_data(self, data):
        if "Traceback (most recent call last)" in data:
            self.tracebacks += 1
        # a separator row |---| (smartquotes turn "---" into an em dash in rendered text)
        if not self._code and re.search(r"\|\s*(?:-{3,}|[\u2014\u2013]+)\s*\|", data):
            self.raw_tables += 1


def _render(server, page):
    dom = _chromium("--dump-dom", f"{server}/{page}.html").stdout
    p = _Page()
    p.feed(dom)
    return p, dom


@pytest.mark.parametrize("page", _toc_pages())
def test_page_renders(server, page):
    p, dom = _render(server, page)
    assert "</html>" in dom, f"{page} did not load"
    assert p.tracebacks == 0, f"{page} shows a traceback"
    assert p.raw_tables == 0, f"{page} shows a markdown table as raw text"
    src = (ROOT / f"{page}.md").read_text()
    if re.search(r"\$[^$\n]+\$|\$\$", src):
        assert p.mathjax > 0, f"{page} has maths that MathJax did not typeset"
        assert "\\(" not in re.sub(r"<script.*?</script>", "", dom, flags=re.S), \
            f"{page} still shows raw \\( \\) maths"
    if "{code-cell}" in src and ("plt." in src or "viz." in src):
        assert p.images > 0, f"{page} has plotting cells but no figure"
    for has_widget, has_image in p.cells:
        if has_widget:
            assert has_image, f"{page}: a widget cell shows no static figure"
    SHOTS.mkdir(parents=True, exist_ok=True)
    _chromium("--window-size=1280,2000", f"--screenshot={SHOTS / (Path(page).name + '.png')}",
              f"{server}/{page}.html")
    assert (SHOTS / (Path(page).name + ".png")).stat().st_size > 10_000


def test_navigation_lists_chapters_in_order(server):
    p, _ = _render(server, "book/00_introduction")
    listed = [re.sub(r"(\.html)?(#.*)?$", "", h).split("/")[-1] for h in p.nav]
    pages = [Path(f).name for f in _toc_pages()][1:]    # the root is the home page
    order = [listed.index(name) for name in pages if name in listed]
    assert len(order) == len(pages), f"navigation misses {set(pages) - set(listed)}"
    assert order == sorted(order), "navigation is not in the order of _toc.yml"
    chapters = [n for n in pages if re.match(r"\d\d_", n)]
    assert chapters == sorted(chapters), "chapters are not numbered in order"
