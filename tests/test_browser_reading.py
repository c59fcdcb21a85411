"""The built book as a reader sees it in a 1280 px window.

* the sidebar numbers the chapters as their file names do (the introduction is the root page,
  unnumbered);
* no table is wider than its column on any page (the table's container does not scroll);
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


@pytest.mark.parametrize("name", _toc_pages())
def test_no_table_overflows_its_column(server, page, name):
    _open(page, server, name)
    over = page.evaluate("""() => [...document.querySelectorAll('article table, main table')]
        .map(t => { const c = t.parentElement;
                    return {head: (t.innerText || '').slice(0, 60).replace(/\\s+/g, ' '),
                            scroll: c.scrollWidth, client: c.clientWidth}; })
        .filter(r => r.scroll > r.client + 1)""")
    assert not over, f"{name}: tables wider than their column at 1280 px: {over}"


def test_exercises_appendix_shows_no_stray_output(server, page):
    _open(page, server, "appendix_exercises")
    outputs = page.evaluate("""() => [...document.querySelectorAll('.cell_output')]
        .map((o, i) => ({i: i, text: (o.innerText || '').trim(),
                         media: o.querySelectorAll('img, svg, canvas, iframe, table').length}))""")
    stray = [o for o in outputs if o["text"] in ("True", "False", "None")]
    empty = [o for o in outputs if not o["text"] and not o["media"]]
    assert not stray, f"outputs that are just True/False/None: {stray}"
    assert not empty, f"empty output boxes: {empty}"
