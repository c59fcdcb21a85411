"""The exercises appendix runs, every solution passes its check, and every starter waits."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
APPENDIX = ROOT / "book" / "appendix_exercises.md"
VERDICT = re.compile(r"^(\d+\.\d+): (PASS|FAIL|not answered yet)", re.M)


def _text(cell) -> str:
    return "".join(o.get("text", "") for o in cell.get("outputs", [])
                   if o.get("output_type") == "stream")


def _tags(cell) -> list:
    return cell.get("metadata", {}).get("tags", [])


def test_every_exercise_has_a_starter_and_a_hidden_solution():
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(APPENDIX)
    code = [c for c in nb.cells if c.cell_type == "code"]
    starters = [c for c in code if re.search(r"^answer_\d+_\d+ = None", c.source, re.M)]
    solutions = [c for c in code if "hide-cell" in _tags(c)]
    assert len(starters) >= 40
    assert len(solutions) == len(starters)
    for cell in starters + solutions:
        assert re.search(r"""^(check_\d+_\d+\(|autocheck\("\d+\.\d+", )answer_\d+_\d+\)""",
                         cell.source, re.M), cell.source


def test_a_handed_out_appendix_keeps_no_check_of_a_worked_answer():
    """The hand-out recipe strips the ``hide-cell`` and ``remove-cell`` cells: every cell that
    asserts a worked answer is one of them (or a ``hide-input`` set-up cell of a section,
    whose printed answers the teaching appendix warns about), so the asserts do not give
    the answers away in a notebook handed to students."""
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(APPENDIX)
    leaks = [c.source.splitlines()[0] for c in nb.cells if c.cell_type == "code"
             and re.search(r"^\s*assert\b", c.source, re.M)
             and not {"hide-cell", "remove-cell", "hide-input"} & set(_tags(c))]
    assert not leaks, leaks


def _names(source: str) -> tuple[set, set]:
    """The names a cell binds and the names it reads (line magics left out)."""
    import ast
    tree = ast.parse("\n".join(ln for ln in source.splitlines() if not ln.startswith("%")))
    bound, read = set(), set()
    for n in ast.walk(tree):
        if isinstance(n, ast.Name):
            (read if isinstance(n.ctx, ast.Load) else bound).add(n.id)
        elif isinstance(n, (ast.FunctionDef, ast.ClassDef)):
            bound.add(n.name)
        elif isinstance(n, (ast.Import, ast.ImportFrom)):
            bound |= {(a.asname or a.name).split(".")[0] for a in n.names}
        elif isinstance(n, ast.arg):
            bound.add(n.arg)
    return bound, read


def test_a_handed_out_appendix_needs_no_removed_cell():
    """With the solutions and the checks stripped (the hand-out recipe), no kept cell reads a
    name that only a stripped cell defines: the handed-out notebook runs."""
    import builtins
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(APPENDIX)
    kept, stripped, missing = set(dir(builtins)), set(), []
    for c in nb.cells:
        if c.cell_type != "code":
            continue
        bound, read = _names(c.source)
        if {"hide-cell", "remove-cell"} & set(_tags(c)):
            stripped |= bound - kept
            continue
        need = (read - bound - kept) & stripped
        if need:
            missing.append((c.source.splitlines()[0], sorted(need)))
        kept |= bound
    assert not missing, missing


def _library_changed() -> float:
    """When a file of the library last changed (seconds since the epoch)."""
    return max(f.stat().st_mtime for f in (ROOT / "src" / "trackbook").rglob("*")
               if f.is_file() and "__pycache__" not in f.parts)


def _executed_appendix():
    """The appendix executed, every cell in order in one kernel from its own folder.

    The book's build executes every page (``book/_ext/execute_pages.py``, the same page in
    the same kind of kernel; it only adds the figure check and the playgrounds' book
    display, neither of which the appendix uses): where its cache holds this page's current
    code executed after the library last changed, that execution is read rather than made a
    second time (it is the slowest page of the book). Otherwise the page runs here.
    """
    jupytext = pytest.importorskip("jupytext")
    try:
        import execute_pages  # from book/_ext, which tests/conftest.py puts on the path
        nb = execute_pages.cached(APPENDIX, after=_library_changed())
    except ImportError:              # no jupyter-cache: the book's extra is not installed
        nb = None
    if nb is not None:
        return nb
    nbclient = pytest.importorskip("nbclient")
    nb = jupytext.read(APPENDIX)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(APPENDIX.parent)}}).execute()
    return nb


@pytest.mark.slow
def test_appendix_executes_and_every_solution_passes():
    nb = _executed_appendix()
    code = [c for c in nb.cells if c.cell_type == "code"]
    errors = [o for c in code for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors, errors[0]
    starter_verdicts, solution_verdicts = {}, {}
    for cell in code:
        found = dict(VERDICT.findall(_text(cell)))
        (solution_verdicts if "hide-cell" in _tags(cell) else starter_verdicts).update(found)
    assert solution_verdicts, "no check ran in the solution cells"
    assert set(solution_verdicts) == set(starter_verdicts)
    failed = {k: v for k, v in solution_verdicts.items() if v != "PASS"}
    assert not failed, f"solutions that do not pass their check: {failed}"
    assert set(starter_verdicts.values()) == {"not answered yet"}
    # the rendered page: every exercise of the registry, in order, under its number, graded
    from trackbook import exercises
    shown = re.findall(r"^\*\*Exercise (\d+\.\d+) (★{1,3}) \(", "\n".join(
        o.get("data", {}).get("text/markdown", "") for c in code for o in c.get("outputs", [])), re.M)
    assert shown == [(e.number, e.stars) for e in exercises.all_exercises()]


def test_check_helper_fails_wrong_answers(capsys):
    jupytext = pytest.importorskip("jupytext")
    helper = next(c for c in jupytext.read(APPENDIX).cells if c.cell_type == "code")
    ns = {}
    exec(helper.source, ns)
    check = ns["check"]
    assert check("a", None, 1.0) is None
    assert check("b", (0.7071, 1.0), (2 ** -0.5, 1.0)) is True      # rounded to 4 decimals
    assert check("c", (0.70, 1.0), (2 ** -0.5, 1.0)) is False
    assert check("d", (1, 2), (1, 2, 3)) is False                    # wrong shape
    assert check("e", {20: 0.5}, {20: 0.5, 100: 0.6}) is False       # missing key
    assert check("f", " IV", "iv") is True
    assert check("g", "OCC", "IV") is False
    assert check("h", 6, lambda: 6, atol=0) is True                  # lazy reference
    assert check("i", lambda x: x, test=lambda f: f(2) == 3) is False
    assert check("j", "not a function", test=lambda f: f(2) == 2) is False  # error -> FAIL
    out = capsys.readouterr().out
    assert "a: not answered yet" in out and "b: PASS" in out and "c: FAIL" in out
    assert "j: FAIL (TypeError" in out
