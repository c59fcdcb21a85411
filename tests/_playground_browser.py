"""Drive every ``.tb-playground`` of a page in Chromium as a reader would (shared by the
browser test and the JupyterLab test)."""

from __future__ import annotations

import re
import shutil
from urllib.parse import urlparse

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeout
except ImportError:         # the tests that drive a page skip without Playwright
    PlaywrightTimeout = TimeoutError

CHROMIUM = next((shutil.which(c) for c in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(c)), None)

#: the canvas as a short fingerprint (sum of sampled pixels), to see that the picture changed
CANVAS_SIG = """(root) => {
  const c = root.querySelector('canvas');
  const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  let s = 0; for (let i = 0; i < d.length; i += 97) s = (s * 31 + d[i]) % 1000000007;
  return s;
}"""


def local_only(page, blocked: list):
    """Fail any request that would leave the machine (only file: and 127.0.0.1 pass)."""
    def route(r):
        u = urlparse(r.request.url)
        if u.scheme in ("file", "data", "blob") or u.hostname in ("127.0.0.1", "localhost"):
            r.continue_()
        else:
            blocked.append(r.request.url)
            r.abort()
    page.route("**/*", route)


def watch_errors(page, errors: list):
    page.on("pageerror", lambda e: errors.append(f"pageerror: {e}"))
    page.on("console", lambda m: errors.append(f"console: {m.text}") if m.type == "error"
            else None)


#: no playground file still loading (the HTML book loads runs and frames on demand)
SETTLED = """() => { const r = window.__tbPlaygroundFiles;
  return !r || Object.keys(r.wait).length === 0; }"""


def settle(page, timeout=20_000):
    """Wait until every run or frame file the page asked for has arrived (or failed)."""
    page.wait_for_function(SETTLED, timeout=timeout)
    page.wait_for_timeout(30)


def set_input(handle, value):
    """Set an input/select's value and fire input + change, as a user's drag does."""
    handle.evaluate("""(e, v) => { if (e.type === 'checkbox') e.checked = !e.checked;
        else e.value = v; e.dispatchEvent(new Event('input', {bubbles: true}));
        e.dispatchEvent(new Event('change', {bubbles: true})); }""", str(value))


def other_value(handle):
    """A value of the knob input other than its current one."""
    return handle.evaluate("""(e) => {
      if (e.tagName === 'SELECT') { const o = [...e.options].map(x => x.value);
        return o[(o.indexOf(e.value) + 1) % o.length]; }
      if (e.type === 'range') { const lo = +e.min, hi = +e.max, v = +e.value;
        return String(v === lo ? hi : lo); }
      if (e.type === 'checkbox') return 'toggle';
      if (e.type === 'text') { const p = e.value.split(',').map(Number);
        return p.map((x, i) => i === 0 ? x * 0.9 : x * 1.1).join(', '); }
      return e.value; }""")


def exercise(page, root, wait_run=None, timeout=60_000):
    """Move each enabled knob, the frame slider and press play on one playground; return a
    list of failures (empty when everything answered)."""
    fails = []
    root.scroll_into_view_if_needed()
    page.wait_for_function("(r) => { const c = r.querySelector('canvas'); return c && c.width > 0 }",
                           arg=root, timeout=timeout)
    page.wait_for_timeout(300)       # the JPEGs decode
    scores = root.query_selector(".tb-scores")
    static = root.get_attribute("data-tb-static") is not None
    if static:
        settle(page)
    all_knobs = root.query_selector_all("[data-knob]")
    knobs = [k for k in all_knobs if k.is_enabled()]
    if all_knobs and not knobs:
        fails.append("no enabled knob")
    if static:
        # the HTML book holds runs for a few values of EVERY knob of the first clip and tracker:
        # a greyed "Jupyter only" knob there is a knob the reader cannot move
        fails += [f"knob {k.get_attribute('data-knob')}: greyed (no precomputed run)"
                  for k in all_knobs if not k.is_enabled()]
        fails += _every_sample(page, root, knobs)
    fr = root.query_selector("[data-frame]")
    # knobs are judged mid-clip: on frame 0 every tracker still sits on its initial box
    set_input(fr, int(fr.evaluate("e => +e.max")) // 2)
    for k in knobs:
        name = k.get_attribute("data-knob")
        before_sig, before_txt = page.evaluate(CANVAS_SIG, root), _scores(scores)
        raw_before = scores.inner_text()
        # the static page: the first of the knob's sampled values that changes the run (a
        # value can leave this clip's track as it was); Jupyter: one other value
        tries = [other_value(k)] + ([str(i) for i in range(int(k.evaluate("e => +e.max")) + 1)]
                                    if static else [])
        start = k.evaluate("e => e.value")
        changed = {"scores": False, "picture": False}
        for v in tries:
            if v == start:
                continue
            set_input(k, v)
            if wait_run:
                wait_run(raw_before)
            if static:
                settle(page)
            page.wait_for_timeout(50)
            changed = {"scores": _scores(scores) != before_txt,
                       "picture": page.evaluate(CANVAS_SIG, root) != before_sig}
            if all(changed.values()):
                break
        if not changed["scores"]:
            fails.append(f"knob {name}: scores did not change (beyond ms/frame)")
        if not changed["picture"]:
            fails.append(f"knob {name}: picture did not change")
        if static:
            set_input(k, start)
            settle(page)
    fails += _choices(page, root, scores)
    set_input(fr, 0)
    label = root.query_selector(".tb-frame-label")
    before, before_label = page.evaluate(CANVAS_SIG, root), label.inner_text()
    set_input(fr, int(fr.get_attribute("max") or fr.evaluate("e => e.max")) // 2)
    if page.evaluate(CANVAS_SIG, root) == before:
        fails.append("frame slider: picture did not change")
    if label.inner_text() == before_label:
        fails.append("frame slider: the frame's label (frame, IoU) did not change")
    set_input(fr, 0)
    before = page.evaluate(CANVAS_SIG, root)
    root.query_selector("[data-play]").click()
    # played: the frame and the picture moved on within 600 ms (asked every animation frame,
    # so a playground that advances at once is not held the whole 600 ms)
    try:
        page.wait_for_function(_PLAYED, arg=[root, before], timeout=600)
    except PlaywrightTimeout:
        fails.append("play: frames did not advance")
    root.query_selector("[data-play]").click()
    return fails


_PLAYED = f"""([r, before]) => +r.querySelector('[data-frame]').value > 0
  && ({CANVAS_SIG})(r) !== before"""


def _scores(scores):
    """The scores line without its timing (ms/frame differs between two runs of the same
    track, so it cannot show that a knob changed the run)."""
    return re.sub(r"[\d.]+\s*ms/frame", "", scores.inner_text())


def _every_sample(page, root, knobs):
    """Static page: every sampled value of every knob has its run (the slider never lands on
    a value the page cannot show); back to the default afterwards."""
    fails = []
    status = root.query_selector(".tb-status")
    scores = root.query_selector(".tb-scores")
    for k in knobs:
        name, start = k.get_attribute("data-knob"), k.evaluate("e => e.value")
        for i in range(int(k.evaluate("e => +e.min")), int(k.evaluate("e => +e.max")) + 1):
            set_input(k, i)
            settle(page)
            if status.inner_text().strip() or not scores.inner_text().strip():
                fails.append(f"knob {name} sample #{i}: no run ({status.inner_text()!r})")
            elif "refused" in scores.inner_text():
                fails.append(f"knob {name} sample #{i}: {scores.inner_text()}")
        set_input(k, start)
        settle(page)
    return fails


def _choices(page, root, scores):
    """The clip and tracker choices (where there are several): each other choice changes the
    picture and the scores; back to the first choice afterwards."""
    fails = []
    for sel in root.query_selector_all("select[data-control]"):
        if not sel.is_enabled():
            continue
        what = sel.get_attribute("data-control")
        options = sel.evaluate("e => [...e.options].map(o => o.value)")
        first = sel.evaluate("e => e.value")
        for v in options:
            if v == first:
                continue
            sig, txt = page.evaluate(CANVAS_SIG, root), scores.inner_text()
            set_input(sel, v)
            settle(page)
            page.wait_for_timeout(150)        # the new clip's JPEGs decode
            if page.evaluate(CANVAS_SIG, root) == sig:
                fails.append(f"{what} {v}: picture did not change")
            if scores.inner_text() == txt or not scores.inner_text().strip():
                fails.append(f"{what} {v}: scores did not change")
        set_input(sel, first)
        settle(page)
        page.wait_for_timeout(150)
    return fails


_PAIR_INFO = """(r) => {
  const data = JSON.parse(r.querySelector('script.tb-data').textContent);
  const fr = r.querySelector('[data-frame]');
  return { clip: r.querySelector('select[data-control=clip]').value,
    tracker: r.querySelector('select[data-control=tracker]').value,
    n_clip: (data.clips[r.querySelector('select[data-control=clip]').value] || {}).n,
    frames: +fr.max + 1,
    label: r.querySelector('.tb-frame-label').innerText,
    greyed: [...r.querySelectorAll('[data-knob]')].filter(k => k.disabled)
      .map(k => k.getAttribute('data-knob')),
    knobs: r.querySelectorAll('[data-knob]').length,
    declared: (data.config.knobs[r.querySelector('select[data-control=tracker]').value] || []).length,
    spread: r.querySelector('.tb-spread').innerText,
    scores: r.querySelector('.tb-scores').innerText,
    status: r.querySelector('.tb-status').innerText };
}"""


def check_pairs(page, root) -> tuple[list, int]:
    """The HTML book's playground, every clip x tracker pair at its defaults: every declared
    knob movable (none greyed "Jupyter only"), the run spanning the whole clip, the spread over
    seeds shown (at least 3 seeds, or the same boxes for every seed). Returns (failures,
    pairs seen); back to the first pair afterwards."""
    fails, seen = [], 0
    clip_sel = root.query_selector("select[data-control=clip]")
    tr_sel = root.query_selector("select[data-control=tracker]")
    clips = clip_sel.evaluate("e => [...e.options].map(o => o.value)")
    trackers = tr_sel.evaluate("e => [...e.options].map(o => o.value)")
    first = (clips[0], trackers[0])
    for c in clips:
        set_input(clip_sel, c)
        for t in trackers:
            set_input(tr_sel, t)
            settle(page)
            info = root.evaluate(_PAIR_INFO)
            seen += 1
            name = f"{c} x {t}"
            if info["status"].strip():
                fails.append(f"{name}: {info['status']}")
            if info["greyed"]:
                fails.append(f"{name}: greyed knobs {info['greyed']}")
            if info["knobs"] != info["declared"]:
                fails.append(f"{name}: {info['knobs']} knobs shown, {info['declared']} declared")
            if info["frames"] != info["n_clip"]:
                fails.append(f"{name}: the run spans {info['frames']} of {info['n_clip']} frames")
            m = re.search(r"over (\d+) seeds", info["spread"])
            if not (m and int(m.group(1)) >= 3) and "same boxes for every seed" not in info["spread"]:
                fails.append(f"{name}: no spread over seeds ({info['spread']!r})")
    set_input(clip_sel, first[0])
    set_input(tr_sel, first[1])
    settle(page)
    return fails, seen


_OVERFLOW = """(r) => {
  const box = r.getBoundingClientRect(), col = r.parentElement.getBoundingClientRect();
  const out = [];
  if (r.scrollWidth > r.clientWidth + 1) out.push(`scrolls: ${r.scrollWidth} > ${r.clientWidth}`);
  if (box.right > col.right + 1) out.push(`wider than its column: ${box.right} > ${col.right}`);
  if (box.right > document.documentElement.clientWidth + 1) out.push('wider than the window');
  for (const c of r.querySelectorAll('canvas')) {     // laid out to fit, not squeezed to fit
    const shown = c.getBoundingClientRect().width, drawn = c.width / (window.devicePixelRatio || 1);
    if (Math.abs(shown - drawn) > 1) out.push(`canvas squeezed: drawn ${drawn} px, shown ${shown} px`);
  }
  for (const e of r.querySelectorAll('canvas, select, input, .tb-scores, .tb-legend')) {
    const b = e.getBoundingClientRect();
    if (b.width && b.right > box.right + 1) out.push(`${e.tagName.toLowerCase()}.${e.className}` +
      ` sticks out by ${Math.round(b.right - box.right)} px`);
  }
  return out;
}"""


def overflow(root) -> list:
    """What of the playground sticks out of its box or its column (empty when it fits)."""
    return root.evaluate(_OVERFLOW)
