"""The playground: pick a clip, a tracker and its knobs; scrub, play, compare.

One JavaScript module (``viewer.js``, shipped in this package) draws everything on a canvas:
the frame, ground truth, estimate, the tracker's state, the IoU-per-frame curve, the tracker's
confidence per frame (``TrackerState.confidence``, frames judged lost shaded), a correlation
filter's response map as an inset (``TrackerState.response``, its area dotted on the frame) and
the scores.

In Jupyter the panel is an `anywidget <https://anywidget.dev>`_ widget: a knob change re-runs
the tracker in the kernel and sends only boxes and state, first up to the frame on screen, then
the rest of the clip in chunks that leave the kernel free (``live.py``); the frames travel
once as JPEG, so a frame step costs no Python. The HTML book shows the same panel as a page
with every run precomputed; the book's build makes that page from the panel
(``book/_ext/playground_export``), so this class holds no page code.
"""

from __future__ import annotations

import difflib
import os

import anywidget
import numpy as np
import traitlets as T

from .. import clips as _clips
from .. import trackers as _trackers
from ..style import VIEWER as VIEWER_COLORS
from . import data as D
from .data import VIEWER_CSS, VIEWER_JS
from .live import LiveRun, running_loop, stream

def _load_own(c):
    """A clip by name or path; an image folder without ground truth (your own frames) loads
    too, with no boxes: the student drags the target on its first frame."""
    try:
        return _clips.load(c)
    except FileNotFoundError as e:
        from pathlib import Path as _P

        from ..clips.clip import Clip, ImageFiles
        from ..clips.loaders import IMAGE_SUFFIXES

        folder = _P(str(c))
        d = folder / "img" if (folder / "img").is_dir() else folder
        paths = sorted(p for p in d.iterdir() if p.suffix.lower() in IMAGE_SUFFIXES) \
            if d.is_dir() else []
        if "ground truth" not in str(e) or not paths:
            raise
        return Clip(folder.name, ImageFiles(paths), np.full((len(paths), 4), np.nan),
                    source=str(folder))


class Refused(T.TraitError, ValueError):
    """A knob, tracker or clip the playground refuses: a ``ValueError`` (what the library
    raises for bad input) that is also a ``TraitError``, so traitlets rolls the trait back."""


def _refuse(what: str, value, choices) -> ValueError:
    """The ValueError for a name that is not among ``choices``, with the nearest one."""
    near = difflib.get_close_matches(str(value), [str(c) for c in choices], n=1)
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    return Refused(f"{what} {value!r} is not one of this playground's {what}s{hint}; "
                      f"choose from {list(choices)}.")


class Playground(anywidget.AnyWidget):
    """A clip x tracker x params panel drawn in the browser.

    Parameters
    ----------
    clips : list of clip names or paths (anything :func:`trackbook.clips.load` takes); a video
        or image folder without ground truth works too: drag the target's box on the first
        frame (or pass ``box=``).
    trackers : list of tracker names (registered or ``"opencv-mil"``)
    params : names of the params to expose as knobs first (any param of the chosen tracker
        can also be set later with :meth:`set`); a name no tracker has is refused
    n_frames : track only the first frames (faster in class)
    seed : the trackers' seed
    values : initial values of params
    samples : ``{knob: [values]}``, the values the HTML book precomputes (default: a few around
        the default within the field's range, see :func:`trackbook.playground.data.sample_values`)
    box : (x, y, w, h) on the first frame, for a clip without ground truth

    Examples
    --------
    >>> pg = Playground(clips=["red-cube"], trackers=["color-pf"], params=["n_particles"],
    ...                 n_frames=30)                                        # doctest: +SKIP
    >>> pg.set(n_particles=300).scores["auc"]                               # doctest: +SKIP
    """

    _esm = T.Unicode(VIEWER_JS.read_text(encoding="utf-8")).tag(sync=True)
    _css = T.Unicode(VIEWER_CSS.read_text(encoding="utf-8")).tag(sync=True)
    config = T.Dict().tag(sync=True)
    clip_data = T.Dict().tag(sync=True)
    run_data = T.Dict().tag(sync=True)
    clip = T.Unicode().tag(sync=True)
    tracker = T.Unicode().tag(sync=True)
    values = T.Dict().tag(sync=True)
    init_box = T.List().tag(sync=True)
    busy = T.Bool(False).tag(sync=True)
    error = T.Unicode("").tag(sync=True)
    #: the frame on screen, which the viewer sends with a knob change: a re-run reaches it
    #: first and streams the rest
    frame = T.Int(0).tag(sync=True)

    def __init__(self, clips, trackers, params=(), n_frames=None, seed=0, values=None,
                 samples=None, box=None, **kwargs):
        clips = [clips] if isinstance(clips, (str, os.PathLike)) else list(clips)
        trackers = [trackers] if isinstance(trackers, str) else list(trackers)
        if not clips or not trackers:
            raise ValueError("Playground needs at least one clip and one tracker, e.g. "
                             "Playground(clips=['red-cube'], trackers=['color-pf']).")
        for t in trackers:
            _trackers.get(t)  # fail early, with the list of names
        params = [params] if isinstance(params, str) else list(params)
        known = sorted({n for t in trackers for n in D.field_names(t)})
        for name in params:     # a typo is refused, not silently dropped
            if name not in known:
                raise _refuse("param", name, known)
        self.param_names = list(params)
        self._trackers_list = list(trackers)
        if values is not None and not isinstance(values, dict):
            raise TypeError(f"values must be a dict {{knob: value}}, got "
                            f"{type(values).__name__}.")
        for name in (values or {}):
            if name not in known:
                raise _refuse("param", name, known)
        for t in trackers:     # each given value through the parser, for the trackers having it
            fields = D.field_names(t)
            D.parse_values(t, {k: v for k, v in (values or {}).items() if k in fields})
        self.n_frames = n_frames
        self.seed = seed
        self._initial = dict(values or {})
        self.samples = dict(samples or {})
        self.clip_objects = {}
        for c in clips:
            self.clip_objects[str(c)] = _load_own(c)
        for name in (values or {}):     # a knob given a value is a knob
            if name not in self.param_names:
                self.param_names.append(name)
        self.result = None
        self.states: list[dict] = []
        self.runs = 0
        self._gen = 0               # the newest run; a streaming run older than it stops
        self._task = None
        self._sync = False
        super().__init__(**kwargs)
        self.config = self._config(list(self.clip_objects), trackers)
        with self.hold_sync():
            self.tracker = trackers[0]
            self.clip = list(self.clip_objects)[0]
            self.values = self.defaults(self.tracker)
            if box is not None:
                self.init_box = [float(v) for v in box]
        self._send_clip()
        self.observe(self._on_clip, names="clip")
        self.observe(self._on_tracker, names="tracker")
        self.observe(self._on_change, names=["values", "init_box"])
        self._run(sync=True)

    # -- refusals: a bad name or value never replaces what the view shows ---------------
    @T.validate("tracker")
    def _valid_tracker(self, proposal):
        t = proposal["value"]
        if t not in self._trackers_list:
            raise _refuse("tracker", t, self._trackers_list)
        return t

    @T.validate("clip")
    def _valid_clip(self, proposal):
        c = proposal["value"]
        if c not in self.clip_objects:
            raise _refuse("clip", c, list(self.clip_objects))
        return c

    @T.validate("values")
    def _valid_values(self, proposal):
        try:
            return D.parse_values(self.tracker, dict(proposal["value"]))
        except (ValueError, TypeError) as e:
            raise Refused(str(e)) from None

    def set_state(self, sync_data):
        """The front-end's path: a refused value leaves the run and the knobs as they were
        (the viewer gets them back) and says why in ``error``."""
        try:
            return super().set_state(sync_data)
        except (ValueError, TypeError, T.TraitError) as e:
            self.error = str(e)
            self.send_state([k for k in ("values", "tracker", "clip") if k in sync_data])
            return None

    # -- configuration -------------------------------------------------------------------
    def _knobs(self, tracker):
        cls = D.params_class(tracker)
        out = []
        for name in self.param_names:
            spec = D.knob_spec(cls, name, self._initial.get(name)) if cls else None
            if spec is not None:
                spec["samples"] = [list(v) if isinstance(v, tuple) else v
                                   for v in self.samples.get(name, D.sample_values(spec))]
                if spec["default"] not in spec["samples"]:   # the default is always a stop
                    spec["samples"].append(spec["default"])
                out.append(spec)
        return out

    def _config(self, clip_names, trackers):
        return {"clips": [{"key": k, "name": self.clip_objects[k].name} for k in clip_names],
                "trackers": trackers,
                "knobs": {t: self._knobs(t) for t in trackers},
                "n_frames": self.n_frames, "colors": VIEWER_COLORS}

    def defaults(self, tracker) -> dict:
        """``{knob: default value}`` of ``tracker``'s knobs on this panel."""
        return {k["name"]: k["default"] for k in self.config["knobs"][tracker]}

    def n_of(self, clip, cap=None) -> int:
        """Frames tracked on ``clip`` (``n_frames`` or the whole clip, at most ``cap``)."""
        n = len(clip) if self.n_frames is None else min(int(self.n_frames), len(clip))
        return n if cap is None else min(n, cap)

    def _send_clip(self):
        clip = self.clip_objects[self.clip]
        self.clip_data = D.clip_payload(clip, self.n_of(clip))

    # -- events (the slider path: JS sets a trait, Python re-runs) -----------------------
    def _on_clip(self, change):
        self._send_clip()
        self.init_box = []
        self._run()

    def _on_tracker(self, change):
        self.values = self.defaults(change["new"])   # triggers _on_change -> _run

    def _on_change(self, change):
        if change["name"] == "values":
            self._adopt(change["new"])
        self._run(sync=self._sync)

    def _adopt(self, names):
        """Knobs set without being declared in ``params=`` join the panel's knobs."""
        extra = [k for k in names if k not in self.param_names]
        if extra:
            self.param_names.extend(extra)
            self.config = self._config(list(self.clip_objects), self._trackers_list)

    def set(self, **knobs):
        """Re-run with these knob values (others unchanged) and return the new result,
        by the path a slider takes (the ``values`` trait).

        Any param of the current tracker is a knob, declared in ``params=`` or not (an
        undeclared one joins the panel's knobs). Every value goes through
        :func:`trackbook.params.parse`: a wrong name or value raises ``ValueError`` naming the
        knob, and the playground keeps its values and the run it shows. The run is whole when
        ``set`` returns, in Jupyter too (a knob moved in the viewer streams instead).
        """
        new = D.parse_values(self.tracker, {**self.values, **knobs})
        self._adopt(knobs)      # now a knob of the panel too
        old, old_error = dict(self.values), self.error
        self.error = ""
        self._sync = True       # the caller waits for the result: the whole run, now
        try:
            if new == dict(self.values):
                if self._task is not None:      # a streaming run of these values: finish it
                    self._run(sync=True)
            else:
                self.values = new
        finally:
            self._sync = False
        if self.error:          # the tracker refused this combination while running
            error = self.error
            self.unobserve(self._on_change, names=["values", "init_box"])
            try:
                self.values = old
            finally:
                self.observe(self._on_change, names=["values", "init_box"])
            self.error = old_error
            raise ValueError(error)
        return self.result

    def params(self) -> dict:
        """The knob values of the current run, as the tracker takes them."""
        return {k: tuple(v) if isinstance(v, list) else v for k, v in self.values.items()}

    # -- work ----------------------------------------------------------------------------
    def first_box(self, clip):
        """The box a run on ``clip`` starts from: the dragged one, None for the first
        ground-truth box, or False when there is neither (wait for the student's box)."""
        if self.init_box:
            return self.init_box
        g = np.asarray(clip.groundtruth[0], dtype=float)
        return None if np.isfinite(g).all() else False

    def _run(self, sync=False):
        """Re-run the tracker with the current clip, values and first box.

        ``sync`` (or no running event loop, as in a script): the whole run now, returning the
        result. Otherwise (the kernel's loop, a knob moved in the viewer) the run streams: the
        frames up to the one on screen first, then the rest in chunks that leave the kernel
        free, each sent as a partial ``run_data`` (``n_done < n_total``), the complete payload
        last; a newer change stops an older run."""
        self._gen += 1
        gen = self._gen
        if self._task is not None:
            self._task.cancel()
            self._task = None
        clip = self.clip_objects[self.clip]
        box = self.first_box(clip)
        if box is False:      # your own video: wait for the box the student drags
            self.busy = False
            self.run_data = {"clip": clip.name, "tracker": self.tracker, "waiting": True}
            self.result = None
            return None
        try:
            run = LiveRun(self.tracker, clip, self.params(), self.n_of(clip), self.seed, box)
        except ValueError as e:
            return self._refused(e)
        loop = None if sync else running_loop()
        if loop is None:
            try:
                run.advance()
            except ValueError as e:
                run.close()
                return self._refused(e)
            return self._finish(run, run.payload())
        self.busy = True

        def send(payload):
            if payload["n_done"] < payload["n_total"]:
                self.run_data = payload
            else:
                self._task = None
                self._finish(run, payload)

        self._task = loop.create_task(stream(run, send, self.frame, lambda: gen == self._gen,
                                             self._refused))
        return self.result

    def _refused(self, e):
        """A knob combination the tracker refuses: say why, keep the last complete run."""
        self.error, self.busy, self._task = str(e), False, None
        return self.result

    def _finish(self, run, payload):
        self.error = ""
        self.result, self.states = run.result(), run.states
        self.runs += 1
        self.busy = False
        self.run_data = payload
        return self.result

    @property
    def scores(self) -> dict:
        return {} if self.result is None else self.result.scores

    def show(self):
        """Display the panel (the live widget in Jupyter, the precomputed page in the book)."""
        from IPython.display import display
        display(self)

    # -- what the HTML book's exporter reads ---------------------------------------------
    def reuse(self, runs: dict) -> "Playground":
        """Take runs the chapter already made (``{clip: Result}`` of
        :func:`trackbook.evaluate` at this playground's seed, first tracker, defaults and whole
        clip) instead of running them again for the HTML book; their boxes and scores are
        shown, not the tracker's state. Returns the playground (``pg.reuse(runs).show()``)."""
        t = self.config["trackers"][0]
        for key, r in runs.items():
            clip = self.clip_objects.get(str(key))
            if clip is None or r.tracker != t or len(r.boxes) != self.n_of(clip):
                raise ValueError(f"reuse: {key!r} is not a whole-clip run of {t} on one of "
                                 f"this playground's clips ({list(self.clip_objects)}).")
            self.reused[str(key)] = r
        return self

    @property
    def reused(self) -> dict:
        """``{clip key: Result}`` given to :meth:`reuse` (runs of the first tracker at its
        defaults over the whole clip)."""
        if "_reused_runs" not in self.__dict__:
            self.__dict__["_reused_runs"] = {}
        return self.__dict__["_reused_runs"]
