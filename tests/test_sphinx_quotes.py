"""The ``{quote}`` role, built with Sphinx and MyST on a one-page project in a temporary folder.

What a reader gets: a marker after the sentence whose tooltip holds the translation and whose
popover holds the passage as printed, the translation and the section; the page's list of
evidence at the end; the stylesheet copied beside the page (no network). What an author gets:
an unknown key stops the build naming the key; the attribution check warns or stops.
"""

from __future__ import annotations

import html
import io
import re

import pytest

pytest.importorskip("myst_parser")
from sphinx.application import Sphinx  # noqa: E402
from sphinx.errors import SphinxError  # noqa: E402

from trackbook import quotes  # noqa: E402
from sphinx_quotes import CSS_NAME  # noqa: E402

PAGE = """# Evidence

Lee et al. keep forty frames {quote}`lee2012.window40` and remove old ones
{quote}`lee2012.remove_old`.
"""


def build(tmp_path, page, builder="html", extensions=("myst_parser", "sphinx_quotes"),
          **config):
    src, out = tmp_path / "src", tmp_path / "out"
    src.mkdir(parents=True, exist_ok=True)
    (src / "conf.py").write_text("", encoding="utf-8")
    (src / "index.md").write_text(page, encoding="utf-8")
    warnings = io.StringIO()
    app = Sphinx(str(src), str(src), str(out / builder), str(out / ".doctrees"), builder,
                 confoverrides={"extensions": list(extensions),
                                **config},
                 status=None, warning=warnings, freshenv=True)
    app.build(force_all=True)
    return out / builder, warnings.getvalue()


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    out, warnings = build(tmp_path_factory.mktemp("quotes"), PAGE)
    return out, (out / "index.html").read_text(encoding="utf-8"), warnings


def test_marker_carries_translation_original_and_section(page):
    _, text, warnings = page
    assert "tb-quote" not in warnings
    q = quotes.quote("lee2012.window40")
    markers = re.findall(r'<sup class="tb-quote-mark" title="([^"]*)">(q\d+)</sup>', text)
    assert [m[1] for m in markers] == ["q1", "q2"]
    title = html.unescape(markers[0][0])
    assert q.translation in title and "Lee et al. (2012)" in title and q.where in title
    # the popover holds the Korean as printed, the translation and where it comes from
    assert html.escape(q.original) in text
    assert 'lang="ko"' in text
    assert html.escape(quotes.quote("lee2012.remove_old").translation) in text


def test_page_ends_with_its_evidence_list(page):
    _, text, _ = page
    tail = text[text.index("Evidence on this page"):]
    assert tail.count("<li ") == 2
    assert tail.index(html.escape(quotes.quote("lee2012.window40").where)) < \
        tail.index(html.escape(quotes.quote("lee2012.remove_old").translation))


def test_stylesheet_is_local_and_fits_a_phone(page):
    out, text, _ = page
    css = (out / "_static" / CSS_NAME).read_text(encoding="utf-8")
    assert f'_static/{CSS_NAME}' in text
    assert "http" not in css                               # nothing fetched
    assert "@media (max-width: 600px)" in css and "position: fixed" in css
    assert ":focus-within" in css                          # tap or tab opens it, no script
    # the popover does not feed raw TeX to MathJax
    assert re.search(r'class="tb-quote mathjax_ignore tex2jax_ignore"', text)


def test_unknown_key_stops_the_build_naming_it(tmp_path):
    with pytest.raises(SphinxError, match=r"lee2012\.window41.*did you mean lee2012\.window40"):
        build(tmp_path, "# P\n\nForty {quote}`lee2012.window41`.\n")


def test_other_builders_get_plain_text(tmp_path):
    out, _ = build(tmp_path, PAGE, builder="text")
    text = " ".join((out / "index.txt").read_text(encoding="utf-8").split())
    assert "[Lee et al. (2012), " + quotes.quote("lee2012.window40").where in text
    assert quotes.quote("lee2012.window40").translation.split()[0] in text


def test_attribution_check_warns_or_stops(tmp_path):
    page = "# P\n\nThe paper says T = 40.\n\nT = 40 {quote}`lee2012.t40`.\n"
    _, warnings = build(tmp_path / "warn", page, quotes_check_attributions="warn")
    assert "attribution without a quote: The paper says T = 40." in warnings
    assert warnings.count("attribution without a quote") == 1
    with pytest.raises(SphinxError, match="index.md:3: attribution without a quote"):
        build(tmp_path / "error", page, quotes_check_attributions="error")
    with pytest.raises(SphinxError, match="quotes_check_attributions"):
        build(tmp_path / "bad", page, quotes_check_attributions="loud")


@pytest.mark.browser
@pytest.mark.parametrize("width", [390, 1280])
def test_popover_opens_inside_the_screen_without_network(page, width):
    """Headless Chromium on the built page, from file://: tabbing to a marker opens its
    popover, wholly inside the viewport, and the page asks for nothing over the network."""
    import shutil
    chromium = next((shutil.which(c) for c in ("chromium", "chromium-browser", "google-chrome")
                     if shutil.which(c)), None)
    sync = pytest.importorskip("playwright.sync_api")
    if chromium is None:
        pytest.skip("no Chromium (apt-get install chromium)")
    out, _, _ = page
    remote = []
    with sync.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        try:
            tab = browser.new_page(viewport={"width": width, "height": 800})
            tab.on("request", lambda r: remote.append(r.url)
                   if not r.url.startswith(("file:", "data:", "about:")) else None)
            tab.goto((out / "index.html").as_uri())
            pop = tab.locator(".tb-quote-pop").first
            assert not pop.is_visible()                       # closed until asked
            tab.locator(".tb-quote").first.focus()
            assert pop.is_visible()
            box = pop.bounding_box()
            assert box["x"] >= 0 and box["x"] + box["width"] <= width
            assert box["y"] >= 0 and box["y"] + box["height"] <= 800
            assert tab.evaluate("document.documentElement.scrollWidth") <= width
            assert "n = 40" in pop.inner_text()
        finally:
            browser.close()
    assert not remote, remote


#: A page whose only maths is in its popovers: a whole display equation (eq. 12 of Cho and
#: Kang), a passage with TeX the seed prints outside any ``$`` and one with inline ``$ $``.
MATH_PAGE = """# Evidence with maths

The mean-shift vector of a candidate {quote}`cho2005.mean_shift_eq12`, the motion in the
state {quote}`cho2005.state_meaning` and the bandwidth {quote}`cho2005.bandwidth_eq3`.
"""


@pytest.fixture(scope="module")
def math_page(tmp_path_factory):
    pytest.importorskip("jupyter_server_mathjax")
    out, _ = build(tmp_path_factory.mktemp("quotes_tex"), MATH_PAGE,
                   extensions=["myst_parser", "sphinx_offline_mathjax",
                               "sphinx_quotes"])
    return out


def test_page_with_tex_only_in_popovers_loads_mathjax(math_page):
    text = (math_page / "index.html").read_text(encoding="utf-8")
    assert "_static/mathjax/MathJax.js" in text          # local, and loaded for the popovers
    assert "<code>" not in text                           # no passage shown as TeX source


@pytest.mark.browser
@pytest.mark.parametrize("width", [390, 1280])
def test_popover_typesets_its_tex(math_page, width):
    """Headless Chromium, the book's offline MathJax: every popover's passage is typeset (a
    MathJax element for each equation), no TeX command is left in the text the reader sees,
    and the open popover stays inside the screen."""
    import shutil
    chromium = next((shutil.which(c) for c in ("chromium", "chromium-browser", "google-chrome")
                     if shutil.which(c)), None)
    sync = pytest.importorskip("playwright.sync_api")
    if chromium is None:
        pytest.skip("no Chromium (apt-get install chromium)")
    with sync.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        try:
            tab = browser.new_page(viewport={"width": width, "height": 800})
            tab.goto((math_page / "index.html").as_uri())
            state = tab.evaluate("""() => new Promise(resolve => {
                if (!(window.MathJax && MathJax.Hub)) return resolve('no MathJax');
                setTimeout(() => resolve('timed out'), 60000);
                MathJax.Hub.Register.StartupHook('End', () => resolve('done'));
            })""")
            assert state == "done"
            pops = tab.locator(".tb-quote-pop")
            assert pops.count() == 3
            for i in range(3):
                quote = tab.locator(".tb-quote").nth(i)
                quote.focus()
                pop = pops.nth(i)
                assert pop.is_visible()
                orig = pop.locator(".tb-quote-orig")
                assert orig.locator(".MathJax, .MathJax_Display").count() >= 1, \
                    quote.get_attribute("data-quote")
                assert orig.locator("code, .MathJax_Error, .merror").count() == 0
                # what the reader sees: MathJax's output, never a TeX command or a $
                seen = orig.inner_text()
                assert not re.search(r"\\[A-Za-z]|\$", seen), seen
                box = pop.bounding_box()
                assert box["x"] >= 0 and box["x"] + box["width"] <= width
            assert tab.evaluate("document.documentElement.scrollWidth") <= width
        finally:
            browser.close()
