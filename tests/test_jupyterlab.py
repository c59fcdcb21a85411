"""The playground in a real JupyterLab (started on 127.0.0.1, driven by headless Chromium)
: a chapter exported by ``trackbook notebooks`` runs ALL its cells (a
last cell appended by the test writes a marker file, and the kernel stops a Run All at the
first error), its first playground renders, answers a knob moved on a later frame (the kernel
re-runs up to that frame first, then streams the rest) and the frame slider.
``TRACKBOOK_LAB_NOTEBOOK=book/NN_name.md`` picks another chapter (the default is a short one,
to keep the suite quick); ``TRACKBOOK_LAB_NOTEBOOK=small`` runs a two-cell notebook instead.

JupyterLab and Playwright come with the test extra; with ``TRACKBOOK_REQUIRE_LAB=1`` (as
``.ci/run`` sets) a missing JupyterLab, Playwright or Chromium fails the test instead of
skipping it, so CI cannot pass without running it."""

from __future__ import annotations

import json
import os
import secrets
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from ._playground_browser import CANVAS_SIG, CHROMIUM, other_value, set_input, watch_errors

ROOT = Path(__file__).resolve().parents[1]

pytestmark = [pytest.mark.jupyterlab, pytest.mark.slow]


def _missing(what: str):
    if os.environ.get("TRACKBOOK_REQUIRE_LAB"):
        pytest.fail(f"{what}, and TRACKBOOK_REQUIRE_LAB is set: install the test extra "
                    "(pip install -e \".[test]\") and Chromium", pytrace=False)
    pytest.skip(what)


def _need(module: str):
    try:
        return __import__(module, fromlist=["_"])
    except ImportError:
        _missing(f"{module} is not installed")

SMALL = [
    "from trackbook.widgets import Playground",
    "pg = Playground(clips=['red-cube'], trackers=['color-pf'], "
    "params=['n_particles', 'sigma_color'], n_frames=20)\npg",
]


# a short chapter whose playground shows a tracker the chapter itself registers
CHAPTER = "book/appendix_own_tracker.md"
MARKER = "all_cells_ran.ok"


def _notebook(tmp: Path) -> Path:
    chapter = os.environ.get("TRACKBOOK_LAB_NOTEBOOK", CHAPTER)
    if chapter != "small":
        subprocess.run([sys.executable, "-m", "trackbook", "notebooks", "--out", str(tmp)],
                       check=True, cwd=ROOT, capture_output=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
        p = next(tmp.rglob(Path(chapter).stem + ".ipynb"))
        nb = json.loads(p.read_text())
    else:
        nb = {"cells": [{"cell_type": "code", "metadata": {}, "execution_count": None,
                         "outputs": [], "source": s} for s in SMALL],
              "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3",
                                          "language": "python"}},
              "nbformat": 4, "nbformat_minor": 5}
        p = tmp / "playground.ipynb"
    # the last cell runs only if every cell before it ran without an error
    nb["cells"].append({"cell_type": "code", "metadata": {}, "execution_count": None,
                        "outputs": [], "source": "import pathlib\n"
                        f"pathlib.Path({str(tmp / MARKER)!r}).write_text('ok')"})
    p.write_text(json.dumps(nb))
    return p


@pytest.fixture
def lab(tmp_path):
    _need("jupyterlab")
    if CHROMIUM is None:
        _missing("no Chromium")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    token = secrets.token_hex(16)
    # every cell in the page (JupyterLab 4 may leave cells out of view out of the DOM)
    user = tmp_path / "cfg" / "lab" / "user-settings" / "@jupyterlab" / "notebook-extension"
    user.mkdir(parents=True)
    (user / "tracker.jupyterlab-settings").write_text(json.dumps({"windowingMode": "none"}))
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
           "JUPYTER_CONFIG_DIR": str(tmp_path / "cfg"), "JUPYTER_RUNTIME_DIR": str(tmp_path / "rt")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "jupyter", "lab", "--no-browser", "--ip=127.0.0.1",
         f"--port={port}", f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={tmp_path}",
         "--allow-root", "--LabApp.news_url=", "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate"],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    for _ in range(120):
        try:
            urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2)
            break
        except OSError:
            time.sleep(0.5)
    else:
        proc.terminate()
        _missing("jupyter lab did not start")
    yield url, token, tmp_path
    proc.terminate()
    proc.wait(timeout=20)


#: some cell's prompt shows it queued, running or run ([*] or [n])
RUNNING = """() => [...document.querySelectorAll('.jp-InputPrompt')]
  .some((e) => /\\[(\\*|\\d+)\\]/.test(e.textContent))"""


def _kernel_ready(url, token, timeout=120):
    """Wait until the notebook's kernel is up and idle (the server's own account)."""
    for _ in range(timeout * 2):
        with urllib.request.urlopen(f"{url}/api/sessions?token={token}", timeout=5) as r:
            sessions = json.load(r)
        if sessions and all(s["kernel"]["execution_state"] == "idle" for s in sessions):
            return
        time.sleep(0.5)
    _missing("the notebook's kernel did not start")


def test_playground_in_jupyterlab(lab):
    sync_api = _need("playwright.sync_api")
    url, token, tmp = lab
    nb = _notebook(tmp)
    rel = nb.relative_to(tmp).as_posix()
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        page = b.new_page(viewport={"width": 1400, "height": 1000})
        errors = []
        watch_errors(page, errors)
        page.goto(f"{url}/lab/tree/{rel}?token={token}")
        page.wait_for_selector(".jp-Notebook", timeout=120_000)
        page.wait_for_selector(".jp-Notebook-ExecutionIndicator[data-status='idle']",
                               timeout=120_000)
        _kernel_ready(url, token)
        for _ in range(4):      # a Run All given before the page holds the kernel runs nothing
            page.click(".jp-Notebook .jp-Cell >> nth=0")
            page.keyboard.press("Escape")
            page.click(".lm-MenuBar-itemLabel:text-is('Run')", timeout=10_000)
            page.click(".lm-Menu-itemLabel:text-is('Run All Cells')", timeout=10_000)
            try:
                page.wait_for_function(RUNNING, timeout=20_000)
                break
            except sync_api.TimeoutError:
                continue
        for _ in range(900):                      # Run All finishes (or stops at an error)
            if (tmp / MARKER).exists() or page.query_selector("text=Traceback"):
                break
            page.wait_for_timeout(500)
        tb = page.query_selector("text=Traceback")
        assert tb is None, f"a cell raised: {tb.inner_text()[:800] if tb else ''}"
        if not (tmp / MARKER).exists():
            page.screenshot(path=str(tmp / "lab.png"))
            pytest.fail(f"Run All did not reach the notebook's last cell (screenshot "
                        f"{tmp / 'lab.png'}); the page ends: "
                        f"{page.inner_text('.jp-Notebook')[-600:]!r}", pytrace=False)
        page.wait_for_selector(".tb-playground canvas", timeout=60_000)
        root = page.query_selector(".tb-playground")
        page.wait_for_function("(r) => r.querySelector('.tb-scores').textContent.includes('AUC')",
                               arg=root, timeout=120_000)
        page.wait_for_timeout(500)
        scores = root.query_selector(".tb-scores")
        knob = root.query_selector("[data-knob]")
        fr = root.query_selector("[data-frame]")
        set_input(fr, 12)                   # the reader is on a later frame
        before_txt, before_sig = scores.inner_text(), page.evaluate(CANVAS_SIG, root)
        set_input(knob, other_value(knob))
        # the complete run's scores replace the old ones (partial answers come first)
        page.wait_for_function("([r, t]) => { const s = r.querySelector('.tb-scores')"
                               ".textContent; return s !== t && s.includes('AUC'); }",
                               arg=[root, before_txt], timeout=120_000)
        page.wait_for_timeout(200)
        assert page.evaluate(CANVAS_SIG, root) != before_sig, "knob: picture did not change"
        before = page.evaluate(CANVAS_SIG, root)
        set_input(fr, 3)
        assert page.evaluate(CANVAS_SIG, root) != before, "frame slider: picture did not change"
        b.close()
    real = [e for e in errors if "tb-" in e or "viewer" in e or "anywidget" in e.lower()]
    assert not real, real
