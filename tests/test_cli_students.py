"""The command line as a student meets it: trackers of one's own, ground truth of one's own
video, presets, output names, error lines and exit codes, notebooks from any folder."""

from __future__ import annotations

import csv
import json
import sys
import textwrap

import cv2
import numpy as np
import pytest
from skimage.color import rgb2lab

from trackbook import cli, clips
from trackbook import _cli_output as out_mod
from trackbook.evaluation.runner import evaluate

STILL = textwrap.dedent("""
    from trackbook import trackers

    @trackers.register
    class Still(trackers.Tracker):
        '''A box that never moves (a test tracker).'''
        name = "still-cli"

        def _init(self, frame, box):
            self._box = tuple(float(v) for v in box)

        def _update(self, frame):
            return True, self._box
""")


def _one_line(capsys, rc):
    err = capsys.readouterr().err
    assert rc == 2, err
    assert "Traceback" not in err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("trackbook: error:"), err
    return lines[0]


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture
def own_video(tmp_path):
    """A video of one's own (a square sliding right 3 px a frame) and its ground truth in a
    file whose name follows no convention."""
    rng = np.random.default_rng(5)
    bg = cv2.resize(rng.integers(0, 255, (12, 16, 3), dtype=np.uint8), (160, 120))
    obj = cv2.resize(rng.integers(0, 255, (4, 4, 3), dtype=np.uint8), (30, 30),
                     interpolation=cv2.INTER_NEAREST)
    frames, gt = [], []
    for i in range(8):
        f = bg.copy()
        x, y = 20 + 3 * i, 40
        f[y:y + 30, x:x + 30] = obj
        frames.append(f)
        gt.append((x, y, 30, 30))
    video = tmp_path / "mine.avi"
    w = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"MJPG"), 10, (160, 120))
    for f in frames:
        w.write(f)
    w.release()
    boxes = tmp_path / "my boxes.txt"
    boxes.write_text("\n".join(",".join(str(v) for v in b) for b in gt) + "\n")
    return video, boxes, np.array(gt, float)


# --- trackbook trackers ------------------------------------------------------------------------

def test_trackers_lists_names_and_reference(capsys):
    assert cli.main(["trackers"]) == 0
    names = [ln.split()[0] for ln in capsys.readouterr().out.splitlines() if ln.strip()]
    for n in ("color-pf", "kalman-covariance", "mean-shift", "opencv-mil"):
        assert n in names


def test_trackers_name_shows_params(capsys):
    assert cli.main(["trackers", "color-pf"]) == 0
    rows = {ln.split()[0]: ln for ln in capsys.readouterr().out.splitlines() if ln.strip()}
    # color-pf: N = 100 particles (section V of Lee et al. 2012); the range shown is the one a
    # value may take (1..100000), not the playground's slider (10..1000)
    assert rows["n_particles"].split()[1:5] == ["1", "..", "100000", "100"]
    # a value the paper does not print says so
    assert "not printed" in rows["min_size"]
    # choices are listed
    assert "systematic" in rows["resampler"]


def test_trackers_unknown_is_one_line(capsys):
    assert "did you mean 'opencv-mil'" in _one_line(capsys, cli.main(["trackers", "mil"]))


# --- track --import ----------------------------------------------------------------------------

def test_track_import_runs_a_tracker_from_a_file(tmp_path, clean_registry, capsys):
    f = tmp_path / "still.py"
    f.write_text(STILL)
    o = tmp_path / "o"
    rc = cli.main(["track", "still-cli", "red-cube", "--import", str(f), "--max-frames", "4",
                   "--out", str(o)])
    assert rc == 0, capsys.readouterr().err
    csvs = list(o.glob("still-cli_red-cube_*.csv"))     # --max-frames: a name with a hash
    assert len(csvs) == 1
    rows = _rows(csvs[0])
    box0 = clips.load("red-cube").groundtruth[0]
    assert len(rows) == 4
    for r in rows:       # the tracker never moves: every row is the first ground-truth box
        assert np.allclose([float(r[k]) for k in "xywh"], box0, atol=1e-3)


def test_track_import_of_a_file_without_tracker_warns_in_one_line(tmp_path, clean_registry,
                                                                  capsys):
    f = tmp_path / "nothing.py"
    f.write_text("X = 1\n")
    rc = cli.main(["track", "still-cli", "red-cube", "--import", str(f),
                   "--out", str(tmp_path / "o")])
    lines = capsys.readouterr().err.splitlines()
    assert rc == 2 and len(lines) == 2
    assert lines[0].startswith("trackbook: warning:") and "@trackers.register" in lines[0]
    assert lines[1].startswith("trackbook: error: unknown tracker 'still-cli'")


def test_track_import_errors(tmp_path, clean_registry, capsys):
    line = _one_line(capsys, cli.main(["track", "x", "red-cube", "--import", "nope/none.py",
                                       "--out", str(tmp_path / "o")]))
    assert "nope/none.py" in line
    assert not (tmp_path / "o").exists()


# --- track --groundtruth and --preset -----------------------------------------------------------

def test_track_groundtruth_file_is_scored(tmp_path, own_video, capsys):
    video, boxes, gt = own_video
    o = tmp_path / "o"
    # without it the video has no first box: one line, exit 2
    _one_line(capsys, cli.main(["track", "mean-shift", str(video), "--out", str(o)]))
    assert not o.exists()
    rc = cli.main(["track", "mean-shift", str(video), "--groundtruth", str(boxes),
                   "--out", str(o)])
    assert rc == 0
    assert "AUC" in capsys.readouterr().out
    csvs = list(o.glob("mean-shift_mine_*.csv"))        # --groundtruth: a name with a hash
    assert len(csvs) == 1
    rows = _rows(csvs[0])
    assert np.allclose([float(rows[0][k]) for k in "xywh"], gt[0])


def test_track_groundtruth_errors(tmp_path, capsys):
    assert "no such file" in _one_line(capsys, cli.main(
        ["track", "mean-shift", "red-cube", "--groundtruth", str(tmp_path / "none.txt")]))
    assert "carries its ground truth" in _one_line(capsys, cli.main(
        ["track", "mean-shift", "red-cube", "--groundtruth", __file__]))


def test_track_preset_paper(tmp_path, capsys):
    o = tmp_path / "o"
    assert cli.main(["track", "color-pf", "red-cube", "--max-frames", "3", "--out", str(o),
                     "--preset", "paper"]) == 0
    written = sorted(p.name for p in o.glob("*.csv"))
    assert len(written) == 1 and written[0] != "color-pf_red-cube.csv"   # not the book's run
    settings = json.loads((o / written[0]).with_suffix(".json").read_text())
    assert settings["preset"] == "paper"
    assert settings["params"]["sigma_color"] == 0.4     # Lee et al. 2012 print sigma = 0.4
    assert settings["params"]["init"] == "frame"        # particles over the whole frame at t=0
    # the boxes are those of the Python API's paper preset
    r = evaluate("color-pf", "red-cube", max_frames=3, preset="paper")
    got = np.array([[float(x[k]) for k in "xywh"] for x in _rows(o / written[0])])
    assert np.allclose(got, r.boxes, atol=1e-3)
    _one_line(capsys, cli.main(["track", "color-pf", "red-cube", "--preset", "papers"]))


# --- output names -----------------------------------------------------------------------------

def test_output_names_carry_the_settings(tmp_path, capsys):
    o = tmp_path / "o"
    base = ["track", "mean-shift", "red-cube", "--max-frames", "3", "--out", str(o)]
    assert cli.main(base) == 0
    assert cli.main(base + ["--param", "eps=1.0"]) == 0
    assert cli.main(base + ["--seed", "1"]) == 0
    assert cli.main(base) == 2                       # the same settings: refused ...
    assert cli.main(base + ["--force"]) == 0         # ... unless asked: the same files
    assert cli.main(base[:3] + base[5:]) == 0        # the whole clip, default settings
    names = sorted(p.name for p in o.glob("*.csv"))
    assert len(names) == 4 and len(set(names)) == 4
    assert "mean-shift_red-cube.csv" in names         # the default settings keep the plain name
    settings = [json.loads((o / n).with_suffix(".json").read_text()) for n in names]
    assert sorted(s["seed"] for s in settings) == [0, 0, 0, 1]
    assert sorted(str(s["max_frames"]) for s in settings) == ["3", "3", "3", "None"]
    assert any(s["params"]["eps"] == 1.0 for s in settings)


def test_output_name_of_a_default_run(tmp_path):
    s = {"tracker": "t", "seed": 0, "params": {"a": 1}}
    assert out_mod.output_stem("t", "c", s, dict(s)) == "t_c"
    other = out_mod.output_stem("t", "c", {**s, "params": {"a": 2}}, s)
    assert other.startswith("t_c_") and len(other) == len("t_c_") + 6


# --- errors: one line, exit code 2, no empty folder ------------------------------------------

@pytest.mark.parametrize("argv, word", [
    (["track", "mean-shift", "red-cube", "--box", "1,2"], "--box"),
    (["track", "mean-shift", "red-cube", "--box", "0,0,5000,10"], "--box"),
    (["track", "mean-shift", "red-cube", "--box", "nan,0,10,10"], "--box"),
    (["track", "mean-shift", "red-cube", "--max-frames", "1"], "--max-frames"),
    (["track", "mean-shift", "red-cube", "--no-such-flag"], "--no-such-flag"),
    (["track", "mean-shift", "red-cube", "--seed", "x"], "--seed"),
    (["trackers", "color-pf", "extra"], "extra"),
])
def test_usage_errors_one_line_exit_2(argv, word, tmp_path, capsys):
    o = tmp_path / "new" / "out"
    argv = argv + (["--out", str(o)] if argv[0] == "track" else [])
    try:
        rc = cli.main(argv)
    except SystemExit as e:          # argparse's errors end the process with the code
        rc = e.code
    assert word in _one_line(capsys, rc)
    assert not (tmp_path / "new").exists()


def test_python_dash_m_usage_error_exit_2(tmp_path):
    import subprocess
    p = subprocess.run([sys.executable, "-m", "trackbook", "track", "mean-shift", "red-cube",
                        "--box", "a,b,c,d", "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert p.stderr.count("\n") == 1 and p.stderr.startswith("trackbook: error: --box")
    assert not (tmp_path / "o").exists()


def test_failed_run_keeps_an_existing_out_folder(tmp_path, capsys):
    (tmp_path / "keep").mkdir()
    _one_line(capsys, cli.main(["track", "mean-shift", "red-cub", "--out",
                                str(tmp_path / "keep")]))
    assert (tmp_path / "keep").is_dir()


# --- the drawing -------------------------------------------------------------------------------

def test_estimate_colour_stands_out_on_every_sample_clip():
    for name in clips.available():
        clip = clips.load(name)
        frame = clip.frames[0]
        boxes = [t[0] for t in clip.targets.values()]
        chosen = out_mod.estimate_colors(frame, boxes)[0]
        assert chosen != out_mod.GT_COLOR
        # independent Lab (scikit-image) of the chosen colour and of each target's median
        # colour: at least 50 units apart (red on the red cube is about 10)
        lab_c = rgb2lab(np.array(chosen[::-1], float).reshape(1, 1, 3) / 255).ravel()
        for b in boxes:
            x, y, w, h = (int(v) for v in b)
            med = np.median(frame[y:y + h, x:x + w].reshape(-1, 3), axis=0)
            lab_t = rgb2lab(med[::-1].reshape(1, 1, 3) / 255).ravel()
            assert np.linalg.norm(lab_c - lab_t) > 50, (name, chosen, med)


def test_red_is_not_chosen_on_the_red_cube():
    clip = clips.load("red-cube")
    order = out_mod.estimate_colors(clip.frames[0], [clip.groundtruth[0]])
    assert order.index((40, 39, 214)) > 0


def test_video_codec_is_named(tmp_path, capsys):
    assert out_mod.video_codec() in ("avc1", "mp4v")
    assert cli.main(["track", "mean-shift", "red-cube", "--max-frames", "3",
                     "--out", str(tmp_path)]) == 0
    outp = capsys.readouterr().out
    assert out_mod.video_codec() in outp
    if out_mod.video_codec() == "mp4v":
        assert "VLC" in outp
    (video,) = tmp_path.glob("*.mp4")
    assert len(clips.load(video)) == 3


# --- notebooks ---------------------------------------------------------------------------------

def test_notebooks_from_another_folder(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)            # no book/ here: the installed chapters are used
    assert cli.main(["notebooks", "--out", "nb"]) == 0
    book = cli.find_book()
    expected = {p.stem for p in cli._chapters(book)}
    assert {p.stem for p in (tmp_path / "nb").glob("*.ipynb")} == expected
    assert "02_particle_filters" in expected and len(expected) >= 10


def test_notebooks_without_jupytext_names_the_extra(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "jupytext", None)      # import jupytext -> ImportError
    line = _one_line(capsys, cli.main(["notebooks", "--out", "nb"]))
    assert "trackbook[book]" in line and "bug" not in line
    assert not (tmp_path / "nb").exists()


def test_clips_listing_cuts_descriptions_at_a_word(capsys):
    assert cli.main(["clips"]) == 0
    lines = [ln for ln in capsys.readouterr().out.splitlines() if " frames " in ln]
    assert len(lines) == len(clips.available())
    for ln, name in zip(lines, clips.available()):
        full = " ".join(clips.describe(name).split(": ", 1)[1].split())
        shown = ln.split(" frames ", 1)[1].split("  ", 1)[1].strip()
        # either the whole description, or whole words of it followed by " ..."
        assert shown == full or (shown.endswith(" ...") and
                                 full.startswith(shown[:-4]) and full[len(shown) - 4] == " ")


def test_trackers_import_shows_your_params(tmp_path, clean_registry, capsys):
    f = tmp_path / "still.py"
    f.write_text(STILL)
    assert cli.main(["trackers", "still-cli", "--import", str(f)]) == 0
    assert "A box that never moves" in capsys.readouterr().out


def test_install_story_in_pyproject_and_readme():
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    meta = tomllib.loads((root / "pyproject.toml").read_text())
    assert any(d.replace(" ", "").startswith("jupyterlab>=4")
               for d in meta["project"]["optional-dependencies"]["book"])
    # the chapters ship inside the package: book/ installed as the package trackbook._book
    assert meta["tool"]["setuptools"]["package-data"]["trackbook._book"] == ["*.md"]
    assert '"trackbook._book": "book"' in (root / "setup.py").read_text()
    readme = (root / "README.md").read_text()
    plain = readme.index("pip install -e .  ")
    assert plain < readme.index('pip install -e ".[book]"')
    assert "git+" in readme[plain - 200:plain + 400]
    assert "book/appendix_own_tracker.md" in readme


def test_trackers_listing_shows_no_markup(capsys):
    """A terminal cannot show a quote popover: the list and a tracker's page carry no
    quote marker of the register, no reST backticks and no repeated name."""
    from trackbook import cli, trackers

    assert cli.main(["trackers"]) == 0
    pages = [capsys.readouterr().out]
    for name in trackers.available():
        assert cli.main(["trackers", name]) == 0
        out = capsys.readouterr().out
        assert not out.startswith(f"{name}: {name}:"), out.splitlines()[0]
        pages.append(out)
    text = "\n".join(pages)
    assert "[quote:" not in text and "``" not in text and ":func:`" not in text
