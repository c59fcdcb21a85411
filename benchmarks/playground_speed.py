"""Measure the playgrounds on the chapters' own configurations; print markdown tables.

Knob latency in Jupyter terms: every clip x tracker pair of every chapter's ``Playground(...)``
call, on the whole clip, in an asyncio event loop as the kernel runs one. A knob is moved by
the comm's path (``set_state`` of ``values``, with the frame on screen) and the time is taken
to the first ``run_data`` payload sent (serialised to JSON, as the comm does) and to the
complete one (``n_done == n_total``): the knob moved one sample from its default with the
reader on frame 0, then back with the reader on the clip's last frame. Target: the first
answer within 300 ms (median over the pairs).

The HTML book, when built (``book/_build/html`` or ``_build/html``): per chapter page, the
bytes its tags load (the page's own at first, the figures it loads lazily as the reader
scrolls, the theme's files every page shares; the run and frame files the viewer adds on demand
are not counted: the browser test measures those), the playgrounds' clip x tracker pairs that have knob runs, the run
length against the clip's length, and the seeds behind the spread, read from the page's
``.tb-data`` JSON (and the run files it names).

    python benchmarks/playground_speed.py            # all chapters
    python benchmarks/playground_speed.py 02 07      # chapters whose file name starts so
"""

from __future__ import annotations

import ast
import asyncio
import json
import re
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

CELL = re.compile(r"```\{code-cell\}[^\n]*\n(.*?)```", re.S)


def _cell_code(text: str) -> str:
    lines = text.split("\n")
    if lines and lines[0].strip() == "---":         # a cell's YAML options
        end = lines[1:].index("---") + 2 if "---" in lines[1:] else 0
        lines = lines[end:]
    return "\n".join(ln for ln in lines if not ln.lstrip().startswith((":", "%", "!")))


def _assigned(stmt) -> set:
    return {n.id for n in ast.walk(stmt)
            if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}


def _loaded(node) -> set:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def _resolve(expr, before: list):
    """The value of a call's argument: a literal, or computed by running only the chapter's
    statements it depends on (and the chapter's imports)."""
    try:
        return ast.literal_eval(expr)
    except ValueError:
        pass
    need, keep = _loaded(expr) - _assigned(expr), []
    for stmt in reversed(before):
        if isinstance(stmt, (ast.Import, ast.ImportFrom)) or _assigned(stmt) & need:
            keep.append(stmt)
            if not isinstance(stmt, (ast.Import, ast.ImportFrom)):
                need |= _loaded(stmt) - _assigned(stmt)     # not a comprehension's own
    ns: dict = {}
    exec(compile(ast.Module(body=keep[::-1], type_ignores=[]), "<chapter>", "exec"), ns)
    return eval(compile(ast.Expression(expr), "<chapter>", "eval"), ns)


def configs(prefixes=()):
    """(chapter, clips, trackers, params) of every chapter's ``Playground(...)`` call."""
    out = []
    for md in sorted((ROOT / "book").glob("*.md")):
        if prefixes and not md.name.startswith(tuple(prefixes)):
            continue
        before: list = []
        for cell in CELL.findall(md.read_text(encoding="utf-8")):
            try:
                tree = ast.parse(_cell_code(cell))
            except SyntaxError:
                continue
            for stmt in tree.body:
                for node in ast.walk(stmt):
                    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                            and node.func.id == "Playground"):
                        kw = {k.arg: k.value for k in node.keywords}
                        clips = _resolve(kw["clips"], before)
                        trackers = _resolve(kw["trackers"], before)
                        params = _resolve(kw["params"], before) if "params" in kw else []
                        out.append((md.stem, [clips] if isinstance(clips, str) else list(clips),
                                    [trackers] if isinstance(trackers, str) else list(trackers),
                                    list(params)))
                before.append(stmt)
    return out


def _move(pg, declared):
    """The knob to move (the first the chapter declares that this tracker has, else the
    tracker's first), a value one sample away from its default, and the default; None
    without knobs."""
    from trackbook.playground import data as D
    from trackbook.playground.data import field_names as _field_names, params_class as _params_cls

    fields = _field_names(pg.tracker)
    if not fields:
        return None
    name = next((p for p in declared if p in fields), fields[0])
    spec = D.knob_spec(_params_cls(pg.tracker), name)
    samples = D.sample_values(spec)
    d = spec["default"]
    others = [v for v in samples if v != d]
    if not others:
        return None
    if spec["kind"] in ("int", "float"):
        above = [v for v in others if v > d]
        v = above[0] if above else others[-1]
    else:
        v = others[0]
    return name, v, d


async def _knob_change(pg, name, value, frame):
    """Seconds from the ``values`` change to the first payload sent and to the complete one."""
    sent = []

    def on(change):
        json.dumps(change["new"])               # what the comm does with the state
        sent.append((time.perf_counter() - t0, change["new"].get("n_done"),
                     change["new"].get("n_total")))
    pg.observe(on, names="run_data")
    t0 = time.perf_counter()
    pg.set_state({"values": {**pg.values, name: value}, "frame": frame})
    while pg._task is not None or not sent:
        await asyncio.sleep(0)
    pg.unobserve(on, names="run_data")
    if pg.error:
        raise ValueError(pg.error)
    return sent[0][0], sent[-1][0], sent[0][1], sent[-1][2], len(sent)


def latency(prefixes=()):
    from trackbook.widgets import Playground

    rows = []
    for chapter, clips, trackers, params in configs(prefixes):
        for clip in clips:
            for tracker in trackers:
                try:
                    pg = Playground(clips=[clip], trackers=[tracker])      # whole clip
                except ValueError:      # a tracker the chapter registers in its own cells
                    rows.append((chapter, clip, tracker, "not registered outside its chapter"))
                    continue
                mv = _move(pg, params)
                if mv is None:
                    rows.append((chapter, clip, tracker, None))
                    continue
                out = {}
                # default -> one sample away with the reader on frame 0, then back to the
                # default with the reader on the last frame
                out["first"] = asyncio.run(_knob_change(pg, mv[0], mv[1], 0))
                out["last"] = asyncio.run(_knob_change(pg, mv[0], mv[2], 10 ** 6))
                rows.append((chapter, clip, tracker, (mv[:2], out)))
                f, last = out["first"], out["last"]
                print(f"{chapter:22s} {tracker:24s} {Path(str(clip)).name[:22]:22s} "
                      f"{mv[0]}={mv[1]!s:8s} first {f[0] * 1e3:5.0f} ms ({f[2]}/{f[3]} fr) "
                      f"| at last frame {last[0] * 1e3:5.0f} ms "
                      f"| complete {f[1] * 1e3:5.0f} ms", flush=True, file=sys.stderr)
    return rows


def _pct(xs, f):
    return f"{f(xs) * 1e3:.0f}" if xs else "–"


def latency_table(rows) -> str:
    done = [r for r in rows if isinstance(r[3], tuple)]
    first0 = [r[3][1]["first"][0] for r in done]
    firstN = [r[3][1]["last"][0] for r in done]
    complete = [r[3][1]["first"][1] for r in done] + [r[3][1]["last"][1] for r in done]
    lines = ["| knob change, whole clips | pairs | median (ms) | max (ms) |", "|---|---|---|---|",
             f"| first payload, reader on frame 0 | {len(done)} | {_pct(first0, statistics.median)}"
             f" | {_pct(first0, max)} |",
             f"| first payload, reader on the last frame | {len(done)} | "
             f"{_pct(firstN, statistics.median)} | {_pct(firstN, max)} |",
             f"| complete payload | {len(done)} | {_pct(complete, statistics.median)} | "
             f"{_pct(complete, max)} |"]
    for why in ("no knob to move", "not registered outside its chapter"):
        skipped = sorted({f"{r[2]} ({r[0]})" for r in rows
                          if (r[3] or "no knob to move") == why})
        if skipped:
            lines.append(f"\n{why[0].upper() + why[1:]}: {', '.join(skipped)}.")
    lines += ["", "| chapter | tracker | clip | knob | first (ms) | frames in first | "
              "first at last frame (ms) | complete (ms) |", "|---|---|---|---|---|---|---|---|"]
    for chapter, clip, tracker, res in rows:
        if not isinstance(res, tuple):
            lines.append(f"| {chapter} | {tracker} | {Path(str(clip)).name} |"
                         + " – |" * 5)
            continue
        (name, v), out = res
        f, last = out["first"], out["last"]
        knob = f"{name}={v}".replace("|", "\\|")      # a features string has bars
        lines.append(f"| {chapter} | {tracker} | {Path(str(clip)).name} | {knob} | "
                     f"{f[0] * 1e3:.0f} | {f[2]}/{f[3]} | {last[0] * 1e3:.0f} | "
                     f"{f[1] * 1e3:.0f} |")
    return "\n".join(lines)


# -- the built HTML book -------------------------------------------------------------------
def _json_in(text: str):
    try:
        return json.loads(text)
    except ValueError:
        a, b = text.find("{"), text.rfind("}")
        return json.loads(text[a:b + 1]) if a >= 0 and b > a else None


def _run_file(f: Path):
    """A run file's data: ``(window.tbPlaygroundRegister||...)("name", {...});``."""
    text = f.read_text(encoding="utf-8").strip()
    m = re.search(r'\("[^"]+",', text)
    if m is None:
        return _json_in(text)
    body = text[m.end():].rstrip(";").rstrip()
    return _json_in(body[:-1] if body.endswith(")") else body)


def _runs_of(data: dict, page: Path, html: Path) -> dict:
    """A playground's runs: inline (``runs``) or named as files (``files``, in the book's
    ``_static/playground``), those loaded too."""
    runs = {}
    named = {**(data.get("runs") or {}), **(data.get("files") or {})}
    for key, r in named.items():
        if isinstance(r, str):
            f = next((g for g in (page.parent / r, html / "_static" / "playground" / r)
                      if g.is_file()), None)
            r = _run_file(f) if f is not None else None
        if isinstance(r, dict):
            runs[key] = r
    return runs


def _first_load(page: Path, html: Path) -> tuple[int, int, int]:
    """Bytes a page loads: its own at first load (its HTML, eager images, playground files its
    tags load), the figures it loads as the reader scrolls (``loading="lazy"``), and the theme's
    files every page shares (cached after the first page)."""
    text = page.read_text(encoding="utf-8", errors="replace")
    own, lazy, shared, seen = page.stat().st_size, 0, 0, set()
    for m in re.finditer(r"<(?:script|img)[^>]*\ssrc=\"([^\"]+)\"[^>]*>|<link[^>]*"
                         r"rel=\"stylesheet\"[^>]*href=\"([^\"]+)\"", text):
        ref = (m.group(1) or m.group(2)).split("?")[0].split("#")[0]
        if re.match(r"^[a-z]+:", ref):
            continue
        f = (page.parent / ref).resolve()
        if f in seen or not f.is_file():
            continue
        seen.add(f)
        root = html.resolve()
        rel = f.relative_to(root).as_posix() if f.is_relative_to(root) else ""
        size = f.stat().st_size
        if 'loading="lazy"' in m.group(0):
            lazy += size
        elif rel.startswith(("_images/", "_static/playground/")):
            own += size
        else:
            shared += size
    return own, lazy, shared


def book_table(prefixes=()) -> str | None:
    html = next((d for d in (ROOT / "book" / "_build" / "html", ROOT / "_build" / "html")
                 if d.is_dir()), None)
    if html is None:
        return None
    lines = [f"Built book: {html.relative_to(ROOT)}, "
             f"{sum(f.stat().st_size for f in html.rglob('*') if f.is_file()) / 1e6:.1f} MB "
             "in all.", "",
             "| chapter | first load, own (MB) | figures on scroll (MB) | theme, shared (MB) "
             "| pairs with knob runs | run length (frames/clip) | seeds |",
             "|---|---|---|---|---|---|---|"]
    for md in sorted((ROOT / "book").glob("*.md")):
        page = next((p for p in (html / "book" / (md.stem + ".html"), html / (md.stem + ".html"))
                     if p.is_file()), None)
        if (prefixes and not md.name.startswith(tuple(prefixes))) or page is None:
            continue
        text = page.read_text(encoding="utf-8", errors="replace")
        blocks = re.findall(r'<script type="application/json" class="tb-data">(.*?)</script>',
                            text, re.S)
        if not blocks:
            continue
        pairs = covered = 0
        lengths, seeds = set(), set()
        for b in blocks:
            data = _json_in(b.replace("<\\/", "</")) or {}
            cfg = data.get("config") or {}
            if not cfg.get("trackers") or data.get("kind") != "playground":
                continue
            runs = _runs_of(data, page, html)
            clip_n = {k: len(c.get("frames") or []) or c.get("n") for k, c in
                      (data.get("clips") or {}).items() if isinstance(c, dict)}
            for c in cfg.get("clips", []):
                for t in cfg["trackers"]:
                    pairs += 1
                    keys = [k for k in runs if k.startswith(f"{c['key']}|{t}|")]
                    covered += any(k.split("|", 2)[2] for k in keys)
                    for k in keys:
                        r = runs[k]
                        n = r.get("n_total") or len(r.get("boxes") or [])
                        lengths.add(f"{n}/{clip_n.get(c['key'], '?')}")
                        sd = r.get("seeds")
                        seeds.add(len(sd["seeds"]) if isinstance(sd, dict) and "seeds" in sd
                                  else 1)
        if not pairs:
            continue
        own, lazy, shared = _first_load(page, html)
        lines.append(f"| {md.stem} | {own / 1e6:.2f} | {lazy / 1e6:.2f} | {shared / 1e6:.2f} | "
                     f"{covered}/{pairs} | "
                     f"{', '.join(sorted(lengths)) or '–'} | "
                     f"{', '.join(map(str, sorted(seeds))) or '–'} |")
    return "\n".join(lines)


def main(argv):
    rows = latency(argv)
    print(latency_table(rows))
    book = book_table(argv)
    print()
    print(book if book is not None else
          "No built book (book/_build/html or _build/html): page weight, pairs covered, run "
          "length and seeds are read from it once built.")


if __name__ == "__main__":
    main(sys.argv[1:])
