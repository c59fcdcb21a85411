"""The tracker playground: pick a clip, a tracker and its knobs, scrub through the frames.

Every chapter reuses :class:`Playground` with its own knobs::

    from trackbook.widgets import Playground
    pg = Playground(clips=["red-cube"], trackers=["kalman-covariance", "covariance"],
                    params=["q_scale", "stride"])
    pg.show()     # a static figure (for the HTML book) and the live panel (in Jupyter)

Sliders are built from the tracker's ``Params`` metadata (range, step, doc), all with
``continuous_update=False`` so a tracker re-runs once per release, not on every pixel of a drag.
"""

from __future__ import annotations

import dataclasses
import html
import io

import ipywidgets as W
import matplotlib.pyplot as plt
import numpy as np
from IPython.display import display

from . import clips as _clips
from . import trackers as _trackers
from .evaluation import metrics
from .evaluation.runner import evaluate
from .viz.core import (EST_COLOR, GT_COLOR, draw_box, draw_ellipse, draw_particles,
                       draw_search_window, show_frame)


def _snapshot(tracker) -> dict:
    """What to draw for one frame, copied (trackers reuse their arrays)."""
    snap = {}
    p = getattr(tracker, "particles", None)
    if p is not None:
        snap["particles"] = np.array(p)[:, :2]
        w = getattr(tracker, "weights", None)
        snap["weights"] = None if w is None else np.array(w)
    for key in ("search_window", "ellipse"):
        v = getattr(tracker, key, None)
        if v is not None:
            snap[key] = tuple(np.asarray(v, dtype=float).ravel())
    return snap


def slider_for(field: dataclasses.Field, value=None) -> W.Widget:
    """An ipywidget for one params field, from its metadata; ``continuous_update=False``."""
    m = field.metadata
    value = field.default if value is None else value
    desc = field.name
    style = {"description_width": "initial"}
    layout = W.Layout(width="320px")
    common = dict(description=desc, style=style, layout=layout, continuous_update=False)
    if m.get("choices"):
        return W.Dropdown(options=list(m["choices"]), value=value, description=desc, style=style,
                          layout=layout)
    if isinstance(value, bool):
        return W.Checkbox(value=value, description=desc, style=style)
    lo, hi, step = m.get("lo"), m.get("hi"), m.get("step")
    if isinstance(value, tuple) and len(value) == 2:
        lo = lo if lo is not None else 0.0
        hi = hi if hi is not None else 2 * max(value)
        return W.FloatRangeSlider(value=value, min=lo, max=hi, step=step or (hi - lo) / 100,
                                  **common)
    if isinstance(value, int):
        lo = int(lo if lo is not None else 0)
        hi = int(hi if hi is not None else max(2 * value, 1))
        return W.IntSlider(value=value, min=lo, max=hi, step=int(step or 1), **common)
    if isinstance(value, float):
        lo = float(lo if lo is not None else 0.0)
        hi = float(hi if hi is not None else max(2 * value, 1.0))
        return W.FloatSlider(value=value, min=lo, max=hi, step=step or (hi - lo) / 100,
                             readout_format=".3g", **common)
    return W.Text(value=str(value), description=desc, style=style, continuous_update=False)


class Playground:
    """A clip x tracker x params panel with a frame slider and the clip's scores.

    Parameters
    ----------
    clips : list of clip names or paths (anything :func:`trackbook.clips.load` takes)
    trackers : list of tracker names (registered or ``"opencv-mil"``)
    params : names of the params to expose as sliders (those the chosen tracker has)
    n_frames : track only the first frames (faster in class)
    seed : the trackers' seed
    values : initial values of params

    Attributes
    ----------
    result : the last :class:`trackbook.Result`
    states : per-frame snapshots of what the tracker exposes (particles, windows, ellipses)
    frame : the frame shown
    widget : the ipywidgets panel
    """

    def __init__(self, clips, trackers, params=(), n_frames=None, seed=0, values=None,
                 samples=None):
        clips = [clips] if isinstance(clips, str) else list(clips)
        trackers = [trackers] if isinstance(trackers, str) else list(trackers)
        if not clips or not trackers:
            raise ValueError("Playground needs at least one clip and one tracker.")
        for t in trackers:
            _trackers.get(t)  # fail early, with the list of names
        self.param_names = list(params)
        self.samples = dict(samples or {})
        self.clip_names = [str(c) for c in clips]
        self.tracker_names = list(trackers)
        self.n_frames = n_frames
        self.seed = seed
        self._values = dict(values or {})
        self.clip_w = W.Dropdown(options=[str(c) for c in clips], description="clip")
        self.tracker_w = W.Dropdown(options=trackers, description="tracker")
        self.frame_w = W.IntSlider(value=0, min=0, max=1, description="frame",
                                   continuous_update=False, layout=W.Layout(width="480px"))
        self.params_box = W.VBox()
        self.scores_w = W.HTML()
        self.image_w = W.Image(format="png", layout=W.Layout(width="900px"))
        self.param_ws: dict[str, W.Widget] = {}
        self.result = None
        self.states: list[dict] = []
        self.frame = 0
        self.renders = 0
        self._build_params()
        self.clip_w.observe(self._on_run, names="value")
        self.tracker_w.observe(self._on_tracker, names="value")
        self.frame_w.observe(self._on_frame, names="value")
        self.run()

    # -- widgets -------------------------------------------------------------------------
    def _build_params(self):
        cls = _trackers.get(self.tracker_w.value)
        fields = {f.name: f for f in dataclasses.fields(cls.Params)}
        self.param_ws = {}
        for name in self.param_names:
            if name in fields:
                w = slider_for(fields[name], self._values.get(name))
                w.observe(self._on_run, names="value")
                self.param_ws[name] = w
        self.params_box.children = list(self.param_ws.values())

    @property
    def widget(self) -> W.Widget:
        top = W.HBox([self.clip_w, self.tracker_w])
        return W.VBox([top, self.params_box, self.frame_w, self.scores_w, self.image_w])

    def _ipython_display_(self):
        self.show()

    def params(self) -> dict:
        """The param values currently set on the sliders."""
        vals = {}
        for k, w in self.param_ws.items():
            v = w.value
            vals[k] = tuple(v) if isinstance(v, (list, tuple)) else v
        return vals

    # -- events --------------------------------------------------------------------------
    def _on_tracker(self, change):
        self._build_params()
        self.run()

    def _on_run(self, change):
        self.run()

    def _on_frame(self, change):
        self.frame = int(change["new"])
        self.render()

    # -- work ----------------------------------------------------------------------------
    def run(self):
        """Track the chosen clip with the chosen tracker and params; then redraw."""
        clip = _clips.load(self.clip_w.value)
        self.states = []

        def record(i, tracker, frame, box):
            self.states.append(_snapshot(tracker))

        self.result = evaluate(self.tracker_w.value, clip, seed=self.seed,
                               max_frames=self.n_frames, on_frame=record, **self.params())
        self.clip = clip
        n = len(self.result.boxes)
        self.frame = min(self.frame, n - 1)
        with self.frame_w.hold_trait_notifications():
            self.frame_w.max = n - 1
            self.frame_w.value = self.frame
        s = self.result.scores
        if "auc" in s:
            text = (f"AUC {s['auc']:.3f} · precision@20px {s['precision20']:.3f} · "
                    f"tracking rate {s['tracking_rate']:.1%} · {s['ms_median']:.2f} ms/frame")
        else:
            text = f"no ground truth · {s['ms_median']:.2f} ms/frame"
        self.scores_w.value = f"<b>{html.escape(self.tracker_w.value)}</b> on " \
                              f"{html.escape(clip.name)}: {text}"
        self.render()
        return self.result

    def figure(self, i=None):
        """The frame ``i`` with ground truth, estimate and tracker state, and IoU over time."""
        i = self.frame if i is None else i
        r = self.result
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(9.0, 3.2),
                                      gridspec_kw={"width_ratios": [1.25, 1]})
        show_frame(self.clip.frames[i], ax=ax, gt=self.clip.groundtruth[i],
                   title=f"{r.tracker} · {r.clip} · frame {i}")
        st = self.states[i] if i < len(self.states) else {}
        if "particles" in st:
            draw_particles(ax, st["particles"], st.get("weights"))
        if "search_window" in st:
            draw_search_window(ax, st["search_window"])
        if "ellipse" in st:
            draw_ellipse(ax, *st["ellipse"])
        draw_box(ax, r.boxes[i], EST_COLOR, "estimate")
        ax.legend(fontsize=7, loc="lower right")
        gt = self.clip.groundtruth[: len(r.boxes)]
        ov = metrics.iou(r.boxes, gt)
        ax2.plot(ov, color=EST_COLOR, lw=1)
        ax2.axvline(i, color="k", lw=0.8, ls=":")
        ax2.axhline(0.5, color=GT_COLOR, lw=0.8, ls="--")
        ax2.set(xlabel="frame", ylabel="IoU with ground truth", ylim=(0, 1.02),
                title="overlap per frame")
        ax2.grid(alpha=0.3)
        fig.tight_layout()
        return fig

    def render(self):
        """Redraw the current frame into the image widget (PNG bytes, so it also works
        without a live kernel, e.g. in tests)."""
        fig = self.figure()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=80)
        plt.close(fig)
        self.image_w.value = buf.getvalue()
        self.renders += 1

    def static_figure(self, frames=None):
        """A static picture of the run (three frames and the IoU curve) for the HTML book."""
        n = len(self.result.boxes)
        frames = frames or [n // 4, n // 2, n - 1]
        fig, axes = plt.subplots(1, len(frames) + 1, figsize=(3.0 * (len(frames) + 1), 2.6))
        for ax, i in zip(axes, frames):
            show_frame(self.clip.frames[i], ax=ax, gt=self.clip.groundtruth[i],
                       title=f"frame {i}")
            st = self.states[i] if i < len(self.states) else {}
            if "particles" in st:
                draw_particles(ax, st["particles"], st.get("weights"), max_size=20)
            if "search_window" in st:
                draw_search_window(ax, st["search_window"])
            draw_box(ax, self.result.boxes[i], EST_COLOR, "estimate")
        gt = self.clip.groundtruth[:n]
        axes[-1].plot(metrics.iou(self.result.boxes, gt), color=EST_COLOR, lw=1)
        axes[-1].set(xlabel="frame", ylabel="IoU", ylim=(0, 1.02))
        axes[-1].grid(alpha=0.3)
        fig.suptitle(self.scores_w.value.replace("<b>", "").replace("</b>", ""), fontsize=9)
        fig.tight_layout()
        return fig

    def set(self, **knobs):
        """Set knobs (as a slider would) and re-run; returns the new :class:`trackbook.Result`."""
        fields = {f.name: f for f in dataclasses.fields(_trackers.get(self.tracker_w.value).Params)}
        unknown = sorted(set(knobs) - set(self.param_ws) - set(fields))
        if unknown:
            raise ValueError(f"unknown knob(s) {unknown}; this playground has "
                             f"{sorted(self.param_ws)}.")
        for k, v in knobs.items():
            if k in self.param_ws:
                with self.param_ws[k].hold_trait_notifications():
                    self.param_ws[k].value = v
            self._values[k] = v
        extra = {k: v for k, v in knobs.items() if k not in self.param_ws}
        return self._run_with(extra)

    def _run_with(self, extra):
        saved = self.params
        self.params = lambda: {**saved(), **extra}
        try:
            return self.run()
        finally:
            self.params = saved

    # -- the browser viewer (HTML book and Jupyter alike) ----------------------------------
    def knob_values(self, name: str, field: dataclasses.Field) -> list:
        """The values the HTML precomputes for one knob (one knob at a time, around the default)."""
        if name in self.samples:
            vals = list(self.samples[name])
        else:
            m, d = field.metadata, field.default
            lo, hi = m.get("lo"), m.get("hi")
            if m.get("choices"):
                vals = list(m["choices"])
            elif isinstance(d, bool):
                vals = [False, True]
            elif name == "n_particles":
                vals = [v for v in (10, 30, 100, 300, 1000)
                        if (lo is None or v >= lo) and (hi is None or v <= hi)]
            elif name == "alpha":
                vals = [0.0, 0.1, 0.3, 0.5, 0.9, 1.0]
            elif isinstance(d, (int, float)) and lo is not None and hi is not None:
                grid = np.linspace(lo, hi, 5)
                if isinstance(d, int):
                    vals = sorted({int(round(v)) for v in grid})
                else:
                    vals = [float(f"{v:.3g}") for v in grid]
            else:
                vals = []
        vals = [v for v in vals if v != field.default]
        return [field.default] + vals[:5]

    def html(self) -> str:
        """The playground as the browser viewer: runs precomputed, frames encoded once."""
        from . import playground as _pg

        n_default = self.n_frames
        main = self.tracker_names[0]
        fields = {f.name: f for f in dataclasses.fields(_trackers.get(main).Params)}
        knobs = {}
        for name in self.param_names:
            if name in fields:
                vals = self.knob_values(name, fields[name])
                if len(vals) > 1:
                    knobs[name] = {"values": [str(v) for v in vals],
                                   "default": str(self._values.get(name, fields[name].default)),
                                   "typed": vals}
        clip_data, runs = {}, {}
        base = {k: v for k, v in self._values.items() if k in fields}
        for cname in self.clip_names:
            clip = _clips.load(cname)
            n = len(clip) if n_default is None else min(n_default, len(clip))
            clip_data[cname] = _pg.clip_entry(clip, n)
            for t in self.tracker_names:
                tf = {f.name for f in dataclasses.fields(_trackers.get(t).Params)}
                r, st = self._record(t, clip, n, {k: v for k, v in base.items() if k in tf})
                runs[f"{t}|{cname}|"] = _pg.run_record(r, st, clip.groundtruth, 40)
            for name, spec in knobs.items():
                for label, v in zip(spec["values"][1:], spec["typed"][1:]):
                    r, st = self._record(main, clip, n, {**base, name: v})
                    rec = _pg.run_record(r, st, clip.groundtruth, 0)
                    rec.pop("particles", None)
                    runs[f"{main}|{cname}|{name}={label}"] = rec
        for spec in knobs.values():
            spec.pop("typed")
        fig = self.static_figure()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=70)
        plt.close(fig)
        note = (f"This page holds precomputed runs: each knob at a few values, one knob at a time, "
                f"for {main}; run the chapter in Jupyter to try any value "
                f"(Playground.set(...) or the sliders below the viewer).")
        return _pg.page_html(clip_data, runs, self.tracker_names, knobs, buf.getvalue(), note)

    def _record(self, tracker, clip, n, params):
        states = []
        r = evaluate(tracker, clip, seed=self.seed, max_frames=n,
                     on_frame=lambda i, t, f, b: states.append(_snapshot(t)), **params)
        return r, states

    def _repr_html_(self):
        return self.html()

    def show(self):
        """Display the browser viewer (live in the HTML book, from disk too) and, in Jupyter,
        the slider panel that re-runs the tracker for any value."""
        from IPython.display import HTML

        display(HTML(self.html()))
        display(self.widget)
