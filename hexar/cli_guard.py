"""What every `hexar` command shares: the console it prints to, and the guard that turns bad input into one line
(`ERROR: ...`, exit code 2) instead of a traceback."""

from __future__ import annotations

import sys
from collections.abc import Callable

from rich.console import Console

from hexar.errors import USER_ERRORS

out = Console(highlight=False)


def guarded(fn: Callable[[], int]) -> int:
    """Run a command body; a user error becomes `ERROR: ...` and exit code 2, never a traceback."""
    from hexar.safe_text import visible

    try:
        return fn()
    except BrokenPipeError:
        # the reader went away (`hexar inspect RUN --json | head -2`): what it wanted was written; stop quietly,
        # and point stdout at nothing so the interpreter's final flush does not raise again
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except USER_ERRORS as e:
        # the message may quote the recording (task ids, file names): never let it drive the terminal
        print(f"ERROR: {visible(e)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as e:  # the last guard: a bug reads as one line the user can report, not a traceback
        print(f"ERROR: internal error, please report it: {type(e).__name__}: {visible(e)}", file=sys.stderr)
        return 2
