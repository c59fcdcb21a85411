"""Loading OTB folders and videos as a user's downloaded sequence would load."""
import cv2
import numpy as np
import pytest

from trackbook import clips
from trackbook.clips import read_groundtruth

from .conftest import SEQUENCES, needs_sequences


def _make_folder(tmp_path, n=5, gt_name="groundtruth_rect.txt", sep=",", size=(40, 30)):
    img = tmp_path / "seq" / "img"
    img.mkdir(parents=True)
    rng = np.random.default_rng(0)
    for i in range(n):
        cv2.imwrite(str(img / f"{i + 1:04d}.jpg"),
                    rng.integers(0, 255, (size[1], size[0], 3), dtype=np.uint8))
    rows = [sep.join(str(v) for v in (i, i + 1, 10, 12)) for i in range(n)]
    (tmp_path / "seq" / gt_name).write_text("\n".join(rows) + "\n")
    return tmp_path / "seq"


@pytest.mark.parametrize("gt_name", ["groundtruth.txt", "groundtruth_rect.txt"])
@pytest.mark.parametrize("sep", [",", "\t", " ", ", "])
def test_otb_folder_any_separator(tmp_path, gt_name, sep):
    folder = _make_folder(tmp_path, gt_name=gt_name, sep=sep)
    clip = clips.load(folder)
    assert len(clip) == 5 and clip.name == "seq"
    assert clip.frames[0].shape == (30, 40, 3) and clip.frames[0].dtype == np.uint8
    np.testing.assert_array_equal(clip.groundtruth[3], [3, 4, 10, 12])
    assert len(list(clip.frames)) == 5
    assert len(clip.frames[1:3]) == 2


def test_polygon_and_nan_and_absent_rows(tmp_path):
    f = tmp_path / "gt.txt"
    f.write_text("1,2,11,2,11,22,1,22\nNaN,NaN,NaN,NaN\n0,0,0,0\n5 6 7 8\n")
    gt = read_groundtruth(f)
    np.testing.assert_array_equal(gt[0], [1, 2, 10, 20])
    assert np.all(np.isnan(gt[1])) and np.all(np.isnan(gt[2]))
    np.testing.assert_array_equal(gt[3], [5, 6, 7, 8])


def test_malformed_groundtruth_names_the_line(tmp_path):
    f = tmp_path / "gt.txt"
    f.write_text("1,2,3,4\n1,2,three,4\n")
    with pytest.raises(ValueError, match="line 2"):
        read_groundtruth(f)
    f.write_text("1,2,3\n")
    with pytest.raises(ValueError, match="expected 4"):
        read_groundtruth(f)
    f.write_text("\n")
    with pytest.raises(ValueError, match="empty"):
        read_groundtruth(f)


def test_missing_groundtruth_and_count_mismatch(tmp_path):
    folder = _make_folder(tmp_path)
    (folder / "groundtruth_rect.txt").unlink()
    with pytest.raises(FileNotFoundError, match="groundtruth"):
        clips.load(folder)
    (folder / "groundtruth.txt").write_text("1,1,5,5\n")
    with pytest.raises(ValueError, match="match one to one"):
        clips.load(folder)


def test_unknown_names_and_paths(tmp_path):
    with pytest.raises(ValueError, match="unknown clip"):
        clips.load("no-such-clip")
    with pytest.raises(FileNotFoundError):
        clips.load(tmp_path / "missing_dir" / "x.mp4")
    bad = tmp_path / "empty.mp4"
    bad.write_bytes(b"")
    with pytest.raises(ValueError):
        clips.load(bad)
    txt = tmp_path / "notes.txt"
    txt.write_text("hello")
    with pytest.raises(ValueError, match="not a video"):
        clips.load(txt)


def test_video_roundtrip_with_groundtruth(tmp_path):
    folder = _make_folder(tmp_path, n=6, size=(64, 48))
    clip = clips.load(folder)
    video, gt = clips.export(clip, tmp_path / "out" / "seq.mp4")
    back = clips.load(video)
    assert len(back) == 6 and back.frames[0].shape == (48, 64, 3)
    np.testing.assert_allclose(back.groundtruth, clip.groundtruth)
    # random access after sequential reads gives the same frame as iteration
    seq = list(back.frames)
    np.testing.assert_array_equal(back.frames[4], seq[4])
    np.testing.assert_array_equal(back.frames[1], seq[1])
    # a video without a ground-truth file loads with unknown boxes
    gt.unlink()
    assert np.all(np.isnan(clips.load(video).groundtruth))


@needs_sequences
@pytest.mark.shared
def test_shared_sequences_load():
    expected = {"David": (471, 320, 240), "Jogging1": (307, 352, 288),
                "MotorRolling": (164, 640, 360), "Couple": (140, 320, 240),
                "Crossing": (120, 360, 240), "Ball1": (105, 1280, 720), "Bag": (196, 480, 360)}
    for name, (n, w, h) in expected.items():
        if name not in SEQUENCES:
            continue
        clip = clips.load(SEQUENCES[name])
        assert len(clip) == n
        assert clip.size == (w, h)
        assert clip.frames[n - 1].shape == (h, w, 3)
        gt = clip.groundtruth
        assert np.all(np.isfinite(gt)) and np.all(gt[:, 2:] > 0)
        assert np.all(gt[:, 0] >= -1) and np.all(gt[:, 0] + gt[:, 2] <= w + 1)
    # by bare name too, as a student would type it
    assert clips.load("Crossing").name == "Crossing"
