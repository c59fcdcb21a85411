"""Shared fixtures. Tests that need the real sequences skip cleanly when they are absent.

The book's build modules (``book/_ext``: its Sphinx extensions, the figure check) are not part
of the package; the tests import them from there by name (``import sphinx_quotes``).
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from trackbook import clips  # noqa: E402

BOOK_EXT = Path(__file__).resolve().parents[1] / "book" / "_ext"
if str(BOOK_EXT) not in sys.path:
    sys.path.insert(0, str(BOOK_EXT))

SEQUENCES = clips.find_sequences()
needs_sequences = pytest.mark.skipif(
    not SEQUENCES, reason="../shared/data/sequences not found (set TRACKBOOK_SEQUENCES)")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture
def textured_frame(rng):
    """A 240x320 BGR frame with smooth texture (random noise upsampled)."""
    import cv2
    small = rng.integers(0, 256, (30, 40, 3), dtype=np.uint8)
    return cv2.resize(small, (320, 240), interpolation=cv2.INTER_CUBIC)


def write_sequence(root, name, n, *, seed, size=(160, 120), side=24, x0=20, y0=40, dx=3,
                   dy=1, ext="png"):
    """An OTB-style folder ``root/name`` (``img/0001.<ext>`` … and ``groundtruth_rect.txt``):
    a random-texture square of ``side`` px moving by ``(dx, dy)`` px a frame over a random
    background of ``size`` (width, height); returns the folder."""
    import cv2

    g = np.random.default_rng(seed)
    bg = cv2.resize(g.integers(0, 255, (12, 16, 3), dtype=np.uint8), size)
    obj = cv2.resize(g.integers(0, 255, (4, 4, 3), dtype=np.uint8), (side, side),
                     interpolation=cv2.INTER_NEAREST)
    img = root / name / "img"
    img.mkdir(parents=True)
    rows = []
    for i in range(n):
        f = bg.copy()
        x, y = x0 + dx * i, y0 + dy * i
        f[y:y + side, x:x + side] = obj
        cv2.imwrite(str(img / f"{i + 1:04d}.{ext}"), f)
        rows.append(f"{x},{y},{side},{side}")
    (root / name / "groundtruth_rect.txt").write_text("\n".join(rows) + "\n")
    return root / name


@pytest.fixture
def clean_registry(monkeypatch):
    """Restore the tracker registry and the plugin loader's memory after the test."""
    from trackbook.trackers import plugins
    from trackbook.trackers import registry

    saved = dict(registry._REGISTRY)
    monkeypatch.setattr(plugins, "_loaded", {})
    yield
    registry._REGISTRY.clear()
    registry._REGISTRY.update(saved)


def moving_square_frames(n, *, size=(100, 80), side=20, grey=(90, 140), top=30, left=20,
                         step=3, colour=(20, 20, 220), stripes=None):
    """``n`` BGR frames of ``size`` (width, height): a ``colour`` square of ``side`` px at row
    ``top`` moving ``step`` px a frame to the right from column ``left`` over grey noise
    (seed 0), every fifth row painted ``stripes`` when given; and its first box."""
    g = np.random.default_rng(0)
    frames = []
    for t in range(n):
        f = g.integers(grey[0], grey[1], (size[1], size[0], 3), dtype=np.uint8)
        x = left + step * t
        f[top:top + side, x:x + side] = colour
        if stripes is not None:
            f[top:top + side:5, x:x + side] = stripes
        frames.append(f)
    return frames, (left, top, side, side)


# ---- the browser checks of the built book ----------------------------------------------------

@pytest.fixture(scope="module")
def browser():
    """A headless Chromium for the module (Playwright's sync API allows one at a time in a
    thread, and some tests start their own: it closes with its module)."""
    from ._playground_browser import CHROMIUM

    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        yield b
        b.close()


@pytest.fixture(scope="session")
def book_visits(tmp_path_factory):
    """Each page of a built book opened once over http for all its checks, shared by the
    run's test processes (tests/_book_pages.py)."""
    from ._book_pages import Visits

    return Visits(_run_store(tmp_path_factory, "book-visits"))


def _run_store(tmp_path_factory, name: str) -> Path:
    """A folder ``name`` of the test run, shared by its test processes (an xdist worker's
    temporary folder lies in its run's folder, which all workers share)."""
    import os

    base = tmp_path_factory.getbasetemp()
    return (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / name


@pytest.fixture(scope="session")
def made_once(tmp_path_factory):
    """``made_once(name, make)``: the folder ``name`` of the test run, filled by ``make(folder)``
    once for all the run's test processes. The first process to need it makes it, under a
    lock; one that needs it meanwhile waits for it; the others read what it made. For
    fixtures whose making is expensive and whose result is files (a playground's page and
    its run files), which a module-scoped fixture would make again on every worker that runs
    one of its tests."""
    try:
        import fcntl
    except ImportError:      # Windows: each test process makes its own
        fcntl = None

    def made(name, make):
        folder = _run_store(tmp_path_factory, "made-once") / name
        folder.parent.mkdir(parents=True, exist_ok=True)
        if fcntl is None:
            folder = tmp_path_factory.mktemp(name)
            make(folder)
            return folder
        with open(folder.with_suffix(".lock"), "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            done = folder.with_suffix(".done")
            if not done.is_file():
                import shutil
                shutil.rmtree(folder, ignore_errors=True)    # a maker that failed midway
                folder.mkdir()
                make(folder)
                done.touch()
        return folder

    return made


# ---- the order of the browser checks -------------------------------------------------------

#: the page that takes the longest to open, as the checks of its visit name it: MathJax
#: typesets its hundreds of formulas for about two minutes on a 2-core machine
#: (tests/_book_pages.py, ``typeset``)
SLOWEST_VISIT = ("appendix_exercises", "exercises_appendix")


def pytest_collection_modifyitems(config, items):
    """The first check that reads the visit of the exercises appendix runs first, the other
    checks of that page last.

    Every check of a page reads its one visit (``book_visits``): the first to need it makes
    it, and a check of the same page on another worker waits meanwhile. Run side by side, the
    page's checks held every worker for the two minutes of its visit (measured: three
    workers, each ~180 s on a busy machine); made first, the visit is ready long before the
    page's other checks run.
    """
    def reads_visit(item):
        return (any(n in item.nodeid for n in SLOWEST_VISIT)
                and "book_visits" in getattr(item, "fixturenames", ()))

    slow = [i for i in items if reads_visit(i)]
    if not slow:
        return
    rest = [i for i in items if not reads_visit(i)]
    items[:] = slow[:1] + rest + slow[1:]
