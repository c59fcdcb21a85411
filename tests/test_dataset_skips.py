"""Datasets say what they skip: every folder (or table entry) that cannot be loaded is listed
with the reason, a warning says how many, strict=True raises, the CLI prints the count."""
import os

import numpy as np
import pytest

from trackbook import cli
from trackbook.clips import _dataset_tables as T
from trackbook.clips.datasets import DatasetWarning, load_dataset

from .test_datasets import _JPG, _gt


def _seq(folder, n=5, gt=True):
    (folder / "img").mkdir(parents=True)
    for i in range(1, n + 1):
        (folder / "img" / f"{i:04d}.jpg").write_bytes(_JPG)
    if gt:
        (folder / "groundtruth_rect.txt").write_text(_gt(n))


def _broken_tree(root):
    _seq(root / "good")
    (root / "empty").mkdir()
    _seq(root / "nogt", gt=False)
    _seq(root / "dangling", gt=False)
    os.symlink(root / "nowhere.txt", root / "dangling" / "groundtruth_rect.txt")
    return root


def test_every_skipped_folder_is_listed_with_why(tmp_path):
    root = _broken_tree(tmp_path / "mine")
    with pytest.warns(DatasetWarning, match="3 folder"):
        ds = load_dataset(root)
    assert [s.name for s in ds] == ["good"] and isinstance(ds, list) and len(ds) == 1
    why = {s.name: s.reason for s in ds.skipped}
    assert set(why) == {"empty", "nogt", "dangling"}
    assert "no images" in why["empty"]
    assert "no ground truth" in why["nogt"]
    assert "dangling" in why["dangling"] and "nowhere.txt" in why["dangling"]
    with pytest.raises(ValueError, match="3 folder.*empty.*Fix or remove"):
        load_dataset(root, strict=True)


def test_a_missing_second_target_file_is_a_skip(tmp_path):
    root = tmp_path / "OTB100"
    for name in ("Jogging.1", "Jogging.2"):
        folder, a, b, nz, ext, anno, skip = T.OTB100[name]
        img = root / folder / "img"
        img.mkdir(parents=True, exist_ok=True)
        for i in range(a, b + 1):
            (img / f"{i:0{nz}d}.{ext}").write_bytes(_JPG)
    (root / "Jogging" / "groundtruth_rect.1.txt").write_text(_gt(b - a + 1))
    with pytest.warns(DatasetWarning):
        ds = load_dataset(root)
    assert [s.name for s in ds] == ["Jogging.1"]
    assert [s.name for s in ds.skipped] == ["Jogging.2"]
    assert "groundtruth_rect.2.txt" in ds.skipped[0].reason


def _uav(root, names, extra=None):
    data, anno = root / "data_seq" / "UAV123", root / "anno" / "UAV123"
    anno.mkdir(parents=True)
    for n in names:
        video, a, b, nz, ext, ann = T.UAV123[n]
        (data / video).mkdir(parents=True, exist_ok=True)
        for i in range(a, b + 1):
            (data / video / f"{i:0{nz}d}.{ext}").write_bytes(_JPG)
        (anno / ann).write_text(_gt(b - a + 1))
    if extra:
        (data / extra).mkdir(parents=True)
        (data / extra / "000001.jpg").write_bytes(_JPG)
    return root


def test_uav_loads_only_the_sub_sequences_present(tmp_path):
    root = _uav(tmp_path / "UAV123", ["bird1_1"])
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")              # nothing skipped: no warning
        ds = load_dataset(root)
    assert [s.name for s in ds] == ["bird1_1"] and ds.skipped == []
    assert len(ds[0].load()) == 253


def test_uav_extra_video_and_half_present_sequence_are_skips(tmp_path):
    root = _uav(tmp_path / "UAV123", ["bird1_1"], extra="mydrone")
    (root / "anno" / "UAV123" / "bird1_2.txt").write_text(_gt(10))   # images not there
    with pytest.warns(DatasetWarning, match="2 folder"):
        ds = load_dataset(root)
    assert [s.name for s in ds] == ["bird1_1"]
    why = {s.name: s.reason for s in ds.skipped}
    assert "does not list" in why["mydrone"] and "000775.jpg" in why["bird1_2"]


def test_cli_bench_prints_the_skipped_count(tmp_path, capsys):
    root = _broken_tree(tmp_path / "mine")
    rng = np.random.default_rng(0)
    import cv2
    for i in range(1, 6):    # texture so the tracker has something to follow
        cv2.imwrite(str(root / "good" / "img" / f"{i:04d}.jpg"),
                    rng.integers(0, 255, (24, 32, 3), dtype=np.uint8))
    code = cli.main(["bench", "--trackers", "mean-shift", "--clips", str(root), "--out",
                     str(tmp_path / "o"), "--max-frames", "3", "--quiet"])
    err = capsys.readouterr().err
    assert code == 0, err
    line = [ln for ln in err.splitlines() if "skipped" in ln]
    assert len(line) == 1 and line[0].startswith("trackbook: warning: 3 folder(s)")
