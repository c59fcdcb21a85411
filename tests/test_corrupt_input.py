"""Corrupt input is named: truncated videos and images, a failed video write, ground truth
with decimal commas or the wrong number of values."""
import warnings

import cv2
import numpy as np
import pytest

from trackbook import cli, clips
from trackbook.clips.clip import CorruptFrameWarning, ImageFiles
from trackbook.clips.loaders import read_groundtruth, write_video

from .test_bench_cli import tiny_folder  # noqa: F401  (fixture)


def _mjpg(path, n=20):
    rng = np.random.default_rng(0)
    w = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 30, (64, 48))
    for _ in range(n):
        w.write(rng.integers(0, 255, (48, 64, 3), dtype=np.uint8))
    w.release()
    return path.read_bytes()


def test_a_truncated_video_names_the_first_bad_frame(tmp_path):
    data = _mjpg(tmp_path / "whole.avi")
    cut = tmp_path / "cut.avi"
    cut.write_bytes(data[:len(data) // 2])          # the file lists 20 frames, holds ~half
    with pytest.warns(CorruptFrameWarning, match=r"frame \d+ .*cannot be decoded.*20 frames"):
        c = clips.load(cut)
    assert 2 <= len(c) < 20
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert len(clips.load(tmp_path / "whole.avi")) == 20     # a whole file: no warning


def test_a_video_corrupt_after_one_frame_is_an_error_naming_the_frame(tmp_path):
    data = _mjpg(tmp_path / "whole.avi")
    movi = data.index(b"movi")
    second = data.index(b"00dc", data.index(b"00dc", movi) + 4)   # the second frame's chunk
    bad = tmp_path / "bad.avi"
    bad.write_bytes(data[:second + 100])               # one whole frame, then a cut
    with pytest.raises(ValueError, match=r"bad.avi: frame 1 .*cannot be decoded.*20 frames"):
        clips.load(bad)


def test_a_truncated_jpeg_warns_naming_the_frame(tmp_path):
    rng = np.random.default_rng(1)
    ok, buf = cv2.imencode(".jpg", rng.integers(0, 255, (48, 64, 3), dtype=np.uint8))
    good, cut = tmp_path / "0001.jpg", tmp_path / "0002.jpg"
    good.write_bytes(buf.tobytes())
    cut.write_bytes(buf.tobytes()[:len(buf) // 2])
    frames = ImageFiles([good, cut])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        frames[0]                                  # a whole JPEG: no warning
    with pytest.warns(CorruptFrameWarning, match=r"frame 1: image .*0002.jpg is truncated"):
        frames[1]


def test_an_undecodable_or_empty_image_is_named(tmp_path):
    junk, empty = tmp_path / "0001.jpg", tmp_path / "0002.png"
    junk.write_bytes(b"not an image at all")
    empty.write_bytes(b"")
    frames = ImageFiles([junk, empty])
    with pytest.raises(ValueError, match=r"frame 0: image .*0001.jpg \(19 bytes\) cannot be "):
        frames[0]
    with pytest.raises(ValueError, match="frame 1: .*empty file"):
        frames[1]


def test_a_failed_video_write_is_an_error(tmp_path, tiny_folder, monkeypatch, capsys):  # noqa: F811
    with pytest.raises(ValueError, match="cannot write video .*20000x2"):
        write_video(tmp_path / "wide.mp4", [np.zeros((2, 20000, 3), np.uint8)], 30, (20000, 2))

    class Refusing:        # OpenCV's writer when the codec refuses the size or the folder
        def __init__(self, *a, **k):
            pass

        def isOpened(self):
            return False

        def release(self):     # a real writer has it, and the codec probe calls it
            pass

    monkeypatch.setattr(cv2, "VideoWriter", Refusing)
    code = cli.main(["track", "mean-shift", str(tiny_folder), "--out", str(tmp_path / "o")])
    out, err = capsys.readouterr()
    assert code == 2 and "cannot write video" in err and "wrote" not in out
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("text, words", [
    ("10,5\t12,25\t30,0\t40,5\n", "line 1: .*decimal commas"),
    ("1,2,3,4\n10,5 12,25 30,0 40,5\n", "line 2: .*decimal commas"),
    ("1,2,3,4\n1,2,3,4,5\n", "line 2: 5 values; expected 4"),
    ("1,2,3,4\n1 2 3 4 5 6 7\n", "line 2: 7 values"),
    ("1,2,3,4\n1;2;3;4\n", "line 2: .*not numbers"),
])
def test_groundtruth_refuses_decimal_commas_and_wrong_counts(tmp_path, text, words):
    f = tmp_path / "gt.txt"
    f.write_text(text)
    with pytest.raises(ValueError, match=words):
        read_groundtruth(f)


def test_groundtruth_separators_still_read(tmp_path):
    f = tmp_path / "gt.txt"
    f.write_text("10, 12, 30, 40\n10.5\t12.25\t30\t40\n1 2 3 4\n")
    np.testing.assert_array_equal(read_groundtruth(f),
                                  [[10, 12, 30, 40], [10.5, 12.25, 30, 40], [1, 2, 3, 4]])
