"""The OTB benchmark's published per-sequence results, beside the book's own trackers.

Source
------
Wu, Lim and Yang's Object Tracking Benchmark (OTB-2013, CVPR; OTB-100, "Object Tracking
Benchmark", TPAMI 2015) distributes, with its toolkit, the result files of the trackers it
evaluated: one file per tracker and sequence with the box the tracker reported on every frame.
Two public copies are used here, each read at a fixed commit:

* MATLAB-toolkit result files ``results/results_OPE/results_OPE_OTB100/<seq>_<tracker>.mat``
  in ``github.com/zhangzheng0131/Tracker_Benchmark_tb100`` (a copy of the OTB toolkit v1.0
  with OPE result files of 16 trackers on OTB-100; the repository does not say where each file
  came from), read as boxes for IVT, Struck, TLD, MEEM and KCF (the file ``KCF_GaussHog``:
  Gaussian kernel on HOG features, the variant the KCF paper calls KCF). Its annotations
  (``anno_TB100``) equal the development set's ground truth on all five sequences.
* Per-sequence scores ``results/OPE/<tracker>/scores_tb100/ALL.json`` of the Python port of
  the toolkit, ``github.com/jwlim/tracker_benchmark`` (Jongwoo Lim, an OTB author), for CPF
  (Pérez et al.'s colour particle filter), KMS (Comaniciu et al.'s kernel mean-shift) and MIL,
  whose boxes are in neither copy. They hold, per sequence, ten times the fraction of frames
  with IoU below 0.5 (``errorNum``), not the boxes: the success rate is one minus that fraction
  (an IoU of exactly 0.5 counts as a success there) and no AUC can be had. Where that
  repository also holds the boxes (Struck, MEEM) its scores are reproduced exactly from them.
  The same files give a second value for IVT, Struck, TLD and MEEM (``alt_success_rate_iou50``):
  close to the first for IVT and MEEM, far from it for Struck and TLD (other runs).

The table ``trackbook/data/otb_published.csv`` is recomputed from downloaded copies of those
files by ``benchmarks/otb_published.py`` (which downloads nothing; the repository, commit and
path of every file are in the ``source`` and ``alt_source`` columns).

Measure
-------
The success rate at IoU 0.5: the fraction of frames whose box overlaps the ground truth by more
than 0.5 (intersection over union), and, where the boxes are available, the AUC of the success
curve (the mean of the 21 rates at thresholds 0, 0.05, ..., 1). As the OTB toolkit scores a run
(``calcSeqErrRobust.m``): every frame 1..N counts, frame 1 being set to the ground truth; a box
with a NaN or a side <= 0 is replaced by the previous frame's box; IVT's affine states are turned
into boxes as the toolkit's ``calcRectCenter.m`` does. The ground truth is the development set's
(``shared/data/sequences``), which is OTB's: the same boxes, David frames 300-770, Jogging-1 the
first target of Jogging; the script checks every file's length against it.

What the comparison can and cannot show
---------------------------------------
It can show where the book's trackers stand among the trackers the benchmark made canonical, on
the same frames and the same ground truth, in the measure the benchmark used. It cannot show
which tracker is better in general: these are five sequences; a published number is the
tracker authors' code run once through a toolkit (their parameters, their initialisation on
the ground-truth box of frame 1, which the Python toolkit passes one pixel shifted to some
trackers), a book number is the book's own implementation run once with one seed, and a
stochastic tracker's single run can change with the seed; the two public copies of the result
files do not agree with each other for Struck and TLD (column ``alt_success_rate_iou50``), so
a published number is one run, not the tracker's value. A gap of a few frames on one sequence
means nothing; a tracker that fails where the canonical ones succeed (or the reverse) is worth
a look at the frames.

A bench of your own
-------------------
:func:`plot_side_by_side` draws a ``trackbook bench`` folder beside the table on the sequences
both cover, and :func:`bench_scores` gives its numbers: the bench scores frames 2..N (frame 1
is the initialisation), the table frames 1..N with frame 1 set to the ground truth, as the OTB
toolkit and got10k count; the bench's numbers are restated to the table's count
(:func:`with_first_frame`), never the reverse, so the published values are drawn as they are.
"""

from __future__ import annotations

import csv
import io
import json
import math
from importlib import resources
from pathlib import Path

import numpy as np

from .._checks import check_boxes
from .metrics import SUCCESS_THRESHOLDS, iou

#: Development-set sequence name -> OTB's name for it.
SEQUENCES = {"David": "David", "Jogging1": "Jogging-1", "MotorRolling": "MotorRolling",
             "Couple": "Couple", "Crossing": "Crossing"}
#: The published trackers in the table, in the order the chapter lists them.
TRACKERS = ("CPF", "KMS", "IVT", "MIL", "Struck", "TLD", "MEEM", "KCF")

#: Where each tracker's numbers come from: ("mat", file stem) or ("json", folder name).
FILES = {"IVT": ("mat", "IVT"), "Struck": ("mat", "Struck"), "TLD": ("mat", "TLD"),
         "MEEM": ("mat", "MEEM"), "KCF": ("mat", "KCF_GaussHog"),
         "CPF": ("json", "CPF"), "KMS": ("json", "KMS"), "MIL": ("json", "MIL")}
#: The Python toolkit's folder for a tracker also present as boxes (the second value).
ALT_JSON = {"IVT": "IVT", "Struck": "STRUCK", "TLD": "TLD", "MEEM": "MEEM"}

MAT_REPO = "github.com/zhangzheng0131/Tracker_Benchmark_tb100"
MAT_COMMIT = "61282dbf14495f7091163917def33a83046f7ca9"
MAT_DIR = "results/results_OPE/results_OPE_OTB100"
JSON_REPO = "github.com/jwlim/tracker_benchmark"
JSON_COMMIT = "e2480f733ffd60332b205374783ff4d682090929"
JSON_DIR = "results/OPE"

COLUMNS = ("tracker", "sequence", "otb_sequence", "success_rate_iou50", "auc", "frames",
           "method", "source", "alt_success_rate_iou50", "alt_source")

_TABLE = "otb_published.csv"


# --- scoring as the OTB toolkit does ----------------------------------------------------------

def ivt_affine_to_rect(tmplsize, p) -> np.ndarray:
    """The box of an IVT affine state, as the OTB toolkit's ``calcRectCenter.m`` computes it.

    ``p`` holds the affine matrix ``M = [[p1, p3, p4], [p2, p5, p6]]`` that maps the template
    (``tmplsize`` = width, height, centred on the origin) into the frame; the box spans the
    floored first and third mapped corners.
    """
    w, h = (float(v) for v in np.ravel(tmplsize)[:2])
    p = np.asarray(p, dtype=float).ravel()
    if p.size != 6:
        raise ValueError(f"an IVT affine state has 6 values, got {p.size}; pass one row of res.")
    M = np.array([[p[0], p[2], p[3]], [p[1], p[4], p[5]]])
    corners = np.floor(M @ np.array([[1.0, 1.0], [-w / 2, w / 2], [-h / 2, h / 2]]))
    (x0, x2), (y0, y2) = corners
    return np.array([x0, y0, x2 - x0, y2 - y0])


def toolkit_boxes(res, gt, *, kind: str = "rect", tmplsize=None) -> np.ndarray:
    """A result file's per-frame boxes as the OTB toolkit scores them.

    ``kind`` is the file's ``type``: ``"rect"`` (x, y, w, h rows; a row with a NaN or a side
    <= 0 takes the previous frame's box) or ``"ivtAff"`` (IVT's affine states, see
    :func:`ivt_affine_to_rect`). Frame 1 is set to the ground truth, as the toolkit does.
    """
    g = check_boxes(gt, name="gt")
    if kind == "rect":
        b = check_boxes(res, name="res").copy()
        for i in range(1, b.shape[0]):
            if np.any(np.isnan(b[i])) or b[i, 2] <= 0 or b[i, 3] <= 0:
                b[i] = b[i - 1]
    elif kind == "ivtAff":
        b = np.array([ivt_affine_to_rect(tmplsize, p) for p in np.atleast_2d(res)])
    else:
        raise ValueError(f"result type {kind!r} is not read here; expected 'rect' or 'ivtAff'.")
    if b.shape[0] != g.shape[0]:
        raise ValueError(f"the result has {b.shape[0]} boxes but the ground truth {g.shape[0]} "
                         "rows; the file is for another frame range of the sequence.")
    b[0] = g[0]
    return b


def score(boxes, gt) -> tuple[float, float]:
    """``(success rate at IoU 0.5, AUC)`` over every frame with a known ground truth.

    The success rate counts IoU **>** 0.5; the AUC is the mean of the 21 success rates at
    thresholds 0, 0.05, ..., 1 (OTB's "AUC"; Wu et al. 2013, the success plot).
    """
    v = iou(boxes, gt)
    v = v[~np.isnan(v)]
    if v.size == 0:
        raise ValueError("no frame has a known ground truth; check the ground-truth file.")
    rates = (v[None, :] > SUCCESS_THRESHOLDS[:, None]).mean(axis=1)
    return float((v > 0.5).mean()), float(rates.mean())


def rate_from_error_num(error_num: float, frames: int) -> float:
    """The success rate held by the Python toolkit's ``errorNum`` (10 x the fraction of frames
    with IoU < 0.5), checked against the sequence length: it must be a whole number of frames.
    """
    k = (1.0 - error_num / 10.0) * frames
    if abs(k - round(k)) > 1e-6:
        raise ValueError(f"errorNum {error_num} is not a whole number of frames out of {frames}: "
                         "the scores were computed on another frame range.")
    return round(k) / frames


# --- building the table from downloaded files (benchmarks/otb_published.py) -------------------

def _mat_source(stem: str) -> str:
    return f"{MAT_REPO}@{MAT_COMMIT}:{MAT_DIR}/{stem}.mat"


def _json_source(folder: str) -> str:
    return f"{JSON_REPO}@{JSON_COMMIT}:{JSON_DIR}/{folder}/scores_tb100/ALL.json"


def _mat_stem(otb_seq: str, tracker_file: str) -> str:
    # the toolkit's file names start with the sequence name's first letter in lower case
    return f"{otb_seq[0].lower()}{otb_seq[1:]}_{tracker_file}"


def _read_mat(path: Path):
    import scipy.io

    m = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)
    r = m["results"]
    return r[0] if isinstance(r, np.ndarray) else r


def _json_rate(json_dir: Path, folder: str, otb_seq: str, frames: int) -> float:
    path = Path(json_dir) / folder / "scores_tb100" / "ALL.json"
    if not path.is_file():
        raise FileNotFoundError(f"{path} not found; --json is the folder {JSON_DIR} of a clone "
                                f"of {JSON_REPO} at {JSON_COMMIT}.")
    d = json.loads(path.read_text())
    i = d["seqs"].index(otb_seq)
    return rate_from_error_num(d["errorNum"][i], frames)


def build_rows(mat_dir, json_dir, groundtruth: dict) -> list[dict]:
    """The table's rows from the downloaded result files.

    ``groundtruth`` maps each development-set name of :data:`SEQUENCES` to its N x 4 ground
    truth. Raises ``FileNotFoundError`` naming a missing file and where it comes from.
    """
    rows = []
    for tracker in TRACKERS:
        kind, name = FILES[tracker]
        for seq, otb_seq in SEQUENCES.items():
            gt = check_boxes(groundtruth[seq], name=f"ground truth of {seq}")
            n = gt.shape[0]
            row = {"tracker": tracker, "sequence": seq, "otb_sequence": otb_seq, "frames": n,
                   "auc": None, "alt_success_rate_iou50": None, "alt_source": ""}
            if kind == "mat":
                stem = _mat_stem(otb_seq, name)
                path = Path(mat_dir) / f"{stem}.mat"
                if not path.is_file():
                    raise FileNotFoundError(f"{path} not found; --mat is the folder {MAT_DIR} of "
                                            f"a clone of {MAT_REPO} at {MAT_COMMIT}.")
                r = _read_mat(path)
                boxes = toolkit_boxes(np.asarray(r.res, dtype=float), gt, kind=str(r.type),
                                      tmplsize=getattr(r, "tmplsize", None))
                rate, area = score(boxes, gt)
                row.update(success_rate_iou50=rate, auc=area, method="boxes",
                           source=_mat_source(stem))
                if tracker in ALT_JSON:
                    row.update(alt_success_rate_iou50=_json_rate(json_dir, ALT_JSON[tracker],
                                                                 otb_seq, n),
                               alt_source=_json_source(ALT_JSON[tracker]))
            else:
                row.update(success_rate_iou50=_json_rate(json_dir, name, otb_seq, n),
                           method="toolkit score", source=_json_source(name))
            rows.append(row)
    return rows


def write_csv(rows, path) -> None:
    """Write the rows with :data:`COLUMNS` (numbers to 12 significant digits, enough to read a
    count of frames back exactly; missing values empty)."""
    def fmt(v):
        if v is None:
            return ""
        if isinstance(v, float):
            return f"{v:.12g}"
        return str(v)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([fmt(r[c]) for c in COLUMNS])


# --- reading the committed table -------------------------------------------------------------

def _parse(text: str) -> list[dict]:
    out = []
    for r in csv.DictReader(io.StringIO(text)):
        row = dict(r)
        row["frames"] = int(r["frames"])
        for c in ("success_rate_iou50", "auc", "alt_success_rate_iou50"):
            row[c] = float(r[c]) if r[c] != "" else None
        out.append(row)
    return out


def load() -> list[dict]:
    """The committed table of published per-sequence results, one dict per tracker and sequence.

    Keys: :data:`COLUMNS`. ``success_rate_iou50`` is the fraction of frames 1..N with IoU > 0.5
    (frame 1 counted as the toolkit does); ``auc`` is None where only the toolkit's score is
    available (CPF, KMS, MIL); ``sequence`` is the development set's name, ``otb_sequence``
    OTB's; ``source`` names repository, commit and path of the file the number comes from.
    """
    text = resources.files("trackbook").joinpath("data", _TABLE).read_text(encoding="utf-8")
    return _parse(text)


def without_first_frame(rate: float, frames: int) -> float:
    """A rate over frames 1..N restated over frames 2..N.

    The toolkit sets frame 1 to the ground truth (IoU 1, a success), so the count of successes
    over frames 2..N is ``rate * N - 1``; the book scores frames 2..N (frame 1 is the
    initialisation for both).
    """
    return (rate * frames - 1.0) / (frames - 1)


def side_by_side(results=None) -> list[dict]:
    """Published and book trackers' success rates at IoU 0.5 on the OTB sequences, one table.

    Rows ``{"tracker", "source", "sequence", "rate"}``, ``source`` being ``"published"`` or
    ``"trackbook"``, ``sequence`` the development set's name; rates are over frames 2..N for
    both (see :func:`without_first_frame`). The book's rates are the ``tracking_rate`` of the
    committed real-sequence results (``trackbook.results.load("real")``, book defaults), or of
    ``results`` (a list of such records) when given.
    """
    rows = []
    for r in load():
        rows.append({"tracker": r["tracker"], "source": "published", "sequence": r["sequence"],
                     "rate": without_first_frame(r["success_rate_iou50"], r["frames"])})
    if results is None:
        from .. import results as _results

        results = _results.load("real").where(preset="book").rows
    for rec in results:
        if rec.get("clip") in SEQUENCES and rec.get("tracking_rate") is not None:
            rate = float(rec["tracking_rate"])
            if not math.isnan(rate):
                rows.append({"tracker": rec["tracker"], "source": "trackbook",
                             "sequence": rec["clip"], "rate": rate})
    return rows


# --- a bench's runs beside the published ones ------------------------------------------------

#: What :func:`plot_side_by_side` can draw: the column of :func:`load` and its axis label.
MEASURES = {"auc": "AUC of the success plot",
            "success_rate_iou50": "success rate (IoU > 0.5)"}


def with_first_frame(value: float, frames: int, *, auc: bool = False) -> float:
    """A rate (or, with ``auc=True``, an AUC) over frames 2..N restated over frames 1..N as
    the OTB toolkit and got10k count them: frame 1 set to the ground truth.

    Frame 1 then has IoU 1: a success at IoU > 0.5 (one more frame) and above 20 of the 21
    thresholds of the success curve (all but 1), so the count of successes grows by 1, or the
    sum of the 21 rates' numerators by 20. The inverse of :func:`without_first_frame` for a
    rate.
    """
    gained = 20.0 / 21.0 if auc else 1.0
    return (float(value) * (frames - 1) + gained) / frames


def _key(name: str) -> str:
    # David, Jogging1, Jogging-1 (OTB's name) and Jogging.1 (trackbook's name for the first
    # target of OTB-100's Jogging) are one sequence
    return "".join(ch for ch in str(name).lower() if ch.isalnum())


def _bench_rows(bench) -> list[dict]:
    if isinstance(bench, (str, Path)) or hasattr(bench, "__fspath__"):
        from . import bench as _bench

        folder = Path(bench)
        if not (folder / "results.json").is_file():
            raise ValueError(f"{folder} has no results.json: it is not the --out folder of a "
                             "finished `trackbook bench` (run the bench, or pass the rows "
                             "bench.run returns).")
        return _bench.load(folder)
    rows = list(bench)
    if rows and not all(isinstance(r, dict) and {"tracker", "clip"} <= set(r) for r in rows):
        raise ValueError("bench rows must be dicts with 'tracker' and 'clip', as bench.run and "
                         "bench.load return them; or pass the bench's --out folder.")
    return rows


def bench_scores(bench) -> list[dict]:
    """A bench's runs on the published sequences, scored as the published ones are.

    Parameters
    ----------
    bench : path or list of dict
        The ``--out`` folder of ``trackbook bench`` (its ``results.json``) or the rows that
        :func:`trackbook.evaluation.bench.run` returns.

    Returns
    -------
    list of dict
        One row per tracker and published sequence the bench ran, ``{"tracker", "sequence",
        "auc", "success_rate_iou50", "frames", "seeds"}``: the bench's AUC and tracking rate
        (frames 2..N) restated over frames 1..N with :func:`with_first_frame`, as the
        toolkit counts them, and averaged over the bench's seeds. ``sequence`` is the
        development set's name (:data:`SEQUENCES`). A bench clip matches a published sequence
        by name (``David``, ``Jogging1``, ``Jogging-1`` or ``Jogging.1``; case and
        punctuation aside).

    Raises
    ------
    ValueError
        When a matching clip was benched on another number of frames than the published
        runs (``--max-frames``), which would compare different frames.
    """
    frames = {r["sequence"]: r["frames"] for r in load()}
    by_key = {_key(k): k for k in SEQUENCES} | {_key(v): k for k, v in SEQUENCES.items()}
    acc: dict = {}
    for r in _bench_rows(bench):
        seq = by_key.get(_key(r["clip"]))
        if seq is None or r.get("auc") is None:
            continue
        n = int(r["frames"])
        if n != frames[seq] or int(r.get("frames_scored", n - 1)) != n - 1:
            raise ValueError(f"the bench ran {r['tracker']} on {n} frames of {r['clip']}, the "
                             f"published runs cover its {frames[seq]} frames; bench it "
                             "without --max-frames to compare.")
        acc.setdefault((r["tracker"], seq), []).append(
            (with_first_frame(r["auc"], n, auc=True), with_first_frame(r["tracking_rate"], n)))
    return [{"tracker": t, "sequence": s, "auc": float(np.mean([v[0] for v in vs])),
             "success_rate_iou50": float(np.mean([v[1] for v in vs])), "frames": frames[s],
             "seeds": len(vs)} for (t, s), vs in acc.items()]


def plot_side_by_side(bench, *, measure: str = "auc", trackers=None):
    """A bench's trackers beside the OTB authors' published runs, on the sequences both cover.

    One panel per published sequence the bench ran, and one for the mean over them: a
    horizontal bar per tracker, best on top, the value at its end. The published runs
    (:func:`load`, the values of the committed table as they are) are grey; the bench's runs
    are coloured and named ``"<tracker> (ours)"``, restated to the toolkit's count of frames
    (:func:`bench_scores`). The mean panel holds the trackers with a value on every panel.

    Parameters
    ----------
    bench : path or list of dict
        The ``--out`` folder of ``trackbook bench`` or the rows :func:`bench.run
        <trackbook.evaluation.bench.run>` returns.
    measure : {"auc", "success_rate_iou50"}
        The AUC of the success plot (published for IVT, Struck, TLD, MEEM and KCF, whose
        boxes are available) or the success rate at IoU 0.5 (all eight trackers).
    trackers : list of str, optional
        The bench's trackers to draw (default: all of them, the ``opencv-mil`` reference
        included).

    Returns
    -------
    matplotlib.figure.Figure
        A figure not attached to pyplot (it does not change a notebook's backend); Jupyter
        shows it as a cell's value, ``fig.savefig(path)`` writes it.

    Raises
    ------
    ValueError
        An unknown ``measure``, a folder that is not a bench's, a bench that ran none of the
        published sequences (or none of ``trackers``), or one run on fewer frames.
    """
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    from ..style import GREY, label_colors

    if measure not in MEASURES:
        raise ValueError(f"unknown measure {measure!r}; use one of {', '.join(MEASURES)}.")
    ours = bench_scores(bench)
    names = list(dict.fromkeys(r["tracker"] for r in ours))
    if trackers is not None:
        trackers = [trackers] if isinstance(trackers, str) else list(trackers)
        missing = [t for t in trackers if t not in names]
        if missing:
            raise ValueError(f"tracker(s) {', '.join(missing)} have no run on a published "
                             f"sequence in this bench; it has {', '.join(names) or 'none'}.")
        names = trackers
    seqs = [s for s in SEQUENCES if any(r["sequence"] == s for r in ours)]
    if not seqs:
        raise ValueError("the bench ran none of the sequences with published results ("
                         f"{', '.join(SEQUENCES)}); bench them, e.g. --clips shared or the "
                         "root of OTB-100, without --max-frames.")
    values: dict = {}                      # label -> {sequence: value}
    colour: dict = {}                      # label -> bar colour
    for r in load():
        if r["sequence"] in seqs and r[measure] is not None:
            values.setdefault(r["tracker"], {})[r["sequence"]] = r[measure]
            colour[r["tracker"]] = GREY
    ours_colour = dict(zip(names, label_colors(names)))
    for r in ours:
        if r["tracker"] in names:
            label = f"{r['tracker']} (ours)"
            values.setdefault(label, {})[r["sequence"]] = r[measure]
            colour[label] = ours_colour[r["tracker"]]
    panels = [(s, {t: v[s] for t, v in values.items() if s in v}) for s in seqs]
    if len(seqs) > 1:
        panels.append((f"mean over {len(seqs)} sequences",
                       {t: float(np.mean([v[s] for s in seqs])) for t, v in values.items()
                        if all(s in v for s in seqs)}))
    ncols = min(3, len(panels))
    nrows = -(-len(panels) // ncols)
    rows_per = max(len(p[1]) for p in panels)
    fig = Figure(figsize=(3.6 * ncols, (0.24 * rows_per + 1.1) * nrows + 0.9))
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    for ax, (title, vals) in zip(axes, panels):
        order = sorted(vals, key=lambda t: -vals[t])
        y = np.arange(len(order))[::-1]
        bars = ax.barh(y, [vals[t] for t in order], height=0.7,
                       color=[colour[t] for t in order])
        ax.bar_label(bars, fmt="%.2f", padding=2, fontsize=7)
        ax.set_yticks(y, order, fontsize=8)
        for label in ax.get_yticklabels():
            if label.get_text().endswith(" (ours)"):
                label.set_fontweight("bold")
        ax.set(xlim=(0, 1.12), title=title)
        ax.title.set_fontsize(9)
        ax.tick_params(axis="x", labelsize=7)
        ax.grid(axis="x", alpha=0.3)
    for ax in axes[len(panels):]:
        ax.set_visible(False)
    seeds = max(r["seeds"] for r in ours)
    fig.suptitle(f"{MEASURES[measure]}: published OTB runs and this bench's"
                 f"{f' (mean of {seeds} seeds)' if seeds > 1 else ''}, frames 1..N as the "
                 "OTB toolkit counts them", fontsize=9)
    handles = [Patch(color=GREY, label="published (the OTB authors' runs)"),
               Patch(color=colour[f"{names[0]} (ours)"],
                     label="ours (this bench; each tracker in its colour)")]
    fig.legend(handles=handles, loc="lower center", ncols=2, fontsize=8, frameon=False)
    no_value = [t for t in TRACKERS if t not in values]
    if no_value:
        fig.text(0.01, 0.005, f"no {'AUC' if measure == 'auc' else measure} published for "
                 f"{', '.join(no_value)} (toolkit scores only)", fontsize=6.5, color="0.4")
    fig.tight_layout(rect=(0, 0.05, 1, 0.95))
    return fig
