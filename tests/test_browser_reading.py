"""The built book as a reader sees it in a 1280 px window.

* the sidebar numbers the chapters as their file names do (the introduction is the root page,
  unnumbered);
* every page renders within its column: no output, table, figure, display equation or
  playground wider than the column (code sources may scroll), no printed output with numbers
  over ``MAX_LINES`` lines, no raw TeX outside typeset maths, no MathJax error; each offender
  is named with its page, section, selector and width;
* the exercises appendix shows no stray output (a bare ``True``/``False``/``None`` or an empty
  output box).

Runs after the book is built (``jupyter-book build .``); skips when there is no
``_build/html`` or no Chromium. Pages are served from 127.0.0.1, as in ``test_browser.py``.
"""

from __future__ import annotations

import functools
import http.server
import re
import shutil
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HTML = ROOT / "_build" / "html"
CHROMIUM = next((shutil.which(c) for c in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(c)), None)

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium (apt-get install chromium)"),
]
needs_build = pytest.mark.skipif(not (HTML / "index.html").is_file(), reason="book not built")


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


@pytest.fixture(scope="module")
def page():
    """One headless Chromium tab with a 1280 px wide viewport, shared by the module."""
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        tab = browser.new_page(viewport={"width": 1280, "height": 900})
        yield tab
        browser.close()


def _open(page, server, name):
    page.goto(f"{server}/{name}.html", wait_until="load", timeout=60_000)


@needs_build
def test_sidebar_numbers_the_chapters_one_to_nine(server, page):
    # index.html only redirects (meta refresh) to the root page: reading it races the redirect
    _open(page, server, _toc_pages()[0])
    entries = page.eval_on_selector_all(
        "nav.bd-links a, .bd-sidenav a",
        "els => els.map(a => [a.getAttribute('href') || '', a.textContent.trim()])")
    numbered = {}
    for href, text in entries:
        m = re.search(r"(?:^|/)0([1-9])_[^/]*\.html", href)
        if m:
            numbered[int(m.group(1))] = text
    assert sorted(numbered) == list(range(1, 10)), f"chapter links in the sidebar: {numbered}"
    wrong = {n: t for n, t in numbered.items() if not re.match(rf"{n}\.\s", t)}
    assert not wrong, f"sidebar entries not numbered '<n>. ': {wrong}"


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


def _offences(r, owners=("",)):
    """One line per offender whose block belongs to one of ``owners``: kind, section,
    selector, widths (or lines) and its first text."""
    r = {k: [o for o in v if o["owner"] in owners] if isinstance(v, list) else v
         for k, v in r.items()}
    out = [f"{o['kind']} wider than the {o['column']} px column: {o['width']} px "
           f"({o['how']}) in #{o['section']} {o['selector']}: {o['text']!r}" for o in r["wide"]]
    out += [f"output of {o['lines']} lines (over {MAX_LINES}) in #{o['section']} "
            f"{o['selector']}: {o['text']!r}" for o in r["long"]]
    out += [f"raw TeX {o['tex']!r} in #{o['section']} {o['selector']}: {o['text']!r}"
            for o in r["raw"]]
    out += [f"MathJax error in #{o['section']} {o['selector']}: {o['text']!r}"
            for o in r["errors"]]
    return out


def _typeset(page):
    """Wait until MathJax (2.7, shipped offline) has typeset the page, where it is loaded.

    An empty queue right after the load event proves nothing (MathJax has not queued its
    typesetting yet): wait for its startup's "End" signal, sent after the first typesetting
    ("End Typeset") and delivered at once if already sent.
    """
    done = page.evaluate("""() => new Promise(resolve => {
        if (!(window.MathJax && MathJax.Hub)) return resolve('no MathJax');
        setTimeout(() => resolve('timed out'), 60000);
        MathJax.Hub.Register.StartupHook('End', () => resolve('done'));
    })""")
    assert done in ("done", "no MathJax"), f"MathJax did not finish typesetting: {done}"


def _measured_pages():
    """The pages, each in an xdist group of its own: under ``--dist loadgroup`` (as CI runs
    these tests) both checks of a page run in the worker that measured it, so no page is
    loaded and typeset twice."""
    return [pytest.param(n, marks=pytest.mark.xdist_group(f"measure-{Path(n).name}"))
            for n in _toc_pages()]


@pytest.fixture(scope="module")
def measured(server, page):
    """Each page measured once at 1280 px, after MathJax has typeset it."""
    seen = {}

    def measure(name):
        if name not in seen:
            _open(page, server, name)
            _typeset(page)
            seen[name] = page.evaluate(MEASURE, MAX_LINES)
        return seen[name]
    return measure


@needs_build
@pytest.mark.parametrize("name", _measured_pages())
def test_page_renders_within_its_column(measured, name):
    """At 1280 px: no output, table, figure or display equation wider than the column, no
    printed output with numbers over MAX_LINES lines, no raw TeX, no MathJax error."""
    offences = _offences(measured(name))
    assert not offences, f"{name} at 1280 px:\n  " + "\n  ".join(offences)


@needs_build
@pytest.mark.parametrize("name", _measured_pages())
def test_playgrounds_fit_their_column(measured, name):
    """The same checks on the playgrounds, which their widget code draws (a fixed-width
    canvas and knob panel) rather than the chapter's cells."""
    offences = _offences(measured(name), owners=("playground",))
    assert not offences, f"{name} at 1280 px:\n  " + "\n  ".join(offences)


@needs_build
def test_exercises_appendix_shows_no_stray_output(server, page):
    _open(page, server, "appendix_exercises")
    outputs = page.evaluate("""() => [...document.querySelectorAll('.cell_output')]
        .map((o, i) => ({i: i, text: (o.innerText || '').trim(),
                         media: o.querySelectorAll('img, svg, canvas, iframe, table').length}))""")
    stray = [o for o in outputs if o["text"] in ("True", "False", "None")]
    empty = [o for o in outputs if not o["text"] and not o["media"]]
    assert not stray, f"outputs that are just True/False/None: {stray}"
    assert not empty, f"empty output boxes: {empty}"


#: A page with one offender of each kind (and blocks that may scroll or are fine), shaped like
#: the built book's HTML: the checks must name every offender and nothing else.
SPECIMEN = """<!doctype html><html><head><meta charset="utf-8"><style>
  pre { overflow-x: auto; white-space: pre; margin: 0 }
  table { border-collapse: collapse } td { white-space: nowrap }
</style></head><body><main><article class="bd-article" style="width: 600px; padding: 0 20px">
<section id="fine">
  <p>A price of $5 and $10 is text; inline code <code>\\frac{a}{b}</code> is a source.</p>
  <div class="cell"><div class="cell_input"><div class="highlight"><pre>SOURCE</pre></div></div>
  <div class="cell_output"><div class="output stream"><div class="highlight"><pre>short 1.5
</pre></div></div></div></div>
  <div class="highlight"><pre>LITERAL</pre></div>
</section>
<section id="broken">
  <div class="cell_output"><div class="output stream"><div class="highlight"><pre>WIDE</pre>
  </div></div></div>
  <div class="pst-scrollable-table-container" style="overflow-x: auto"><table><tr>
    <td>TABLE</td></tr></table></div>
  <figure><img alt="a plot" style="width: 900px; height: 20px"
    src="data:image/gif;base64,R0lGODlhAQABAIAAAAAAAP///yH5BAEAAAAALAAAAAABAAEAAAIBRAA7"></figure>
  <div class="math"><span style="display: inline-block; width: 800px">eq</span></div>
  <div class="math"><span style="display: inline-block; width: 100%; overflow: hidden;
    white-space: nowrap">CLIPPED</span></div>
  <p>The motion model \\begin{split} x_t = x_{t-1} \\end{split} printed raw.</p>
  <span class="merror">Missing close brace</span>
  <script type="math/tex">\\mathcal{N}(0, 1)</script>
  <div class="cell_output"><div class="output stream"><div class="highlight"><pre>LONG</pre>
  </div></div></div>
</section>
<section id="exercises"><div class="cell_output"><div class="output stream">
  <div class="highlight"><pre>WIDE</pre></div></div></div></section>
<div class="output text_html"><div class="tb-playground" style="width: 800px">knobs</div></div>
</article></main></body></html>"""


def test_measure_names_each_offender_and_nothing_else(page):
    wide = "AUC " + " ".join(f"{k / 100:.2f}" for k in range(60))
    html = (SPECIMEN.replace("SOURCE", "x = " + "1 + " * 80).replace("LITERAL", "pip " * 60)
            .replace("WIDE", wide).replace("TABLE", "0.123 " * 40)
            .replace("CLIPPED", "x + " * 200)
            .replace("LONG", "\n".join(f"row {i}" for i in range(MAX_LINES + 5))))
    page.set_content(html)
    r = page.evaluate(MEASURE, MAX_LINES)
    mine = [(o["kind"], o["section"]) for o in r["wide"] if o["owner"] == ""]
    assert sorted(mine) == sorted([("output", "broken"), ("table", "broken"), ("figure", "broken"),
                                   ("equation", "broken"), ("equation", "broken"),
                                   ("output", "exercises")]), r["wide"]
    assert all(o["width"] > o["column"] == 600 for o in r["wide"]), r["wide"]
    assert [o["owner"] for o in r["wide"] if o["owner"]] == ["playground"]
    assert [(o["section"], o["lines"]) for o in r["long"]] == [("broken", MAX_LINES + 5)]
    assert [o["tex"] for o in r["raw"]] == ["\\begin{"], r["raw"]
    assert sorted(o["text"] for o in r["errors"]) == [
        "Missing close brace", "no offline font for \\mathcal: \\mathcal{N}(0, 1)"], r["errors"]
    lines = _offences(r)
    assert len(lines) == 10 and all("#broken" in line or "#exercises" in line
                                   for line in lines), lines
