"""Each page of the built book opened once over http, for every check that reads it there.

Opening a page is most of what the browser checks cost, and it is CPU: Chromium lays the page
out and MathJax typesets every formula (two to three seconds for a chapter, about twenty for the
exercises appendix). The checks of ``test_browser.py`` (the page renders; it loads, stays on the
machine and its playgrounds load their files over http) and of ``test_browser_reading.py``
(everything fits the 1280 px column, the sidebar, the exercises' outputs) all read a page as
served over http in a 1280 px window, so :func:`visit` opens it once and gathers what each of
them reads, in an order that leaves every reading as it was when each check loaded the page
itself (the column is measured before any playground control is touched). The tests assert on
the visit, one test per check and page, so a failure still names both.

:class:`Visits` shares a visit with the whole test run, xdist workers included: the first
worker to need a page visits it and leaves the visit in a folder of the run, where the other
workers read it (one that needs a page while another visits it waits for that visit). So the
tests need no xdist grouping, which ``--dist loadgroup`` no longer does under pytest 9.2
(pytest-dev/pytest-xdist#1386: the tests are spread as if the marks were not there).
"""

from __future__ import annotations

import functools
import hashlib
import http.server
import pickle
import re
import threading
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urlparse

from ._playground_browser import check_pairs, exercise, local_only, overflow, settle, watch_errors

try:
    import fcntl
except ImportError:         # Windows: each test process makes its own visits
    fcntl = None

#: most bytes a chapter page may load before the reader touches it
MAX_FIRST_LOAD = 1_500_000
#: the widths the playground must fit: a laptop's window and a phone's
WIDTHS = (1280, 390)
#: the window of the screenshot kept for every page (a reader's first two screens)
SHOT_WINDOW = (1280, 2000)


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):      # no line on stderr for each of a page's ~100 requests
        pass


def serve(directory):
    """An http server of ``directory`` on 127.0.0.1 in a thread: (server, base url)."""
    handler = functools.partial(_QuietHandler, directory=str(directory))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    t = threading.Thread(target=httpd.serve_forever, daemon=True)
    t.start()
    return httpd, f"http://127.0.0.1:{httpd.server_address[1]}"


# ---- opening a page as the offline checks do ------------------------------------------------

@dataclass
class Opened:
    """A page opened with its error, off-machine and request watchers."""
    page: object
    url: str
    errors: list = field(default_factory=list)
    blocked: list = field(default_factory=list)
    loaded: list = field(default_factory=list)


def open_watched(browser, url) -> Opened:
    """Open ``url`` in a 1280 px window, every script error and request recorded and every
    request off the machine refused, and wait until the playgrounds' first files arrived."""
    page = browser.new_page(viewport={"width": WIDTHS[0], "height": 900})
    o = Opened(page, url)
    watch_errors(page, o.errors)
    local_only(page, o.blocked)
    page.on("request", lambda r: o.loaded.append(r.url))
    resp = page.goto(url, wait_until="load", timeout=60_000)
    # index.html only redirects (a meta refresh, after its load, later on a busy machine):
    # wait until the page it leads to has loaded before anything reads the page
    try:
        first = resp.text() if resp is not None else ""
    except Exception:      # noqa: BLE001  a body the browser no longer holds: read the file
        first = ""
    if not first and url.startswith("file://"):
        first = Path(unquote(urlparse(url).path)).read_text(encoding="utf-8", errors="ignore")
    redirects = bool(re.search(r"http-equiv=\W?refresh", first, re.I))
    if not redirects:
        # the body can be gone over http too: ask the page itself whether it still is the
        # redirect (a destroyed context means the redirect is already under way)
        try:
            redirects = page.query_selector('meta[http-equiv="refresh" i]') is not None
        except Exception:  # noqa: BLE001
            redirects = True
    if redirects:
        if page.url == url:
            page.wait_for_url(lambda u: u != url, timeout=60_000)
        page.wait_for_load_state("load")
        # and until the document is the book's page: once (CI, a busy machine) the checks
        # still read the redirect's own document after the waits above
        wait_for_article(page)
    page.wait_for_timeout(300)
    settle(page)
    return o


def wait_for_article(page, tries: int = 5) -> None:
    """Wait until the page's document has loaded and holds the book's article (or ``main``);
    a navigation still under way destroys the context the wait runs in, so it is tried again."""
    for i in range(tries):
        try:
            page.wait_for_function(
                "() => document.readyState === 'complete'"
                " && !!document.querySelector('article.bd-article, main')",
                timeout=60_000)
            return
        except Exception as e:  # noqa: BLE001 -- a context destroyed by the navigation
            if i == tries - 1 or "destroyed" not in str(e).lower():
                raise
            page.wait_for_load_state("load")


def _local_file(url, root: Path, base: str | None):
    """The file on disk behind a request of the page (None for data: and the like)."""
    u = urlparse(url)
    if u.scheme == "file":
        return Path(unquote(u.path))
    if base and url.startswith(base):
        return root / unquote(u.path).lstrip("/")
    return None


def own_weight(loaded, root_dir: Path, base: str | None) -> int:
    """Bytes of the page's own files among the requests ``loaded`` so far."""
    files = {f for f in {_local_file(u, root_dir, base) for u in loaded}
             if f is not None and f.is_file()}
    # the theme's and MathJax's files (_static, outside _static/playground) are the same for
    # every page of the book and cached after the first: the page's own weight is the rest
    return sum(f.stat().st_size for f in files
               if not ("_static" in f.parts and "playground" not in f.parts))


def playground_fails(page, own: int, walk: bool) -> tuple[list, int]:
    """The page's weight and every playground at both widths: (failures, playgrounds).

    Every playground: every clip x tracker pair has its run (each pair's run file and each
    clip's first frames loaded as the page loads files), it fits its column at 1280 px and at
    390 px; the page loads at most ``MAX_FIRST_LOAD`` bytes of its own first. With ``walk``
    also every knob, sampled value, choice, the frame slider and play answer the reader
    (:func:`exercise`): that is the viewer's code on the same run files, whichever way they
    arrived, so one scheme walks it (see ``test_built_pages_offline_and_playgrounds_live``).
    Leaves the window at 390 px.
    """
    fails = []
    roots = page.query_selector_all(".tb-playground")
    if any(r.get_attribute("data-tb-static") is not None for r in roots) \
            and own > MAX_FIRST_LOAD:
        fails.append(f"{own} bytes of its own at first load, over {MAX_FIRST_LOAD}")
    for i, root in enumerate(roots):
        if root.query_selector("script.tb-data") and '"kind":"playground"' in \
                root.query_selector("script.tb-data").text_content():
            pair_fails, _ = check_pairs(page, root)
            fails += [f"playground {i}: {f}" for f in pair_fails]
        fails += [f"playground {i} at {WIDTHS[0]} px: {f}" for f in overflow(root)]
        if walk:
            fails += [f"playground {i}: {f}" for f in exercise(page, root)]
    page.set_viewport_size({"width": WIDTHS[1], "height": 844})
    page.wait_for_timeout(300)
    for i, root in enumerate(roots):
        fails += [f"playground {i} at {WIDTHS[1]} px: {f}" for f in overflow(root)]
    return fails, len(roots)


def assert_offline(url, blocked, errors, fails):
    """The offline check's verdict on a page: nothing off the machine, no script error, no
    playground failure."""
    assert not blocked, f"{url} requested off-machine: {blocked[:5]}"
    assert not errors, f"{url} raised: {errors[:5]}"
    assert not fails, f"{url}: {fails}"


# ---- what the reading checks measure (test_browser_reading.py) ------------------------------

#: Outputs that carry numbers must be read beside the sentence that interprets them: a printed
#: output taller than about half the 900 px window (MAX_LINES lines of 20 px) is scrolled past,
#: not read; its numbers belong in a short table, a figure or a shorter print.
MAX_LINES = 20

#: Runs in the page: every block of the article that reaches past the column, or whose content
#: is clipped inside a horizontal scroller; text outputs with numbers longer than MAX_LINES;
#: raw TeX left in the text; MathJax errors. Code *sources* (``div.highlight pre`` of an input
#: cell, and literal code blocks) may scroll; nothing else may.
MEASURE = r"""(maxLines) => {
  const art = document.querySelector('article.bd-article') || document.querySelector('main');
  const st = getComputedStyle(art), ar = art.getBoundingClientRect();
  const left = ar.left + parseFloat(st.paddingLeft), right = ar.right - parseFloat(st.paddingRight);
  const KINDS = [['playground', '.tb-playground'], ['equation', 'div.math, .MathJax_Display'],
                 ['table', 'table'], ['figure', 'figure, img, svg, canvas'],
                 ['output', '.cell_output .output, .cell_output'], ['source', '.cell_input'],
                 ['code', 'div.highlight'], ['text', 'p, li, dl, blockquote, h1, h2, h3, h4']];
  const name = (e) => {
    let s = e.tagName.toLowerCase();
    if (e.id) return s + '#' + e.id;
    const c = [...e.classList].filter(c => !/^(docutils|container|notranslate)$/.test(c));
    return s + (c.length ? '.' + c.slice(0, 2).join('.') : '');
  };
  const where = (e) => { const sec = e.closest('section'); return sec ? sec.id : ''; };
  // the playgrounds are drawn by their own widget code, checked on their own
  const owner = (e) => e.closest('.tb-playground') ? 'playground' : '';
  const blockOf = (e) => {
    // a wrapper that scrolls its one table (the theme's table container) stands for the table
    if (e.children.length === 1 && e.children[0].matches('table')) e = e.children[0];
    for (const [kind, sel] of KINDS) { const b = e.closest(sel); if (b && art.contains(b)) return [kind, b]; }
    return ['other', e];
  };
  const found = new Map();
  const offend = (e, width, how) => {
    const [kind, b] = blockOf(e);
    if (kind === 'source' || kind === 'code') return;     // code sources may scroll
    const key = b; const o = found.get(key);
    if (!o || o.width < width)
      found.set(key, {kind: kind, section: where(b), selector: name(b.parentElement) + ' > ' + name(b),
                      width: Math.round(width), column: Math.round(right - left), how: how,
                      owner: owner(b),
                      text: ((b.innerText || '').trim() || (b.textContent || b.getAttribute('alt') || '').trim())
                        .slice(0, 60).replace(/\s+/g, ' ')});
  };
  // MathJax's assistive MathML is clipped to 1 px for screen readers: never seen
  const unseen = '.cell_input, aside.margin, aside.sidebar, .MJX_Assistive_MathML, .MathJax_Preview';
  for (const e of art.querySelectorAll('*')) {
    if (e.closest(unseen)) continue;
    const r = e.getBoundingClientRect();
    if (r.width === 0 || r.height === 0) continue;       // hidden (a closed toggle, a tab)
    if (r.right > right + 1) offend(e, r.right - left, 'reaches past the column');
    const ox = getComputedStyle(e).overflowX;            // a scroller hides what is past its edge
    if ((ox === 'auto' || ox === 'scroll') && e.scrollWidth > e.clientWidth + 1)
      offend(e, e.scrollWidth, 'scrolls sideways');
  }
  // text runs past its box without moving the box's edge (MathJax clips a wide equation at
  // the column): measure the text itself
  const range = document.createRange();
  const texts = document.createTreeWalker(art, NodeFilter.SHOW_TEXT);
  for (let t = texts.nextNode(); t; t = texts.nextNode()) {
    if (!t.parentElement || t.parentElement.closest(unseen) || !t.textContent.trim()) continue;
    range.selectNodeContents(t);
    const r = range.getBoundingClientRect();
    if (r.width > 0 && r.right > right + 1) offend(t.parentElement, r.right - left, 'text past the column');
  }
  const long = [];
  for (const o of art.querySelectorAll('.cell_output .output pre')) {
    if (o.closest('.tb-playground')) continue;
    const lines = o.innerText.replace(/\n+$/, '').split('\n');
    if (lines.length > maxLines && /\d/.test(o.innerText))
      long.push({section: where(o), selector: name(o.parentElement.parentElement) + ' > pre',
                 lines: lines.length, owner: owner(o), text: lines[0].slice(0, 60)});
  }
  // raw TeX: text the reader sees outside typeset maths and code sources
  const TEX = /\\(begin|end)\{|\\(frac|tfrac|dfrac|tag|mathrm|mathbf|mathcal|operatorname|left|right|sum|prod|hat|bar|sqrt|cdot|times|alpha|beta|gamma|sigma|lambda|theta|quad|qquad|text|label|nonumber|leq|geq|approx|propto|lVert|rVert|Vert|mid)\b|\$\$|\\\[|\\\]|\\\(|\\\)|\$[^$\s][^$\n]*\\[A-Za-z]+[^$\n]*\$/;
  const raw = [];
  const skip = 'script, style, code, .MathJax, .MathJax_Display, .MathJax_Preview, .MathJax_SVG, mjx-container, .cell_input';
  const walk = document.createTreeWalker(art, NodeFilter.SHOW_TEXT);
  for (let t = walk.nextNode(); t; t = walk.nextNode()) {
    const p = t.parentElement;
    if (!p || p.closest(skip)) continue;
    if (p.closest('div.highlight') && !p.closest('.cell_output')) continue;   // a code block in prose
    const m = t.textContent.match(TEX);
    if (m) raw.push({section: where(p), selector: name(p), tex: m[0], owner: owner(p),
                     text: t.textContent.trim().slice(0, 80).replace(/\s+/g, ' ')});
  }
  const errors = [...art.querySelectorAll('.merror, .noError, .MathJax_Error, [data-mjx-error], mjx-merror')]
    .map(e => ({section: where(e), selector: name(e), owner: owner(e),
                text: (e.textContent || '').trim().slice(0, 80)}));
  // the offline MathJax ships the STIX-Web fonts without a script alphabet
  for (const e of art.querySelectorAll('script[type^="math/tex"]'))
    if (/\\mathcal\b/.test(e.textContent))
      errors.push({section: where(e), selector: name(e), owner: owner(e),
                   text: 'no offline font for \\mathcal: ' + e.textContent.trim().slice(0, 60)});
  for (const e of art.querySelectorAll('*'))
    if (!e.children.length && /Math (input|Processing) error/i.test(e.textContent))
      errors.push({section: where(e), selector: name(e), owner: owner(e),
                   text: e.textContent.trim().slice(0, 80)});
  return {wide: [...found.values()], long: long, raw: raw, errors: errors,
          column: Math.round(right - left)};
}"""

#: the sidebar's links: (href, text)
SIDEBAR = """els => els.map(a => [a.getAttribute('href') || '', a.textContent.trim()])"""

#: every cell output: its text and how many pictures or tables it holds
OUTPUTS = """() => [...document.querySelectorAll('.cell_output')]
    .map((o, i) => ({i: i, text: (o.innerText || '').trim(),
                     media: o.querySelectorAll('img, svg, canvas, iframe, table').length}))"""


def typeset(page) -> str:
    """Wait until MathJax (2.7, shipped offline) has typeset the page, where it is loaded:
    ``done``, ``no MathJax`` or ``timed out``.

    An empty queue right after the load event proves nothing (MathJax has not queued its
    typesetting yet): wait for its startup's "End" signal, sent after the first typesetting
    ("End Typeset") and delivered at once if already sent.
    """
    # The exercises appendix, the largest page, takes ~110 s to typeset alone on a 2-core
    # machine (measured in Chromium on the built page; ~35 s before 22 pen-and-paper
    # exercises were added) and longer with two browser workers sharing the cores, so the wait
    # is 360 s: how long typesetting takes is not what these checks measure.
    return page.evaluate("""() => new Promise(resolve => {
        if (!(window.MathJax && MathJax.Hub)) return resolve('no MathJax');
        setTimeout(() => resolve('timed out'), 360000);
        MathJax.Hub.Register.StartupHook('End', () => resolve('done'));
    })""")


# ---- the visit --------------------------------------------------------------------------

@dataclass
class Visit:
    """What the checks read from one page served over http (see :func:`visit`)."""
    url: str
    typeset: str = ""          # MathJax's end: done, no MathJax or timed out
    measured: dict = None      # MEASURE at 1280 px, once typeset
    sidebar: list = None       # the sidebar's links (SIDEBAR)
    outputs: list = None       # the cell outputs (OUTPUTS)
    dom: str = ""              # the DOM once typeset, before any control is touched
    shot: bytes = b""          # a PNG of the top of the page in a SHOT_WINDOW window
    fails: list = None         # the playgrounds' and the first load's failures over http
    playgrounds: int = 0       # how many .tb-playground the page shows
    errors: list = None        # script errors during the whole visit
    blocked: list = None       # requests refused for leaving the machine


def visit(browser, server: str, html_dir: Path, rel: str) -> Visit:
    """Open page ``rel`` (``book/03_hog.html``) of the build in ``html_dir``, served at
    ``server``, and read it for every check.

    In this order: open in a 1280 x 900 window, every request and script error watched
    (:func:`open_watched`); the page's own first-load weight; MathJax typesets; MEASURE, the
    sidebar, the outputs and the DOM are read; a screenshot in a SHOT_WINDOW window; then the
    playgrounds are driven over http (:func:`playground_fails` without the walk) and the
    window narrowed to 390 px, after everything else has read the page.
    """
    o = open_watched(browser, f"{server}/{rel}")
    page = o.page
    try:
        own = own_weight(list(o.loaded), Path(html_dir), server)
        wait_for_article(page)     # a redirect missed by open_watched's test is still followed
        v = Visit(o.url, typeset=typeset(page))
        v.measured = page.evaluate(MEASURE, MAX_LINES)
        v.sidebar = page.eval_on_selector_all("nav.bd-links a, .bd-sidenav a", SIDEBAR)
        v.outputs = page.evaluate(OUTPUTS)
        v.dom = page.content()
        page.set_viewport_size({"width": SHOT_WINDOW[0], "height": SHOT_WINDOW[1]})
        v.shot = page.screenshot()
        page.set_viewport_size({"width": WIDTHS[0], "height": 900})
        v.fails, v.playgrounds = playground_fails(page, own, walk=False)
        v.errors, v.blocked = list(o.errors), list(o.blocked)
    finally:
        page.close()
    return v


class Visits:
    """The run's visits: ``visits(browser, server, html_dir, rel)`` is :func:`visit` made
    once, kept in this process and, for the run's other test processes, in the folder
    ``store`` (None: in this process only).

    A visit that fails is kept in this process only and raised to each of its tests (another
    process tries the page again).
    """

    def __init__(self, store: Path | None):
        self.store, self.made = store, {}
        if store is not None:
            store.mkdir(parents=True, exist_ok=True)

    def __call__(self, browser, server: str, html_dir: Path, rel: str) -> Visit:
        key = f"{Path(html_dir).resolve()}|{rel}"
        if key not in self.made:
            try:
                self.made[key] = self._shared(key, lambda: visit(browser, server, html_dir, rel))
            except Exception as e:  # noqa: BLE001 -- raised again to every test of the page
                self.made[key] = e
        v = self.made[key]
        if isinstance(v, Exception):
            raise v
        return v

    def _shared(self, key, make):
        if self.store is None or fcntl is None:
            return make()
        path = self.store / (hashlib.sha1(key.encode()).hexdigest()[:16] + ".pickle")
        with open(path.with_suffix(".lock"), "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)        # held while this process visits the page
            if path.is_file():
                return pickle.loads(path.read_bytes())
            v = make()
            part = path.with_suffix(".part")
            part.write_bytes(pickle.dumps(v))
            part.replace(path)
            return v


# ---- the Korean font shipped with the book (test_korean_font.py, test_browser.py) ----------

#: the family ``_static/korean-font.css`` declares for ``fonts/noto-sans-kr-subset.woff``
FONT_FACE = "Noto Sans KR subset"
#: the font's own family name, which Chromium reports for the glyphs it drew with it
FONT_FAMILY = "Noto Sans KR"
#: the Unicode blocks of Korean text (inclusive): Hangul Jamo, circled digits, CJK Symbols and
#: Punctuation, Hangul Compatibility Jamo, Enclosed CJK, CJK Unified Ideographs and Extension
#: A, Hangul Jamo Extended-A, Hangul Syllables and Jamo Extended-B, CJK Compatibility
#: Ideographs, Halfwidth and Fullwidth Forms
KOREAN_BLOCKS = ((0x1100, 0x11FF), (0x2460, 0x24FF), (0x3000, 0x303F), (0x3130, 0x318F),
                 (0x3200, 0x32FF), (0x3400, 0x4DBF), (0x4E00, 0x9FFF), (0xA960, 0xA97F),
                 (0xAC00, 0xD7FF), (0xF900, 0xFAFF), (0xFF00, 0xFFEF))


def is_korean(ch: str) -> bool:
    """Whether ``ch`` lies in one of :data:`KOREAN_BLOCKS`."""
    return any(lo <= ord(ch) <= hi for lo, hi in KOREAN_BLOCKS)


#: how many characters of the element's own text nodes are Korean, and how many are not blank
_OWN_TEXT = """(el, blocks) => {
  let korean = 0, other = 0;
  for (const n of el.childNodes) {
    if (n.nodeType !== Node.TEXT_NODE) continue;
    for (const ch of n.textContent) {
      const c = ch.codePointAt(0);
      if (blocks.some(([lo, hi]) => lo <= c && c <= hi)) korean++;
      else if (ch.trim()) other++;
    }
  }
  return {korean: korean, other: other};
}"""


def _drawn_with(page, selector: str) -> list[dict]:
    """The fonts Chromium drew the own text nodes of the first element matching ``selector``
    with (DevTools' ``CSS.getPlatformFontsForNode``: each font's family name, whether it is a
    web font, how many glyphs it drew)."""
    client = page.context.new_cdp_session(page)
    try:
        client.send("DOM.enable")
        client.send("CSS.enable")
        root = client.send("DOM.getDocument", {"depth": 0})["root"]["nodeId"]
        node = client.send("DOM.querySelector", {"nodeId": root, "selector": selector})["nodeId"]
        return client.send("CSS.getPlatformFontsForNode", {"nodeId": node})["fonts"]
    finally:
        client.detach()


def _font_use(page, selector: str, what: str) -> list[str]:
    """What is wrong with how the element's own text was drawn: each of its Korean characters
    with the shipped face, the rest (Latin, digits) with another font."""
    el = page.query_selector(selector)
    if el is None:
        return [f"{what}: no {selector}"]
    count = el.evaluate(_OWN_TEXT, [list(b) for b in KOREAN_BLOCKS])
    fonts = _drawn_with(page, selector)
    ours = sum(f["glyphCount"] for f in fonts
               if f["isCustomFont"] and f["familyName"] == FONT_FAMILY)
    others = sum(f["glyphCount"] for f in fonts
                 if not (f["isCustomFont"] and f["familyName"] == FONT_FAMILY))
    problems = []
    if not count["korean"]:
        problems.append(f"{what}: no Korean text in {selector}")
    if ours != count["korean"]:
        problems.append(f"{what}: {ours} glyphs drawn with the shipped face for "
                        f"{count['korean']} Korean characters (fonts used: {fonts})")
    if count["other"] and not others:
        problems.append(f"{what}: its Latin text is drawn with the shipped face too ({fonts})")
    return problems


def font_check(browser, root: str, rel: str, key: str, prose: str | None = None) -> dict:
    """Open page ``rel`` of the book at ``root`` (a ``file:`` or ``http:`` URL), open the
    popover of quote ``key`` (a Korean passage) and read how its passage, and the page's
    element ``prose`` when given, were drawn.

    Returns ``{"faces": the statuses of the shipped face in document.fonts, "fetched": the
    font files the page loaded, "problems": [...]}``; no problem means: the face was fetched
    from the book's ``_static/fonts`` and is loaded, every Korean character of the passage
    (and of ``prose``) was drawn with it and the rest of their text with another font.
    """
    page = browser.new_page(viewport={"width": WIDTHS[0], "height": 900})
    fetched, failed, blocked = [], [], []
    try:
        local_only(page, blocked)
        page.on("response", lambda r: fetched.append(r.url)       # a 404 is no font
                if r.request.resource_type == "font" and r.ok else None)
        page.on("requestfailed", lambda r: failed.append(f"{r.url}: {r.failure}"))
        page.goto(f"{root}/{rel}", wait_until="load", timeout=60_000)
        typeset(page)                   # MathJax rewrites the passage while it typesets
        quote = f'.tb-quote[data-quote="{key}"]'
        page.focus(quote)               # a popover is laid out, and its font asked for, once open
        # lay the open popover out (which asks for the face), wait for the face, then for the
        # frame drawn with it
        page.evaluate("""(sel) => {
            document.querySelector(sel).getBoundingClientRect();
            return document.fonts.ready.then(() => new Promise(
                done => requestAnimationFrame(() => requestAnimationFrame(() => done(null)))));
        }""", f"{quote} .tb-quote-pop")
        faces = page.evaluate("""(name) => [...document.fonts]
            .filter(f => f.family.replace(/["']/g, '') === name).map(f => f.status)""",
                              FONT_FACE)
        problems = [f"failed: {f}" for f in failed] + [f"left the machine: {b}" for b in blocked]
        if faces != ["loaded"]:
            problems.append(f"the face {FONT_FACE!r} is {faces} in document.fonts, not loaded")
        if f"{root}/_static/fonts/noto-sans-kr-subset.woff" not in fetched:
            problems.append(f"the font was not fetched from the book's _static: {fetched}")
        problems += _font_use(page, f"{quote} .tb-quote-orig", f"quote {key}")
        if prose is not None:
            problems += _font_use(page, prose, prose)
        return {"faces": faces, "fetched": fetched, "problems": problems}
    finally:
        page.close()
