"""The experiments behind the book's committed results, declared as data and run by the benchmark.

An :class:`Experiment` is a grid: configurations ``(label, tracker, preset, params)`` x clips x
seeds. :func:`run` turns it into benchmark tasks (:class:`trackbook.evaluation.bench.Task`)
and executes them with the benchmark's workers (:func:`trackbook.evaluation.parallel.execute`:
local processes or a Dask cluster), saving every run as it ends under ``RUNS/<name>/runs/`` so
an interrupted experiment resumes; then it writes one results file, ``<name>.json``, read back
by :func:`trackbook.results.load`. Scores are written at full precision.

From the repository root::

    python -m trackbook.evaluation.experiments list
    python -m trackbook.evaluation.experiments run lee2015_real --workers 2
    python -m trackbook.evaluation.experiments run all --workers 2          # every experiment
    python -m trackbook.evaluation.experiments run claims --clips Crossing --check

``--clips`` and ``--seeds`` keep only the named clips and seeds; such a partial run is not
written over the committed file (give ``--out DIR`` to write it elsewhere), and ``--check``
compares its AUCs with the committed rows of the same configuration, clip and seed.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

from .. import papers as _papers
from .. import trackers as _trackers
from . import protocol_bench
from .bench import (REFERENCE, Task, _frozen, _jsonable, fingerprint, load_run, parse_seeds,
                    resolve_clips, write_atomic)
from .runs import code_fingerprint


@dataclasses.dataclass(frozen=True)
class Config:
    """One row of an experiment's grid: a tracker with a preset and params, under a label
    (``clips``: only on these clips of the experiment, by name; ``None``: on all)."""

    label: str
    tracker: str
    params: dict = dataclasses.field(default_factory=dict)
    preset: str = "book"
    clips: tuple | None = None


@dataclasses.dataclass(frozen=True)
class Experiment:
    """A declared experiment.

    Attributes
    ----------
    name : the results file's name (``trackbook.results.load(name)``)
    description : what the rows are, one sentence
    configs : the grid's configurations; ``None`` means every registered tracker (or those of
        ``trackers``), at each of ``presets``, labelled by its name
    clips : clip specs (``"shared"``: the real sequences; sample names)
    seeds : the seeds of every configuration
    presets : for ``configs=None``
    reference : also run OpenCV's MIL, once per clip (the first seed)
    plugins : modules or ``.py`` files (relative to the repository root) defining trackers the
        configurations use that the library does not register
    false_losses : rows carry ``false_losses``, ``[lost, on]`` of
        :func:`trackbook.evaluation.metrics.false_losses` (on a sample clip, over the frames
        whose target is at least half in view): what the failure contract's tests read
    protocols : the evaluation protocols every (configuration, clip, seed) runs through
        (:func:`trackbook.evaluation.protocol_bench.parse`: ``ope``, ``tre``, ``tre:N``,
        ``sre``, ``reset``); rows then carry a ``protocol`` field unless it is ``("ope",)``
    """

    name: str
    description: str
    configs: tuple | None = None
    clips: tuple = ("shared",)
    seeds: tuple = (0,)
    presets: tuple = ("book",)
    reference: bool = False
    plugins: tuple = ()
    trackers: tuple | None = None
    protocols: tuple = ("ope",)
    false_losses: bool = False

    def __post_init__(self):
        if self.false_losses and tuple(self.protocols) != ("ope",):
            raise ValueError(f"experiment {self.name!r}: false_losses counts one-pass runs; "
                             "give it protocols=('ope',).")

    def grid(self) -> list[Config]:
        """The configurations, in order (MIL last when ``reference``)."""
        if self.configs is None:
            names = [t for t in _trackers.available(reference=False)
                     if self.trackers is None or t in self.trackers]
            out = [Config(t, t, preset=p) for t in names for p in self.presets]
        else:
            out = list(self.configs)
        if self.reference:
            out.append(Config(REFERENCE, REFERENCE))
        return out


def _c(label, tracker, **params) -> Config:
    return Config(label, tracker, params)


# ------------------------------------------------------------------ Lee et al. 2012
LEE2012_TRACKERS = ("color-pf", "color-hog-pf", "color-hog-ipca")
#: Sequences the learning defaults were tuned on, and the ones held out (never used to choose).
LEE2012_DEV = ("Bag", "Couple", "Crossing", "Jogging1")
LEE2012_TEST = ("Ball1", "David", "MotorRolling")
#: The sample clips of Lee et al.'s scenario.
LEE2012_SAMPLES = ("robot-corridor-day", "robot-corridor-night")

#: Unchecked learning (every frame, subspace-only likelihood after T, as eq. 12-13) with the
#: book's sigma = 0.2, z = sqrt(h), K = 2, f = 0.95 and init "box": NOT the paper's
#: configuration (that is ``preset="paper"``: sigma 0.4 [quote: lee2012.sigma04], raw
#: histograms, a 40-frame window [quote: lee2012.window40], D in the exponent of eq. 12-13
#: [quote: lee2012.likelihood_eq12], whole-frame start; no K is printed). Spelled out so that every row below means the same thing
#: whatever the current defaults are.
UNCHECKED = {"anchor": 0.0, "gate_k": 0.0, "learn_threshold": 0.0, "learn_every": 1,
             "K": 2, "forgetting": 0.95, "centre": False}

#: Every configuration tried while choosing how ``color-hog-ipca`` learns, in the order tried.
LEE2012_LEARNING = (
    _c("color-pf", "color-pf"),
    _c("color-hog-pf", "color-hog-pf"),
    _c("color-pf, sigma 0.4 (paper)", "color-pf", sigma_color=0.4),
    _c("color-hog-pf, sigma 0.4 (paper)", "color-hog-pf", sigma_color=0.4, sigma_hog=0.4),
    _c("color-pf, sigma 0.1", "color-pf", sigma_color=0.1),
    _c("color-hog-pf, sigma 0.1", "color-hog-pf", sigma_color=0.1, sigma_hog=0.1),
    _c("color-pf, init frame (paper)", "color-pf", init="frame"),
    _c("color-hog-pf, init frame (paper)", "color-hog-pf", init="frame"),
    _c("unchecked learning (anchor 0)", "color-hog-ipca", **UNCHECKED),
    _c("unchecked learning, K 16", "color-hog-ipca", **{**UNCHECKED, "K": 16}),
    _c("absolute gate s >= 0.05", "color-hog-ipca", **{**UNCHECKED, "learn_threshold": 0.05}),
    _c("absolute gate s >= 0.2", "color-hog-ipca", **{**UNCHECKED, "learn_threshold": 0.2}),
    _c("mean-centred (Ross)", "color-hog-ipca", **{**UNCHECKED, "centre": True}),
    _c("no forgetting (f 1)", "color-hog-ipca", **{**UNCHECKED, "forgetting": 1.0}),
    _c("learn every 5th frame", "color-hog-ipca", **{**UNCHECKED, "learn_every": 5}),
    _c("relative gate k 1, model", "color-hog-ipca", **{**UNCHECKED, "gate_k": 1.0}),
    _c("relative gate k 3, model", "color-hog-ipca", **{**UNCHECKED, "gate_k": 3.0}),
    _c("relative gate k 3, reference", "color-hog-ipca",
       **{**UNCHECKED, "gate_k": 3.0, "gate_on": "reference"}),
    _c("anchor 0.3", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.3}),
    _c("anchor 0.5", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.5}),
    _c("anchor 0.6", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.6}),
    _c("anchor 0.7", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.7}),
    _c("anchor 0.85", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.85}),
    _c("anchor 0.5, f 1", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.5, "forgetting": 1.0}),
    _c("anchor 0.5, centred", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.5, "centre": True}),
    _c("anchor 0.7, f 1", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.7, "forgetting": 1.0}),
    _c("anchor 0.7, f 0.99", "color-hog-ipca",
       **{**UNCHECKED, "anchor": 0.7, "forgetting": 0.99}),
    _c("anchor 0.7, K 4", "color-hog-ipca", **{**UNCHECKED, "anchor": 0.7, "K": 4}),
    _c("anchor 0.7, every 2nd frame", "color-hog-ipca",
       **{**UNCHECKED, "anchor": 0.7, "learn_every": 2}),
    _c("anchor 0.7, gate k 3, model", "color-hog-ipca",
       **{**UNCHECKED, "anchor": 0.7, "gate_k": 3.0}),
    _c("anchor 0.7, gate k 3, reference", "color-hog-ipca",
       **{**UNCHECKED, "anchor": 0.7, "gate_k": 3.0, "gate_on": "reference"}),
)

# ------------------------------------------------------------------ Kim et al. 2016
#: The search for a better edge observation model (lab notes on Kim et al. 2016): each variant
#: of ``edge-ray-x`` (defined in experiments/kim2016_edge_variants.py) switches on one
#: departure from the paper; then the library's ``velocity_gain`` for the three trackers.
#: The edge trackers run without re-detection (the canonical names): a whole-frame search
#: would hide what the edge model alone does, the question of this search.
def _e(label, tracker="edge-ray-x", **params) -> Config:
    return _c(label, tracker, **params)


KIM2016_EDGES = (
    _e("paper (edge-ray-pf)", "edge-ray-pf"),
    _e("(a) per-ray log-ratio distance, sigma 0.3", dist="log", obs_sigma=0.3),
    _e("(a) per-ray log-ratio distance, sigma 0.15", dist="log", obs_sigma=0.15),
    _e("(a) log-ratio, 10 px added to every ray", dist="log", log_c=10.0, obs_sigma=0.3),
    _e("(a) log-ratio, Laplacian", dist="logl1", obs_sigma=0.1),
    _e("(c) soft Ratio window", soft_ratio=0.15),
    _e("(a+c) log-ratio + soft Ratio", dist="log", obs_sigma=0.2, soft_ratio=0.2),
    _e("(d) CLAHE before Canny", clahe=2.0),
    _e("(d) Canny thresholds follow the local gradient gain", gain="local"),
    _e("(d) Canny thresholds follow the frame's gradient gain", gain="global"),
    _e("(b) 5 points, a model and a Ratio test each", points=5),
    _e("(b) 5 points, 40 rays in one model", combine="pool", points=5),
    _e("(b) 9 points, 72 rays in one model", combine="pool", points=9),
    _e("edges dilated 3x3", dilate=1),
    _e("rays stop only at edges across them (60 deg)", orient=60.0),
    _e("rays stop only at edges across them (45 deg)", orient=45.0),
    _e("(e) estimate from the top 3 % of particles", top_frac=0.03),
    _e("(e) estimate from the top 10 %", top_frac=0.1),
    _e("(e) estimate from the top 30 %", top_frac=0.3),
    _e("velocity_gain 0.5", "edge-ray-pf", velocity_gain=0.5),
    _e("velocity_gain 0", "edge-ray-pf", velocity_gain=0.0),
    _c("hsi-color-pf", "hsi-color-pf"),
    _c("hsi-color-pf, velocity_gain 0.5", "hsi-color-pf", velocity_gain=0.5),
    _c("hsi-color-pf, velocity_gain 0", "hsi-color-pf", velocity_gain=0.0),
    _c("hog-pf", "hog-pf"),
    _c("hog-pf, velocity_gain 0.5", "hog-pf", velocity_gain=0.5),
)


def _plain(*names) -> tuple:
    return tuple(Config(t, t) for t in names)


# ------------------------------------------------------------------ evaluation protocols
#: The trackers of the protocols experiment: the book's canonical trackers that run at a few
#: milliseconds a frame (Median Flow and OpenCV's MIL take ~100 ms a frame, too slow for the
#: ~25 passes over every sequence that OPE + TRE + SRE + reset make).
PROTOCOL_TRACKERS = ("kcf", "mosse", "mean-shift", "camshift", "color-pf")
#: TRE with 10 starts, not OTB's 20: on these 105-471-frame sequences 10 starts are still
#: at most 51 frames apart (David), and TRE's cost (about starts x length / 2 frames) halves.
PROTOCOLS = ("ope", "tre:10", "sre", "reset")


EXPERIMENTS = {e.name: e for e in (
    Experiment("real", "every registered tracker at the book's defaults on the real "
               "sequences, seed 0, with OpenCV's MIL", reference=True, false_losses=True),
    Experiment("failure_samples", "every registered tracker at the book's defaults on the "
               "sample clips, seed 0, with OpenCV's MIL (the false-loss counts the failure "
               "contract's tests read)", clips=("samples",), reference=True,
               false_losses=True),
    Experiment("claims", "the four papers' trackers, both presets, the real sequences, seeds "
               "0-2 (the paired comparisons of 09_trackers_compared)",
               seeds=(0, 1, 2), presets=("book", "paper"), trackers=_papers.TRACKERS),
    Experiment("samples", "the four papers' trackers at the book's defaults on the sample "
               "clips, seed 0, with OpenCV's MIL (the sample-clip ranking of "
               "09_trackers_compared)", clips=("samples",), trackers=_papers.TRACKERS,
               reference=True),
    Experiment("lee2012_real", "Table 3 of Lee et al. 2012 on the real sequences: the three "
               "trackers at their defaults, seeds 0-2, MIL with seed 0",
               _plain(*LEE2012_TRACKERS), seeds=(0, 1, 2), reference=True),
    Experiment("lee2012_learning", "every configuration tried while choosing how "
               "color-hog-ipca learns, real sequences, seeds 0-2", LEE2012_LEARNING,
               seeds=(0, 1, 2)),
    Experiment("lee2012_learning_samples", "the learning configurations on the sample clips "
               "of Lee et al.'s scenario, seeds 0-2", LEE2012_LEARNING,
               clips=LEE2012_SAMPLES, seeds=(0, 1, 2)),
    Experiment("kim2016_real", "Table 3 of Kim et al. 2016 on the real sequences: the three "
               "trackers at their defaults, seed 0, with MIL",
               _plain("hsi-color-pf", "hog-pf", "edge-ray-pf"), reference=True),
    Experiment("kim2016_edges", "the edge-observation variants of the lab notes on Kim et al. "
               "2016, real sequences, seeds 0-2", KIM2016_EDGES, seeds=(0, 1, 2),
               plugins=("experiments/kim2016_edge_variants.py",)),
    Experiment("lee2015_real", "Table 1 of Lee 2015 on the real sequences: covariance, "
               "kalman-covariance, the book's kalman-covariance-manoeuvre and MIL, seed 0",
               _plain("covariance", "kalman-covariance", "kalman-covariance-manoeuvre",
                      REFERENCE)),
    Experiment("protocols", "OTB's one-pass, temporal (10 starts) and spatial robustness "
               "evaluations and VOT's reset protocol for five canonical trackers on the real "
               "sequences, seed 0 (the evaluation protocols chapter)",
               _plain(*PROTOCOL_TRACKERS), protocols=PROTOCOLS),
    Experiment("cho2005_real", "Tables 1-2 of Cho & Kang 2005 on the real sequences: the "
               "three trackers, seed 0, with MIL on MotorRolling as the speed reference",
               _plain("condensation", "mean-shift", "condensation-mean-shift")
               + (Config(REFERENCE, REFERENCE, clips=("MotorRolling",)),)),
)}


def get(name: str) -> Experiment:
    """The experiment called ``name`` (``ValueError`` naming the known ones otherwise)."""
    if name not in EXPERIMENTS:
        raise ValueError(f"unknown experiment {name!r}; known: {', '.join(EXPERIMENTS)}.")
    return EXPERIMENTS[name]


def _plugin_paths(exp: Experiment, root: Path) -> tuple:
    return tuple(str((root / p).resolve()) if p.endswith(".py") else p for p in exp.plugins)


def plan(exp: Experiment, clips=None, root=".", seeds=None) -> list[tuple[Config, Task]]:
    """The (configuration, benchmark task) pairs of ``exp``, in the order of its rows:
    configurations, then clips, then seeds (MIL: the first seed only). ``clips`` and
    ``seeds`` keep only those clips (by name) and seeds; ``root`` is where the plugins'
    relative paths start."""
    from ..trackers import plugins

    plugs = _plugin_paths(exp, Path(root))
    for p in plugs:
        plugins.load(p)
    grid = exp.grid()
    protocols = [protocol_bench.canonical(p) for p in exp.protocols]
    for c in grid:
        if c.tracker != REFERENCE:   # a bad name or value fails here, before any run
            _trackers.create(c.tracker, seed=0, preset=c.preset, **c.params)
    refs = resolve_clips(list(exp.clips))
    if clips is not None:
        wanted = set(clips)
        unknown = wanted - {r.name for r in refs}
        if unknown:
            raise ValueError(f"clips {', '.join(sorted(unknown))} are not in experiment "
                             f"{exp.name!r} (its clips: {', '.join(r.name for r in refs)}).")
        refs = [r for r in refs if r.name in wanted]
    loaded = []
    for ref in refs:
        clip = ref.load()
        loaded.append((ref, fingerprint(clip), len(clip)))
    code = {c.tracker: code_fingerprint(c.tracker) for c in grid}   # an edited tracker re-runs
    out = []
    for c in grid:
        for ref, fp, n in loaded:
            if c.clips is not None and ref.name not in c.clips:
                continue
            for s in exp.seeds:
                if (c.tracker == REFERENCE and s != exp.seeds[0]) or (
                        seeds is not None and s not in seeds):
                    continue
                out.extend((c, Task(c.tracker, ref, s, None, _frozen(c.params), fp, n,
                                    preset=c.preset, code=code[c.tracker], protocol=p))
                           for p in protocols)
    return out


def _row(c: Config, task: Task, rec: dict, exp: Experiment) -> dict:
    scores = {k: v for k, v in rec["row"].items() if k not in ("tracker", "clip", "seed")}
    if tuple(exp.protocols) != ("ope",):
        scores["protocol"] = task.protocol
        # what a chapter needs beyond the scores: TRE's starts and each run's AUC; the reset
        # protocol's overlaps and (re)initialisation and failure frames, for a pooled EAO
        for k, name in (("starts", "starts"), ("run_auc", "run_auc"), ("inits", "inits"),
                        ("failures", "failure_frames"), ("overlaps", "overlaps")):
            if k in rec and not (k == "starts" and task.protocol == "sre"):
                scores[name] = rec[k]
    if exp.false_losses:
        # the counts, and the code they came from (versions left out): the contract's tests
        # read every row, so every row must name its code (tests/test_results_fresh.py)
        scores["false_losses"] = rec["false_losses"]
        scores["code"] = code_fingerprint(c.tracker, versions=False)
    return {"label": c.label, "tracker": c.tracker, "preset": c.preset,
            "params": json.dumps(c.params, sort_keys=True), "clip": rec["row"]["clip"],
            "seed": task.seed, **scores}


def run(name: str, runs="experiment-runs", clips=None, workers: int = 1, scheduler=None,
        progress: bool = True, force: bool = False, root=".", seeds=None) -> dict:
    """Run experiment ``name`` through the benchmark and return its results document
    (``{"name", "description", "command", "clips", "seeds", "plugins", "rows"}``).

    Saved runs live under ``runs/<name>/runs/`` (a re-run reuses every run whose key matches);
    :func:`write` puts the document where :func:`trackbook.results.load` finds it.
    """
    from . import parallel

    exp = get(name)
    pairs = plan(exp, clips, root, seeds)
    out = Path(runs) / exp.name
    done = {} if force else {t: r for _, t in pairs if (r := load_run(t, out)) is not None
                             and (not exp.false_losses or "false_losses" in r)}
    todo = [t for _, t in pairs if t not in done]
    bar = None
    if progress:
        from tqdm.auto import tqdm
        bar = tqdm(total=len(pairs), initial=len(done), desc=exp.name, unit="run")

    def finished(group, recs):
        done.update(zip(group, recs))
        if bar is not None:
            bar.update(len(group))

    try:
        parallel.execute(todo, out, finished, workers=workers, scheduler=scheduler,
                         imports=_plugin_paths(exp, Path(root)))
    finally:
        if bar is not None:
            bar.close()
    return {"name": exp.name, "description": exp.description,
            "command": f"python -m trackbook.evaluation.experiments run {exp.name}",
            "clips": sorted({t.clip.name for _, t in pairs}), "seeds": list(exp.seeds),
            "plugins": list(exp.plugins), "rows": [_row(c, t, done[t], exp) for c, t in pairs]}


def write(doc: dict, folder=None) -> Path:
    """Write a results document as ``<folder>/<name>.json`` (default: the committed results of
    :mod:`trackbook.results`), atomically; return the path."""
    from .. import results

    path = Path(folder or results.HERE) / f"{doc['name']}.json"
    doc = _jsonable(doc)
    head = json.dumps({k: v for k, v in doc.items() if k != "rows"}, indent=1, allow_nan=False)
    rows = ",\n".join(json.dumps(r, allow_nan=False) for r in doc["rows"])
    # one row per line: a regenerated file diffs row by row
    write_atomic(path, head[:-2] + f',\n "rows": [\n{rows}\n ]\n}}\n')
    return path


def _key(r) -> tuple:
    return (r["label"], r["tracker"], r["preset"], r["params"], r["clip"], int(r["seed"]),
            r.get("protocol", "ope"))


def check(doc: dict, metric: str = "auc") -> list[dict]:
    """Each row of ``doc`` against the committed row of the same configuration, clip and seed:
    ``{label, tracker, preset, clip, seed, new, committed, diff}`` (``committed`` is ``nan``
    when there is no such row)."""
    from .. import results

    old = {_key(r): r for r in results.load(doc["name"])}
    out = []
    for r in doc["rows"]:
        c = old.get(_key(r), {}).get(metric, float("nan"))
        new = float("nan") if r.get(metric) is None else r[metric]
        out.append({"label": r["label"], "tracker": r["tracker"], "preset": r["preset"],
                    "clip": r["clip"], "seed": r["seed"], "new": new, "committed": c,
                    "diff": new - c})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m trackbook.evaluation.experiments",
                                 description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="the experiments and their sizes")
    r = sub.add_parser("run", help="run experiments and write their results files")
    r.add_argument("name", help=f"an experiment ({', '.join(EXPERIMENTS)}) or 'all'")
    r.add_argument("--workers", type=int, default=1)
    r.add_argument("--scheduler", help="a Dask scheduler address (tcp://HOST:8786)")
    r.add_argument("--clips", help="comma-separated clip names: run only these (not written "
                   "over the committed file)")
    r.add_argument("--seeds", help="run only these seeds (e.g. 0 or 0-2; not written over "
                   "the committed file)")
    r.add_argument("--runs", default="experiment-runs", help="folder of the saved runs")
    r.add_argument("--out", help="folder for <name>.json (default: the committed results; "
                   "required to write a --clips run)")
    r.add_argument("--check", action="store_true",
                   help="compare the AUCs with the committed rows and report the differences")
    r.add_argument("--tolerance", type=float, default=0.0,
                   help="with --check, list only the rows whose AUC differs by more")
    r.add_argument("--force", action="store_true", help="re-run saved runs")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    a = ap.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        if a.cmd == "list":
            for e in EXPERIMENTS.values():
                print(f"{e.name:26s} {len(e.grid()):3d} configurations x {len(e.seeds)} seeds "
                      f"on {', '.join(e.clips)}: {e.description}")
            return 0
        names = list(EXPERIMENTS) if a.name == "all" else [get(a.name).name]
        clips = [c.strip() for c in a.clips.split(",") if c.strip()] if a.clips else None
        seeds = parse_seeds(a.seeds) if a.seeds else None
        for n in names:
            doc = run(n, a.runs, clips, a.workers, a.scheduler, not a.quiet, a.force,
                      seeds=seeds)
            if a.check:
                rows = check(doc)
                diffs = np.array([abs(x["diff"]) for x in rows], dtype=float)
                bad = [x for x in rows if not abs(x["diff"]) <= a.tolerance]
                print(f"{n}: {len(rows)} rows, max |AUC - committed| = "
                      f"{np.nanmax(diffs) if np.isfinite(diffs).any() else float('nan'):.3g}, "
                      f"{len(bad)} differ by more than {a.tolerance:g}")
                for x in bad:
                    print(f"  {x['label']} [{x['tracker']}, {x['preset']}] {x['clip']} "
                          f"seed {x['seed']}: {x['new']!r} vs committed {x['committed']!r}")
            if (clips is None and seeds is None) or a.out:
                print(f"wrote {write(doc, a.out)}")
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted; run the same command again to resume", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
