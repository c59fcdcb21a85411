"""Finding the small result files the book commits under ``book/results/``.

Chapters read real-sequence results from there (the sequences themselves are not in the
repository). A chapter runs with its own folder as the working directory when the book is
built, from ``notebooks/`` when exported for class, and from anywhere in a student's session,
so the files are looked up in each of those places and in the source tree of an editable
install.
"""

from __future__ import annotations

from pathlib import Path


def candidates(name: str) -> list[Path]:
    """Where ``book/results/<name>`` may be, in the order they are tried."""
    here = Path.cwd()
    import trackbook

    src_root = Path(trackbook.__file__).resolve().parents[2]   # <repo>/src/trackbook/__init__.py
    return [here / "results" / name,                  # running in book/
            here / "book" / "results" / name,          # running at the repository root
            here.parent / "book" / "results" / name,   # running in notebooks/ (exported)
            src_root / "book" / "results" / name]      # editable install, anywhere


def path(name: str) -> Path:
    """The committed result ``book/results/<name>`` (a file or a folder).

    Raises
    ------
    FileNotFoundError
        Naming the places tried and how to regenerate the results.
    """
    for p in candidates(name):
        if p.exists():
            return p
    tried = ", ".join(str(p) for p in candidates(name))
    raise FileNotFoundError(
        f"book/results/{name} not found (tried {tried}); run from the repository (or its "
        "book/ or notebooks/ folder), or regenerate it with the command given in the chapter."
    )
