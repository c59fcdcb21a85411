"""Property-based fuzz of all eleven trackers.

Random valid params drawn from each tracker's ``Params`` metadata (range, step, choices) and
random degenerate clips -- black, white, constant grey, noise, a target that leaves the frame,
tiny frames, a large frame with a tiny box: ``init`` and ``update`` never raise and never hand
back a non-finite or empty box. Examples are bounded so the file runs in CI in well under a
minute.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from trackbook import params as _params
from trackbook import trackers

NAMES = trackers.available(reference=False)


def _field_value(f: dataclasses.Field):
    choices = _params.choices_of(f)
    if choices:
        return st.sampled_from(choices)
    d = f.default
    if isinstance(d, bool):
        return st.booleans()
    # the slider's range: the values a reader tries (the allowed range may go much further,
    # e.g. 100 000 particles, which would only test patience)
    lo, hi = _params.slider_of(f)
    if isinstance(d, int):
        lo = int(np.ceil(lo)) if lo is not None else d
        hi = int(np.floor(hi)) if hi is not None else d
        return st.integers(lo, hi)
    if isinstance(d, float):
        lo = lo if lo is not None else d
        hi = hi if hi is not None else d
        return st.floats(lo, hi, allow_nan=False, allow_infinity=False)
    return st.just(d)


@st.composite
def tracker_and_params(draw):
    name = draw(st.sampled_from(NAMES))
    cls = trackers.get(name)
    fields = dataclasses.fields(cls.Params)
    # a few knobs at random values, the rest at their defaults (all of them at once would
    # mostly test the slowest corner: every count at its maximum)
    chosen = draw(st.lists(st.sampled_from(fields), max_size=3, unique_by=lambda f: f.name)) \
        if fields else []
    params = {f.name: draw(_field_value(f)) for f in chosen}
    return name, params


KINDS = ("black", "white", "grey", "noise", "leaving", "tiny", "huge")


@st.composite
def clip(draw):
    kind = draw(st.sampled_from(KINDS))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    n = 5
    if kind == "tiny":
        H, W = draw(st.integers(2, 12)), draw(st.integers(2, 12))
    elif kind == "huge":
        H, W = 480, 640
    else:
        H, W = 60, 80
    frames = np.zeros((n, H, W, 3), np.uint8)
    bw, bh = (min(W, draw(st.integers(1, 4))), min(H, draw(st.integers(1, 4)))) \
        if kind in ("tiny", "huge") else (16, 12)
    x0 = draw(st.integers(0, W - bw))
    y0 = draw(st.integers(0, H - bh))
    if kind == "white":
        frames[:] = 255
    elif kind == "grey":
        frames[:] = draw(st.integers(0, 255))
    elif kind == "noise":
        frames[:] = rng.integers(0, 256, frames.shape, dtype=np.uint8)
    else:
        frames[:] = rng.integers(0, 60, frames.shape, dtype=np.uint8)
        for i in range(n):
            x = x0 + (30 * i if kind == "leaving" else 0)
            if x < W:
                frames[i, y0:y0 + bh, x:x + bw] = (40, 40, 220)
    return kind, frames, (float(x0), float(y0), float(bw), float(bh))


@settings(max_examples=150, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(tp=tracker_and_params(), c=clip(), seed=st.integers(0, 2**31 - 1))
def test_fuzz_trackers_never_raise_and_never_return_bad_boxes(tp, c, seed):
    name, params = tp
    kind, frames, box = c
    t = trackers.create(name, seed=seed, **params)
    t.init(frames[0], box)
    for f in frames[1:]:
        ok, b = t.update(f)
        assert isinstance(ok, bool)
        b = np.asarray(b, dtype=float)
        assert b.shape == (4,) and np.all(np.isfinite(b)), (name, params, kind, b)
        assert b[2] > 0 and b[3] > 0, (name, params, kind, b)
