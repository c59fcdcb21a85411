"""The folder of sequences loadable by name comes from one rule: ``$TRACKBOOK_SEQUENCES``, else
``../shared/data/sequences`` beside the source checkout; the working directory plays no part."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import trackbook
from trackbook.clips import loaders

REPO = Path(__file__).resolve().parents[1]       # this checkout: it holds pyproject.toml


def _sequence(root: Path, name: str) -> Path:
    seq = root / name
    (seq / "img").mkdir(parents=True)
    import cv2
    for i in range(2):
        cv2.imwrite(str(seq / "img" / f"{i + 1:04d}.jpg"), np.zeros((8, 8, 3), np.uint8))
    (seq / "groundtruth_rect.txt").write_text("1,1,4,4\n1,1,4,4\n")
    return seq


def test_the_environment_variable_names_the_folder(tmp_path, monkeypatch):
    _sequence(tmp_path, "Tiny")
    monkeypatch.setenv("TRACKBOOK_SEQUENCES", str(tmp_path))
    assert loaders.sequences_root() == tmp_path
    assert trackbook.clips.find_sequences() == {"Tiny": tmp_path / "Tiny"}


def test_without_it_the_folder_beside_the_checkout(monkeypatch):
    monkeypatch.delenv("TRACKBOOK_SEQUENCES", raising=False)
    assert (REPO / "pyproject.toml").is_file()
    assert loaders.sequences_root() == REPO.parent / "shared" / "data" / "sequences"


def test_the_working_directory_is_not_searched(tmp_path, monkeypatch):
    """A ``shared/data/sequences`` above the working directory is not picked up."""
    monkeypatch.delenv("TRACKBOOK_SEQUENCES", raising=False)
    _sequence(tmp_path / "shared" / "data" / "sequences", "Stray")
    (tmp_path / "deep" / "er").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "deep" / "er")
    assert "Stray" not in trackbook.clips.find_sequences()
