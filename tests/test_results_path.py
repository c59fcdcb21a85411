"""Committed book results are found from book/, the repository root and notebooks/."""
import os
from pathlib import Path

import pytest

from trackbook.evaluation import results

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("cwd", [ROOT / "book", ROOT, ROOT / "tests"])
def test_found_from_anywhere_in_the_checkout(cwd, monkeypatch):
    monkeypatch.chdir(cwd)
    p = results.path("real")
    assert (p / "results.json").is_file() and p.resolve() == (ROOT / "book/results/real").resolve()


def test_missing_names_the_fix(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError, match="regenerate"):
        results.path("no-such-result.csv")
