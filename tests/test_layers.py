"""Imports in ``src/trackbook`` run one way: no cycle between modules, no upward import.

Every module's imports are read with :mod:`ast` (imports inside functions count too: a lazy
import still makes the lower layer depend on the higher one) and resolved to modules of the
package. Layers, bottom up:

0. ``_checks``, ``_user_code``, ``_memory``, ``_markdown``, ``params``, ``style``, ``papers``
   (helpers, data)
1. ``clips``, ``features``, ``learning``
2. ``filters``
3. ``trackers``, ``mot``
4. ``evaluation``, ``metrics``, ``results``, ``quotes`` (the register of passages, and which
   trackers' params they back: it reads the trackers' declarations)
5. ``viz``
6. ``playground``
7. ``widgets``, ``cli``, ``_cli_output``, ``_cli_errors``, ``_cli_notebooks``, ``__main__``, ``exercises``

A module may import its own layer or a lower one. The package's ``__init__`` re-exports the
public names and may import any layer.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "trackbook"

LAYERS = {
    "_checks": 0, "_user_code": 0, "_memory": 0, "_markdown": 0, "params": 0, "style": 0, "papers": 0,
    "clips": 1, "features": 1, "learning": 1,
    "filters": 2,
    "trackers": 3, "mot": 3,
    "evaluation": 4, "metrics": 4, "results": 4, "quotes": 4,
    "viz": 5,
    "playground": 6,
    "widgets": 7, "cli": 7, "_cli_output": 7, "_cli_errors": 7, "_cli_notebooks": 7, "__main__": 7, "exercises": 7,
}


def layer(module: str) -> int:
    """The layer of ``trackbook.<top>...`` (its first component below the package)."""
    parts = module.split(".")
    if len(parts) == 1:
        return max(LAYERS.values()) + 1          # trackbook/__init__: the re-exports
    top = parts[1]
    if top not in LAYERS:
        raise KeyError(f"module {module} has no layer: add {top!r} to LAYERS in "
                       f"tests/test_layers.py (and to the layer list of the README)")
    return LAYERS[top]


def modules() -> dict[str, Path]:
    """``{dotted name: path}`` of every module of the package."""
    out = {}
    for p in sorted(PACKAGE.rglob("*.py")):
        rel = p.relative_to(SRC).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = p
    return out


def imports(name: str, path: Path, known: set) -> set[str]:
    """The package's modules that module ``name`` imports (anywhere in its body)."""
    is_package = path.name == "__init__.py"
    here = name.split(".") if is_package else name.split(".")[:-1]
    found = set()

    def add(target: str):
        # the longest prefix that is a module: ``trackbook.clips.Clip`` -> ``trackbook.clips``
        parts = target.split(".")
        for k in range(len(parts), 0, -1):
            cand = ".".join(parts[:k])
            if cand in known:
                if cand != name:
                    found.add(cand)
                return

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "trackbook":
                    add(a.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[:len(here) - (node.level - 1)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if mod.split(".")[0] != "trackbook":
                continue
            for a in node.names:           # ``from . import clips`` names a module
                if f"{mod}.{a.name}" in known:
                    add(f"{mod}.{a.name}")
                else:
                    add(mod)
    return found


def graph() -> dict[str, set[str]]:
    mods = modules()
    return {n: imports(n, p, set(mods)) for n, p in mods.items()}


def cycles(g: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan's algorithm)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(g.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(g):
        if v not in index:
            visit(v)
    return out


def test_the_import_reader_resolves_relative_and_absolute_imports(tmp_path):
    pkg = tmp_path / "trackbook" / "viz"
    pkg.mkdir(parents=True)
    f = pkg / "core.py"
    f.write_text("from ..evaluation import metrics\nfrom .. import style\n"
                 "import trackbook.clips.scenes\nimport numpy\n"
                 "def late():\n    from ..playground.core import X\n")
    known = {"trackbook", "trackbook.style", "trackbook.evaluation",
             "trackbook.evaluation.metrics", "trackbook.clips", "trackbook.clips.scenes",
             "trackbook.playground", "trackbook.playground.core", "trackbook.viz.core"}
    assert imports("trackbook.viz.core", f, known) == {
        "trackbook.evaluation.metrics", "trackbook.style", "trackbook.clips.scenes",
        "trackbook.playground.core"}
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_every_module_has_a_layer():
    for name in modules():
        layer(name)


def test_no_module_imports_a_higher_layer():
    g = graph()
    upward = [f"{a} (layer {layer(a)}) imports {b} (layer {layer(b)})"
              for a, bs in sorted(g.items()) if a != "trackbook"
              for b in sorted(bs) if layer(b) > layer(a)]
    assert not upward, "upward imports:\n" + "\n".join(upward)


def test_no_two_modules_import_each_other():
    g = graph()
    found = []
    for comp in cycles(g):
        edges = [f"{a} -> {b}" for a in comp for b in sorted(g[a]) if b in comp]
        found.append(", ".join(edges))
    assert not found, "import cycles:\n" + "\n".join(found)


@pytest.mark.parametrize("name", ["trackbook.style", "trackbook._checks"])
def test_the_bottom_modules_import_nothing_of_the_package(name):
    mods = modules()
    assert imports(name, mods[name], set(mods)) == set()
