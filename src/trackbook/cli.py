"""The ``trackbook`` command (also ``python -m trackbook``).

    trackbook clips                       list the sample clips (and sequences found)
    trackbook clips export red-cube out/red-cube.mp4
    trackbook track kalman-covariance red-cube --out out/
    trackbook track condensation-mean-shift two-faces --all-targets --out out/
    trackbook track color-pf my_video.mp4 --box 120,80,40,60   your own video, no ground truth
    trackbook bench --trackers color-pf,kalman-covariance --clips samples --out bench-results/
    trackbook notebooks --out notebooks/  export the book's chapters to .ipynb for class
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np


class CLIError(Exception):
    """A user error the command reports in one line (exit code 2)."""


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


def _out_dir(path) -> Path:
    """``--out``: an existing folder or a new one; a file in the way is named in the error."""
    out = Path(path)
    for p in (out, *out.parents):
        if p.exists() and not p.is_dir():
            raise ValueError(f"--out {path}: {p} is a file, not a folder; pass a folder name "
                             "(it is created if missing).")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise ValueError(f"--out {path}: cannot create the folder ({e.strerror}); pass a "
                         "writable folder.") from None
    return out


def cmd_clips(args) -> int:
    from . import clips

    if args.action == "export":
        if not args.name or not args.path:
            raise ValueError("usage: trackbook clips export NAME OUT.mp4")
        video, gt = clips.export(args.name, args.path)
        print(f"wrote {video} and {gt}")
        return 0
    for name in clips.available():
        c = clips.load(name)
        print(f"{name:22s} {len(c):4d} frames {c.size[0]}x{c.size[1]}  "
              f"{clips.describe(name).split(': ', 1)[1][:90]}")
    found = clips.find_sequences()
    if found:
        print(f"\nsequences found ({Path(next(iter(found.values()))).parent}):")
        for name, p in found.items():
            print(f"  {name}")
    return 0


def annotate(frame, boxes: dict, gt=None):
    """Draw boxes on a copy of a BGR frame (OpenCV drawing, for videos)."""
    import cv2

    img = frame.copy()
    colors = [(40, 39, 214), (180, 119, 31), (14, 127, 255), (189, 103, 148)]
    if gt is not None and np.all(np.isfinite(gt)):
        x, y, w, h = (int(round(v)) for v in gt)
        cv2.rectangle(img, (x, y), (x + w, y + h), (44, 160, 44), 1, cv2.LINE_AA)
    for i, (label, b) in enumerate(boxes.items()):
        if b is None or not np.all(np.isfinite(b)):
            continue
        x, y, w, h = (int(round(v)) for v in b)
        c = colors[i % len(colors)]
        cv2.rectangle(img, (x, y), (x + w, y + h), c, 2, cv2.LINE_AA)
        cv2.putText(img, label, (x, max(y - 4, 10)), cv2.FONT_HERSHEY_SIMPLEX, 0.4, c, 1,
                    cv2.LINE_AA)
    return img


def _parse_box(text: str, clip) -> tuple:
    """``--box x,y,w,h`` (pixels of the first frame) -> a float tuple, checked against the
    frame size so a typo fails with a clear message rather than a lost tracker."""
    try:
        x, y, w, h = (float(v) for v in text.replace(" ", "").split(","))
    except ValueError:
        raise SystemExit(f"--box {text!r}: expected four numbers x,y,w,h, e.g. --box 40,30,24,24")
    width, height = clip.size
    if w <= 0 or h <= 0 or x < 0 or y < 0 or x + w > width or y + h > height:
        raise SystemExit(f"--box {text!r} is not a box inside the {width}x{height} first frame; "
                         "give x,y of its top-left corner and a positive width and height.")
    return (x, y, w, h)


def cmd_track(args) -> int:
    import csv

    import cv2

    from . import clips
    from .evaluation.runner import evaluate
    from .viz.core import draw_state_cv

    from . import trackers

    trackers.get(args.tracker)          # unknown name: one line before any work
    if args.max_frames is not None and args.max_frames < 1:
        raise ValueError(f"--max-frames {args.max_frames}: pass at least 1 (the first frame "
                         "is the one the tracker starts from).")
    params = _track_params(args.tracker, args.param)
    clip = clips.load(args.clip)
    out = _out_dir(args.out)
    init_box = _parse_box(args.box, clip) if args.box else None
    if args.all_targets:
        if init_box is not None:
            raise ValueError("--box starts one target; it cannot be combined with --all-targets.")
        return _track_all_targets(args, clip, params, out)
    stem = f"{args.tracker}_{clip.name}"
    states = []     # what the tracker shows of itself on each frame, drawn on the video
    r = evaluate(args.tracker, clip, seed=args.seed, max_frames=args.max_frames,
                 init_box=init_box, on_frame=lambda i, t, f, b: states.append(t.state()),
                 **params)
    with open(out / f"{stem}.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["frame", "x", "y", "w", "h", "ok", "ms"])
        for i, (b, ok, ms) in enumerate(zip(r.boxes, r.ok, r.ms)):
            w.writerow([i, *(f"{v:.3f}" for v in b), int(ok), f"{ms:.3f}"])
    width, height = clip.size
    writer = cv2.VideoWriter(str(out / f"{stem}.mp4"), cv2.VideoWriter_fourcc(*"mp4v"),
                             clip.fps, (width, height))
    for i, frame in enumerate(clip.frames):
        if i >= len(r.boxes):
            break
        writer.write(draw_state_cv(annotate(frame, {args.tracker: r.boxes[i]},
                                            clip.groundtruth[i]), states[i]))
    writer.release()
    s = r.scores
    print(f"{args.tracker} on {clip.name}: " + (
        f"AUC {s['auc']:.3f}, precision@20 {s['precision20']:.3f}, tracking rate "
        f"{s['tracking_rate']:.1%}, " if "auc" in s else "") + f"{s['ms_median']:.2f} ms/frame")
    print(f"wrote {out / (stem + '.csv')} and {out / (stem + '.mp4')}")
    return 0


def _track_all_targets(args, clip, params, out) -> int:
    """``track --all-targets``: one tracker per annotated target of the clip (e.g. the two
    faces of ``two-faces``), run by ``trackbook.evaluate(..., targets="all")``; one CSV per
    target and one video with every target's box."""
    import csv

    import cv2

    from .evaluation.runner import evaluate

    res = evaluate(args.tracker, clip, seed=args.seed, max_frames=args.max_frames,
                   targets="all", **params)
    ms, oks, boxes_of = res.ms, res.ok, res.boxes
    stem = f"{args.tracker}_{clip.name}"
    for name, boxes in boxes_of.items():
        with open(out / f"{stem}_{name}.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["frame", "x", "y", "w", "h", "ok", "ms"])   # ms: all targets' update
            for i, (b, ok, t) in enumerate(zip(boxes, oks[name], ms)):
                w.writerow([i, *(f"{v:.3f}" for v in b), int(ok), f"{t:.3f}"])
    width, height = clip.size
    video = out / f"{stem}.mp4"
    writer = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"mp4v"), clip.fps,
                             (width, height))
    n = len(ms)
    for i, frame in enumerate(clip.frames):
        if i >= n:
            break
        writer.write(annotate(frame, {name: boxes[i] for name, boxes in boxes_of.items()}))
    writer.release()
    for name, r in res.results.items():
        print(f"{args.tracker} on {clip.name}/{name}: AUC {r.scores.get('auc', float('nan')):.3f}")
    print(f"{float(np.median(ms[1:])) if n > 1 else 0.0:.2f} ms/frame for {len(boxes_of)} targets; "
          f"wrote {len(boxes_of)} CSVs ({stem}_<target>.csv) and {video}")
    return 0


def cmd_bench(args) -> int:
    from .evaluation import bench

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
                         scheduler=args.scheduler)
    except KeyboardInterrupt:
        print(f"\ntrackbook: interrupted; finished runs are saved in {args.out}/runs; run the "
              "same command again to resume.", file=sys.stderr)
        return 130
    except ImportError as e:   # --scheduler without the dask extra
        print(f"trackbook: error: {e}", file=sys.stderr)
        return 2
    print(bench.markdown_table(rows))
    print(f"wrote {args.out}/results.csv, results.json, table.md, success.png, precision.png")
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


def cmd_notebooks(args) -> int:
    import jupytext

    book = Path(args.book)
    chapters = (sorted(book.glob("[0-9][0-9]_*.md")) + sorted(book.glob("appendix_*.md"))
                + sorted(book.glob("lab_notes_*.md")))
    if not chapters:
        raise ValueError(f"no chapters in {book}; run from the repository root or pass --book.")
    out = _out_dir(args.out)
    for md in chapters:
        nb = jupytext.read(md)
        jupytext.write(nb, out / (md.stem + ".ipynb"))
        print(out / (md.stem + ".ipynb"))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="trackbook", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)

    c = sub.add_parser("clips", help="list or export sample clips")
    c.add_argument("action", nargs="?", choices=["list", "export"], default="list")
    c.add_argument("name", nargs="?")
    c.add_argument("path", nargs="?")
    c.set_defaults(fn=cmd_clips)

    t = sub.add_parser("track", help="run a tracker on a clip: annotated video + CSV of boxes")
    t.add_argument("tracker")
    t.add_argument("clip", help="sample name, OTB folder or video file")
    t.add_argument("--out", default="track-output")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--max-frames", type=int)
    t.add_argument("--param", action="append", help="NAME=VALUE, repeatable")
    t.add_argument("--box", help="x,y,w,h: the target on the first frame, for a video without "
                   "ground truth (your own video); scores are then left out")
    t.add_argument("--all-targets", action="store_true",
                   help="track every annotated target of the clip at once (one tracker each): "
                        "one CSV per target, one video with all boxes")
    t.set_defaults(fn=cmd_track)

    b = sub.add_parser("bench", help="trackers x clips -> tables and plots (resumable)")
    b.add_argument("--trackers", required=True, help="comma-separated names; opencv-mil is "
                   "always added as the reference row")
    b.add_argument("--clips", default="samples",
                   help="comma-separated: names, paths, 'samples' (all), 'shared' (all "
                        "sequences), or a dataset root (OTB-100, UAV123, a folder of sequences)")
    b.add_argument("--out", default="bench-results")
    b.add_argument("--seed", type=int, default=0)
    b.add_argument("--seeds", help="sweep seeds: 0-9, 0,3,7 or 0-2,5 (overrides --seed)")
    b.add_argument("--max-frames", type=int)
    b.add_argument("--param", action="append", help="TRACKER:NAME=VALUE, repeatable")
    b.add_argument("--force", action="store_true", help="re-run finished runs")
    b.add_argument("--quiet", action="store_true", help="no progress bar")
    b.add_argument("--workers", type=int, default=None,
                   help="worker processes (default: the number of cores)")
    b.add_argument("--scheduler", default=None,
                   help="Dask scheduler address, e.g. tcp://HOST:8786 (default: "
                        "$TRACKBOOK_DASK_SCHEDULER; needs pip install 'trackbook[dask]')")
    b.set_defaults(fn=cmd_bench)

    n = sub.add_parser("notebooks", help="export the chapters to .ipynb for class use")
    n.add_argument("--book", default="book")
    n.add_argument("--out", default="notebooks")
    n.set_defaults(fn=cmd_notebooks)
    return p


def main(argv=None) -> int:
    """Run one subcommand; every error is one line on stderr and a non-zero exit code."""
    args = build_parser().parse_args(argv)
    try:
        return args.fn(args)
    except KeyboardInterrupt:
        print("trackbook: interrupted (Ctrl-C).", file=sys.stderr)
        return 130
    except (ValueError, CLIError, OSError, KeyError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else e
        if isinstance(e, OSError) and e.filename is not None and e.strerror:
            msg = f"{e.filename}: {e.strerror}"
        print(f"trackbook: error: {' '.join(str(msg).split())}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001  a bug, still reported in one line
        print(f"trackbook: error: {type(e).__name__}: {' '.join(str(e).split())} (this is a "
              "bug; please report it with the command line)", file=sys.stderr)
        return 1
