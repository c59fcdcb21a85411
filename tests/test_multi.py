"""Several targets at once: ``trackbook track --all-targets`` and ``multi.track_clip``."""
import csv

import numpy as np
import pytest

from trackbook import cli, clips
from trackbook.trackers.multi import track_clip

pytestmark = pytest.mark.skipif("two-faces" not in clips.available(),
                                reason="sample clip two-faces not built")


def _rows(path):
    with open(path) as fh:
        return list(csv.reader(fh))


def test_track_clip_reports_boxes_ok_flags_and_times_per_target():
    clip = clips.load("two-faces")
    out = track_clip("mean-shift", clip, seed=0, max_frames=6)
    assert set(out) == set(clip.targets) | {"_ms", "_ok"}
    for name, gt in clip.targets.items():
        assert out[name].shape == (6, 4)
        np.testing.assert_allclose(out[name][0], gt[0])     # frame 0 is the initial box
        assert out["_ok"][name].shape == (6,) and out["_ok"][name].dtype == bool
    assert out["_ms"].shape == (6,) and np.all(out["_ms"] >= 0)


def test_cli_all_targets_writes_one_csv_per_target_and_one_video(tmp_path, capsys):
    clip = clips.load("two-faces")
    n = 8
    assert cli.main(["track", "condensation-mean-shift", "two-faces", "--all-targets",
                     "--max-frames", str(n), "--out", str(tmp_path)]) == 0
    stem = "condensation-mean-shift_two-faces"
    direct = track_clip("condensation-mean-shift", clip, seed=0, max_frames=n)
    for name in clip.targets:
        rows = _rows(tmp_path / f"{stem}_{name}.csv")
        assert rows[0] == ["frame", "x", "y", "w", "h", "ok", "ms"]
        assert len(rows) == n + 1
        boxes = np.array([[float(v) for v in r[1:5]] for r in rows[1:]])
        # the CSV holds what track_clip computes with the same seed (3 decimals)
        np.testing.assert_allclose(boxes, direct[name], atol=1e-3)
    video = clips.load(tmp_path / f"{stem}.mp4")
    assert len(video) == n and video.size == clip.size
    printed = capsys.readouterr().out
    assert all(f"two-faces/{name}" in printed for name in clip.targets)


def test_cli_all_targets_on_a_single_target_clip_writes_one_csv(tmp_path):
    assert cli.main(["track", "mean-shift", "occluder", "--all-targets", "--max-frames", "4",
                     "--out", str(tmp_path)]) == 0
    assert len(list(tmp_path.glob("mean-shift_occluder_*.csv"))) == 1


def test_cli_all_targets_unknown_tracker_is_an_error_message(capsys):
    assert cli.main(["track", "no-such-tracker", "two-faces", "--all-targets"]) == 2
    assert "unknown tracker" in capsys.readouterr().err
