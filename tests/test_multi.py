"""Several targets at once: ``trackbook track --all-targets`` and
``trackbook.evaluate(..., targets=...)``."""
import csv

import numpy as np
import pytest

import trackbook
from trackbook import cli, clips
from trackbook.trackers import MultiTracker

pytestmark = pytest.mark.skipif("two-faces" not in clips.available(),
                                reason="sample clip two-faces not built")


def _rows(path):
    with open(path) as fh:
        return list(csv.reader(fh))


def test_evaluate_targets_reports_boxes_ok_flags_and_times_per_target():
    clip = clips.load("two-faces")
    res = trackbook.evaluate("mean-shift", clip, seed=0, max_frames=6, targets="all")
    assert isinstance(res, trackbook.MultiResult)
    assert set(res.results) == set(clip.targets) and res.tracker == "mean-shift"
    for name, gt in clip.targets.items():
        r = res.results[name]
        assert r.boxes.shape == (6, 4) and res.boxes[name] is r.boxes
        np.testing.assert_allclose(r.boxes[0], gt[0])      # frame 0 is the initial box
        assert r.ok.shape == (6,) and r.ok.dtype == bool
        assert "auc" in r.scores                             # scored on its own target
    # the frame's time is every target's update together
    np.testing.assert_allclose(res.ms, sum(r.ms for r in res.results.values()))
    assert res.ms.shape == (6,) and np.all(res.ms >= 0)


def test_evaluate_targets_is_what_a_multitracker_does_by_hand():
    """The one loop with targets= gives exactly the boxes of a MultiTracker stepped by hand
    (same per-target seeds, same frames)."""
    clip = clips.load("two-faces")
    n = 5
    res = trackbook.evaluate("condensation", clip, seed=3, max_frames=n, targets="all",
                             n_particles=30)
    names = list(clip.targets)
    mt = MultiTracker("condensation", seed=3, n_particles=30)
    frames = list(clip.frames)[:n]
    mt.init(frames[0], [clip.targets[k][0] for k in names])
    by_hand = [mt.update(f)[1] for f in frames[1:]]
    for k, name in enumerate(names):
        np.testing.assert_array_equal(res.boxes[name][1:], [b[k] for b in by_hand])


def test_evaluate_targets_bad_input():
    with pytest.raises(ValueError, match="no target"):
        trackbook.evaluate("mean-shift", "two-faces", max_frames=3, targets=["nobody"])
    with pytest.raises(ValueError, match="init_box"):
        trackbook.evaluate("mean-shift", "two-faces", max_frames=3, targets="all",
                           init_box=(1, 1, 10, 10))
    with pytest.raises(ValueError, match="targets"):
        trackbook.evaluate("mean-shift", "two-faces", max_frames=3, targets="face")


def test_multitracker_checks_params_when_made():
    with pytest.raises(ValueError, match="bogus"):
        MultiTracker("mean-shift", bogus=1)


def test_cli_all_targets_writes_one_csv_per_target_and_one_video(tmp_path, capsys):
    clip = clips.load("two-faces")
    n = 8
    assert cli.main(["track", "condensation-mean-shift", "two-faces", "--all-targets",
                     "--max-frames", str(n), "--out", str(tmp_path)]) == 0
    # a shortened run (--max-frames) is named with its settings' hash: one video, one hash
    (video_file,) = tmp_path.glob("condensation-mean-shift_two-faces_*.mp4")
    stem = video_file.stem
    direct = trackbook.evaluate("condensation-mean-shift", clip, seed=0, max_frames=n,
                                targets="all").boxes
    for name in clip.targets:
        rows = _rows(tmp_path / f"{stem}_{name}.csv")
        assert rows[0] == ["frame", "x", "y", "w", "h", "ok", "ms"]
        assert len(rows) == n + 1
        boxes = np.array([[float(v) for v in r[1:5]] for r in rows[1:]])
        # the CSV holds what evaluate computes with the same seed (3 decimals)
        np.testing.assert_allclose(boxes, direct[name], atol=1e-3)
    video = clips.load(video_file)
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
