"""The ``trackbook`` command (also ``python -m trackbook``).

    trackbook trackers                    the tracker names; trackbook trackers color-pf: its params
    trackbook clips                       list the sample clips (and sequences found)
    trackbook clips export red-cube out/red-cube.mp4
    trackbook track kalman-covariance red-cube --out out/
    trackbook track condensation-mean-shift two-faces --all-targets --out out/
    trackbook track color-pf my_video.mp4 --box 120,80,40,60   your own video, no ground truth
    trackbook track color-pf my_video.mp4 --groundtruth my_boxes.txt --preset paper
    trackbook track lab-color-pf red-cube --import my_tracker.py   a tracker of your own
    trackbook bench --trackers color-pf,kalman-covariance --clips samples --out bench-results/
    trackbook notebooks --out notebooks/  export the book's chapters to .ipynb for class

An output that exists is replaced only with --force; an error is one line (the whole
traceback too with --traceback, anywhere on the line).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import textwrap
from pathlib import Path

import numpy as np

from . import _cli_output as _out
from ._cli_errors import report
from ._cli_notebooks import _chapters, cmd_notebooks, find_book  # noqa: F401  (cli.find_book)
from ._cli_output import annotate  # noqa: F401  (trackbook.cli.annotate, used by the book)


def _parse_params(items) -> dict:
    """``["n_particles=200", "window=(0.8,1.2)"]`` -> ``{name: text}``; the values stay text
    and are converted by :func:`trackbook.params.parse` with each field's type."""
    out = {}
    for item in items or []:
        if "=" not in item:
            raise ValueError(f"--param {item!r}: write NAME=VALUE, e.g. --param n_particles=200")
        k, v = item.split("=", 1)
        if not k.strip():
            raise ValueError(f"--param {item!r} has no name; write NAME=VALUE.")
        out[k.strip()] = v
    return out


def _track_params(tracker: str, items) -> dict:
    """``track``'s ``--param [TRACKER:]NAME=VALUE`` converted by the one parser; a TRACKER
    prefix must name the tracker being run."""
    from . import trackers
    from .params import make_params, parse

    cls = trackers.get(tracker)
    plain = []
    for item in items or []:
        head = item.split("=", 1)[0]
        if ":" in head:
            t, rest = item.split(":", 1)
            if t.strip() != tracker:
                raise ValueError(
                    f"--param {item!r} is for tracker {t.strip()!r}, but this run uses "
                    f"{tracker!r}; write --param {rest} (or TRACKER:NAME=VALUE with {tracker}).")
            item = rest
        plain.append(item)
    raw = _parse_params(plain)
    params = {k: parse(cls.Params, k, v) for k, v in raw.items()}
    make_params(cls.Params, params)
    return params


def cmd_trackers(args) -> int:
    """``trackbook trackers [NAME]``: the registered names (and the reference), or one
    tracker's params with their doc, allowed range, book default and printed value."""
    from . import params as _params
    from . import trackers
    from .params import NOT_PRINTED
    from .quotes import fields as quote_fields

    _load_imports(args.imports)
    if not args.name:
        for name in trackers.available(reference=True):
            doc = _out.plain_doc(trackers.get(name).__doc__, name)
            print(f"{name:24s} {textwrap.shorten(doc, 100, placeholder=' ...')}")
        print("\ntrackbook trackers NAME lists a tracker's params.")
        return 0
    cls = trackers.get(args.name)
    print(f"{args.name}: {_out.plain_doc(cls.__doc__, args.name)}")
    if not dataclasses.is_dataclass(cls.Params) or not dataclasses.fields(cls.Params):
        print("(no params)")
        return 0
    rows = []
    for f in dataclasses.fields(cls.Params):
        m = f.metadata
        if m.get("choices"):
            rng = " | ".join(str(c) for c in m["choices"])
        elif m.get("lo") is not None or m.get("hi") is not None:
            rng = f"{m.get('lo')} .. {m.get('hi')}"
        elif isinstance(f.default, bool):
            rng = "true | false"
        else:
            rng = "any"
        paper = m.get("paper", None)
        if paper is NOT_PRINTED:
            paper_txt = "not printed"
        elif _params.has_paper(f):
            # a printed value, or the book's reading of an ambiguous passage
            reading = quote_fields.state(args.name, f.name)[0] == "reading"
            paper_txt = repr(paper) + (" (a reading)" if reading else "")
        else:
            paper_txt = "-"
        rows.append((f.name, rng, repr(f.default), paper_txt, _out.plain_doc(m.get("doc", ""))))
    heads = ("param", "allowed", "book", "paper")
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(heads)]
    print("  ".join(h.ljust(w) for h, w in zip(heads, widths)) + "  doc")
    for r in rows:
        print("  ".join(v.ljust(w) for v, w in zip(r[:4], widths)) + "  " + r[4])
    print("\nset one with --param NAME=VALUE; --preset paper starts from the paper column.")
    return 0


def cmd_clips(args) -> int:
    from . import clips

    if args.action == "export":
        if not args.name or not args.path:
            raise ValueError("usage: trackbook clips export NAME OUT.mp4")
        # the files clips.export writes: never replaced unless asked
        _out.refuse_existing([Path(args.path), Path(args.path).with_suffix(".groundtruth.txt")],
                         args.force)
        video, gt = clips.export(args.name, args.path)
        print(f"wrote {video} and {gt}")
        return 0
    for s in clips.catalogue():            # from the registry: nothing is rendered
        print(f"{s.name:22s} {s.paper:8s} {s.frames:4d} frames {s.size[0]}x{s.size[1]}  "
              f"{textwrap.shorten(s.description, 90, placeholder=' ...')}")
    found = clips.find_sequences()
    if found:
        print(f"\nsequences found ({Path(next(iter(found.values()))).parent}):")
        for name in found:
            print(f"  {name}")
    return 0


def _parse_box(text: str, clip) -> tuple:
    """``--box x,y,w,h`` (pixels of the first frame) -> a float tuple, checked against the
    frame size so a typo fails with a clear message rather than a lost tracker."""
    import math
    import re

    # ASCII decimals only: float() would also take "١٢" (Arabic-Indic digits), "1_0",
    # "inf" and "nan", none of which a box of pixels is written in
    number = r"[0-9]+(?:\.[0-9]*)?|\.[0-9]+"
    parts = text.replace(" ", "").split(",")
    if len(parts) != 4 or not all(re.fullmatch(number, v, re.ASCII) for v in parts):
        raise ValueError(f"--box {text!r}: expected four numbers x,y,w,h in plain digits, "
                         "e.g. --box 40,30,24,24")
    x, y, w, h = (float(v) for v in parts)
    width, height = clip.size
    # written so that NaN (every comparison False) is refused too
    if not (all(math.isfinite(v) for v in (x, y, w, h)) and w > 0 and h > 0
            and x >= 0 and y >= 0 and x + w <= width and y + h <= height):
        raise ValueError(f"--box {text!r} is not a box inside the {width}x{height} first frame; "
                         "give x,y of its top-left corner and a positive width and height.")
    return (x, y, w, h)


def _load_imports(specs) -> None:
    """``--import MODULE_OR_FILE`` (repeatable): load the user's trackers before any name is
    looked up."""
    import warnings

    from .trackers import plugins

    for spec in specs or []:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            plugins.load(spec)   # its error or sys.exit: reported as the file's by _cli_errors
        for w in caught:          # e.g. "registered no new tracker": one line, not two
            print(f"trackbook: warning: {' '.join(str(w.message).split())}", file=sys.stderr)


def _track_settings(args, cls, params, box=None) -> tuple[dict, dict]:
    """What the output name's hash covers: everything that changes the run (the tracker, its
    seed, every param resolved from the preset, the starting box, --max-frames and the
    ground-truth file); and the same for the default run."""
    from .params import make_params, paper_values

    def values(p):
        return dataclasses.asdict(p) if dataclasses.is_dataclass(p) else repr(p)

    base = paper_values(cls.Params) if args.preset == "paper" else {}
    gt = args.groundtruth and str(Path(args.groundtruth).resolve())
    full = {"tracker": args.tracker, "seed": args.seed,
            "params": values(make_params(cls.Params, {**base, **params})),
            "box": box, "max_frames": args.max_frames, "groundtruth": gt}
    default = {**full, "seed": 0, "params": values(make_params(cls.Params, {})), "box": None,
               "max_frames": None, "groundtruth": None}
    return full, default


def _stopped(e: KeyboardInterrupt, out) -> int:
    """One line for Ctrl-C or SIGTERM/SIGHUP during ``track``; the exit code 128 + signal."""
    signum = getattr(e, "signum", 2)
    how = "interrupted (Ctrl-C)" if signum == 2 else f"stopped by a signal ({signum})"
    print(f"trackbook: {how}; the unfinished outputs were removed, nothing in {out} was "
          "changed.", file=sys.stderr)
    return 128 + signum


def _without_groundtruth(clip):
    """``clip`` with no ground truth: ``--box`` starts the tracker, and a ground-truth file
    found beside the video is not used to score it unless given with ``--groundtruth``."""
    nan = np.full_like(np.asarray(clip.groundtruth, dtype=float), np.nan)
    return dataclasses.replace(clip, groundtruth=nan, targets={"target": nan})


def cmd_track(args) -> int:
    import json

    from . import trackers
    from ._checks import check_max_frames
    from .clips.loaders import write_video
    from .evaluation.metrics import scores_line
    from .evaluation.parallel import stop_on_signals
    from .evaluation.runner import evaluate
    from .evaluation.runs import check_tracker_name
    from .viz.core import draw_state_cv

    _load_imports(args.imports)
    cls = trackers.get(args.tracker)          # unknown name: one line before any work
    check_tracker_name(args.tracker)          # it names the output files
    check_max_frames(args.max_frames, name="--max-frames")
    if args.preset not in trackers.PRESETS:
        raise ValueError(f"--preset {args.preset!r}: use one of {', '.join(trackers.PRESETS)}.")
    params = _track_params(args.tracker, args.param)
    clip = _load_clip(args.clip, args.groundtruth)
    out = _out.check_out_dir(args.out)
    init_box = _parse_box(args.box, clip) if args.box else None
    if args.all_targets:
        if init_box is not None:
            raise ValueError("--box starts one target; it cannot be combined with --all-targets.")
        if args.preset == "paper":
            from .params import paper_values
            params = {**paper_values(cls.Params), **params}
        return _track_all_targets(args, clip, params, out)
    scored = init_box is None or args.groundtruth is not None
    if not scored:
        clip = _without_groundtruth(clip)
    settings, default = _track_settings(args, cls, params, init_box)
    stem = _out.output_stem(args.tracker, clip.name, settings, default)
    files = [out / f"{stem}{ext}" for ext in (".csv", ".json", ".mp4")]
    _out.refuse_existing(files, args.force)
    try:
        with stop_on_signals():
            states = []     # what the tracker shows of itself on each frame, drawn on the video
            r = evaluate(args.tracker, clip, seed=args.seed, max_frames=args.max_frames,
                         init_box=init_box, preset=args.preset,
                         on_frame=lambda i, t, f, b: states.append(t.state()), **params)
            _out.out_dir(out)
            record = {**settings, "preset": args.preset, "clip": clip.name}
            colors = _out.estimate_colors(clip.frames[0], [r.boxes[0]])
            codec = _out.video_codec()
            with _out.staged(files) as tmp:
                tmp[files[0]].write_text(_out.csv_text(
                    [["frame", "x", "y", "w", "h", "ok", "ms"]]
                    + [[i, *(f"{v:.3f}" for v in b), int(ok), f"{ms:.3f}"]
                       for i, (b, ok, ms) in enumerate(zip(r.boxes, r.ok, r.ms))]),
                    newline="")
                tmp[files[1]].write_text(json.dumps(record, indent=1, default=repr) + "\n")
                frames = (draw_state_cv(annotate(frame, {args.tracker: r.boxes[i]},
                                                 clip.groundtruth[i], colors), states[i])
                          for i, frame in zip(range(len(r.boxes)), clip.frames))
                _out.write_video_as(write_video, files[2], tmp[files[2]], frames, clip.fps,
                                    clip.size, codec)
    except KeyboardInterrupt as e:
        return _stopped(e, out)
    if scored:
        print(f"{args.tracker} on {clip.name}: {scores_line(r.scores, sep=', ')}"
              + (f" (against {args.groundtruth})" if args.groundtruth else ""))
    else:
        print(f"{args.tracker} on {clip.name}: not scored (--box starts the tracker; pass "
              "--groundtruth FILE to score it against a ground truth)")
    print(f"wrote {files[0]}, {stem}.json (the settings) and {stem}.mp4 "
          f"({codec}: {_out.CODEC_NOTE[codec]})")
    return 0


def _load_clip(name, groundtruth):
    """``track CLIP [--groundtruth FILE]``: the ground truth of a video or folder of your own."""
    from . import clips

    if groundtruth is not None:
        if not Path(groundtruth).is_file():
            raise ValueError(f"--groundtruth {groundtruth}: no such file; give a text file with "
                             "one x,y,w,h line per frame.")
        if isinstance(name, str) and name in clips.available():
            raise ValueError(f"--groundtruth is for a video or image folder of your own; the "
                             f"sample clip {name!r} carries its ground truth.")
    return clips.load(name, groundtruth=groundtruth)


def _track_all_targets(args, clip, params, out) -> int:
    """``track --all-targets``: one tracker per annotated target of the clip (e.g. the two
    faces of ``two-faces``), run by ``trackbook.evaluate(..., targets="all")``; one CSV per
    target and one video with every target's box."""
    from .clips.loaders import write_video
    from .evaluation.parallel import stop_on_signals
    from .evaluation.runner import evaluate
    from .evaluation.runs import safe_name

    settings = {"tracker": args.tracker, "seed": args.seed, "params": params,
                "max_frames": args.max_frames}
    default = {**settings, "seed": 0, "params": {}, "max_frames": None}
    stem = _out.output_stem(args.tracker, clip.name, settings, default)
    csvs = {name: out / f"{stem}_{safe_name(name)}.csv" for name in clip.targets}
    video = out / f"{stem}.mp4"
    _out.refuse_existing([*csvs.values(), video], args.force)
    try:
        with stop_on_signals():
            res = evaluate(args.tracker, clip, seed=args.seed, max_frames=args.max_frames,
                           targets="all", **params)
            ms, oks, boxes_of = res.ms, res.ok, res.boxes
            _out.out_dir(out)
            colors = _out.estimate_colors(clip.frames[0], [b[0] for b in boxes_of.values()])
            codec = _out.video_codec()
            n = len(ms)
            with _out.staged([*(csvs[k] for k in boxes_of), video]) as tmp:
                for name, boxes in boxes_of.items():
                    tmp[csvs[name]].write_text(_out.csv_text(
                        [["frame", "x", "y", "w", "h", "ok", "ms"]]   # ms: all targets' update
                        + [[i, *(f"{v:.3f}" for v in b), int(ok), f"{t:.3f}"]
                           for i, (b, ok, t) in enumerate(zip(boxes, oks[name], ms))]),
                        newline="")
                _out.write_video_as(write_video, video, tmp[video],
                                    (annotate(frame, {k: b[i] for k, b in boxes_of.items()},
                                              colors=colors)
                                     for i, frame in zip(range(n), clip.frames)),
                                    clip.fps, clip.size, codec)
    except KeyboardInterrupt as e:
        return _stopped(e, out)
    for name, r in res.results.items():
        print(f"{args.tracker} on {clip.name}/{name}: AUC {r.scores.get('auc', float('nan')):.3f}")
    print(f"{float(np.median(ms[1:])) if n > 1 else 0.0:.2f} ms/frame for {len(boxes_of)} "
          f"targets; wrote {len(boxes_of)} CSVs ({stem}_<target>.csv) and {video} ({codec}: "
          f"{_out.CODEC_NOTE[codec]})")
    return 0


def cmd_bench(args) -> int:
    from .evaluation import bench, runs

    runs.load_imports(args.imports)   # before --param looks the trackers up
    params: dict[str, dict] = {}
    for item in args.param or []:
        if ":" not in item:
            raise ValueError(f"--param {item!r}: write TRACKER:NAME=VALUE, e.g. "
                             "--param color-pf:n_particles=200")
        t, kv = item.split(":", 1)
        params.setdefault(t.strip(), {}).update(_bench_param(t.strip(), kv))
    try:
        rows = bench.run(args.trackers, args.clips, args.out, seed=args.seed,
                         seeds=args.seeds, max_frames=args.max_frames, params=params,
                         progress=not args.quiet, force=args.force, workers=args.workers,
                         scheduler=args.scheduler, imports=args.imports or (),
                         preset=args.preset, max_runs=args.max_runs,
                         scheduler_timeout=args.scheduler_timeout, protocol=args.protocol)
    except KeyboardInterrupt as e:   # Ctrl-C, or SIGTERM/SIGHUP (parallel.Stopped)
        signum = getattr(e, "signum", 2)
        print(f"\ntrackbook: {'interrupted' if signum == 2 else 'stopped by a signal'}; "
              f"finished runs are saved in {Path(args.out, 'runs')}; run the same command "
              "again to resume.", file=sys.stderr)
        return 128 + signum
    except ImportError as e:   # --scheduler without the dask extra
        print(f"trackbook: error: {e}", file=sys.stderr)
        return 2
    print(getattr(rows, "table", "") or bench.markdown_table(rows))
    read_back, ran = getattr(rows, "read_back", 0), getattr(rows, "ran", len(rows))
    print(f"{read_back} read back, {ran} run"      # Path: no doubled slash from --out dir/
          + (f" (the {read_back} read back from {Path(args.out, 'runs')} keep the timings of "
             "the bench that saved them; --force re-runs them)" if read_back else ""))
    print(f"wrote {Path(args.out, 'results.csv')}, results.json, table.md, " + ("eao.png" if
          args.protocol == "reset" else "success.png, precision.png"))
    return 0


def _bench_param(tracker: str, kv: str, flag: str = "") -> dict:
    """One ``NAME=VALUE`` for ``tracker``, through the shared parameter parser when present.

    ``flag`` is the ``track`` form (``--param NAME=VALUE``); by default the ``bench`` form
    (``--param TRACKER:NAME=VALUE``) is named in the message.
    """
    from . import params as _params
    from . import trackers

    if "=" not in kv:
        if flag:
            raise ValueError(f"{flag} {kv!r}: write NAME=VALUE, e.g. --param n_particles=200")
        raise ValueError(f"--param {tracker}:{kv!r}: write TRACKER:NAME=VALUE, e.g. "
                         "--param color-pf:n_particles=200")
    name, value = (x.strip() for x in kv.split("=", 1))
    parse = getattr(_params, "parse", None)
    if parse is not None:
        cls = getattr(trackers.get(tracker), "Params", None)
        if cls is not None:
            return {name: parse(cls, name, value)}
    return _parse_params([f"{name}={value}"])


class _Parser(argparse.ArgumentParser):
    """argparse with the command's error style: one line on stderr, exit code 2."""

    def error(self, message):
        print(f"trackbook: error: {' '.join(message.split())} (see {self.prog} --help)",
              file=sys.stderr)
        raise SystemExit(2)


def _seed(text: str) -> int:
    """``--seed``: a whole number >= 0 (the Python API's None cannot be typed here)."""
    if not (text.strip().isascii() and text.strip().isdigit()):
        raise argparse.ArgumentTypeError(f"{text!r} is not a seed; give 0 or a positive whole "
                                         "number, e.g. --seed 3")
    return int(text)


_FORCE_HELP = "replace outputs that already exist (without it, the command refuses)"
_TRACEBACK_HELP = ("on an error, print the whole Python traceback, not only its one-line "
                   "summary (accepted anywhere on the command line)")
_IMPORT_HELP = ("MODULE_OR_FILE: load a tracker of your own first (a .py file or a dotted "
                "module that uses @trackers.register); repeatable")


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="trackbook", description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--traceback", action="store_true", help=_TRACEBACK_HELP)
    sub = p.add_subparsers(dest="command", required=True)

    k = sub.add_parser("trackers", help="list the trackers, or one tracker's params")
    k.add_argument("name", nargs="?", help="a tracker name: show its params")
    k.add_argument("--import", dest="imports", action="append", metavar="MODULE_OR_FILE",
                   help=_IMPORT_HELP)
    k.set_defaults(fn=cmd_trackers)

    c = sub.add_parser("clips", help="list or export sample clips")
    c.add_argument("action", nargs="?", choices=["list", "export"], default="list")
    c.add_argument("name", nargs="?")
    c.add_argument("path", nargs="?")
    c.add_argument("--force", action="store_true", help=_FORCE_HELP)
    c.set_defaults(fn=cmd_clips)

    t = sub.add_parser("track", help="run a tracker on a clip: annotated video + CSV of boxes")
    t.add_argument("tracker")
    t.add_argument("clip", help="sample name, OTB folder or video file")
    t.add_argument("--out", default="track-output", help="the folder of the outputs "
                   "(default: track-output/)")
    t.add_argument("--seed", type=_seed, default=0)
    t.add_argument("--max-frames", type=int)
    t.add_argument("--param", action="append", help="NAME=VALUE, repeatable")
    t.add_argument("--preset", default="book", help="'book' (the book's defaults) or 'paper' "
                   "(the printed values; see trackbook trackers NAME)")
    t.add_argument("--groundtruth", metavar="FILE", help="ground truth of your own video or "
                   "folder: one x,y,w,h line per frame (comma, tab or space separated)")
    t.add_argument("--import", dest="imports", action="append", metavar="MODULE_OR_FILE",
                   help=_IMPORT_HELP)
    t.add_argument("--box", help="x,y,w,h: the target on the first frame, for a video without "
                   "ground truth (your own video); scores are left out unless --groundtruth "
                   "FILE is given too")
    t.add_argument("--all-targets", action="store_true",
                   help="track every annotated target of the clip at once (one tracker each): "
                        "one CSV per target, one video with all boxes")
    t.add_argument("--force", action="store_true", help=_FORCE_HELP)
    t.set_defaults(fn=cmd_track)

    b = sub.add_parser("bench", help="trackers x clips -> tables and plots (resumable)")
    b.add_argument("--trackers", required=True, help="comma-separated names; opencv-mil is "
                   "always added as the reference row")
    b.add_argument("--clips", default="samples",
                   help="comma-separated: names, paths, 'samples' (all), 'shared' (all "
                        "sequences), or a dataset root (OTB-100, UAV123, a folder of sequences)")
    b.add_argument("--out", default="bench-results")
    b.add_argument("--seed", type=_seed, default=0)
    b.add_argument("--seeds", help="sweep seeds: 0-9, 0,3,7 or 0-2,5 (overrides --seed)")
    b.add_argument("--max-frames", type=int)
    b.add_argument("--param", action="append", help="TRACKER:NAME=VALUE, repeatable")
    b.add_argument("--force", action="store_true", help=_FORCE_HELP + ": re-run the runs "
                   "saved in OUT/runs and replace the tables, also another bench's (without "
                   "it the same bench resumes, and an OUT holding another bench is refused)")
    b.add_argument("--quiet", action="store_true", help="no progress bar")
    b.add_argument("--workers", type=int, default=None,
                   help="worker processes (default: the number of cores)")
    b.add_argument("--scheduler", default=None,
                   help="Dask scheduler address, e.g. tcp://HOST:8786 (default: "
                        "$TRACKBOOK_DASK_SCHEDULER; needs pip install 'trackbook[dask]')")
    b.add_argument("--scheduler-timeout", type=float, default=None, metavar="SECONDS",
                   help="seconds the scheduler has to connect and answer (default: "
                        "$TRACKBOOK_DASK_TIMEOUT or 5)")
    b.add_argument("--import", dest="imports", action="append", metavar="MODULE_OR_FILE",
                   help="a module or .py file that registers your own tracker(s); "
                        "repeatable; loaded in every worker")
    b.add_argument("--preset", choices=["book", "paper"], default="book",
                   help="start every tracker from the book's defaults or the printed values")
    b.add_argument("--max-runs", type=int, default=None, metavar="N",
                   help="the most runs one bench may do (default 5000)")
    b.add_argument("--protocol", default="ope", help="ope (one pass, default), tre (20 starts; "
                   "tre:N for N), sre (12 perturbed first boxes) or reset (VOT's)")
    b.set_defaults(fn=cmd_bench)

    n = sub.add_parser("notebooks", help="export the chapters to .ipynb for class use")
    n.add_argument("--book", default=None, help="the folder of the chapters (default: ./book, else the chapters installed with trackbook)")
    n.add_argument("--out", default="notebooks")
    n.add_argument("--force", action="store_true", help=_FORCE_HELP + " (notebooks you edited "
                   "included)")
    n.set_defaults(fn=cmd_notebooks)
    return p


def _one_line_warnings():
    """Data warnings (folders a dataset skipped, a truncated frame) as one line on stderr."""
    import warnings

    from .clips.clip import CorruptFrameWarning
    from .clips.datasets import DatasetWarning

    shown = warnings.showwarning

    def show(message, category, *rest, **kw):
        if issubclass(category, (DatasetWarning, CorruptFrameWarning)):
            print(f"trackbook: warning: {' '.join(str(message).split())}", file=sys.stderr)
        else:
            shown(message, category, *rest, **kw)
    warnings.showwarning = show


def main(argv=None) -> int:
    """Run one subcommand; every error is one line on stderr and a non-zero exit code
    (the whole traceback too with ``--traceback``)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    # --traceback is global: accepted before or after the subcommand
    show_traceback = "--traceback" in argv[:argv.index("--")] if "--" in argv else \
        "--traceback" in argv
    if show_traceback:
        argv = [a for i, a in enumerate(argv) if not (a == "--traceback" and (
            "--" not in argv or i < argv.index("--")))]
    args = build_parser().parse_args(argv)
    _one_line_warnings()
    new_folders = []
    try:
        new_folders = _out.made_folders(getattr(args, "out", None))
        rc = args.fn(args)
        if sys.stdout is not None:    # None: started with stdout closed (>&-)
            sys.stdout.flush()        # a reader that went away is seen here, not at exit
    except BaseException:
        _out.remove_if_empty(new_folders)
        return report(sys.exc_info()[1], show_traceback)
    if rc:
        _out.remove_if_empty(new_folders)
    return rc
