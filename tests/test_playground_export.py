"""The HTML book's exporter (:mod:`trackbook.playground.export`) reads a live
:class:`~trackbook.playground.Playground` and writes its page; the widget holds no page code."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import trackbook
from trackbook.playground import Playground, export
from trackbook.playground import static as S


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


def test_the_widget_class_has_no_page_code():
    assert not [a for a in vars(Playground) if a.startswith("static_")]


def test_how_a_panel_displays_is_its_argument(monkeypatch):
    """``static_page=`` decides; the book build's environment variable is only its default,
    read when the panel is made (not each time it is displayed)."""
    monkeypatch.delenv(export.BOOK_ENV, raising=False)
    live = Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=3)
    monkeypatch.setenv(export.BOOK_ENV, "1")
    assert not live.static_page
    assert "application/vnd.jupyter.widget-view+json" in live._repr_mimebundle_()[0]
    assert Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=3).static_page
    assert not Playground(clips=["red-cube"], trackers=["mean-shift"], n_frames=3,
                          static_page=False).static_page
