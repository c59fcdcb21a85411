"""The built HTML book as a reader meets it, in a real headless Chromium.

Runs after the book is built (``jupyter-book build .``); skips when there is no
``_build/html`` or no Chromium. ``TRACKBOOK_BOOK_HTML=/path/to/_build/html`` points the
playground and offline checks at another build (e.g. a one-page throwaway book); the checks of
the book's own pages then skip. The playground's static page is also checked without any book
build (``test_static_playground_*``). Pages are served from 127.0.0.1 (MathJax and the theme load
their files by script, which ``file://`` pages may block). Screenshots of every page are kept in
``_build/screenshots/`` as test artifacts (never committed). The checks that read a page over
http read the one visit of it that ``_book_pages.py`` makes for them and for
``test_browser_reading.py``.
"""

from __future__ import annotations

import json
import os
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from . import _toc
from ._book_pages import (assert_offline, font_check, open_watched, own_weight, playground_fails,
                          serve)
from ._playground_browser import CHROMIUM, exercise, settle, watch_errors

ROOT = Path(__file__).resolve().parents[1]
OTHER_HTML = os.environ.get("TRACKBOOK_BOOK_HTML")
HTML = Path(OTHER_HTML) if OTHER_HTML else ROOT / "_build" / "html"
SHOTS = ROOT / "_build" / "screenshots"
BUILT = (HTML / "index.html").is_file()
needs_build = pytest.mark.skipif(not BUILT, reason="book not built")
own_book = pytest.mark.skipif(not BUILT or bool(OTHER_HTML),
                              reason="book not built (or another build was given)")

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium (apt-get install chromium)"),
]


def _toc_pages():
    return _toc.files()


@pytest.fixture(scope="module")
def server():
    httpd, url = serve(HTML)
    yield url
    httpd.shutdown()


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


def _parsed(v):
    """The visit's DOM read by :class:`_Page`."""
    p = _Page()
    p.feed(v.dom)
    return p


# The page's checks read its one visit over http (tests/_book_pages.py): the DOM once MathJax
# has typeset it, at the screenshot's 1280 px, a reader's window, and the screenshot of the same
# load (the page was once loaded a second time for these, by a chromium --dump-dom of its own).
@own_book
@pytest.mark.parametrize("page", _toc_pages())
def test_page_renders(browser, book_visits, server, page):
    v = book_visits(browser, server, HTML, f"{page}.html")
    SHOTS.mkdir(parents=True, exist_ok=True)
    shot = SHOTS / (Path(page).name + ".png")
    shot.write_bytes(v.shot)
    p, dom = _parsed(v), v.dom
    assert "</html>" in dom, f"{page} did not load"
    assert p.tracebacks == 0, f"{page} shows a traceback"
    assert p.raw_tables == 0, f"{page} shows a markdown table as raw text"
    src = (ROOT / f"{page}.md").read_text()
    if re.search(r"\$[^$\n]+\$|\$\$", src):
        assert p.mathjax > 0, f"{page} has maths that MathJax did not typeset"
        assert "\\(" not in re.sub(r"<script.*?</script>", "", dom, flags=re.S), \
            f"{page} still shows raw \\( \\) maths"
    # a page that draws (matplotlib or a trackbook.viz figure; the table helpers are text)
    draws = re.search(r"plt\.|viz\.(?!departures_table\b|covariance import markdown_table\b)\w",
                      src)
    if "{code-cell}" in src and draws:
        assert p.images > 0, f"{page} has plotting cells but no figure"
    for has_widget, has_image in p.cells:
        if has_widget:
            assert has_image, f"{page}: a widget cell shows no static figure"
    assert shot.stat().st_size > 10_000


@own_book
def test_navigation_lists_chapters_in_order(browser, book_visits, server):
    p = _parsed(book_visits(browser, server, HTML, "book/00_introduction.html"))
    listed = [re.sub(r"(\.html)?(#.*)?$", "", h).split("/")[-1] for h in p.nav]
    pages = [Path(f).name for f in _toc_pages()][1:]    # the root is the home page
    order = [listed.index(name) for name in pages if name in listed]
    assert len(order) == len(pages), f"navigation misses {set(pages) - set(listed)}"
    assert order == sorted(order), "navigation is not in the order of _toc.yml"


# ---- the playgrounds: live offline, from disk and over http ---------------------------------

def _pages_of(html_dir: Path):
    return sorted(str(p.relative_to(html_dir)) for p in html_dir.rglob("*.html")
                  if "_static" not in p.parts and "_sources" not in p.parts
                  and p.name not in ("genindex.html", "search.html"))


def _check_page(browser, url, root_dir: Path = HTML, base: str | None = None):
    """Open ``url``; every playground answers its knobs, frame slider and play button, every
    clip x tracker pair has its knobs, whole-clip runs and the spread over seeds, and it fits
    the column at 1280 px and at 390 px; the page loads at most 1.5 MB of its own (HTML,
    figures, playground files; the theme's shared files aside) before the reader touches it;
    no request leaves the machine; no script error."""
    o = open_watched(browser, url)
    try:
        fails, n = playground_fails(o.page, own_weight(list(o.loaded), root_dir, base), walk=True)
    finally:
        o.page.close()
    assert_offline(url, o.blocked, o.errors, fails)
    return n


#: every page of the build, one case each (so xdist spreads them over its workers and a
#: failure names its page); empty when the book is not built (the test then skips)
BUILT_PAGES = _pages_of(HTML) if BUILT else []


@needs_build
@pytest.mark.parametrize("rel", BUILT_PAGES)
@pytest.mark.parametrize("scheme", ["file", "http"])
def test_built_pages_offline_and_playgrounds_live(browser, book_visits, server, scheme, rel):
    """From file:// the whole check of :func:`_check_page`. Over http the same, except the
    walk through every knob, sampled value, choice, frame slider and play button: the two
    schemes differ only in how the page and its files arrive (the theme's and MathJax's
    scripts, the playgrounds' run and frame files by <script> tag, which Chromium treats more
    strictly from file://), and over http that is checked on every file the playgrounds load
    at first and on the run and first frames of every clip x tracker pair (the pair walk, under
    a second); what the walk then checks is the viewer's code drawing the same run files,
    which arrive through the same loader in both schemes and differ in nothing once there."""
    if scheme == "file":
        seen = _check_page(browser, (HTML / rel).as_uri(), HTML, None)
    else:
        v = book_visits(browser, server, HTML, rel)
        assert_offline(v.url, v.blocked, v.errors, v.fails)
        seen = v.playgrounds
    src = ROOT / Path(rel).with_suffix(".md")
    if not OTHER_HTML and src.is_file() and "Playground(" in src.read_text():
        assert seen > 0, f"{rel}: the chapter calls Playground but the page has no .tb-playground"


def _korean_quote_page():
    """The smallest built page with a quote in Korean, and that quote's key (None, None when
    no page has one)."""
    from trackbook import quotes

    for rel in sorted(BUILT_PAGES, key=lambda r: (HTML / r).stat().st_size):
        for key in re.findall(r'class="tb-quote[^"]*"[^>]*data-quote="([^"]+)"',
                              (HTML / rel).read_text(encoding="utf-8")):
            if quotes.quote(key).language == "ko":
                return rel, key
    return None, None


@needs_build
@pytest.mark.parametrize("scheme", ["file", "http"])
def test_korean_quote_drawn_with_the_shipped_font(browser, server, scheme):
    """The book ships its Korean font (``_static/korean-font.css``): on a page with a quote in
    Korean, once its popover is open, the face is fetched from the book's ``_static/fonts``
    and loaded, every Korean character of the passage is drawn with it and its Latin text
    with the theme's font, from file:// as over http (no system font needed)."""
    rel, key = _korean_quote_page()
    if rel is None:
        assert OTHER_HTML, "no page of the book shows a quote in Korean"
        pytest.skip("no page of this build shows a quote in Korean")
    seen = font_check(browser, HTML.as_uri() if scheme == "file" else server, rel, key)
    assert not seen["problems"], f"{rel}, quote {key}: {seen['problems']}"


@pytest.fixture(scope="module")
def static_page(made_once):
    """One small playground's static page (as the book shows it: its run and frame files
    copied beside it by the Sphinx extension), without a book build; made once for the test
    run, whichever workers run its tests (its runs take a minute on a busy machine)."""
    return made_once("static-playground", _make_static_page) / "site"


def _make_static_page(d):
    """Write the page into ``d / "site"`` and its runs into ``d / "store"``."""
    from playground_export.export import STATIC_BASE, static_html
    from playground_export.static import OUT_ENV
    from sphinx_playground import STATIC_DIR, copy_files
    from trackbook.widgets import Playground

    mp = pytest.MonkeyPatch()
    mp.setenv(OUT_ENV, str(d / "store"))
    try:
        pg = Playground(clips=["red-cube", "yellow-ball"], trackers=["color-pf", "mean-shift"],
                        params=["n_particles", "resampler"], n_frames=30,
                        samples={"n_particles": [10, 100, 300]})
        body = static_html(pg, workers=1).replace(STATIC_BASE, STATIC_DIR + "/")
        (d / "site").mkdir()
        (d / "site" / "index.html").write_text(
            '<!doctype html><html><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1"></head>'
            f'<body style="margin:0 auto;max-width:688px">{body}</body></html>', encoding="utf-8")
        assert copy_files(d / "site") > 0
    finally:
        mp.undo()


@pytest.mark.parametrize("scheme", ["file", "http"])
def test_static_playground_answers(browser, static_page, scheme):
    httpd, base = serve(static_page)
    try:
        url = (static_page / "index.html").as_uri() if scheme == "file" else f"{base}/index.html"
        assert _check_page(browser, url, static_page, base) == 1
    finally:
        httpd.shutdown()


def test_static_playground_loads_runs_on_demand(browser, static_page):
    """The page holds no run: the first pair's run and frames arrive as files, a knob's run
    when the reader picks it; the IoU band and the spread over three seeds are drawn."""
    page = browser.new_page()
    asked = []
    page.on("request", lambda r: asked.append(r.url.rsplit("/", 1)[-1]))
    page.goto((static_page / "index.html").as_uri(), wait_until="load")
    settle(page)
    first = [a for a in asked if a.startswith("tbpg-")]
    assert len(first) == 2, first                # the first run and the first frames
    root = page.query_selector(".tb-playground")
    assert re.search(r"AUC \d\.\d\d \(\d\.\d\d\u2013\d\.\d\d over 3 seeds",
                     root.query_selector(".tb-spread").inner_text())
    knob = root.query_selector('[data-knob="n_particles"]')
    knob.evaluate("e => { e.value = 0; e.dispatchEvent(new Event('input', {bubbles: true})); }")
    settle(page)
    assert len([a for a in asked if a.startswith("tbpg-")]) == 3
    assert "10" in root.query_selector(".tb-knob-value").inner_text()
    page.close()


def test_static_playground_ships_the_widget_module(static_page):
    from trackbook.playground import VIEWER_JS, Playground

    html = (static_page / "index.html").read_text(encoding="utf-8")
    js = re.search(r'<script type="module">(.*?)</script>', html, re.S).group(1)
    assert js.replace("<\\/script", "</script") == VIEWER_JS.read_text(encoding="utf-8")
    assert Playground._esm.default_value == js
    assert len(html.encode()) < 300_000          # the runs and frames are files of their own


@pytest.fixture(scope="module")
def cf_page(made_once):
    """A correlation filter's playground (and mean-shift's, which has no response) as the book
    shows it, without a book build; made once for the test run, whichever workers run its
    tests."""
    return made_once("cf-playground", _make_cf_page) / "site"


def _make_cf_page(d):
    """Write the page into ``d / "site"`` and its runs into ``d / "store"``."""
    from playground_export.export import STATIC_BASE, static_html
    from playground_export.static import OUT_ENV
    from sphinx_playground import STATIC_DIR, copy_files
    from trackbook.widgets import Playground

    mp = pytest.MonkeyPatch()
    mp.setenv(OUT_ENV, str(d / "store"))
    try:
        pg = Playground(clips=["yellow-ball"], trackers=["dsst", "mean-shift"], params=["eta"],
                        n_frames=16, samples={"eta": [0.01, 0.025]})
        body = static_html(pg, workers=1).replace(STATIC_BASE, STATIC_DIR + "/")
        (d / "site").mkdir()
        (d / "site" / "index.html").write_text(
            '<!doctype html><html><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1"></head>'
            f'<body style="margin:0 auto;max-width:688px">{body}</body></html>', encoding="utf-8")
        assert copy_files(d / "site") > 0
    finally:
        mp.undo()


#: per panel of the viewer (data-tb-panels, CSS px): how many pixels have the colour ``rgb``
#: (within 40 a channel) and how many distinct colours it holds
PANEL_PIXELS = """([root, name, rgb]) => {
  const p = JSON.parse(root.getAttribute('data-tb-panels'))[name];
  if (!p) return null;
  const c = root.querySelector('canvas'), k = c.width / parseFloat(c.style.width);
  const d = c.getContext('2d').getImageData(Math.round(p.x * k), Math.round(p.y * k),
                                            Math.round(p.w * k), Math.round(p.h * k)).data;
  let hits = 0; const seen = new Set();
  for (let i = 0; i < d.length; i += 4) {
    if (Math.abs(d[i] - rgb[0]) < 40 && Math.abs(d[i + 1] - rgb[1]) < 40 &&
        Math.abs(d[i + 2] - rgb[2]) < 40) hits++;
    seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
  }
  return [hits, seen.size];
}"""


@pytest.mark.parametrize("width", [1280, 390])
@pytest.mark.parametrize("scheme", ["file", "http"])
def test_correlation_filter_playground_draws_confidence_and_response(browser, cf_page, scheme,
                                                                     width):
    """DSST's run: the confidence curve is drawn in its colour beside the IoU curve, and the
    response inset holds a heat map (many colours) on a frame past the first; mean-shift's run
    keeps the curve and has no inset."""
    from trackbook.style import VIEWER

    httpd, base = serve(cf_page)
    try:
        url = (cf_page / "index.html").as_uri() if scheme == "file" else f"{base}/index.html"
        page = browser.new_page(viewport={"width": width, "height": 900})
        errors, missing = [], []
        watch_errors(page, errors)
        # a 404 is told by URL (the console's message has none; the browser asks for a favicon)
        page.on("response", lambda r: missing.append(r.url) if r.status >= 400
                and not r.url.endswith("favicon.ico") else None)
        page.goto(url, wait_until="load")
        settle(page)
        root = page.query_selector(".tb-playground")
        page.wait_for_timeout(300)
        fr = root.query_selector("[data-frame]")
        fr.evaluate("e => { e.value = 8; e.dispatchEvent(new Event('input', {bubbles: true})); }")
        conf_rgb = [int(VIEWER["conf"][i:i + 2], 16) for i in (1, 3, 5)]
        conf = page.evaluate(PANEL_PIXELS, [root, "conf", conf_rgb])
        resp = page.evaluate(PANEL_PIXELS, [root, "resp", [0, 0, 0]])
        assert conf is not None and conf[0] > 30, conf            # the curve's pixels
        assert resp is not None and resp[1] > 12, resp            # a heat map, not a blank
        assert "confidence" in root.query_selector(".tb-frame-label").inner_text()
        width_px = page.evaluate("() => document.documentElement.scrollWidth")
        assert width_px <= width, "the playground must not widen the page"
        sel = root.query_selector('[data-control="tracker"]')
        sel.select_option("mean-shift")
        settle(page)
        page.wait_for_timeout(100)
        assert page.evaluate(PANEL_PIXELS, [root, "resp", [0, 0, 0]]) is None
        assert page.evaluate(PANEL_PIXELS, [root, "conf", conf_rgb])[0] > 30
        assert not missing, missing
        assert not [e for e in errors if "Failed to load resource" not in e], errors
        page.close()
    finally:
        httpd.shutdown()


def test_partial_run_shows_progress_and_never_a_blank_frame(browser, tmp_path):
    """A run payload with n_done < n_total (the Jupyter widget streams them): the slider spans
    the whole clip, the scores line says how far the run is, and past n_done the frame is
    drawn with the previous complete run's box (greyed) instead of nothing."""
    import json

    from trackbook import clips
    from trackbook.playground import VIEWER_JS
    from trackbook.playground import data as D
    from trackbook.style import VIEWER

    clip = clips.load("red-cube")
    full = D.run_payload("mean-shift", clip, {}, 20)[0]
    shifted = [[b[0] + 30, b[1], b[2], b[3]] for b in full["boxes"]]   # another run's boxes
    partial = {**full, "boxes": shifted[:5], "ok": full["ok"][:5], "iou": full["iou"][:5],
               "n_done": 5, "n_total": 20, "state": {}}
    cfg = {"clips": [{"key": "c", "name": clip.name}], "trackers": ["mean-shift"],
           "knobs": {"mean-shift": []}, "colors": VIEWER}
    host = """
const root = document.getElementById('pg');
let run = @FULL@;
const host = { live: true, config: () => (@CFG@), clipKey: () => 'c', tracker: () => 'mean-shift',
  clip: () => (@CLIP@), run: () => run, knobs: () => [], value: () => undefined,
  sampled: () => true, note: () => '', status: () => '', setClip() {}, setTracker() {},
  setKnob() {}, setBox() {} };
const v = new Viewer(root, host);
v.update();
window.__v = v;
window.__setRun = (r) => { run = r; v.update(); };
"""
    values = {"FULL": full, "CFG": cfg, "CLIP": D.clip_payload(clip, 20)}
    host = re.sub(r"@(\w+)@", lambda m: json.dumps(values[m.group(1)]), host)   # one pass
    (tmp_path / "index.html").write_text(
        '<!doctype html><html><body><div id="pg"></div><script type="module">'
        + VIEWER_JS.read_text(encoding="utf-8") + host + "</script></body></html>",
        encoding="utf-8")
    page = browser.new_page()
    errors = []
    watch_errors(page, errors)
    page.goto((tmp_path / "index.html").as_uri(), wait_until="load")
    page.wait_for_timeout(300)
    assert not errors and page.evaluate("() => !!window.__v"), errors
    page.evaluate("(p) => window.__setRun(p)", partial)
    scores = page.inner_text(".tb-scores")
    assert scores.startswith("running\u2026 5/20"), scores
    assert page.eval_on_selector("[data-frame]", "e => +e.max") == 19
    pixels = """() => { const c = document.querySelector('canvas');
        return c.getContext('2d').getImageData(0, 0, c.width, c.height).data.join(','); }"""
    page.evaluate("() => window.__v.seek(12)")
    with_previous = page.evaluate(pixels)
    page.evaluate("() => { window.__v.lastFull = null; window.__v.seek(12); }")
    without = page.evaluate(pixels)
    assert with_previous != without         # frame 12: the previous run's box is drawn
    assert len(set(without.split(",")[:4000])) > 8     # and the frame itself, not a blank
    page.close()


def test_book_animation_loads_its_frames_and_runs_from_files(browser, tmp_path, monkeypatch):
    """In the book build an animation's inline runs and frames become files beside the page
    (its HTML stays small), and the viewer draws and steps through them as before."""
    from playground_export import page_bundle
    from playground_export.export import STATIC_BASE
    from playground_export.static import OUT_ENV
    from sphinx_playground import STATIC_DIR, copy_files
    from trackbook.playground.animations import kalman_ball

    monkeypatch.setenv(OUT_ENV, str(tmp_path / "store"))
    a = kalman_ball(n_frames=40)
    inline = len(json.dumps(a.static_data))
    body = page_bundle(a)[0]["text/html"]       # as a chapter's kernel in the build shows it
    assert '"runs"' not in body and "data:image/png" not in body
    assert len(body) < inline / 3 and len(body) < 60_000
    site = tmp_path / "site"
    site.mkdir()
    (site / "index.html").write_text(
        '<!doctype html><html><head><meta charset="utf-8"></head><body style="max-width:688px">'
        + body.replace(STATIC_BASE, STATIC_DIR + "/") + "</body></html>", encoding="utf-8")
    assert copy_files(site) >= 3                       # runs, frames, the picture
    page = browser.new_page()
    errors = []
    watch_errors(page, errors)
    page.goto((site / "index.html").as_uri(), wait_until="load")
    settle(page)
    root = page.query_selector(".tb-playground")
    fails = exercise(page, root)
    assert not errors and not fails, (errors, fails)
    page.close()
