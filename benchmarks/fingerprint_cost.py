"""What hashing clips' bytes costs the bench: the fingerprint of every shared sequence.

The bench keys each saved run by a hash of the clip's files (``runs.fingerprint``), computed
once per clip per bench. Run from the repository root (the README quotes a measured figure)::

    python benchmarks/fingerprint_cost.py            # the shared sequences
    python benchmarks/fingerprint_cost.py /data/OTB100
"""

import sys
import time

from trackbook.evaluation import bench, runs


def main(spec: str = "shared") -> None:
    clips = [r.load() for r in bench.resolve_clips(spec)]
    n = sum(len(c) for c in clips)
    size = sum(sum(p.stat().st_size for p in c.frames.paths) for c in clips
               if getattr(c.frames, "paths", None) is not None)
    for label in ("first pass", "second pass (page cache)"):
        t0 = time.perf_counter()
        for c in clips:
            runs.fingerprint(c)
        dt = time.perf_counter() - t0
        print(f"{label}: {len(clips)} clips, {n} frames, {size / 1e6:.0f} MB of images: "
              f"{dt:.2f} s ({dt / n * 1e3:.3f} ms/frame)")


if __name__ == "__main__":
    main(*sys.argv[1:2])
