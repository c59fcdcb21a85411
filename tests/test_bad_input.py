"""Bad input from the CLI, the loaders and the clip names is refused in our words.

One reproducer per class of the hostile probe: every CLI error is one line on stderr and a
non-zero exit code (never a traceback); every ground-truth error names the file, the line and
the fix; near-miss names are suggested.
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import cli, clips, trackers
from trackbook.clips.loaders import read_groundtruth


def _one_line_error(capsys, rc):
    err = capsys.readouterr().err
    assert rc != 0, err
    assert "Traceback" not in err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    return lines[0]


# --- CLI --------------------------------------------------------------------------------------

def test_track_out_is_an_existing_file(tmp_path, capsys):
    f = tmp_path / "taken.txt"
    f.write_text("x")
    rc = cli.main(["track", "mean-shift", "red-cube", "--max-frames", "2", "--out", str(f)])
    assert "is a file" in _one_line_error(capsys, rc)


def test_track_out_below_a_file(tmp_path, capsys):
    f = tmp_path / "taken.txt"
    f.write_text("x")
    rc = cli.main(["track", "mean-shift", "red-cube", "--max-frames", "2",
                   "--out", str(f / "sub")])
    assert "is a file" in _one_line_error(capsys, rc)


@pytest.mark.parametrize("extra", [[], ["--all-targets"]])
def test_track_max_frames_zero(tmp_path, capsys, extra):
    rc = cli.main(["track", "mean-shift", "two-faces", *extra, "--max-frames", "0",
                   "--out", str(tmp_path)])
    assert "--max-frames" in _one_line_error(capsys, rc)


def test_track_all_targets_api_max_frames_zero():
    from trackbook import evaluate
    with pytest.raises(ValueError, match="max_frames = 0: .*at least 2"):
        evaluate("mean-shift", "two-faces", max_frames=0, targets="all")


def test_track_param_for_another_tracker_is_refused(tmp_path, capsys):
    rc = cli.main(["track", "mean-shift", "red-cube", "--param", "color-pf:n_particles=50",
                   "--max-frames", "2", "--out", str(tmp_path)])
    assert "color-pf" in _one_line_error(capsys, rc)


def test_track_param_bool_false_is_false():
    assert cli._track_params("mean-shift", ["scale_adapt=false"]) == {"scale_adapt": False}
    assert cli._track_params("mean-shift", ["mean-shift:scale_adapt=yes"]) == \
        {"scale_adapt": True}


@pytest.mark.parametrize("argv", [
    ["track", "mean-shfit", "red-cube"],
    ["track", "mean-shift", "red-cub"],
    ["track", "mean-shift", "red-cube", "--param", "eps=nan"],
    ["track", "mean-shift", "red-cube", "--param", "n_bins"],
    ["clips", "export", "red-cub", "x.mp4"],
    ["notebooks", "--book", "no/such/folder"],
])
def test_cli_errors_are_one_line(argv, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _one_line_error(capsys, cli.main(argv))


def test_cli_ctrl_c_is_one_line(capsys, monkeypatch):
    def interrupted(args):
        raise KeyboardInterrupt
    monkeypatch.setattr(cli, "cmd_clips", interrupted)
    parser_fn = cli.build_parser
    monkeypatch.setattr(cli, "build_parser", lambda: _with_fn(parser_fn(), interrupted))
    rc = cli.main(["clips"])
    assert "interrupted" in _one_line_error(capsys, rc)


def _with_fn(parser, fn):
    orig = parser.parse_args

    def parse(argv=None):
        a = orig(argv)
        a.fn = fn
        return a
    parser.parse_args = parse
    return parser


# --- names ------------------------------------------------------------------------------------

@pytest.mark.parametrize("call, arg, says", [
    (clips.describe, "red-cub", "did you mean 'red-cube'"),        # a near miss is suggested
    (clips.load, "two_faces", "did you mean 'two-faces'"),
    (clips.load, "", "sample name"),                                 # what an empty name lacks
    (trackers.create, "colour-pf", "unknown tracker"),
])
def test_unknown_names_are_value_errors_that_help(call, arg, says):
    with pytest.raises(ValueError, match=says):
        call(arg)


# --- boxes and seeds --------------------------------------------------------------------------

def test_sub_pixel_box_is_named_as_such():
    t = trackers.create("mean-shift")
    frame = np.zeros((60, 80, 3), np.uint8)
    with pytest.raises(ValueError, match=r"\(10, 10, 30, 0.5\) has a side under 1 px"):
        t.init(frame, (10, 10, 30, 0.5))


def test_negative_seed_in_our_words():
    with pytest.raises(ValueError, match="seed = -1 is negative"):
        trackers.create("mean-shift", seed=-1)
    with pytest.raises(ValueError, match="seed"):
        trackers.create("mean-shift", seed=True)


def test_init_box_strings_in_our_words():
    from trackbook import evaluate
    with pytest.raises(ValueError, match="init_box must be four numbers"):
        evaluate("mean-shift", "red-cube", max_frames=2, init_box=("a", 1, 2, 3))


# --- ground truth -----------------------------------------------------------------------------

def test_groundtruth_inf_refused_with_file_and_line(tmp_path):
    p = tmp_path / "gt.txt"
    p.write_text("1,2,3,4\n62,41,inf,30\n")
    with pytest.raises(ValueError, match=r"gt.txt, line 2: .*infinite"):
        read_groundtruth(p)


def test_groundtruth_negative_width_refused(tmp_path):
    p = tmp_path / "gt.txt"
    p.write_text("1,2,3,4\n62,41,-5,30\n")
    with pytest.raises(ValueError, match=r"gt.txt, line 2: .*negative width"):
        read_groundtruth(p)


def test_groundtruth_zero_size_stays_unknown(tmp_path):
    p = tmp_path / "gt.txt"
    p.write_text("1,2,3,4\n0,0,0,0\n")
    gt = read_groundtruth(p)
    assert np.isnan(gt[1]).all() and np.array_equal(gt[0], [1, 2, 3, 4])


def test_groundtruth_bom_accepted(tmp_path):
    p = tmp_path / "gt.txt"
    p.write_bytes("\ufeff1,2,3,4\n5,6,7,8\n".encode("utf-8"))
    np.testing.assert_array_equal(read_groundtruth(p), [[1, 2, 3, 4], [5, 6, 7, 8]])


def test_groundtruth_undecodable_names_the_file(tmp_path):
    p = tmp_path / "gt.txt"
    p.write_bytes(b"1,2,3,4\n\xff\xfe,2,3,4\n")
    with pytest.raises(ValueError, match=r"gt.txt, line 2: not UTF-8"):
        read_groundtruth(p)


def _folder(tmp_path, n=3):
    import cv2
    img = tmp_path / "seq" / "img"
    img.mkdir(parents=True)
    for i in range(n):
        cv2.imwrite(str(img / f"{i + 1:04d}.jpg"), np.full((40, 50, 3), 60 * i, np.uint8))
    (tmp_path / "seq" / "groundtruth_rect.txt").write_text("1,1,5,5\n" * n)
    return tmp_path / "seq"


def test_folder_groundtruth_argument_is_honoured(tmp_path):
    folder = _folder(tmp_path)
    other = tmp_path / "other.txt"
    other.write_text("2,3,10,11\n" * 3)
    clip = clips.load(folder, groundtruth=other)
    np.testing.assert_array_equal(clip.groundtruth[0], [2, 3, 10, 11])
    np.testing.assert_array_equal(clips.load(folder).groundtruth[0], [1, 1, 5, 5])


def test_video_without_groundtruth_tells_api_and_cli(tmp_path):
    from trackbook import evaluate
    import cv2
    v = tmp_path / "clip.mp4"
    w = cv2.VideoWriter(str(v), cv2.VideoWriter_fourcc(*"mp4v"), 10, (64, 48))
    for i in range(3):
        w.write(np.full((48, 64, 3), 40 * i, np.uint8))
    w.release()
    with pytest.raises(ValueError, match=r"init_box=\(x, y, w, h\).*--box x,y,w,h"):
        evaluate("mean-shift", v)
