"""Box values that are not real numbers are refused at every entry point, with the problem and
the fix named: a huge Python int (``float()`` would raise ``OverflowError``), masked arrays,
complex numbers, booleans, ``timedelta64``/``datetime64``, bytes, bytearray and text would
otherwise be taken as numbers (0/1, the real part, nanoseconds) or crash."""

from __future__ import annotations

import datetime

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import metrics, trackers
from trackbook._checks import as_box, check_boxes, clip_box
from trackbook.clips.clip import ArrayFrames, Clip

GOOD = (10, 12, 20, 16)
FRAME = np.zeros((60, 80, 3), np.uint8)
FRAME[12:28, 10:30] = 200

# (box, words the message must hold): each value is a box a caller could plausibly pass.
BAD = [
    pytest.param((10 ** 400, 12, 20, 16), "too large for a float", id="huge-int"),
    pytest.param((10, 12, -(10 ** 400), 16), "too large for a float", id="huge-negative-int"),
    pytest.param(np.ma.array([10.0, 12, 20, 16]), "masked array", id="masked-array"),
    pytest.param(np.ma.array([10.0, 12, 20, 16], mask=[0, 1, 0, 0]), "masked array",
                 id="masked-array-with-mask"),
    pytest.param([np.ma.masked, 12, 20, 16], "masked value", id="masked-element"),
    pytest.param((10 + 0j, 12, 20, 16), "complex", id="complex-element"),
    pytest.param(np.array(GOOD, dtype=complex), "complex", id="complex-array"),
    pytest.param((True, 12, 20, 16), "boolean", id="bool-element"),
    pytest.param((np.bool_(True), 12, 20, 16), "boolean", id="numpy-bool-element"),
    pytest.param(np.ones(4, dtype=bool), "boolean", id="bool-array"),
    pytest.param(np.array(GOOD, dtype="m8[s]"), "timedelta64", id="timedelta64-array"),
    pytest.param((np.timedelta64(10, "s"), 12, 20, 16), "timedelta64", id="timedelta64-element"),
    pytest.param(np.array(GOOD, dtype="M8[D]"), "datetime64", id="datetime64-array"),
    pytest.param((np.datetime64("2020-01-01"), 12, 20, 16), "datetime64",
                 id="datetime64-element"),
    pytest.param((datetime.date(2020, 1, 1), 12, 20, 16), "date", id="date-element"),
    pytest.param(bytearray(b"\x0a\x0c\x14\x10"), "bytes", id="bytearray"),
    pytest.param(b"10,12,20,16", "bytes", id="bytes"),
    pytest.param((b"10", 12, 20, 16), "bytes", id="bytes-element"),
    pytest.param("10,12,20,16", "text", id="str"),
    pytest.param(("10", 12, 20, 16), "text", id="str-element"),
    pytest.param(np.array(["10", "12", "20", "16"]), "text", id="str-array"),
    pytest.param((None, 12, 20, 16), "None", id="none-element"),
]


def _says(e, words):
    msg = str(e.value)
    assert words in msg
    assert "(x, y, w, h)" in msg                  # what a box is
    assert "\n" not in msg                        # one line, as the command line prints it


@pytest.mark.parametrize("box, words", BAD)
def test_tracker_init_refuses(box, words):
    t = trackers.create("mean-shift", seed=0)
    with pytest.raises(ValueError) as e:
        t.init(FRAME, box)
    _says(e, words)


@pytest.mark.parametrize("box, words", BAD)
def test_clip_box_and_as_box_refuse(box, words):
    with pytest.raises(ValueError) as e:
        clip_box(box, FRAME.shape)
    _says(e, words)
    with pytest.raises(ValueError) as e:
        as_box(box, name="init_box")
    assert str(e.value).startswith("init_box must be four numbers")


@pytest.mark.parametrize("box, words", BAD)
def test_multi_tracker_init_refuses(box, words):
    mt = trackers.MultiTracker("mean-shift", seed=0)
    with pytest.raises(ValueError) as e:
        mt.init(FRAME, [GOOD, box])
    _says(e, words)


@pytest.mark.parametrize("box, words", [b for b in BAD if b.id not in (
    "bytes", "bytearray", "str")])                   # text is not an N x 4 array at all
def test_clip_groundtruth_refuses(box, words):
    frames = ArrayFrames(np.zeros((2, 20, 20, 3), np.uint8))
    rows = ([GOOD, box] if not isinstance(box, np.ndarray)
            else np.ma.stack([box, box]) if isinstance(box, np.ma.MaskedArray)
            else np.stack([box, box]))
    with pytest.raises(ValueError) as e:
        Clip("c", frames, rows)
    assert words in str(e.value) and "clip 'c': ground truth" in str(e.value)
    with pytest.raises(ValueError) as e:
        Clip("c", frames, [GOOD, GOOD], targets={"a": [GOOD, GOOD], "b": rows})
    assert words in str(e.value) and "target 'b'" in str(e.value)


@pytest.mark.parametrize("box, words", [b for b in BAD if b.id not in (
    "bytes", "bytearray", "str")])
def test_metrics_refuse(box, words):
    rows = ([GOOD, box] if not isinstance(box, np.ndarray)
            else np.ma.stack([box, box]) if isinstance(box, np.ma.MaskedArray)
            else np.stack([box, box]))
    with pytest.raises(ValueError) as e:
        metrics.iou(rows, [GOOD, GOOD])
    assert words in str(e.value) and str(e.value).startswith("pred ")
    with pytest.raises(ValueError) as e:
        metrics.auc([GOOD, GOOD], rows)
    assert words in str(e.value) and str(e.value).startswith("gt ")


@pytest.mark.parametrize("box, fix", [
    ((1 + 2j, 1, 2, 3), "np.real"),
    ((True, 1, 2, 3), "not True/False"),
    ("1,2,3,4", r"float\(v\) for v in"),
    (np.ma.array([1.0, 2, 3, 4]), "filled"),
    (np.array([1, 2, 3, 4], "M8[D]"), "not a date"),
])
def test_the_message_names_a_fix(box, fix):
    with pytest.raises(ValueError, match=fix):
        as_box(box)


def test_real_numbers_of_every_kind_still_pass():
    """Python and numpy ints and floats (any width), 0-d arrays, fractions and an int just
    below the float limit are real numbers: they pass unchanged."""
    from fractions import Fraction
    for box in [GOOD, list(GOOD), np.array(GOOD), np.array(GOOD, np.uint8),
                np.array(GOOD, np.float32), (np.int16(10), np.float16(12), 20, 16),
                (np.array(10.0), 12, 20, 16), (Fraction(20, 2), 12, 20, 16)]:
        np.testing.assert_array_equal(as_box(box), [10.0, 12.0, 20.0, 16.0])
    big = 10 ** 300                   # finite as a float: a valid (absurd) coordinate
    assert as_box((big, 0, 1, 1))[0] == float(big)
    # NaN rows stay allowed in ground truth (frames without a box)
    g = check_boxes([GOOD, [np.nan] * 4], name="gt")
    assert g.shape == (2, 4) and np.isnan(g[1]).all()


_NON_REAL = st.one_of(
    st.complex_numbers(allow_nan=False, min_magnitude=0.5).filter(lambda z: z.imag != 0),
    st.booleans(),
    st.integers(min_value=2 ** 1024).map(lambda v: v if v % 2 else -v),
    st.text(max_size=4),
    st.binary(max_size=4),
    st.binary(max_size=4).map(bytearray),
    st.integers(-10 ** 6, 10 ** 6).map(lambda v: np.timedelta64(v, "ms")),
    st.integers(-10 ** 4, 10 ** 4).map(lambda v: np.datetime64(v, "D")),
    st.none(),
)


@settings(max_examples=150, deadline=None)
@given(bad=_NON_REAL, pos=st.integers(0, 3))
def test_any_non_real_value_anywhere_is_a_value_error(bad, pos):
    """Never an OverflowError, TypeError or a silent conversion, wherever the value sits."""
    box = list(GOOD)
    box[pos] = bad
    with pytest.raises(ValueError, match=r"must be four numbers \(x, y, w, h\)"):
        clip_box(box, FRAME.shape)
