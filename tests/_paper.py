"""Helpers for the per-paper tests (``test_paper_*.py``): a tracker's params as fields, and the
check that they are exactly the printed ones (each pinned to the paper's value) and the
not-printed ones (each marked ``NOT_PRINTED``). That every field records the paper and every
departure says why is checked once for all trackers in ``test_presets.py``."""

from __future__ import annotations

import dataclasses

from trackbook import trackers
from trackbook.params import NOT_PRINTED


def fields(name: str) -> dict:
    return {f.name: f for f in dataclasses.fields(trackers.get(name).Params)}


def assert_fields_are(name: str, printed: dict, not_printed) -> None:
    f = fields(name)
    assert set(f) == set(printed) | set(not_printed), \
        f"{name}: fields neither printed nor listed as not printed: " \
        f"{sorted(set(f) - set(printed) - set(not_printed))}"
    for key, value in printed.items():
        assert f[key].metadata["paper"] == value, f"{name}.{key}"
    for key in not_printed:
        assert f[key].metadata["paper"] is NOT_PRINTED, f"{name}.{key}"
