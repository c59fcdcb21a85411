"""The HTML book's exporter (``book/_ext/playground_export``) reads a live
:class:`~trackbook.playground.Playground` and writes its page; the widget holds no page code.
In the book's build a kernel's startup file installs the exporter, and every panel displayed
there is its page."""

from __future__ import annotations

import dataclasses
import json
from types import SimpleNamespace

import numpy as np
import playground_export  # from book/_ext, which tests/conftest.py puts on the path
import pytest
from IPython.core.formatters import DisplayFormatter
from playground_export import export
from playground_export import static as S

import trackbook
from trackbook.playground import Playground


def _run_file(folder, name):
    text = (folder / "files" / name).read_text(encoding="utf-8")
    return json.loads(text[text.index(",") + 1:-3].replace("<\\/", "</"))


def test_the_page_shows_a_run_the_chapter_made(tmp_path, monkeypatch):
    """``reuse`` hands the exporter a finished run: the page's defaults run is that run's
    boxes, not a second tracking (shifted boxes tell which was used)."""
    monkeypatch.setenv(S.OUT_ENV, str(tmp_path))
    pg = Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=6)
    made = trackbook.evaluate("mean-shift", "red-cube", max_frames=6)
    shifted = dataclasses.replace(made, boxes=made.boxes + [3.0, 0.0, 0.0, 0.0])
    data = export.static_payload(pg.reuse({"red-cube": shifted}), workers=1)
    run = _run_file(tmp_path, data["files"]["red-cube|mean-shift|"])
    np.testing.assert_allclose(np.asarray(run["boxes"], dtype=float)[1],
                               shifted.boxes[1], atol=0.06)


def test_reuse_refuses_a_run_of_another_length():
    pg = Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=6)
    r = trackbook.evaluate("mean-shift", "red-cube", max_frames=5)
    with pytest.raises(ValueError, match="not a whole-clip run of mean-shift"):
        pg.reuse({"red-cube": r})


def test_the_library_holds_no_page_code():
    """The widgets know nothing of the book: no exporter module, no switch to a page."""
    import importlib.util

    from trackbook.playground.animation import Animation

    for name in ("export", "static"):
        assert importlib.util.find_spec(f"trackbook.playground.{name}") is None
    for cls in (Playground, Animation):
        assert not [a for a in vars(cls) if a.startswith("static_") and a != "static_data"]
        assert "_repr_mimebundle_" not in vars(cls)


def test_a_shell_with_the_exporter_shows_the_page(tmp_path, monkeypatch):
    """IPython's display of a panel: the live widget, or, in a shell the book's build set up
    (:func:`playground_export.install`), the page; another shell keeps the widget."""
    monkeypatch.setenv(S.OUT_ENV, str(tmp_path))
    monkeypatch.setattr(S, "WORKERS", 1)
    pg = Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=3)
    live, book = DisplayFormatter(), DisplayFormatter()
    playground_export.install(SimpleNamespace(display_formatter=book))
    data, _ = book.format(pg)
    assert data["text/html"].startswith('<div class="tb-playground"')
    assert data["text/plain"] == "Playground(mean-shift on red-cube)"
    assert "application/vnd.jupyter.widget-view+json" not in data
    assert "application/vnd.jupyter.widget-view+json" in live.format(pg)[0]
    page = json.loads(data["text/html"].split('class="tb-data">')[1].split("</script>")[0]
                      .replace("<\\/", "</"))
    assert (tmp_path / "files" / page["files"]["red-cube|mean-shift|"]).is_file()


def test_a_kernel_started_as_the_build_starts_it_shows_pages(tmp_path, monkeypatch):
    """End to end, as the book runs a page: the startup file :func:`playground_export.
    add_startup` writes installs the exporter in the kernel before the first cell."""
    nbclient = pytest.importorskip("nbclient")
    nbformat = pytest.importorskip("nbformat")
    monkeypatch.setenv("IPYTHONDIR", str(playground_export.add_startup(tmp_path / "ipython")))
    monkeypatch.setenv(S.OUT_ENV, str(tmp_path / "store"))
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        "from trackbook.playground.animations import sir_cycle\n"
        "sir_cycle(frames=[1, 2])")])
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3").execute()
    data = nb.cells[0].outputs[0]["data"]
    assert data["text/html"].startswith('<div class="tb-playground"')
    assert "application/vnd.jupyter.widget-view+json" not in data
    assert list((tmp_path / "store" / "files").glob(S.PREFIX + "*.js"))


def test_the_sphinx_extension_gives_its_kernels_the_exporter(tmp_path, monkeypatch):
    """A page Jupyter Book executes itself (not from ``execute_pages.py``'s cache) starts its
    kernel with the environment the extension set up: IPython's folder with the startup file."""
    import os
    from pathlib import Path

    import sphinx_playground

    monkeypatch.setattr(os, "environ", {k: v for k, v in os.environ.items()
                                        if k not in ("IPYTHONDIR", S.OUT_ENV)})
    app = SimpleNamespace(outdir=str(tmp_path / "html"), connect=lambda *a, **k: None)
    sphinx_playground.setup(app)
    startup = Path(os.environ["IPYTHONDIR"]) / "profile_default" / "startup"
    assert (startup / playground_export.STARTUP_NAME).is_file()
    assert Path(os.environ[S.OUT_ENV]) == sphinx_playground.store_dir(app.outdir)
