"""One ``max_frames`` check (``_checks.check_max_frames``) behind every entry point."""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import cli
from trackbook._checks import MIN_FRAMES, check_max_frames
from trackbook.evaluation import bench
from trackbook.evaluation.runner import evaluate

BAD = [0, 1, -3, 2.5, True, "5"]


def test_the_check():
    assert MIN_FRAMES == 2     # frame 0 starts the tracker, frame 1 is the first one scored
    assert check_max_frames(None) is None
    assert check_max_frames(np.int64(7)) == 7 and type(check_max_frames(np.int64(7))) is int
    for bad in BAD:
        with pytest.raises(ValueError, match="max_frames = .*at least 2"):
            check_max_frames(bad)


@pytest.mark.parametrize("bad", [1, 2.5, True])
def test_every_entry_point_refuses_the_same_values(bad, tmp_path):
    with pytest.raises(ValueError, match="max_frames = .*at least 2"):
        evaluate("mean-shift", "red-cube", max_frames=bad)
    with pytest.raises(ValueError, match="max_frames = .*at least 2"):
        evaluate("mean-shift", "two-faces", max_frames=bad, targets="all")
    with pytest.raises(ValueError, match="max_frames = .*at least 2"):
        bench.run(["mean-shift"], "red-cube", tmp_path, progress=False, reference=False,
                  max_frames=bad)


def test_the_command_line_names_its_flag(tmp_path, capsys):
    rc = cli.main(["track", "mean-shift", "red-cube", "--max-frames", "1", "--out",
                   str(tmp_path)])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "\n" not in err and "--max-frames = 1" in err
    assert len(evaluate("mean-shift", "red-cube", max_frames=2).boxes) == 2
