"""The built book as a reader sees it in a 1280 px window.

* the sidebar shows the parts of ``_toc.yml`` in order, each page under its part, and numbers
  nothing (a chapter's file number is a fixed label, not its place);
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

import html
import re
from pathlib import Path

import pytest

from . import _toc
from ._book_pages import MAX_LINES, MEASURE, serve
from ._playground_browser import CHROMIUM

ROOT = Path(__file__).resolve().parents[1]
HTML = ROOT / "_build" / "html"

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium (apt-get install chromium)"),
]
needs_build = pytest.mark.skipif(not (HTML / "index.html").is_file(), reason="book not built")


def _toc_pages():
    return _toc.files()


@pytest.fixture(scope="module")
def server():
    httpd, url = serve(HTML)
    yield url
    httpd.shutdown()


@pytest.fixture(scope="module")
def page(browser):
    """One headless Chromium tab with a 1280 px wide viewport, shared by the module."""
    tab = browser.new_page(viewport={"width": 1280, "height": 900})
    yield tab
    tab.close()


# The checks of the book's pages read each page's one visit over http (tests/_book_pages.py),
# made once MathJax has typeset the page in a 1280 x 900 window.
@needs_build
def test_sidebar_shows_the_parts_in_order_and_numbers_nothing(browser, book_visits, server):
    # index.html only redirects (meta refresh) to the root page: reading it races the redirect
    v = book_visits(browser, server, HTML, _toc_pages()[0] + ".html")
    nav = re.search(r'<nav [^>]*class="[^"]*\bbd-links\b.*?</nav>', v.dom, re.S)
    assert nav, "the page has no sidebar navigation"
    nav = nav.group(0)
    captions = [(m.start(), html.unescape(m.group(1)).strip()) for m in
                re.finditer(r'class="caption-text">([^<]*)<', nav)]
    assert [c for _, c in captions] == _toc.captions(), "the sidebar's parts are not _toc.yml's"
    # each page's link stands under its own part's caption
    for stem, part in _toc.parts().items():
        at = nav.find(f'{stem}.html"')
        if at < 0:              # the page being visited is marked current, without its name
            continue
        under = [c for pos, c in captions if pos < at][-1]
        assert under == part, f"{stem} is under {under!r}, not {part!r}"
    numbered = [t for _, t in v.sidebar if re.match(r"\d+\.\s", t)]
    assert not numbered, f"sidebar entries carry a number: {numbered}"


# MAX_LINES and the MEASURE script that runs in the page live in tests/_book_pages.py, which
# runs MEASURE as it visits each page.


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


@pytest.fixture(scope="module")
def measured(browser, book_visits, server):
    """Each page measured once at 1280 px, after MathJax has typeset it (the page's visit)."""
    def measure(name):
        v = book_visits(browser, server, HTML, f"{name}.html")
        assert v.typeset in ("done", "no MathJax"), \
            f"MathJax did not finish typesetting: {v.typeset}"
        return v.measured
    return measure


@needs_build
@pytest.mark.parametrize("name", _toc_pages())
def test_page_renders_within_its_column(measured, name):
    """At 1280 px: no output, table, figure or display equation wider than the column, no
    printed output with numbers over MAX_LINES lines, no raw TeX, no MathJax error."""
    offences = _offences(measured(name))
    assert not offences, f"{name} at 1280 px:\n  " + "\n  ".join(offences)


@needs_build
@pytest.mark.parametrize("name", _toc_pages())
def test_playgrounds_fit_their_column(measured, name):
    """The same checks on the playgrounds, which their widget code draws (a fixed-width
    canvas and knob panel) rather than the chapter's cells."""
    offences = _offences(measured(name), owners=("playground",))
    assert not offences, f"{name} at 1280 px:\n  " + "\n  ".join(offences)


@needs_build
def test_exercises_appendix_shows_no_stray_output(browser, book_visits, server):
    outputs = book_visits(browser, server, HTML, "book/appendix_exercises.html").outputs
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


@needs_build
@pytest.mark.parametrize("name", _toc_pages())
def test_figures_have_alt_texts_that_describe_them(name):
    """Every image of a page has an alt text, and none is a file's path (``figure_alt.py``
    gives each figure a page's code draws the description the figure hook wrote)."""
    html = (HTML / f"{name}.html").read_text(encoding="utf-8")
    bad = []
    for tag in re.findall(r"<img\b[^>]*>", html):
        alt = re.search(r'\balt="([^"]*)"', tag)
        text = alt.group(1) if alt else ""
        if not text.strip() or "_images/" in text or re.search(r"\.(png|jpe?g|svg|gif)$", text):
            bad.append(tag[:160])
    assert not bad, f"{name}: images without a describing alt text:\n" + "\n".join(bad)
