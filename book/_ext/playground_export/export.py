"""The HTML book's playgrounds: a :class:`~trackbook.playground.Playground` exported as a page
fragment that runs with no kernel and no network.

For every clip and tracker of a playground, the runs at the defaults and for a few values of
each knob (one knob at a time) over whole clips and several seeds are computed
(:mod:`playground_export.static`) and written as small files the page loads when the reader
picks them. In the book's build every chapter's kernel displays a playground or an animation
as this page (:func:`playground_export.install`); in Jupyter it is the live widget.
"""

from __future__ import annotations

import base64
import dataclasses
import html
import io
import json

import numpy as np

from trackbook import params as _params
from trackbook.playground import data as D
from trackbook.playground.data import VIEWER_CSS, VIEWER_JS, sample_values

from . import static as S

#: what the Sphinx extension replaces with the page's path to ``_static/playground/``
STATIC_BASE = "@@tb-static-playground@@"


def refuse_unknown_keywords(where: str, kwargs: dict) -> None:
    """The static runs' cost limit is ``max_cost`` (tracker-frames); any other keyword is
    refused naming it (an older name of that limit included)."""
    if kwargs:
        raise TypeError(f"{where}() got {', '.join(map(repr, kwargs))}: the limit on the "
                        "precomputed runs' cost is max_cost= (tracker-frames)")


def page_html(payload: dict, png: bytes, alt: str, files: bool = False) -> str:
    """One fragment: root ``div.tb-playground``, the data as JSON in a ``<script>`` (no
    fetch, so ``file://`` works), the viewer module inline and ``png`` in a ``<noscript>``
    (print, no JavaScript). Files the data names (``payload["files"]``) are loaded from
    ``data-tb-base``, the path the book's ``sphinx_playground`` extension writes there. With
    ``files`` (the book's pages) inline runs and frames (an animation's) and the picture
    become files too (:func:`playground_export.static.to_files`): the page stays light."""
    if files:
        payload = S.to_files(payload)
        src = STATIC_BASE + S.write_png(png)
    else:
        src = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
    data = json.dumps(payload, separators=(",", ":")).replace("</", "<\\/")
    js = VIEWER_JS.read_text(encoding="utf-8").replace("</script", "<\\/script")
    css = VIEWER_CSS.read_text(encoding="utf-8")
    return (f'<div class="tb-playground" data-tb-static="1" data-tb-base="{STATIC_BASE}">'
            f'<script type="application/json" class="tb-data">{data}</script>'
            f'<noscript><img alt="{html.escape(alt)}" src="{src}">'
            f'</noscript></div><style>{css}</style><script type="module">{js}</script>')


def paper_sample(cls, name: str):
    """The paper preset's value of knob ``name`` of a tracker class, as ``preset="paper"``
    sets it (:func:`trackbook.params.paper_value`): the printed value, or for an addition of
    the book the setting that switches it off (0 or False); ``None`` for a field whose value
    is not printed."""
    fields = {f.name: f for f in dataclasses.fields(cls.Params)} if cls else {}
    f = fields.get(name)
    if f is None or not _params.has_paper(f):
        return None
    v = _params.paper_value(f)
    if f.metadata.get("paper") is _params.NOT_PRINTED and (
            f.metadata.get("paper_value", _params._UNSET) is _params._UNSET
            or isinstance(v, str) or bool(v)):
        # not printed: only an addition's "off" (0, False) counts as the preset's value;
        # a reading of a value that is not printed does not
        return None
    return list(v) if isinstance(v, tuple) else v


def static_samples(spec: dict, paper=None, others: int = 2) -> list:
    """The values of one knob the HTML book precomputes: the book's default, the preset value
    ``paper`` (where there is one; the caller checks the params take it) and ``others``
    more from :func:`sample_values` (one fewer when ``paper`` is a stop of its own) --
    the nearest below and above the default, then the next ones out -- sorted; a choice or a
    switch keeps all its values. Each run costs build time, hence so few stops."""
    d = spec["default"]
    if spec["kind"] in ("choice", "bool", "text"):
        vals = sample_values(spec)
        if paper is not None and paper not in vals:
            vals.append(paper)
        return vals if spec["kind"] != "choice" else [v for v in spec["choices"] if v in vals]
    keep = [d]
    if paper is not None and paper != d:      # outside the slider's range too: the preset's
        keep.append(paper)
    if len(keep) > 1:          # the preset value is one of the "others": three stops in all
        others = max(1, others - 1)
    rest = [v for v in sample_values(spec) if v not in keep]
    key = (lambda v: max(v)) if spec["kind"] == "pair" else (lambda v: v)
    dk = key(d)
    below = sorted((v for v in rest if key(v) < dk), key=key, reverse=True)
    above = sorted((v for v in rest if key(v) > dk), key=key)
    picks = []
    while len(picks) < others and (below or above):
        for side in (below, above):
            if side and len(picks) < others:
                picks.append(side.pop(0))
    return sorted(keep + picks, key=key)


def static_knobs(pg, tracker) -> list:
    """The knobs of ``tracker`` as the HTML book offers them: each knob's default, the
    printed value where there is one (:func:`paper_sample`)
    and about two others (:func:`static_samples`), or the
    values given in ``samples=``."""
    cls = D.params_class(tracker)
    out = []
    for k in pg.config["knobs"][tracker]:
        if k["name"] in pg.samples:
            out.append({**k, "samples": list(k["samples"])})
            continue
        paper = paper_sample(cls, k["name"])
        try:
            if paper is not None:
                D.parse_values(tracker, {k["name"]: paper})
        except (ValueError, TypeError):
            paper = None
        out.append({**k, "samples": static_samples(k, paper), "paper": paper})
    return out


def static_runs(pg, workers: int | None = None, **kwargs) -> dict:
    """``{run key: file name}`` of every run the HTML book offers (see
    :func:`playground_export.static.book_files`): every clip x tracker at its defaults
    and each knob at each of its :func:`static_knobs` samples, over the seeds."""
    refuse_unknown_keywords("static_runs", kwargs)
    known = {}
    t0 = pg.config["trackers"][0]
    for key, r in pg.reused.items():    # runs the chapter made (Playground.reuse)
        clip, n = pg.clip_objects[key], pg.n_of(pg.clip_objects[key])
        p = D.result_payload(r, clip, pg.defaults(t0), [], n, t0)
        known[S.Runner.known_key(t0, key, pg.defaults(t0), n, pg.seed)] = {
            "seed": pg.seed, "boxes": p["boxes"], "iou": p["iou"],
            "auc": float(r.scores.get("auc", float("nan"))), "payload": p}
    if pg.result is not None and len(pg.result.boxes) == pg.n_of(pg.clip_objects[pg.clip]):
        t, c = pg.tracker, pg.clip      # the run the Jupyter half has just made
        p = D.result_payload(pg.result, pg.clip_objects[c], dict(pg.values), pg.states,
                             pg.n_of(pg.clip_objects[c]), t)
        known.setdefault(S.Runner.known_key(t, c, pg.values, pg.n_of(pg.clip_objects[c]),
                                            pg.seed),
                         {"seed": pg.seed, "boxes": p["boxes"], "iou": p["iou"],
                          "auc": float(pg.result.scores.get("auc", float("nan"))),
                          "payload": p})
    trackers = pg.config["trackers"]
    return S.book_files(pg.clip_objects, trackers, {t: static_knobs(pg, t) for t in trackers},
                       {t: pg.defaults(t) for t in trackers},
                       {c: pg.n_of(clip) for c, clip in pg.clip_objects.items()},
                       {c: pg.first_box(clip) for c, clip in pg.clip_objects.items()},
                       pg.seed, known, S.WORKERS if workers is None else workers)


def static_payload(pg, workers: int | None = None, **kwargs) -> dict:
    """What the page holds: the configuration, each clip's ground truth and the names of
    its frame files, the name of every run file; the files themselves are written to
    :func:`playground_export.static.store`."""
    refuse_unknown_keywords("static_payload", kwargs)
    runs = static_runs(pg, workers)
    clips = {}
    for c, clip in pg.clip_objects.items():
        n = pg.n_of(clip)
        info = {k: v for k, v in D.clip_payload(clip, 0).items() if k != "frames"}
        gt = np.asarray(clip.groundtruth[:n], dtype=float)
        info.update(n=n, per=S.CHUNK_FRAMES, chunks=S.write_frames(clip, n),
                    gt=[[round(float(v), 1) for v in b] if np.isfinite(b).all() else None
                        for b in gt] if np.isfinite(gt).all(axis=1).any() else None)
        clips[c] = info
    config = {**pg.config, "knobs": {t: static_knobs(pg, t)
                                       for t in pg.config["trackers"]}}
    return {"kind": "playground", "config": config, "clips": clips, "files": runs,
            "initial": {"clip": list(pg.clip_objects)[0], "tracker": pg.config["trackers"][0]}}


def static_html(pg, workers: int | None = None, files: bool = False, **kwargs) -> str:
    """The panel as an HTML fragment: root ``div.tb-playground``, the configuration in a
    ``<script type="application/json">``, the viewer module inline and a PNG of the first
    run in ``<noscript>`` for print and no-JavaScript; the runs and frames are files
    beside the page, loaded when the reader picks them."""
    refuse_unknown_keywords("static_html", kwargs)
    return page_html(static_payload(pg, workers), static_png(pg),
                     "the playground's first run: frames and IoU", files=files)


def static_png(pg) -> bytes:
    import matplotlib.pyplot as plt

    fig = static_figure(pg)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=60)
    plt.close(fig)
    return buf.getvalue()


def static_figure(pg, frames=None):
    """A static picture of the current run (three frames and the IoU curve): the
    fallback for print and browsers without JavaScript."""
    import matplotlib.pyplot as plt

    from trackbook.evaluation import metrics
    from trackbook.viz.core import EST_COLOR, draw_box, draw_particles, show_frame

    clip = pg.clip_objects[pg.clip]
    r = pg.result
    if r is None:
        fig, ax = plt.subplots(figsize=(3, 2.4))
        show_frame(clip.frames[0], ax=ax, title="drag the target's box (Jupyter)")
        return fig
    n = len(r.boxes)
    frames = frames or [n // 4, n // 2, n - 1]
    fig, axes = plt.subplots(1, len(frames) + 1, figsize=(3.0 * (len(frames) + 1), 2.6))
    for ax, i in zip(axes, frames):
        show_frame(clip.frames[i], ax=ax, gt=clip.groundtruth[i], title=f"frame {i}")
        st = pg.states[i] if i < len(pg.states) else {}
        if "particles" in st:
            draw_particles(ax, st["particles"], st.get("weights"), max_size=20)
        draw_box(ax, r.boxes[i], EST_COLOR, "estimate")
    gt = clip.groundtruth[:n]
    if np.isfinite(gt[1:]).all(axis=1).any():
        axes[-1].plot(metrics.iou(r.boxes, gt), color=EST_COLOR, lw=1)
        axes[-1].set(xlabel="frame", ylabel="IoU", ylim=(0, 1.02))
    else:
        axes[-1].plot(np.asarray(r.ok, float), color=EST_COLOR, lw=1)
        axes[-1].set(xlabel="frame", ylabel="tracker ok", ylim=(-0.02, 1.02))
    axes[-1].grid(alpha=0.3)
    fig.suptitle(html.unescape(D.scores_text(r)), fontsize=9)
    fig.tight_layout()
    return fig


def animation_html(anim, files: bool = False) -> str:
    """An :class:`~trackbook.playground.animation.Animation` as a page fragment (``files``:
    its runs and frames as files beside the page, as the book's pages have them), with the
    animation's still picture for print and pages without JavaScript."""
    return page_html(anim.static_data, anim.still_png(), "one step of the animation", files)
