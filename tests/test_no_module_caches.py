"""No module-level cache in the playground, its exporter for the book or the run loop: a dict,
list or set a module fills at run time only grows (a notebook session keeps every run it ever
made)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "trackbook"
# the book's exporter runs in the chapters' kernels too, beside the widget
FILES = (sorted((PACKAGE / "playground").glob("*.py")) + [PACKAGE / "evaluation" / "runner.py"]
         + sorted((ROOT / "book" / "_ext" / "playground_export").glob("*.py")))


def _empty_container(node) -> bool:
    if isinstance(node, (ast.Dict, ast.List, ast.Set)):
        return not (getattr(node, "keys", None) or getattr(node, "elts", None))
    return (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
            and node.func.id in {"dict", "list", "set", "defaultdict", "OrderedDict"}
            and not node.args)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_module_level_empty_container(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = [ast.unparse(n).split("=")[0].strip() for n in tree.body
             if isinstance(n, (ast.Assign, ast.AnnAssign)) and n.value is not None
             and _empty_container(n.value)]
    assert not found, f"{path.name}: module-level containers filled at run time: {found}"


def test_the_check_sees_a_cache():
    tree = ast.parse("_RUN_CACHE: dict = {}\nX = dict()\nY = {'a': 1}\n")
    assert [_empty_container(n.value) for n in tree.body] == [True, True, False]
