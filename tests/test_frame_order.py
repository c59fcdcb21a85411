"""Image folders load in natural (numeric) order, matching their ground truth line by line, and
ground-truth values are plain ASCII numbers (or NaN), everything else named with file and line."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import clips
from trackbook.clips import read_groundtruth
from trackbook.clips.loaders import frame_order


def _folder(root, names, *, grey=None):
    """An OTB-style folder whose image called ``names[i]`` is filled with grey level
    ``grey[i]`` (PNG: lossless), with a ground truth whose line i is the box (grey[i], 1, 5, 5)
    in the order ``names`` is given."""
    grey = list(range(10, 10 + 10 * len(names), 10)) if grey is None else grey
    img = root / "img"
    img.mkdir(parents=True)
    for name, g in zip(names, grey):
        _, buf = cv2.imencode(".png", np.full((20, 24, 3), g, np.uint8))
        (img / name).write_bytes(buf.tobytes())
    (root / "groundtruth.txt").write_text("".join(f"{g},1,5,5\n" for g in grey))
    return root


def _assert_frames_match_groundtruth(clip):
    """Frame i is the image whose grey level is ground-truth line i's x: image and box agree."""
    for i, frame in enumerate(clip.frames):
        assert int(frame[0, 0, 0]) == clip.groundtruth[i, 0]


def test_unpadded_numbers_load_in_numeric_order(tmp_path):
    names = [f"{i}.png" for i in range(1, 13)]           # the ground truth is in 1..12 order
    clip = clips.load(_folder(tmp_path / "s", names))
    assert [p.name for p in clip.frames.paths] == names   # not 1, 10, 11, 12, 2, ...
    _assert_frames_match_groundtruth(clip)


def test_zero_padded_names_keep_their_order(tmp_path):
    names = [f"{i:04d}.png" for i in range(1, 13)]
    clip = clips.load(_folder(tmp_path / "s", names))
    assert [p.name for p in clip.frames.paths] == names
    _assert_frames_match_groundtruth(clip)


def test_text_around_the_number_is_fine_when_every_frame_shares_it(tmp_path):
    names = [f"frame_{i}_left.png" for i in (1, 2, 9, 10, 100)]
    clip = clips.load(_folder(tmp_path / "s", names))
    assert [p.name for p in clip.frames.paths] == names
    _assert_frames_match_groundtruth(clip)


@settings(max_examples=25, deadline=None)
@given(n=st.integers(2, 30), pad=st.booleans(), data=st.data())
def test_natural_order_whatever_order_the_files_come_in(tmp_path_factory, n, pad, data):
    from pathlib import Path
    names = [f"{i:0{4 if pad else 1}d}.jpg" for i in range(1, n + 1)]
    shuffled = data.draw(st.permutations(names))
    got = frame_order([Path("/x") / m for m in shuffled], "/x")
    assert [p.name for p in got] == names


@pytest.mark.parametrize("names, named", [
    (["a1.png", "b1.png"], ["a1.png", "b1.png"]),                      # two series
    (["1.png", "2.png", "cover.png"], ["cover.png"]),                  # a stray picture
    (["img1.png", "img_2.png"], ["img1.png", "img_2.png"]),            # two spellings
    (["\u0661.png", "\u0662.png"], ["\u0661.png", "\u0662.png"]),      # Arabic-Indic digits
])
def test_names_of_several_patterns_are_refused_naming_them(tmp_path, names, named):
    folder = _folder(tmp_path / "s", names)
    with pytest.raises(ValueError, match="ambiguous") as e:
        clips.load(folder)
    for n in named:
        assert n in str(e.value)
    assert str(folder / "img") in str(e.value)


@pytest.mark.parametrize("names", [["1.png", "01.png", "2.png"], ["1.png", "1.jpg", "2.png"]])
def test_one_frame_number_twice_is_refused_naming_both(tmp_path, names):
    with pytest.raises(ValueError, match="same frame number") as e:
        clips.load(_folder(tmp_path / "s", names))
    assert names[0] in str(e.value) and names[1] in str(e.value)


# -- ground-truth values --------------------------------------------------------------------

@pytest.mark.parametrize("value, why", [
    ("\u0661\u0662", "digits other than 0-9"),        # Arabic-Indic 12: float() reads it
    ("\uff11\uff12", "digits other than 0-9"),        # fullwidth 12: float() reads it
    ("1_000", "groups digits"),                       # float() reads it as 1000
    ("0x10", "hexadecimal"),
    ("None", "not a number"),
    ("null", "not a number"),
    ("nan(1)", "not a number"),
    ("NaNa", "not a number"),
])
def test_odd_values_are_refused_with_file_and_line(tmp_path, value, why):
    f = tmp_path / "gt.txt"
    f.write_text(f"1,2,3,4\n5,{value},7,8\n", encoding="utf-8")
    with pytest.raises(ValueError) as e:
        read_groundtruth(f)
    msg = str(e.value)
    assert f"{f}, line 2" in msg and why in msg and value in msg


def test_documented_spellings_are_read():
    """The docstring's accepted forms: signs, a bare fraction, an exponent, nan in any case
    with a sign."""
    import tempfile
    from pathlib import Path
    with tempfile.TemporaryDirectory() as d:
        f = Path(d) / "gt.txt"
        f.write_text("+1,.5,1e1,2.\nNaN,nan,-nan,NAN\n")
        gt = read_groundtruth(f)
    np.testing.assert_array_equal(gt[0], [1.0, 0.5, 10.0, 2.0])
    assert np.isnan(gt[1]).all()
