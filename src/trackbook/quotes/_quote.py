"""The record of one quote: a passage of a paper, verbatim, with its English translation."""

from __future__ import annotations

import re
from dataclasses import dataclass

#: The four papers, by key.
PAPERS = ("lee2012", "kim2016", "lee2015", "cho2005")

#: ``printed``: the passage states the value or the fact. ``reading``: the passage is
#: ambiguous and supports the book's reading of it (the chapter says it is a reading).
KINDS = ("printed", "reading")

KEY = re.compile(r"^(lee2012|kim2016|lee2015|cho2005)\.[a-z0-9_]+$")
_HANGUL = re.compile(r"[\uac00-\ud7a3]")


@dataclass(frozen=True)
class Quote:
    """One passage of a paper.

    Attributes
    ----------
    key : str
        ``<paper>.<name>``, e.g. ``lee2012.window40``; the name is lower case.
    where : str
        The section, table, figure or equation the passage comes from.
    original : str
        The passage verbatim (Korean, or the English abstract); runs of
        whitespace (line and page breaks, table cells) may be written as one space.
    translation : str
        A faithful English translation (the passage itself when it is English).
    kind : str
        ``"printed"`` or ``"reading"`` (see :data:`KINDS`).
    """

    key: str
    where: str
    original: str
    translation: str
    kind: str = "printed"

    def __post_init__(self):
        if not KEY.match(self.key):
            raise ValueError(f"quote key {self.key!r} is not '<paper>.<name>' with paper one of "
                             f"{', '.join(PAPERS)} and a lower-case name")
        if self.kind not in KINDS:
            raise ValueError(f"quote {self.key}: kind {self.kind!r} is not one of {KINDS}")
        for field in ("where", "original", "translation"):
            if not getattr(self, field).strip():
                raise ValueError(f"quote {self.key}: {field} is empty")

    @property
    def paper(self) -> str:
        """The paper's key (``lee2012``, ``kim2016``, ``lee2015`` or ``cho2005``)."""
        return self.key.split(".", 1)[0]

    @property
    def language(self) -> str:
        """``"ko"`` when the original is Korean, else ``"en"``."""
        return "ko" if _HANGUL.search(self.original) else "en"
