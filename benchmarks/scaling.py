"""Scaling benchmark for ``trackbook bench``: 1 worker, 2 workers, a two-worker Dask cluster.

Generates a dataset of OTB-style sequences (``img/0001.jpg ...`` + ``groundtruth_rect.txt``: a
textured patch drifting over a textured background), runs the same bench on it three ways and
prints wall time, runs/s, frames/s, speed-up over one worker and the peak resident memory of
the whole process tree (this process, its workers and their children, sampled every 0.2 s).
It also checks that the three give identical scores.

    python benchmarks/scaling.py                     # 60 sequences x 300 frames, 640 x 360
    python benchmarks/scaling.py --sequences 12 --frames 100    # a quick run
    python benchmarks/scaling.py --trackers mean-shift,covariance --mil

Run it on a quiet machine: speed-ups measured while other jobs share the cores are depressed.
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import threading
import time
from pathlib import Path

import cv2
import numpy as np


def make_dataset(root: Path, n_seq: int, n_frames: int, size=(640, 360)) -> Path:
    """``n_seq`` OTB-style folders; each sequence its own seed (the same on every call)."""
    W, H = size
    for s in range(n_seq):
        rng = np.random.default_rng(s)
        d = root / f"seq{s:03d}"
        img = d / "img"
        img.mkdir(parents=True, exist_ok=True)
        bg = cv2.resize(rng.integers(0, 255, (H // 20, W // 20, 3), dtype=np.uint8), (W, H))
        w, h = int(rng.integers(30, 70)), int(rng.integers(30, 70))
        obj = cv2.resize(rng.integers(0, 255, (6, 6, 3), dtype=np.uint8), (w, h),
                         interpolation=cv2.INTER_NEAREST)
        x, y = float(rng.uniform(w, W - 2 * w)), float(rng.uniform(h, H - 2 * h))
        v = rng.normal(0, 2, 2)
        rows = []
        for i in range(n_frames):
            v = 0.9 * v + rng.normal(0, 0.8, 2)
            x = float(np.clip(x + v[0], 0, W - w - 1))
            y = float(np.clip(y + v[1], 0, H - h - 1))
            f = bg.copy()
            xi, yi = int(round(x)), int(round(y))
            f[yi:yi + h, xi:xi + w] = obj
            cv2.imwrite(str(img / f"{i + 1:04d}.jpg"), f, [cv2.IMWRITE_JPEG_QUALITY, 90])
            rows.append(f"{xi},{yi},{w},{h}")
        (d / "groundtruth_rect.txt").write_text("\n".join(rows) + "\n")
    return root


class PeakRSS:
    """Peak summed RSS of this process and all its descendants (psutil, sampled)."""

    def __init__(self, every=0.2):
        import psutil

        self._p, self._every, self.peak = psutil.Process(), every, 0
        self._stop = threading.Event()
        self._t = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        import psutil

        while not self._stop.is_set():
            total = 0
            for q in [self._p, *self._p.children(recursive=True)]:
                try:
                    total += q.memory_info().rss
                except psutil.Error:
                    pass
            self.peak = max(self.peak, total)
            self._stop.wait(self._every)

    def __enter__(self):
        self._t.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._t.join()


def timed(label, fn):
    with PeakRSS() as m:
        t0 = time.perf_counter()
        rows = fn()
        wall = time.perf_counter() - t0
    return {"label": label, "wall": wall, "rows": rows, "peak_mb": m.peak / 2**20}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sequences", type=int, default=60)
    ap.add_argument("--frames", type=int, default=300)
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--trackers", default="mean-shift,covariance,color-pf")
    ap.add_argument("--mil", action="store_true", help="add OpenCV's MIL (the reference row)")
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--keep", help="generate the dataset here and keep it")
    args = ap.parse_args(argv)

    from trackbook.evaluation import bench

    W, H = (int(v) for v in args.size.lower().split("x"))
    work = Path(args.keep or tempfile.mkdtemp(prefix="trackbook-scaling-"))
    data = work / "data"
    t0 = time.perf_counter()
    if not data.is_dir():
        make_dataset(data, args.sequences, args.frames, (W, H))
    print(f"dataset: {args.sequences} sequences x {args.frames} frames at {W}x{H} in {data} "
          f"({time.perf_counter() - t0:.1f} s to generate); trackers: {args.trackers}"
          f"{' + opencv-mil' if args.mil else ''}; load average "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}")

    def go(out, **kw):
        return lambda: bench.run(args.trackers, str(data), work / out, progress=False,
                                 reference=args.mil, force=True, **kw)

    results = [timed("1 worker", go("w1", workers=1)),
               timed("2 workers", go("w2", workers=2))]
    if not args.no_dask:
        from distributed import LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          dashboard_address=":0") as cluster:
            results.append(timed("Dask LocalCluster, 2 workers",
                                 go("dask", scheduler=cluster.scheduler_address)))
    runs = len(results[0]["rows"])
    frames = sum(r["frames"] for r in results[0]["rows"])
    base = results[0]["wall"]
    print(f"\n{runs} runs, {frames} frames tracked per configuration\n")
    print("| configuration | wall s | runs/s | frames/s | speed-up | peak RSS MB | same scores |")
    print("|---|---:|---:|---:|---:|---:|---|")
    key = lambda rows: sorted((r["tracker"], r["clip"], r["auc"], r["precision20"]) for r in rows)  # noqa: E731
    for r in results:
        same = key(r["rows"]) == key(results[0]["rows"])
        print(f"| {r['label']} | {r['wall']:.1f} | {runs / r['wall']:.2f} | "
              f"{frames / r['wall']:.0f} | {base / r['wall']:.2f} | {r['peak_mb']:.0f} | "
              f"{'yes' if same else 'NO'} |")
    print(f"\nload average after: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
