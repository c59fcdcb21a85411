"""Frames that carry no information are reported lost.

Every tracker is started on a textured frame (the ``red-cube`` sample) and then shown an
all-black, an all-white and a constant grey frame: each must answer ``ok=False`` with a finite,
non-empty box. Identical black frames must not make the covariance trackers walk with
``ok=True`` (a singular covariance carries no information).
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import clips, trackers

NAMES = trackers.available(reference=False)


@pytest.fixture(scope="module")
def start():
    c = clips.load("red-cube")
    frames = [f for _, f in zip(range(4), c.frames)]
    return frames, c.groundtruth[0]


def test_every_registered_tracker():
    # the four papers' eleven, the correlation filters mosse and kcf, camshift and median-flow
    assert len(NAMES) == 15


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("value", [0, 255, 128], ids=["black", "white", "grey"])
def test_blank_frame_is_lost(name, value, start):
    frames, box = start
    t = trackers.create(name)
    t.init(frames[0], box)
    for f in frames[1:]:
        t.update(f)                         # a few normal frames first
    blank = np.full_like(frames[0], value)
    for _ in range(3):
        ok, b = t.update(blank)
        assert ok is False, f"{name} says ok=True on a constant frame of {value}"
        assert np.all(np.isfinite(b)) and b[2] > 0 and b[3] > 0


@pytest.mark.parametrize("name", ["covariance", "kalman-covariance"])
def test_identical_black_frames_do_not_walk_with_ok(name):
    frame = np.zeros((120, 160, 3), np.uint8)
    first = frame.copy()
    first[40:70, 60:90] = (30, 180, 220)       # a textured target on the first frame only
    first[50:60, 70:80] = (200, 20, 20)
    t = trackers.create(name)
    t.init(first, (60, 40, 30, 30))
    for _ in range(10):
        ok, b = t.update(frame)
        assert ok is False
        assert np.all(np.isfinite(b)) and b[2] > 0 and b[3] > 0


def _gate_by_hand(d2s, below, k, window=30):
    """The distance gate of ``ParticleFilterTracker`` written out as a slow loop: which frames
    of a sequence of best D^2 values are lost."""
    hist, lost = [], []
    for d2 in d2s:
        if len(hist) >= 5 and 1 - d2 < below:
            med = np.median(hist)
            mad = np.median([abs(v - med) for v in hist])
            if d2 > med + k * max(1.4826 * mad, med / 2):
                lost.append(True)
                continue
        hist = (hist + [d2])[-window:]
        lost.append(False)
    return lost


@pytest.mark.parametrize("name", ["color-pf", "hsi-color-pf"])
def test_distance_gate_matches_the_rule_by_hand(name, start, monkeypatch):
    """Feed the gate a chosen series of best distances (the likelihood is replaced by one
    that reports them) and compare its lost frames with the rule computed by hand."""
    frames, box = start
    d2s = [0.05, 0.04, 0.06, 0.05, 0.07, 0.05, 0.5, 0.06, 0.25, 0.2, 0.9, 0.04]
    # hand-worked: range of the first six: median 0.05, MAD 0.01 -> spread max(0.0148, 0.025)
    # = 0.025, bound 0.05 + 3 * 0.025 = 0.125: 0.5 and 0.9 (match < 0.7) are lost; 0.25
    # (match 0.75) and 0.2 (match 0.8) are not lost whatever their distance.
    expected = _gate_by_hand(d2s, 0.7, 3.0)
    assert expected == [False] * 6 + [True, False, False, False, True, False]
    t = trackers.create(name, seed=0)
    t.init(frames[0], box)
    series = iter(d2s)

    def fake_likelihood(frame, particles):
        d2 = next(series)
        t._match = np.full(len(particles), 1.0 - d2)
        return np.full(len(particles), np.exp(-d2 / 0.08))

    monkeypatch.setattr(t, "likelihood", fake_likelihood)
    monkeypatch.setattr(t, "gate_contrast", 0.0)     # the distance gate alone (no second look)
    got = [not t.update(frames[1 + i % 3])[0] for i in range(len(d2s))]
    assert got == expected


@pytest.mark.parametrize("name", ["color-pf", "hsi-color-pf"])
@pytest.mark.parametrize("around, lost", [(0.3, False), (0.55, True), (0.45, False)])
def test_second_look_keeps_a_match_that_stands_out(name, around, lost, start, monkeypatch):
    """After six frames at D^2 = 0.05, a frame whose best match is 0.6 (D^2 = 0.4, far above
    the range: the gate fires). Its second look compares 0.6 with the boxes around the best
    particle, all matching ``around``: 0.6 - 0.3 = 0.3 and 0.6 - 0.45 = 0.15 stand out (>= 0.12:
    kept, ok=True); 0.6 - 0.55 = 0.05 does not (lost)."""
    frames, box = start
    t = trackers.create(name, seed=0)
    t.init(frames[0], box)
    calls = []

    def fake_likelihood(frame, particles):
        calls.append(len(particles))
        m = 0.95 if len(calls) <= 6 else (0.6 if len(calls) == 7 else around)
        t._match = np.full(len(particles), m)
        return np.full(len(particles), np.exp(-(1 - m) / 0.08))

    monkeypatch.setattr(t, "likelihood", fake_likelihood)
    oks = [t.update(frames[1 + i % 3])[0] for i in range(7)]
    assert oks[:6] == [True] * 6
    assert oks[6] is (not lost)
    assert calls[7] >= 2                           # one extra call, on the probes
    # ... and hsi-color-pf, when the probes do not keep the frame, one on its best particle
    # relit (the relit look, which reports ``around`` here too: still lost)
    relit = name == "hsi-color-pf" and lost
    assert len(calls) == 8 + relit and (not relit or calls[8] == 1)


def test_distance_gate_is_off_in_the_paper_preset():
    for name in ["color-pf", "color-hog-pf", "color-hog-ipca", "hsi-color-pf", "hog-pf"]:
        assert trackers.create(name, preset="paper").params.lost_below == 0.0


@pytest.mark.parametrize("gain", [0.4, 2.2])
@pytest.mark.parametrize("present", [True, False], ids=["present", "covered"])
def test_hsi_colour_relit_look_keeps_a_target_under_a_change_of_light(gain, present):
    """hsi-color-pf's relit look: a light change multiplies every pixel by ``gain`` (the HSI
    intensity bins move, hue and saturation do not), so the cube, still there, matches its
    first-frame histogram poorly; scaled back to the last frame's mean intensity it matches
    again (ok=True). With the cube covered by the gravel three box widths to its right, the
    same change of light is lost (ok=False) -- relit or not, gravel is not a red cube."""
    from trackbook.features.color import bhattacharyya_coefficient
    from trackbook.features.hsi import hsi_histograms

    c = clips.load("red-cube")
    frames = [f for _, f in zip(range(11), c.frames)]
    gt = c.groundtruth
    frame = frames[10].copy()
    if not present:
        x, y, w, h = (int(round(v)) for v in gt[10])
        frame[y - 8:y + h + 8, x - 8:x + w + 8] = \
            frames[10][y - 8:y + h + 8, x - 8 + 3 * w:x + w + 8 + 3 * w]
    changed = np.clip(np.rint(frame * float(gain)), 0, 255).astype(np.uint8)
    # the premise, from the histograms alone: under the new light the cube's own box matches
    # below the gate's 0.7 (the distance gate fires)
    ref = hsi_histograms(frames[0], gt[0][None])
    assert bhattacharyya_coefficient(hsi_histograms(changed, gt[10][None]), ref)[0] < 0.7
    t = trackers.create("hsi-color-pf", seed=0)
    t.init(frames[0], gt[0])
    assert all(t.update(f)[0] for f in frames[1:10])
    ok, box = t.update(changed)
    assert ok is present
    assert np.all(np.isfinite(box))
