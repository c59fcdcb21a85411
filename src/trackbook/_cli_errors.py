"""How the ``trackbook`` command reports an error: one line on stderr and an exit code.

Kept apart from :mod:`trackbook.cli` (the subcommands and their arguments): this module only
turns an exception into its line, and says whose it is (see :mod:`trackbook._user_code`).
"""

from __future__ import annotations

import sys


class CLIError(Exception):
    """A user error the command reports in one line (exit code 2)."""


def os_problem(e: OSError) -> str:
    """What went wrong with a file, and the fix, from the ``errno`` of ``e``."""
    import errno

    what = e.strerror or type(e).__name__
    fix = {errno.ENAMETOOLONG: "use a shorter folder or file name",
           errno.EACCES: "pass a folder you can write to (--out) or fix its permissions",
           errno.EPERM: "pass a folder you can write to (--out) or fix its permissions",
           errno.EROFS: "the disk is read-only; pass a folder on a writable disk (--out)",
           errno.ENOTDIR: "a file is in the way of a folder; pass another --out",
           errno.ENOSPC: "free some disk space or pass a folder on another disk (--out)",
           errno.EDQUOT: "free some space in your quota or pass another --out"}
    return f"{what}; {fix.get(e.errno, 'pass a writable --out folder')}."


def _quiet_stdout() -> None:
    """Point stdout at /dev/null: the reader is gone, and Python's final flush must not
    print a BrokenPipeError of its own."""
    import os
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def report(e: BaseException, show_traceback: bool = False) -> int:
    """One line on stderr for an exception of a subcommand; the exit code.

    An exception raised in the user's own code (a ``--import`` file, an entry-point plugin;
    see :mod:`trackbook._user_code`) is reported as theirs with its file and line, whatever
    its type, and so is ``sys.exit`` called there.
    """
    from ._user_code import UserCodeError, describe

    if isinstance(e, BrokenPipeError):  # the reader went away (trackbook trackers | head)
        _quiet_stdout()
        return 0
    if show_traceback and not isinstance(e, KeyboardInterrupt):
        import traceback
        details = getattr(e, "details", "") if isinstance(e, UserCodeError) else ""
        print(details or "".join(traceback.format_exception(type(e), e, e.__traceback__)),
              file=sys.stderr, end="")
    user = None if isinstance(e, KeyboardInterrupt) else describe(e)
    if isinstance(e, SystemExit) and user is None:
        raise e
    if user is not None:
        print(f"trackbook: {user}" + ("" if show_traceback else
                                       " (re-run with --traceback for the whole traceback)"),
              file=sys.stderr)
        return 2
    try:
        raise e
    except KeyboardInterrupt:
        signum = getattr(e, "signum", 2)
        print("trackbook: interrupted (Ctrl-C)." if signum == 2 else
              f"trackbook: stopped by a signal ({signum}).", file=sys.stderr)
        return 128 + signum
    except (ValueError, CLIError, OSError, KeyError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else e
        if isinstance(e, OSError) and e.filename is not None and e.strerror:
            msg = f"{e.filename}: {os_problem(e)}"
        print(f"trackbook: error: {' '.join(str(msg).split())}", file=sys.stderr)
        return 2
    except ImportError as e:   # an optional package (an extra) is not installed
        print(f"trackbook: error: this needs the package {e.name or e}, which is not installed; "
              "pip install it, or the extra that has it (pip install 'trackbook[book]').",
              file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001  a bug, still reported in one line
        print(f"trackbook: error: {type(e).__name__}: {' '.join(str(e).split())} (this is a "
              "bug; please report it with the command line"
              + ("" if show_traceback else " and the output of --traceback") + ")",
              file=sys.stderr)
        return 1
