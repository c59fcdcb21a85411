"""The Jupyter playground's streamed re-run: on the kernel's event loop a knob change sends
partial payloads (frames up to the one on screen first), then the complete one, which is
``evaluate``'s run; a newer change stops an older run; outside an event loop ``set`` answers
with the whole run at once. No timing is asserted: the chunk lengths are set to zero or to
"never" so that each chunk is one frame, or the first answer stops exactly at the frame on
screen."""

from __future__ import annotations

import asyncio

import numpy as np
import pytest

from trackbook.evaluation import evaluate
from trackbook.playground import live
from trackbook.widgets import Playground

CLIP, TRACKER = "yellow-ball", "color-pf"


@pytest.fixture
def one_frame_chunks(monkeypatch):
    """Each streamed chunk is one frame and every chunk is sent; the first answer stops at
    the frame on screen (never earlier, whatever the machine's speed)."""
    monkeypatch.setattr(live, "CHUNK_S", 0.0)
    monkeypatch.setattr(live, "SEND_EVERY_S", 0.0)
    monkeypatch.setattr(live, "FIRST_S", None)


def _record(pg):
    got = []
    pg.observe(lambda ch: got.append(ch["new"]), names="run_data")
    return got


async def _settle(pg):
    while pg._task is not None:
        await asyncio.sleep(0)


def _change(pg, **knobs):
    """What the viewer does: set the ``values`` trait (and the frame on screen) through
    ``set_state``, the comm's path."""
    state = {"values": {**pg.values, **knobs}}
    return state


def test_partial_payloads_then_the_complete_run_of_evaluate(one_frame_chunks):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=24, seed=3)
    got = _record(pg)

    async def move():
        pg.set_state({**_change(pg, n_particles=40), "frame": 9})
        assert got == []                    # nothing is tracked before the loop runs the task
        await _settle(pg)
    asyncio.run(move())
    n = [p["n_done"] for p in got]
    assert all(p["n_total"] == 24 for p in got)
    assert n[0] == 10                       # frames 0..9: up to the frame on screen
    assert n == list(range(10, 25))         # then one frame a chunk, in order
    assert all(len(p["boxes"]) == p["n_done"] == len(p["ok"]) for p in got)
    assert "running" in got[0]["scores"] and "AUC" in got[-1]["scores"]
    ref = evaluate(TRACKER, CLIP, seed=3, max_frames=24, n_particles=40)
    np.testing.assert_array_equal(pg.result.boxes, ref.boxes)       # exactly, same seed
    np.testing.assert_array_equal(pg.result.ok, ref.ok)
    assert pg.result.scores["auc"] == ref.scores["auc"]
    assert got[-1]["boxes"] == np.round(ref.boxes, 1).tolist()
    for p in got[:-1]:                      # every partial is a prefix of the complete run
        assert p["boxes"] == got[-1]["boxes"][:p["n_done"]]
    assert pg.run_data is got[-1] and not pg.busy and pg.values["n_particles"] == 40


def test_a_newer_change_stops_the_older_run(one_frame_chunks):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=30, seed=0)
    got = _record(pg)

    async def move_twice():
        pg.set_state(_change(pg, n_particles=25))
        while not got:                      # the first run's first answer (frame 0)
            await asyncio.sleep(0)
        await asyncio.sleep(0)
        await asyncio.sleep(0)
        pg.set_state(_change(pg, n_particles=60))
        await _settle(pg)
        for _ in range(20):                 # a stale chunk would have run by now
            await asyncio.sleep(0)
    asyncio.run(move_twice())
    first = [p for p in got if p["values"]["n_particles"] == 25]
    second = [p for p in got if p["values"]["n_particles"] == 60]
    assert first and all(p["n_done"] < 30 for p in first)    # never completed
    assert got[:len(first)] == first                          # and nothing after the change
    assert second[-1]["n_done"] == 30 and got[-1] is second[-1]
    ref = evaluate(TRACKER, CLIP, seed=0, max_frames=30, n_particles=60)
    np.testing.assert_array_equal(pg.result.boxes, ref.boxes)


def test_set_answers_the_whole_run_at_once_without_and_with_a_loop():
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=16, seed=1)
    got = _record(pg)
    r = pg.set(n_particles=35)              # plain Python: no event loop
    ref = evaluate(TRACKER, CLIP, seed=1, max_frames=16, n_particles=35)
    np.testing.assert_array_equal(r.boxes, ref.boxes)
    assert [p["n_done"] for p in got] == [16]

    async def in_a_loop():                  # a notebook cell: the kernel's loop is running
        return pg.set(n_particles=45)
    r = asyncio.run(in_a_loop())
    np.testing.assert_array_equal(
        r.boxes, evaluate(TRACKER, CLIP, seed=1, max_frames=16, n_particles=45).boxes)
    assert got[-1]["n_done"] == got[-1]["n_total"] == 16 and pg._task is None


def test_an_undeclared_knob_from_the_viewer(one_frame_chunks):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=12)
    assert "sigma_color" not in [k["name"] for k in pg.config["knobs"][TRACKER]]
    pg.set_state(_change(pg, sigma_color=0.4))          # no loop: runs at once
    assert pg.error == "" and pg.result.params["sigma_color"] == 0.4
    assert "sigma_color" in [k["name"] for k in pg.config["knobs"][TRACKER]]

    async def streamed():
        pg.set_state(_change(pg, vx_noise=3.0))
        await _settle(pg)
    asyncio.run(streamed())
    assert pg.error == "" and pg.result.params["vx_noise"] == 3.0
    assert pg.run_data["n_done"] == 12
    np.testing.assert_array_equal(
        pg.result.boxes, evaluate(TRACKER, CLIP, seed=0, max_frames=12, sigma_color=0.4,
                                  vx_noise=3.0).boxes)


def test_the_whole_clip_streams_to_the_same_run():
    """No ``n_frames``: the whole clip, with the real chunk lengths."""
    pg = Playground(clips=["two-faces"], trackers=["mean-shift"])
    got = _record(pg)

    async def move():
        pg.set_state(_change(pg, max_iter=5))
        await _settle(pg)
    asyncio.run(move())
    n = [p["n_done"] for p in got]
    assert n == sorted(n) and n[-1] == got[-1]["n_total"] == 120
    np.testing.assert_array_equal(pg.result.boxes,
                                  evaluate("mean-shift", "two-faces", max_iter=5).boxes)


def test_a_run_cut_short_is_closed_and_says_how_far_it_got():
    run = live.LiveRun(TRACKER, __import__("trackbook").clips.load(CLIP), {}, 10)
    run.advance(until=4)
    assert run.n_done == 4 and len(run.payload()["boxes"]) == 4
    with pytest.raises(ValueError, match="4 of 10"):
        run.result()


def test_a_refusal_while_streaming_keeps_the_last_complete_run(one_frame_chunks, monkeypatch):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=12)
    before = pg.result
    real = live.LiveRun.step

    def step(self):                 # the tracker refuses this setting on frame 5
        if self.n_done == 5 and self.values.get("n_particles") == 70:
            raise ValueError("70 particles refused on frame 5")
        real(self)
    monkeypatch.setattr(live.LiveRun, "step", step)

    async def move():
        pg.set_state(_change(pg, n_particles=70))
        await _settle(pg)
    asyncio.run(move())
    assert "refused on frame 5" in pg.error and not pg.busy and pg.result is before
    assert pg.set(n_particles=71).params["n_particles"] == 71 and pg.error == ""


def test_set_while_a_run_streams_answers_whole_and_stops_the_stream(one_frame_chunks):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=14)
    got = _record(pg)

    async def stream_then_set():
        pg.set_state(_change(pg, n_particles=25))   # streams once the loop runs it
        r = pg.set(n_particles=55)                   # a cell's call before that
        for _ in range(20):
            await asyncio.sleep(0)
        return r
    r = asyncio.run(stream_then_set())
    np.testing.assert_array_equal(
        r.boxes, evaluate(TRACKER, CLIP, max_frames=14, n_particles=55).boxes)
    assert [p["values"]["n_particles"] for p in got] == [55] and got[0]["n_done"] == 14


def test_set_to_the_values_a_run_streams_finishes_it_now(one_frame_chunks):
    pg = Playground(clips=[CLIP], trackers=[TRACKER], n_frames=10)

    async def stream_then_same():
        pg.set_state(_change(pg, n_particles=30))
        return pg.set(n_particles=30)
    r = asyncio.run(stream_then_same())
    assert r.params["n_particles"] == 30 and pg.run_data["n_done"] == 10 and pg._task is None
