"""A student's bench beside the OTB authors' published runs, and the same bench read by got10k.

The bench runs for real (``color-pf`` on two of the published sequences, when the development
sequences are here). Expected values come from outside the code under test: the published
numbers from the committed CSV read with :mod:`csv`, the bench's from its own OTB-layout box
files scored by a one-frame-at-a-time loop written the way the OTB toolkit scores a run.
"""
from __future__ import annotations

import csv
import re
from pathlib import Path

import numpy as np
import pytest

from trackbook.clips import read_groundtruth
from trackbook.evaluation import bench, published

from .conftest import SEQUENCES

ROOT = Path(__file__).resolve().parents[1]
CSV = ROOT / "src" / "trackbook" / "data" / "otb_published.csv"
BENCHED = ("Crossing", "Couple")          # the two shortest published sequences
needs_benched = pytest.mark.skipif(
    not all(s in SEQUENCES for s in BENCHED),
    reason="the development sequences Crossing and Couple are not here (set TRACKBOOK_SEQUENCES)")


def published_csv() -> dict:
    """``{(tracker, sequence): {column: text}}`` straight from the committed file."""
    with open(CSV, newline="", encoding="utf-8") as f:
        return {(r["tracker"], r["sequence"]): r for r in csv.DictReader(f)}


def groundtruth(name):
    folder = SEQUENCES[name]
    gt = folder / "groundtruth.txt"
    return read_groundtruth(gt if gt.is_file() else folder / "groundtruth_rect.txt")


def toolkit_score(boxes, gt):
    """(AUC, success rate at IoU 0.5) as the OTB toolkit scores a run: frame 1 set to the
    ground truth, every frame counted, IoU > threshold, one frame at a time."""
    boxes = [list(b) for b in boxes]
    boxes[0] = list(gt[0])
    ious = []
    for a, b in zip(boxes, gt):
        iw = max(0.0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
        ih = max(0.0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
        inter = iw * ih
        ious.append(inter / (a[2] * a[3] + b[2] * b[3] - inter))
    rates = [sum(1 for o in ious if o > k / 20) / len(ious) for k in range(21)]
    return sum(rates) / 21, sum(1 for o in ious if o > 0.5) / len(ious)


def read_otb_file(path):
    return [[float(v) for v in line.split(",")] for line in Path(path).read_text().splitlines()]


@pytest.fixture(scope="module")
def bench_out(tmp_path_factory):
    if not all(s in SEQUENCES for s in BENCHED):
        pytest.skip("the development sequences Crossing and Couple are not here")
    out = tmp_path_factory.mktemp("bench") / "mine"
    bench.run(["color-pf"], [str(SEQUENCES[s]) for s in BENCHED], out, progress=False,
              reference=False, workers=1)
    return out


def bars(ax) -> dict:
    """``{tick label: bar length}`` of a horizontal bar panel, matched by position."""
    labels = {round(float(y), 6): t.get_text() for y, t in zip(ax.get_yticks(),
                                                               ax.get_yticklabels())}
    return {labels[round(p.get_y() + p.get_height() / 2, 6)]: p.get_width()
            for p in ax.patches}


def panels(fig) -> dict:
    return {ax.get_title(): ax for ax in fig.axes if ax.get_visible() and ax.get_title()}


# --- the side-by-side plot -------------------------------------------------------------------

@needs_benched
@pytest.mark.parametrize("measure, column, index", [("auc", "auc", 0),
                                                    ("success_rate_iou50",
                                                     "success_rate_iou50", 1)])
def test_plot_draws_the_published_values_and_ours_scored_the_same_way(bench_out, measure,
                                                                      column, index):
    from matplotlib.figure import Figure

    fig = published.plot_side_by_side(bench_out, measure=measure)
    assert isinstance(fig, Figure)
    table = published_csv()
    got = panels(fig)
    assert set(got) == {*BENCHED, "mean over 2 sequences"}
    want_all = {}
    for seq in BENCHED:
        want = {t: float(r[column]) for (t, s), r in table.items() if s == seq and r[column]}
        boxes = read_otb_file(bench_out / "otb" / "color-pf" / f"{seq}.txt")
        want["color-pf (ours)"] = toolkit_score(boxes, groundtruth(seq))[index]
        drawn = bars(got[seq])
        assert set(drawn) == set(want)
        for label, v in want.items():
            assert drawn[label] == pytest.approx(v, abs=1e-12), (seq, label)
        ax = got[seq]
        bottom_up = sorted(zip(ax.get_yticks(), (t.get_text() for t in ax.get_yticklabels())))
        lengths = [drawn[label] for _, label in bottom_up]
        assert lengths == sorted(lengths)        # the best on top
        want_all[seq] = want
    mean = bars(got["mean over 2 sequences"])
    assert mean == pytest.approx({t: np.mean([want_all[s][t] for s in BENCHED])
                                  for t in want_all[BENCHED[0]]}, abs=1e-12)


@needs_benched
def test_ours_are_marked_as_ours(bench_out):
    from trackbook.style import GREY
    from matplotlib.colors import to_hex

    fig = published.plot_side_by_side(bench_out)
    ax = panels(fig)["Crossing"]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    ours = [t for t in ax.get_yticklabels() if t.get_text().endswith("(ours)")]
    assert [t.get_text() for t in ours] == ["color-pf (ours)"]
    assert ours[0].get_fontweight() == "bold"
    colours = {to_hex(p.get_facecolor()) for p in ax.patches}
    assert len(colours) == 2 and GREY.lower() in colours
    assert "KCF" in labels and "MIL" not in labels    # MIL has no published AUC
    from matplotlib.text import Text

    texts = [t.get_text() for t in fig.findobj(Text)]
    assert "no AUC published for CPF, KMS, MIL (toolkit scores only)" in texts
    assert any(t.startswith("AUC of the success plot") and "frames 1..N" in t for t in texts)
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert legend == ["published (the OTB authors' runs)",
                      "ours (this bench; each tracker in its colour)"]


@needs_benched
def test_bench_scores_restate_the_bench_to_the_toolkits_count(bench_out):
    rows = {r["clip"]: r for r in bench.load(bench_out)}
    for r in published.bench_scores(bench_out):
        seq = r["sequence"]
        n = rows[seq]["frames"]
        assert n == len(groundtruth(seq))
        # by hand: frame 1 adds one success and clears 20 of the 21 thresholds
        assert r["success_rate_iou50"] == pytest.approx(
            (rows[seq]["tracking_rate"] * (n - 1) + 1) / n, abs=1e-12)
        assert r["auc"] == pytest.approx((rows[seq]["auc"] * (n - 1) * 21 + 20) / (21 * n),
                                         abs=1e-12)
        assert r["seeds"] == 1


def test_with_first_frame_by_hand():
    # 4 of frames 2..10 succeed; frame 1 makes it 5 of 10
    assert published.with_first_frame(4 / 9, 10) == pytest.approx(0.5)
    assert published.without_first_frame(published.with_first_frame(0.3, 7), 7) == \
        pytest.approx(0.3)
    # a tracker that scores IoU 0 on frames 2..3 of 3 frames: only frame 1, 20 thresholds
    assert published.with_first_frame(0.0, 3, auc=True) == pytest.approx(20 / 63)


# --- refusals --------------------------------------------------------------------------------

def test_a_bench_of_sample_clips_is_refused_naming_the_sequences(tmp_path):
    out = tmp_path / "samples"
    bench.run(["color-pf"], ["red-cube"], out, progress=False, reference=False, workers=1,
              max_frames=8)
    with pytest.raises(ValueError, match="none of the sequences.*David.*--clips shared"):
        published.plot_side_by_side(out)


@needs_benched
def test_a_shortened_run_is_refused(tmp_path):
    out = tmp_path / "short"
    bench.run(["color-pf"], [str(SEQUENCES["Crossing"])], out, progress=False,
              reference=False, workers=1, max_frames=10)
    with pytest.raises(ValueError, match="10 frames of Crossing.*120.*--max-frames"):
        published.plot_side_by_side(out)


def test_a_folder_that_is_not_a_bench_is_refused(tmp_path):
    with pytest.raises(ValueError, match="no results.json"):
        published.plot_side_by_side(tmp_path)


def test_rows_are_accepted_and_bad_options_refused():
    rows = [{"tracker": "mine", "clip": "Jogging-1", "frames": 307, "frames_scored": 306,
             "auc": 0.5, "tracking_rate": 0.5}]
    (r,) = published.bench_scores(rows)
    assert r["sequence"] == "Jogging1"                # OTB's name matches the table's
    with pytest.raises(ValueError, match="unknown measure 'iou'"):
        published.plot_side_by_side(rows, measure="iou")
    with pytest.raises(ValueError, match="theirs.*has mine"):
        published.plot_side_by_side(rows, trackers=["theirs"])
    with pytest.raises(ValueError, match="dicts with 'tracker' and 'clip'"):
        published.bench_scores([("mine", "David")])


# --- got10k's metric functions on the same bench (the README's recipe, run) -------------------

def readme_recipe() -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    (block,) = [b for b in blocks if "class OTBSubset(ExperimentOTB)" in b]
    return block


@needs_benched
def test_the_readme_got10k_recipe_gives_trackbooks_numbers(bench_out, tmp_path, monkeypatch,
                                                            capsys):
    pytest.importorskip("got10k", reason="got10k is an optional extra (pip install got10k six)")
    pytest.importorskip("six", reason="got10k's experiments import six (pip install six)")
    import matplotlib.pyplot as plt

    code = readme_recipe()
    for name, value in (("OUT", repr(str(bench_out))),
                        ("ROOT", repr(str(SEQUENCES[BENCHED[0]].parent))),
                        ("NAMES", repr(list(BENCHED)))):
        code, n = re.subn(rf"^{name} = .*$", f"{name} = Path({value})" if name != "NAMES"
                          else f"{name} = {value}", code, flags=re.M)
        assert n == 1, name
    monkeypatch.chdir(tmp_path)                 # report() writes reports/ where it runs
    ns: dict = {}
    try:
        exec(compile(code, "README.md", "exec"), ns)
    finally:
        plt.close("all")
    assert (tmp_path / "reports" / "color-pf" / "success_plots.png").is_file()
    perf, same = ns["perf"], ns["same"]
    aucs = []
    for row in bench.load(bench_out):
        seq, n = row["clip"], row["frames"]
        # trackbook's count: got10k's score equals results.csv's AUC
        assert same["color-pf"]["seq_wise"][seq]["success_score"] == pytest.approx(
            row["auc"], abs=1e-12)
        # got10k's count: the OTB toolkit's score of the same box file, by the slow loop
        boxes = read_otb_file(bench_out / "otb" / "color-pf" / f"{seq}.txt")
        auc, rate = toolkit_score(boxes, groundtruth(seq))
        g = perf["color-pf"]["seq_wise"][seq]
        assert g["success_score"] == pytest.approx(auc, abs=1e-12)
        assert g["success_rate"] == pytest.approx(rate, abs=1e-12)
        assert g["success_score"] == pytest.approx(
            published.with_first_frame(row["auc"], n, auc=True), abs=1e-12)
        aucs.append(row["auc"])
    assert same["color-pf"]["overall"]["success_score"] == pytest.approx(np.mean(aucs),
                                                                         abs=1e-12)
    assert "color-pf     Crossing   trackbook" in capsys.readouterr().out
