"""File-system and type errors named: permission, link loops, dangling links and missing files
told apart; single-row frames, nested and text boxes, the dtype advice; negative boxes in
metrics."""
import os
from pathlib import Path

import cv2
import numpy as np
import pytest

from trackbook import clips
from trackbook._checks import as_box, check_frame
from trackbook.clips.clip import ImageFiles
from trackbook.clips.datasets import Sequence, load_dataset
from trackbook.clips.loaders import read_groundtruth
from trackbook.evaluation import bench, metrics

from .test_datasets import _JPG, _gt


def _loop(path):
    os.symlink(path, path)          # a link to itself: ELOOP on open
    return path


def _deny(monkeypatch, target, method="read_bytes"):
    """Running as root ignores file modes, so a denied read is simulated where it happens."""
    real = getattr(Path, method)

    def denied(self, *a, **k):
        if Path(self) == Path(target):
            raise PermissionError(13, "Permission denied", str(self))
        return real(self, *a, **k)
    monkeypatch.setattr(Path, method, denied)


def test_groundtruth_missing_dangling_looping_and_denied(tmp_path, monkeypatch):
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read_groundtruth(tmp_path / "none.txt")
    os.symlink(tmp_path / "gone.txt", tmp_path / "dangling.txt")
    with pytest.raises(FileNotFoundError, match="dangling.txt is a link to .*gone.txt"):
        read_groundtruth(tmp_path / "dangling.txt")
    with pytest.raises(ValueError, match="loop.txt is a symbolic-link loop"):
        read_groundtruth(_loop(tmp_path / "loop.txt"))
    f = tmp_path / "gt.txt"
    f.write_text("1,2,3,4\n")
    _deny(monkeypatch, f)
    with pytest.raises(PermissionError, match="gt.txt: permission denied"):
        read_groundtruth(f)


def test_images_missing_unreadable_and_looping_are_told_apart(tmp_path, monkeypatch):
    good = tmp_path / "0001.jpg"
    good.write_bytes(_JPG)
    loop = _loop(tmp_path / "0003.jpg")
    denied = tmp_path / "0004.jpg"
    denied.write_bytes(_JPG)
    frames = ImageFiles([good, tmp_path / "0002.jpg", loop, denied])
    assert frames[0].shape == (24, 32, 3)
    with pytest.raises(FileNotFoundError, match="frame 1: image .*0002.jpg does not exist"):
        frames[1]
    with pytest.raises(ValueError, match="frame 2: image .*0003.jpg is a symbolic-link loop"):
        frames[2]
    real = cv2.imread
    monkeypatch.setattr(cv2, "imread", lambda p, *a: None if p.endswith("0004.jpg")
                        else real(p, *a))
    _deny(monkeypatch, denied)
    with pytest.raises(PermissionError, match="frame 3: image .*0004.jpg: permission denied"):
        frames[3]


def _one_seq_root(tmp_path):
    root = tmp_path / "mine"
    (root / "a" / "img").mkdir(parents=True)
    for i in range(1, 4):
        (root / "a" / "img" / f"{i:04d}.jpg").write_bytes(_JPG)
    (root / "a" / "groundtruth.txt").write_text(_gt(3))
    return root


def test_load_dataset_and_plan_name_the_path(tmp_path, monkeypatch):
    with pytest.raises(ValueError, match="symbolic-link loop"):
        load_dataset(_loop(tmp_path / "looproot"))
    root = _one_seq_root(tmp_path)
    _deny(monkeypatch, root, "iterdir")
    with pytest.raises(PermissionError, match=f"{root}: permission denied"):
        load_dataset(root, kind="folders")
    with pytest.raises(PermissionError, match="permission denied"):
        bench.plan(["mean-shift"], [str(root)], reference=False)


def test_sequence_load_names_a_looping_image_and_a_denied_groundtruth(tmp_path, monkeypatch):
    root = _one_seq_root(tmp_path)
    imgs = sorted(str(p) for p in (root / "a" / "img").iterdir())
    os.remove(imgs[-1])
    _loop(Path(imgs[-1]))
    with pytest.raises(ValueError, match="0003.jpg is a symbolic-link loop"):
        Sequence("a", tuple(imgs), str(root / "a" / "groundtruth.txt")).load()
    imgs2 = imgs[:2]
    _deny(monkeypatch, root / "a" / "groundtruth.txt")
    with pytest.raises(PermissionError, match="groundtruth.txt: permission denied"):
        Sequence("a", tuple(imgs2), str(root / "a" / "groundtruth.txt")).load()
    with pytest.raises(PermissionError, match="groundtruth.txt: permission denied"):
        clips.load_folder(root / "a")


def test_a_single_row_frame_is_not_called_empty():
    with pytest.raises(ValueError) as e:
        check_frame(np.zeros((1, 20000, 3), np.uint8))
    assert "empty" not in str(e.value) and "single row or column" in str(e.value)
    with pytest.raises(ValueError, match="empty"):
        check_frame(np.zeros((0, 20, 3), np.uint8))


@pytest.mark.parametrize("box, words", [
    ([[10, 20], [40, 60]], "nested"), (np.array([[10, 20], [40, 60]]), "nested"),
    ([10, 20, [30], 40], "nested"), (["10", "20", "30", "40"], "text"),
    ("10,20,30,40", "text"), (np.array(["10", "20", "30", "40"]), "text"),
])
def test_nested_and_text_boxes_are_refused(box, words):
    with pytest.raises(ValueError, match=words):
        as_box(box)


def _advice(frame):
    with pytest.raises(ValueError) as e:
        check_frame(frame)
    return str(e.value)


def test_uint16_advice_keeps_the_picture():
    frame = np.array([[[0, 32768, 65535]] * 2] * 2, np.uint16)     # black, mid-grey, white
    msg = _advice(frame)
    assert "frame * 255" not in msg and "frame*255" not in msg
    # both advised conversions, run as written: 0 -> 0, 32768 -> 128, 65535 -> 255
    for expr in ("(frame >> 8).astype(np.uint8)",
                 "cv2.convertScaleAbs(frame, alpha=255 / 65535)"):
        assert expr in msg
        out = eval(expr, {"np": np, "cv2": cv2, "frame": frame})
        assert out.dtype == np.uint8 and list(out[0, 0]) == [0, 128, 255], expr


def test_float_advice_follows_the_values():
    frame = np.array([[[0.0, 100.0, 255.0]] * 2] * 2)               # already 0..255
    msg = _advice(frame)
    expr = "np.clip(frame, 0, 255).astype(np.uint8)"
    assert expr in msg and "not frame * 255" in msg
    assert list(eval(expr, {"np": np, "frame": frame})[0, 0]) == [0, 100, 255]
    assert "frame * 255" in _advice(frame / 255)                     # 0..1: scale it


def test_metrics_refuse_negative_ground_truth_and_score_negative_predictions_zero():
    gt = np.array([[0, 0, 10, 10], [50, 50, -10, 10]])
    with pytest.raises(ValueError, match="gt row 1 .*negative width or height"):
        metrics.auc(gt, gt)
    gt = np.array([[0, 0, 10, 10], [0, 0, 10, 10]])
    pred = np.array([[0, 0, 10, 10], [10, 10, -10, -10]])   # corners written as a size
    np.testing.assert_array_equal(metrics.iou(pred, gt), [1.0, 0.0])
    assert np.isinf(metrics.center_error(pred, gt)[1])
