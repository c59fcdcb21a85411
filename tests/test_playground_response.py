"""The playground's payload of a tracker's confidence and response map: the confidence per
frame, and each frame's response shrunk (block means), quantised to uint8 and base64-encoded,
decoding back to the shrunk map within the quantisation's half step."""

import base64

import numpy as np
import pytest

from trackbook import clips
from trackbook.playground import data as D
from trackbook.trackers import TrackerState


def _gaussian(rows, cols, cy, cx, sigma):
    y, x = np.mgrid[0:rows, 0:cols]
    return np.exp(-((y - cy) ** 2 + (x - cx) ** 2) / (2 * sigma ** 2)) - 0.1


def _within_quantisation(decoded, expected, rng):
    lo, hi = rng
    # half a step of 1/255 of the stored range, and the range's own rounding to 6 digits
    tol = (hi - lo) / 255 / 2 + 1e-5 * max(abs(lo), abs(hi))
    return np.max(np.abs(decoded - expected)) <= tol


def test_a_response_decodes_to_its_block_means():
    m = _gaussian(64, 48, 20, 30, 5.0)
    enc = D.encode_responses([None, m], max_bytes=10 ** 9)
    assert enc["rshape"] == [None, [32, 24]]
    dec = D.decode_responses(enc)
    assert dec[0] is None
    expected = m.reshape(32, 2, 24, 2).mean(axis=(1, 3))       # 2 x 2 block means
    assert _within_quantisation(dec[1], expected, enc["rrange"][1])
    lo, hi = enc["rrange"][1]
    assert lo == pytest.approx(expected.min(), rel=1e-5) and hi == pytest.approx(expected.max(), rel=1e-5)


def test_a_small_response_is_sent_as_it_is():
    m = _gaussian(11, 9, 3, 7, 1.5)
    enc = D.encode_responses([m])
    assert enc["rshape"] == [[11, 9]]
    assert _within_quantisation(D.decode_responses(enc)[0], m, enc["rrange"][0])


def test_many_frames_shrink_the_maps_to_fit_max_bytes():
    maps = [_gaussian(64, 64, 10 + k % 40, 30, 4.0) for k in range(100)]
    enc = D.encode_responses(maps, max_bytes=100 * 16 * 16)
    assert all(s == [16, 16] for s in enc["rshape"])
    assert len(base64.b64decode(enc["response"])) == 100 * 16 * 16
    for m, d, rng in zip(maps, D.decode_responses(enc), enc["rrange"]):
        assert _within_quantisation(d, m.reshape(16, 4, 16, 4).mean(axis=(1, 3)), rng)


def test_a_flat_response_decodes_to_its_value():
    enc = D.encode_responses([np.zeros((5, 5))])
    assert enc["rrange"] == [[0.0, 0.0]] and np.all(D.decode_responses(enc)[0] == 0)


def test_run_payload_of_a_correlation_filter_has_confidence_and_responses():
    clip = clips.load("red-cube")
    p, r, states = D.run_payload("kcf", clip, {}, 8)
    st = p["state"]
    n = len(p["boxes"])
    assert n == 8 and len(st["confidence"]) == n and len(st["rshape"]) == n
    assert st["confidence"][0] is None            # no update yet on the first frame
    assert all(isinstance(c, float) and np.isfinite(c) for c in st["confidence"][1:])
    assert st["rshape"][0] is None and st["response_box"][0] is None
    assert all(max(s) <= D.MAX_RESPONSE_SIDE for s in st["rshape"][1:])
    # each frame's map is the tracker's own response, shrunk: compare with state() directly
    dec = D.decode_responses(st)
    for k in range(1, n):
        full = np.asarray(states[k]["response"])
        assert dec[k].shape == full.shape
        assert _within_quantisation(dec[k], full, st["rrange"][k])


def test_a_tracker_without_a_response_sends_none():
    clip = clips.load("red-cube")
    st = D.run_payload("mean-shift", clip, {}, 6)[0]["state"]
    assert len(st["confidence"]) == 6 and st["confidence"][0] is None
    for key in ("response", "rshape", "rrange", "response_box"):
        assert key not in st


def test_a_state_without_confidence_sends_no_curve():
    snap = D.snapshot(TrackerState(particles=np.zeros((3, 2)), weights=np.ones(3) / 3))
    enc = D._encode_state([snap, snap])
    assert "confidence" not in enc and "response" not in enc and "pcount" in enc
