"""The playground viewer: precomputed runs in the page, the one JS module, set() re-runs."""
import shutil
from importlib import resources

import pytest

from trackbook.widgets import Playground


@pytest.fixture(scope="module")
def pg():
    return Playground(clips=["red-cube"], trackers=["color-pf"],
                      params=["n_particles", "resampler"], n_frames=20)


def test_page_carries_the_contract_and_the_shipped_module(pg):
    html = pg.html()
    js = resources.files("trackbook.playground").joinpath("viewer.js").read_text()
    assert js in html                                   # the one module, byte for byte
    assert 'class="tb-playground"' in html
    for attr in ("data-knob", "data-frame", "data-play"):
        assert attr in js
    assert "https://" not in html and "http://" not in html   # nothing fetched from anywhere
    assert len(html) < 3_000_000


def test_knob_values_one_at_a_time_around_the_default(pg):
    import dataclasses

    from trackbook import trackers
    f = {x.name: x for x in dataclasses.fields(trackers.get("color-pf").Params)}
    v = pg.knob_values("n_particles", f["n_particles"])
    assert v[0] == f["n_particles"].default and len(set(v)) == len(v) and len(v) > 2
    assert set(pg.knob_values("resampler", f["resampler"])) == set(f["resampler"].metadata["choices"])


def test_set_reruns_with_the_knob_and_changes_the_state(pg):
    before = pg.result.boxes.copy()
    r = pg.set(n_particles=10)
    assert r.params["n_particles"] == 10 and pg.result is r
    assert (r.boxes != before).any()
    with pytest.raises(ValueError, match="unknown knob"):
        pg.set(no_such_knob=1)


@pytest.mark.browser
@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium not installed")
def test_viewer_answers_every_control_offline(pg, tmp_path):
    """From file://, every knob, the frame slider and play change the drawing; nothing leaves
    the machine and no script error is raised."""
    playwright = pytest.importorskip("playwright.sync_api")
    page_file = tmp_path / "pg.html"
    page_file.write_text('<html><head><meta charset="utf-8"></head><body>' + pg.html()
                         + "</body></html>", encoding="utf-8")
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=shutil.which("chromium"), args=["--no-sandbox"])
        page = b.new_page(viewport={"width": 1280, "height": 800})
        errors, external = [], []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("console", lambda m: m.type == "error" and errors.append(m.text))

        def route(r):
            if r.request.url.startswith(("file:", "data:")):
                r.continue_()
            else:
                external.append(r.request.url)
                r.abort()
        page.route("**/*", route)
        page.goto(page_file.as_uri())
        page.wait_for_timeout(500)
        root = page.locator(".tb-playground")
        shot = lambda: page.evaluate(  # noqa: E731
            "() => document.querySelector('.tb-playground canvas').toDataURL()")
        a = shot()
        root.locator("[data-frame]").fill("12")
        page.wait_for_timeout(200)
        assert shot() != a
        for knob in root.locator("[data-knob]").all():
            opts = knob.locator("option").all_inner_texts()
            before, text = shot(), root.locator(".tb-scores").inner_text()
            knob.select_option(opts[-1])
            page.wait_for_timeout(200)
            assert shot() != before and root.locator(".tb-scores").inner_text() != text
        a = shot()
        root.locator("[data-play]").click()
        page.wait_for_timeout(600)
        assert shot() != a
        b.close()
    assert not errors and not external
