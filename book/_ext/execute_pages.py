"""Execute every page of the book, one page per core, into the build's execution cache.

``jupyter-book build .`` executes pages one after another, and takes a page from
``_build/.jupyter_cache`` when its code cells have not changed since that page last ran
(``_config.yml``: ``execute_notebooks: cache``). This script first runs every page of the
table of contents afresh, on all cores, and stores the executed pages there, so the build
that follows executes nothing. Run it again after changing the library: a cached page is
matched on its own code, not on the library it imports.

    python book/_ext/execute_pages.py          # then: jupyter-book build .
    python book/_ext/execute_pages.py book/13_camshift.md    # only these pages, cache kept

A page that fails prints its traceback and the script exits with 1 (nothing is cached for
it, so the build would execute it again and fail the same way).
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CACHE = ROOT / "_build" / ".jupyter_cache"
READER = {"name": "myst_nb_md", "type": "plugin"}     # the reader MyST-NB itself uses


def pages() -> list[Path]:
    """The pages the table of contents lists, largest first (so the workers end together)."""
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    found = [ROOT / f"{f}.md" for f in re.findall(r"(?:root|file):\s*(\S+)", toc)]
    return sorted(found, key=lambda p: -p.stat().st_size)


def execute(page: str):
    """Run one page in a fresh kernel in its own folder: ``(notebook, seconds, error)``."""
    import nbformat
    from jupyter_cache.executors.utils import single_nb_execution
    from jupyter_cache.readers import get_reader
    from jupyter_client.manager import KernelManager

    nb = get_reader(READER)(page)
    with tempfile.TemporaryDirectory() as sockets:
        # Unix sockets in a folder of this worker's own, not TCP ports: two kernels started at
        # the same moment by two workers could otherwise pick the same free port.
        km = KernelManager(kernel_name="python3", transport="ipc",
                           ip=os.path.join(sockets, "kernel"))
        try:
            result = single_nb_execution(nb, cwd=str(Path(page).parent), timeout=900,
                                         allow_errors=False, km=km)
        finally:                       # a kernel manager passed in is not shut down for us
            if km.has_kernel:
                km.shutdown_kernel(now=True)
    return nbformat.writes(nb), result.time, result.exc_string


def book_environment() -> None:
    """What the book's Sphinx extension sets for the kernels it starts (``sphinx_playground``):
    the playgrounds display as the HTML book's pages (``playground_export``) and write their
    run files where the build copies them from. Their runs are computed in the page's own
    kernel here (the pages already run one per core). Each kernel also checks every figure it
    shows (``figure_check.py``: tracker colours, legends clear of the data)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import figure_check
    from playground_export import add_startup
    from playground_export.static import BACKGROUND_ENV, OUT_ENV
    from sphinx_playground import store_dir

    # every figure of every page is checked as it is shown (figure_check.py), and every
    # playground and animation is shown as the book's page (playground_export)
    os.environ["IPYTHONDIR"] = str(add_startup(
        figure_check.ipython_dir(ROOT / "_build" / ".kernel")))
    os.environ[figure_check.ALTS_ENV] = str(ROOT / "_build" / ".figure_alts")
    os.environ[OUT_ENV] = str(store_dir(ROOT / "_build" / "html"))
    os.environ.pop(BACKGROUND_ENV, None)


def cached(page: Path, after: float = 0.0, cache: Path = CACHE):
    """The executed notebook of ``page`` from the cache, its outputs merged into the page as
    it reads now; None when the cache holds no execution of the page's current code cells, or
    only one stored before the time ``after`` (seconds since the epoch).

    A cached page is matched on its own code, not on the library it imports: a caller that
    reads its outputs passes the time the library last changed as ``after``.
    """
    from datetime import timezone

    from jupyter_cache import get_cache
    from jupyter_cache.readers import get_reader

    if not Path(cache).is_dir():
        return None
    store = get_cache(str(cache))
    nb = get_reader(READER)(str(page))
    try:
        record = store.match_cache_notebook(nb)
    except KeyError:
        return None
    made = record.created
    if made.tzinfo is None:          # the cache's database keeps UTC without its zone
        made = made.replace(tzinfo=timezone.utc)
    if made.timestamp() < after:
        return None
    return store.merge_match_into_notebook(nb)[1]


def main() -> int:
    import nbformat
    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn

    book_environment()

    if len(sys.argv) > 1:
        todo = [str(Path(p).resolve()) for p in sys.argv[1:]]
    else:
        shutil.rmtree(CACHE, ignore_errors=True)       # every page afresh
        shutil.rmtree(ROOT / "_build" / ".figure_alts", ignore_errors=True)
        todo = [str(p) for p in pages()]
    cache = get_cache(str(CACHE))
    start, failed = time.time(), []
    with ProcessPoolExecutor(max_workers=max(1, min(len(todo), os.cpu_count() or 1))) as pool:
        for page, (text, seconds, error) in zip(todo, pool.map(execute, todo)):
            name = Path(page).name
            if error:
                failed.append(name)
                print(f"--- {name} failed:\n{error}", file=sys.stderr)
                continue
            cache.cache_notebook_bundle(CacheBundleIn(nbformat.reads(text, 4), page),
                                        check_validity=False, overwrite=True)
            print(f"{name}: {seconds:.0f} s", flush=True)
    print(f"executed {len(todo) - len(failed)} of {len(todo)} pages in "
          f"{time.time() - start:.0f} s" + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
