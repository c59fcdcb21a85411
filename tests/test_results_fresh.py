"""The committed results (``trackbook.results``) still match the library of this commit.

Chapters read these files instead of re-running minutes of tracking, so a change to a tracker
or a feature can leave them stale without any chapter failing (the edge-ray results once kept
``hog-pf`` rows from before a HOG fix). This re-runs every committed row on one short sequence
(Crossing, 120 frames; a result of the sample clips only, on its shortest clip) and demands
the committed AUC: the files are written at full precision,
so one tolerance (a float's round trip) fits every file. A row that carries the failure
contract's counts (``false_losses``: frames reported lost with the box on the target, and
frames with the box on the target) must give the same two numbers exactly; and since the
contract's tests read every such row, not one clip's, each of those rows also names the code
it came from (``code``: the tracker's code and calibrated thresholds, versions left out),
which must be this commit's -- OpenCV's MIL included (its wrapper and child script; not
OpenCV's own MIL, whose boxes depend on OpenCV's build). In a grid that runs a tracker under
several configurations, seed 0 of each configuration is checked. OpenCV's MIL is left out: its
score depends on OpenCV's build. When a tracker changes on purpose, regenerate the result with
``python -m trackbook.evaluation.experiments run NAME`` (the lab notes give each command).

A row of another evaluation protocol (its ``protocol`` field: TRE, SRE, the reset protocol)
is re-run through that protocol (:mod:`trackbook.evaluation.protocols`) and checked on its
own scores: the pooled AUC for TRE and SRE; the accuracy, the failure count and the EAO for
the reset protocol.
"""

import functools
import json
from pathlib import Path

import pytest

import trackbook
from trackbook import clips, results
from trackbook.clips import samples
from trackbook.evaluation import metrics, protocol_bench, protocols
from trackbook.evaluation.runs import code_fingerprint
from trackbook.trackers import plugins

from .conftest import SEQUENCES, needs_sequences

ROOT = Path(__file__).resolve().parents[1]
CLIP = "Crossing"          # 120 frames: the shortest sequence that every result covers
TOL = 1e-12                # the AUC written as a float and read back


@functools.lru_cache(maxsize=None)
def _run(tracker: str, seed: int, params: str, preset: str, plugin_specs: tuple,
         clip: str = CLIP) -> tuple[float, list]:
    """The run's AUC and its ``[lost, on]`` false-loss count (what the rows carry)."""
    for spec in plugin_specs:
        plugins.load(str(ROOT / spec) if spec.endswith(".py") else spec)
    source = str(SEQUENCES[clip]) if clip == CLIP else clip      # a sample clip by name
    c = clips.load(source)
    r = trackbook.evaluate(tracker, c, seed=seed, preset=preset, **json.loads(params))
    in_view = samples.in_view(clip) if clip in samples.names() else None
    return r.scores["auc"], list(metrics.false_losses(r.ok, r.boxes, c.groundtruth, in_view))


@functools.lru_cache(maxsize=None)
def _protocol_scores(protocol: str, tracker: str, seed: int, params: str, preset: str,
                     clip: str = CLIP) -> dict:
    source = str(SEQUENCES[clip]) if clip == CLIP else clip
    kw = dict(seed=seed, preset=preset, **json.loads(params))
    name, starts = protocol_bench.parse(protocol)
    if name == "reset":
        run = protocols.evaluate_reset(tracker, source, **kw)
        return {"accuracy": run.accuracy, "failures": run.n_failures,
                "eao": protocols.eao([run])}
    res = (protocols.evaluate_tre(tracker, source, n_segments=starts, **kw) if name == "tre"
           else protocols.evaluate_sre(tracker, source, **kw))
    return {"auc": res.scores["auc"]}


def _clip_of(table) -> str:
    """Crossing, or for a result without it (the sample clips) its shortest clip."""
    names = {r["clip"] for r in table}
    if CLIP in names:
        return CLIP
    return min(names, key=lambda c: (min(int(r["frames"]) for r in table.where(clip=c)), c))


def _cases():
    for name in results.available():
        table = results.load(name)
        plugs = tuple(table.meta.get("plugins", ()))
        first = min(int(r["seed"]) for r in table)
        clip = _clip_of(table)
        for r in table.where(clip=clip):
            # one seed of every configuration: a stale file is stale for every seed, and the
            # seeds' runs come from the same code as the first seed's
            if r["tracker"] == "opencv-mil" or int(r["seed"]) != first:
                continue
            proto = r.get("protocol", "ope")
            proto = "ope" if proto != proto else proto           # nan: a one-pass file
            yield pytest.param(name, r["label"], r["tracker"], r["seed"], r["params"],
                               r["preset"], plugs, r, clip, proto,
                               id=f"{name}:{r['label']}:{r['preset']}:seed{r['seed']}"
                               + ("" if proto == "ope" else f":{proto}"))


@needs_sequences
@pytest.mark.shared
@pytest.mark.slow
@pytest.mark.skipif(CLIP not in SEQUENCES, reason=f"sequence {CLIP} not found")
@pytest.mark.parametrize("name, label, tracker, seed, params, preset, plugin_specs, row, "
                         "clip, protocol", list(_cases()))
def test_committed_auc_is_reproduced(name, label, tracker, seed, params, preset, plugin_specs,
                                     row, clip, protocol):
    if protocol != "ope":
        new = _protocol_scores(protocol, tracker, seed, params, preset, clip)
        assert new == pytest.approx({k: row[k] for k in new}, abs=TOL), (
            f"the committed result {name!r} is stale for {label} ({tracker}, {protocol}) on "
            f"{clip}; regenerate it with: python -m trackbook.evaluation.experiments run {name}")
        return
    auc, losses = _run(tracker, seed, params, preset, plugin_specs, clip)
    stale = (f"the committed result {name!r} is stale for {label} ({tracker}, seed {seed}) on "
             f"{clip}; regenerate it with: python -m trackbook.evaluation.experiments run {name}")
    assert auc == pytest.approx(row["auc"], abs=TOL), stale
    if "false_losses" in row:       # the failure contract's counts: frame counts, exactly
        assert losses == list(row["false_losses"]), stale


def _counted_rows():
    for name in results.available():
        for r in results.load(name):
            if "false_losses" in r:
                yield name, r


def test_every_committed_false_loss_count_comes_from_this_code():
    """No run needed: a change to a tracker's code or its failure thresholds changes the
    fingerprint, so a count on a clip the test above does not re-run cannot go stale."""
    rows = list(_counted_rows())
    assert {n for n, _ in rows} >= {"real", "failure_samples"}
    stale = sorted({(n, r["tracker"]) for n, r in rows
                    if r.get("code") != code_fingerprint(r["tracker"], versions=False)})
    assert not stale, ("committed false-loss counts from other code: "
                       + ", ".join(f"{t} in {n}" for n, t in stale)
                       + "; regenerate with: python -m trackbook.evaluation.experiments run "
                       + " / ".join(sorted({n for n, _ in stale})))
