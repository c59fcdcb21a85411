"""No module of the library over 600 lines: a module that grows past it holds two subjects."""

from __future__ import annotations

from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "trackbook"
MAX_LINES = 600


def test_no_module_is_over_600_lines():
    sizes = {p.relative_to(PACKAGE).as_posix(): len(p.read_text(encoding="utf-8").splitlines())
             for p in PACKAGE.rglob("*.py")}
    assert len(sizes) > 30                      # the walk found the package
    over = {k: n for k, n in sorted(sizes.items()) if n > MAX_LINES}
    assert not over, f"modules over {MAX_LINES} lines (split them by subject): {over}"
