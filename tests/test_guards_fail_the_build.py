"""The build fails on a wrong claim: a page's guard, fed a deliberately broken value, stops
the page's execution, and so the book's build.

The camshift chapter works the moments of a five-pixel diagonal by hand (M00 = 1275, θ = 45°,
σ_l = 2, σ_w = 0) and guards the sentence with asserts. Run through the book's own executor
(``book/_ext/execute_pages.py``) as written, the page passes; with the pixels' value changed
from 255 to 254 -- the sentence's 1275 no longer true -- it fails, naming the assertion.
"""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "book" / "13_camshift.md"
GUARDED = "assert m.m00 == 1275 and (m.m10, m.m01) == (2550, 2550)"
DATA = "diag[np.arange(5), np.arange(5)] = 255"


def _page_up_to_the_guard(tmp_path: Path, broken: bool) -> Path:
    text = PAGE.read_text(encoding="utf-8")
    assert GUARDED in text and DATA in text, "the worked example moved: update this test"
    end = text.index("```", text.index(GUARDED)) + 3       # the guard's cell, and no further
    text = text[:end] + "\n"
    if broken:
        text = text.replace(DATA, DATA.replace("255", "254"))
    page = tmp_path / PAGE.name
    page.write_text(text, encoding="utf-8")
    return page


@pytest.mark.parametrize("broken", [False, True], ids=["as written", "broken value"])
def test_a_guard_fails_the_page_on_a_broken_value(tmp_path, broken):
    pytest.importorskip("jupyter_cache")
    import execute_pages  # from book/_ext, which tests/conftest.py puts on the path

    _, _, error = execute_pages.execute(str(_page_up_to_the_guard(tmp_path, broken)))
    if broken:
        assert error and "AssertionError" in error and GUARDED in error, error
    else:
        assert not error, error
