"""Measure the playgrounds on the chapters' own configurations.

For every ``Playground(...)`` cell in ``book/*.md``: the median time of a knob change
(``Playground.set``, the path a slider takes: re-run + the state sent), the median time of a
frame step in Chromium (``performance.now()`` around the slider's input event, which draws the
canvas synchronously), the time to precompute the HTML book's runs, and the page weight of
the playground's static HTML. Targets on a 2-core machine: knob <= 300 ms, frame step <= 20 ms,
<= 3 MB per playground.

    python benchmarks/playground_speed.py            # all chapters
    python benchmarks/playground_speed.py 02 06      # chapters whose file starts so
"""

from __future__ import annotations

import ast
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT))


def configs(prefixes=()):
    """(chapter, kwargs) of every Playground call whose arguments are literals (a call built
    from the chapter's variables is evaluated with the variables it names left out)."""
    out = []
    for md in sorted((ROOT / "book").glob("*.md")):
        if prefixes and not md.name.startswith(tuple(prefixes)):
            continue
        for m in re.finditer(r"Playground\((.*?)\)(?:\.show\(\))?\s*\n```", md.read_text(), re.S):
            call = ast.parse("f(" + m.group(1) + ")", mode="eval").body
            kw = {}
            for k in call.keywords:
                try:
                    kw[k.arg] = ast.literal_eval(k.value)
                except ValueError:
                    src = md.read_text()
                    name = ast.unparse(k.value)
                    d = re.search(rf"^{re.escape(name)}\s*=\s*(\[.*?\])\s*$", src, re.M)
                    try:
                        kw[k.arg] = ast.literal_eval(d.group(1)) if d else None
                    except ValueError:
                        kw[k.arg] = None
            if kw.get("clips") is None:
                kw["clips"] = ["red-cube"]   # built from found sequences: a sample clip here
            out.append((md.stem, kw))
    return out


def knob_moves(pg, k=3):
    """A few values for each knob: its samples other than the default, with the default."""
    for spec in pg.config["knobs"][pg.tracker]:
        for v in [s for s in spec["samples"] if s != spec["default"]][:k]:
            yield spec["name"], v, spec["default"]


def frame_step_ms(html: str, steps: int = 40) -> float:
    from playwright.sync_api import sync_playwright

    from tests._playground_browser import CHROMIUM

    with tempfile.TemporaryDirectory() as d:
        f = Path(d) / "p.html"
        f.write_text(f'<!doctype html><html><head><meta charset="utf-8"></head><body>{html}'
                     "</body></html>", encoding="utf-8")
        with sync_playwright() as p:
            b = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
            page = b.new_page()
            page.goto(f.as_uri())
            page.wait_for_selector(".tb-playground canvas")
            page.wait_for_timeout(800)
            times = page.evaluate("""(n) => {
              const s = document.querySelector('.tb-playground [data-frame]');
              const out = [];
              for (let i = 0; i < n; i++) {
                s.value = (i * 7) % (+s.max + 1);
                const t0 = performance.now();
                s.dispatchEvent(new Event('input', {bubbles: true}));
                out.push(performance.now() - t0);
              }
              return out; }""", steps)
            b.close()
    return statistics.median(times)


def main(argv):
    from trackbook.widgets import Playground

    rows = []
    for chapter, kw in configs(argv):
        t0 = time.perf_counter()
        pg = Playground(**kw)
        first = time.perf_counter() - t0
        times = []
        for name, v, default in knob_moves(pg):
            t = time.perf_counter()
            pg.set(**{name: v})
            times.append(time.perf_counter() - t)
            # back to the default, untimed: every move is one knob away from the defaults (as
            # the HTML book samples them), not a drift that leaves e.g. 1000 particles behind
            pg.set(**{name: default})
        t = time.perf_counter()
        html = pg.static_html()
        pre = time.perf_counter() - t
        step = frame_step_ms(html)
        rows.append((chapter, ",".join(kw["trackers"]), len(times),
                     1e3 * statistics.median(times) if times else float("nan"),
                     step, len(html.encode()) / 1e6, pre, first))
        print(f"{chapter:24s} {rows[-1][1][:34]:34s} knob n={len(times):2d} median "
              f"{rows[-1][3]:7.0f} ms | frame step {step:5.2f} ms | page {rows[-1][5]:5.2f} MB"
              f" | precompute {pre:5.1f} s", flush=True)
    print()
    print("| chapter | trackers | knob changes | knob median (ms) | frame step median (ms) "
          "| playground HTML (MB) | book precompute (s) |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.0f} | {r[4]:.2f} | {r[5]:.2f} | {r[6]:.1f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
