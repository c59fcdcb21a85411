"""Property-based fuzz of the loaders (ground-truth text, dataset folder layouts) and of the
playground's ``set``: never an error other than the documented ones, never a stored bad
value, and what loads is what was written."""
from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from trackbook import params as P
from trackbook.clips.datasets import load_dataset
from trackbook.clips.loaders import read_groundtruth
from trackbook.trackers import registry
from trackbook.widgets import Playground

from .test_datasets import _JPG
from .test_widgets import _Slider

FAST = settings(max_examples=60, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture,
                                       HealthCheck.too_slow])

# -- ground-truth text ---------------------------------------------------------------------
_num = st.one_of(st.integers(-50, 500).map(str),
                 st.floats(-50, 500, allow_nan=False).map(lambda v: f"{v:.2f}"),
                 st.sampled_from(["NaN", "nan", "inf", "-inf", "1e3", "10,5", "abc", "", "0"]))
_sep = st.sampled_from([",", "\t", " ", ", ", ";", "  ", ",,"])
_line = st.builds(lambda xs, s: s.join(xs), st.lists(_num, min_size=0, max_size=9), _sep)


@FAST
@given(lines=st.lists(_line, min_size=0, max_size=6), bom=st.booleans())
def test_any_groundtruth_text_reads_or_is_refused(lines, bom):
    with tempfile.TemporaryDirectory() as d:
        f = Path(d) / "gt.txt"
        f.write_bytes((b"\xef\xbb\xbf" if bom else b"") + "\n".join(lines).encode())
        try:
            gt = read_groundtruth(f)
        except ValueError as e:
            assert str(f) in str(e)                  # the message names the file
            return
    assert gt.ndim == 2 and gt.shape[1] == 4 and len(gt) >= 1
    known = np.isfinite(gt).all(axis=1)
    assert ((gt[known, 2] > 0) & (gt[known, 3] > 0)).all()  # unknown rows are whole-NaN
    assert np.isnan(gt[~known]).all()


@FAST
@given(boxes=st.lists(st.tuples(st.integers(0, 300), st.integers(0, 300), st.integers(1, 99),
                                st.integers(1, 99)), min_size=1, max_size=8),
       sep=st.sampled_from([",", "\t", " ", ", "]))
def test_written_boxes_read_back(boxes, sep):
    with tempfile.TemporaryDirectory() as d:
        f = Path(d) / "gt.txt"
        f.write_text("\n".join(sep.join(str(v) for v in b) for b in boxes) + "\n")
        np.testing.assert_array_equal(read_groundtruth(f), np.asarray(boxes, float))


# -- dataset folder layouts -----------------------------------------------------------------
_folder = st.fixed_dictionaries({
    "n_images": st.integers(0, 4),
    "in_img": st.booleans(),
    "gt": st.sampled_from(["match", "none", "empty", "short", "dangling", "junk"]),
})


def _make(root: Path, name: str, spec: dict):
    d = root / name
    img = d / "img" if spec["in_img"] else d
    img.mkdir(parents=True)
    for i in range(1, spec["n_images"] + 1):
        (img / f"{i:04d}.jpg").write_bytes(_JPG)
    gt = d / "groundtruth_rect.txt"
    n = spec["n_images"]
    if spec["gt"] == "match":
        gt.write_text("".join(f"{i},2,5,6\n" for i in range(n)))
    elif spec["gt"] == "empty":
        gt.write_text("")
    elif spec["gt"] == "short":
        gt.write_text("".join(f"{i},2,5,6\n" for i in range(n + 1)))
    elif spec["gt"] == "dangling":
        os.symlink(d / "gone.txt", gt)
    elif spec["gt"] == "junk":
        gt.write_text("10,5\t2,5\t5,0\t6,0\n" * max(n, 1))


@FAST
@given(specs=st.lists(_folder, min_size=1, max_size=5))
def test_every_folder_is_loaded_or_said_skipped(specs):
    with tempfile.TemporaryDirectory() as d:
        root = Path(d) / "data"
        root.mkdir()
        for i, spec in enumerate(specs):
            _make(root, f"s{i}", spec)
        good = {f"s{i}" for i, s in enumerate(specs) if s["gt"] == "match" and s["n_images"]}
        try:
            import warnings
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ds = load_dataset(root, kind="folders")
        except (ValueError, FileNotFoundError):
            assert not good                           # refused only when nothing loads
            return
        assert {s.name for s in ds} == good
        assert {s.name for s in ds} | {k.name for k in ds.skipped} == \
            {f"s{i}" for i in range(len(specs))}      # every folder accounted for
        for s in ds:
            assert len(s.load()) == specs[int(s.name[1:])]["n_images"]
        assert all(k.reason for k in ds.skipped)


# -- the playground's set() -------------------------------------------------------------------
@pytest.fixture(scope="module")
def pg():
    registry.register(_Slider)
    try:
        yield Playground(clips=["red-cube"], trackers=["test-slider"], n_frames=4)
    finally:
        del registry._REGISTRY[_Slider.name]


_names = st.sampled_from(["speed", "n_particles", "window", "mode", "sped", "bogus", ""])
_values = st.one_of(st.none(), st.booleans(), st.integers(-1000, 1000),
                    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=5),
                    st.sampled_from(["a", "b", "12", "0.5", "nan"]),
                    st.lists(st.floats(0, 3), max_size=3), st.tuples(st.floats(0, 3)))


@FAST
@given(knobs=st.dictionaries(_names, _values, min_size=1, max_size=3))
def test_set_stores_only_values_the_parser_accepts(pg, knobs):
    before, runs = dict(pg.values), pg.runs
    try:
        pg.set(**knobs)
    except (ValueError, TypeError):
        assert pg.values == before and pg.runs == runs
    for k, v in pg.values.items():              # whatever is stored parses to itself
        parsed = P.parse(_Slider.Params, k, v)
        assert (list(parsed) if isinstance(parsed, tuple) else parsed) == v
        assert not (isinstance(v, float) and not math.isfinite(v))
