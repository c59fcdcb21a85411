"""The book's exercises, defined once and rendered in the chapters and in the exercises appendix.

Every exercise lives in the text of its chapter's module (``_01_kernel_histograms.py`` ...):
its number, its grade (★ short, ★★ longer, ★★★ an implementation or a project), its kind, a
title, the statement
(MyST), an optional hint and an optional worked solution. A chapter shows an exercise with
``show("1.6")`` in a ``remove-input`` cell; the appendix shows the same exercise, with the
same number, the same way. The ★★★ exercises with an auto-check have it in
:mod:`trackbook.exercises.checks`; ``autocheck("1.5", answer)`` prints PASS or FAIL.

The text format of a module's ``TEXT``::

    === 1.6 ★ pen and paper | ρ as a cosine
    The statement, Markdown with $maths$ and {doc}`links <02_particle_filters>`.
    --- hint
    An optional hint.
    --- solution
    An optional worked solution.

A header may end with ``| after <stem>``: the exercise uses a chapter that the book teaches
later (``=== 3.4 ★★ modify | How much colour? | after 02_particle_filters``), and it is shown
with that chapter's link, so a course sets it once the class has read that chapter.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass

from ._check import check

__all__ = ["Exercise", "autocheck", "chapters", "check", "for_chapter", "get", "markdown",
           "show", "all_exercises"]

from ._chapters import CHAPTERS  # noqa: E402  (the one list, shared with checks)

#: The grades and the kinds an exercise may have.
STARS = ("★", "★★", "★★★")
KINDS = ("use", "modify", "implement", "pen and paper", "project")
#: What the grades and the kinds mean: the sentence every chapter's exercises open with (a test
#: holds the chapters and the exercises to it). The stars measure effort; the kind says what
#: the student does, so a pen-and-paper exercise can be short (★) or longer (★★).
LEGEND = ("Graded by effort, ★ short, ★★ longer, ★★★ an implementation or a project, with the "
          "kind in brackets: *use* (run trackbook and read the answer off), *modify* (change a "
          "parameter, a clip or a few lines and explain what changes), *implement* (write a "
          "function from an equation), *pen and paper* (a derivation or a calculation by hand) "
          "or *project*.")
#: The grades each kind may have (:data:`LEGEND` as a table).
GRADES = {"use": ("★",), "modify": ("★★",), "implement": ("★★★",),
          "pen and paper": ("★", "★★"), "project": ("★★★",)}

_HEAD = re.compile(r"^=== (\d+)\.(\d+) (★+) ([a-z ]+?) \| (.*?)(?: \| after (\w+))?$")
_PART = re.compile(r"^--- (hint|solution)$")


@dataclass(frozen=True)
class Exercise:
    """One exercise: where it belongs, its grade and its text.

    Attributes
    ----------
    stem : the chapter's file stem (``"06_kalman"``).
    number : ``"6.8"``: the chapter's number, a dot, the exercise's place in the chapter.
    stars : ``"★"`` (use), ``"★★"`` (modify) or ``"★★★"`` (implement).
    kind : one of :data:`KINDS`.
    title : a few words.
    statement, hint, solution : MyST text (hint and solution may be empty).
    after : the stem of a chapter the book teaches after this one and the exercise needs
        (``"02_particle_filters"``), or ``""``.
    """

    stem: str
    number: str
    stars: str
    kind: str
    title: str
    statement: str
    hint: str = ""
    solution: str = ""
    after: str = ""

    @property
    def autocheck(self):
        """The predicate that verifies an answer, or None when the exercise has none."""
        from .checks import CHECKS
        return CHECKS.get(self.number)


def parse(text: str, stem: str) -> list[Exercise]:
    """The exercises of one chapter module's ``TEXT`` (see the module docstring)."""
    out, cur, part = [], None, "statement"
    for line in text.strip("\n").split("\n"):
        head, sub = _HEAD.match(line), _PART.match(line)
        if head:
            if cur:
                out.append(cur)
            chapter, k, stars, kind, title, after = head.groups()
            if stars not in STARS or kind not in KINDS:
                raise ValueError(f"{stem}: exercise {chapter}.{k} has grade {stars!r} and kind "
                                 f"{kind!r}; use one of {STARS} and one of {KINDS}")
            cur, part = {"number": f"{chapter}.{k}", "stars": stars, "kind": kind,
                         "title": title.strip(), "after": after or "", "statement": [],
                         "hint": [], "solution": []}, "statement"
        elif sub and cur:
            part = sub.group(1)
        elif cur is None:
            if line.strip():
                raise ValueError(f"{stem}: text before the first '=== N.M' line: {line!r}")
        else:
            cur[part].append(line)
    if cur:
        out.append(cur)
    return [Exercise(stem=stem, **{k: "\n".join(v).strip() if isinstance(v, list) else v
                                   for k, v in e.items()}) for e in out]


def for_chapter(stem: str) -> list[Exercise]:
    """The exercises of chapter ``stem``, in their order."""
    if stem not in CHAPTERS:
        raise ValueError(f"no exercises for {stem!r}; chapters with exercises: {CHAPTERS}")
    module = importlib.import_module(f"{__name__}._{stem}")
    return parse(module.TEXT, stem)


def chapters() -> tuple[str, ...]:
    """The chapter stems that have exercises."""
    return CHAPTERS


def all_exercises() -> list[Exercise]:
    """Every exercise of the book, chapter by chapter."""
    return [e for stem in CHAPTERS for e in for_chapter(stem)]


def get(number: str) -> Exercise:
    """The exercise numbered ``number`` (``"6.8"``)."""
    number = str(number)
    chapter = number.split(".")[0]
    stems = [s for s in CHAPTERS if chapter.isdigit() and int(s[:2]) == int(chapter)]
    for e in for_chapter(stems[0]) if stems else []:
        if e.number == number:
            return e
    raise ValueError(f"no exercise {number!r}; numbers look like '6.8' (chapter.exercise)")


def _fence(text: str) -> str:
    """A backtick fence longer than any fence inside ``text``."""
    runs = [len(m) for m in re.findall(r"`{3,}", text)]
    return "`" * max([3] + [n + 1 for n in runs])


def markdown(number, *, solution: bool = True, title_level: int | None = None) -> str:
    """An exercise as MyST: its number, grade, kind and title in bold, the statement, the
    hint, and the worked solution in a closed dropdown.

    Parameters
    ----------
    number : the exercise's number (``"6.8"``) or an :class:`Exercise`.
    solution : show the worked solution (folded) when the exercise has one.
    title_level : None: the header is a bold lead-in of the statement's first paragraph;
        an int: a Markdown heading of that level (not used by the book's pages).
    """
    e = number if isinstance(number, Exercise) else get(number)
    title = e.title if e.title.endswith(("?", "!", ".")) else e.title + "."
    head = f"Exercise {e.number} {e.stars} ({e.kind}). {title}"
    # an exercise that needs a later chapter says which, before its statement
    after = f"*(After {{doc}}`{e.after}`.)* " if e.after else ""
    if title_level:
        parts = ["#" * title_level + " " + head, after + e.statement]
    else:
        parts = [f"**{head}** {after}{e.statement}"]
    if e.hint:
        parts.append(f"*Hint.* {e.hint}")
    if solution and e.solution:
        f = _fence(e.solution)
        parts.append(f"{f}{{admonition}} Solution to {e.number}\n:class: dropdown\n"
                     f"{e.solution}\n{f}")
    return "\n\n".join(parts) + "\n"


def show(*numbers, **kwargs):
    """:func:`markdown` of one exercise or of several in a row (``show("1.8", "1.9")``), as an
    ``IPython.display.Markdown`` for a ``remove-input`` cell."""
    from IPython.display import Markdown
    if "number" in kwargs:          # show(solution=False, number="6.8"): the appendix's recipe
        numbers = numbers + (kwargs.pop("number"),)
    if not numbers:
        raise ValueError("show() needs an exercise number, e.g. show('6.8')")
    return Markdown("\n".join(markdown(n, **kwargs) for n in numbers))


def autocheck(number: str, answer):
    """Print PASS or FAIL for an answer to an auto-checked exercise (``not answered yet``
    while it is None); return that verdict (None, True or False)."""
    test = get(number).autocheck
    if test is None:
        raise ValueError(f"exercise {number} has no auto-check; the auto-checked ones are "
                         "listed in trackbook.exercises.checks.CHECKS")
    return check(str(number), answer, test=test)
