"""The auto-check behind the book's exercises: ``check(label, answer, expected=..., test=...)``.

A starter cell sets the answer to ``None`` and calls :func:`check`; it prints ``PASS`` or
``FAIL`` once the student fills the answer in, and ``not answered yet`` while it is ``None``.
Solution cells call the same check, so every build of the book verifies every solution.
"""

from __future__ import annotations

import numpy as np

__all__ = ["check"]


def _same(answer, expected, atol):
    """True when the answer matches the expected value (numbers within atol, text exactly)."""
    if isinstance(expected, dict):
        return (isinstance(answer, dict) and set(answer) == set(expected)
                and all(_same(answer[k], expected[k], atol) for k in expected))
    if isinstance(expected, str):
        return isinstance(answer, str) and answer.strip().lower() == expected.strip().lower()
    a, e = np.asarray(answer, dtype=float), np.asarray(expected, dtype=float)
    return a.shape == e.shape and bool(np.allclose(a, e, rtol=0.0, atol=atol))


def check(label, answer, expected=None, test=None, atol=1e-3):
    """Print PASS or FAIL for a student's answer, or "not answered yet" while it is None.

    Parameters
    ----------
    label : the exercise's number, printed in front of the verdict.
    answer : the student's value (a number, array, string, dict or function).
    expected : the reference value, or a function computing it (so a starter cell costs nothing
        until it is answered).
    test : a predicate for answers that are functions or that are verified by a property
        instead of a value.
    atol : numbers match within this, so answers rounded to three decimals pass.

    Returns
    -------
    ``None`` while unanswered, else whether the answer passed. The value is returned, not
    displayed: a cell that ends in ``check(...);`` or assigns it shows only the printed line.
    """
    if answer is None:
        print(f"{label}: not answered yet")
        return None
    try:
        if test is not None:
            ok = bool(test(answer))
        else:
            ok = _same(answer, expected() if callable(expected) else expected, atol)
    except Exception as e:  # a malformed answer is a FAIL, not a crashed notebook
        print(f"{label}: FAIL ({type(e).__name__}: {e})")
        return False
    print(f"{label}: {'PASS' if ok else 'FAIL'}")
    return ok
