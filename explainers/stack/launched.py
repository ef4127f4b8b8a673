"""A command launch could not execute at all (stable API).

    exec_failed(line, after) -> str | None

launch's ExecuteProcess logs "exception occurred while executing process:" with the traceback of the error that
spawning the command raised (launch/actions/execute_local.py:581@rolling); the console reader keeps that traceback as
one record whose first line is the exception (events/console.py). FileNotFoundError is the operating system's "no
such program" (ENOENT: not installed, or not on the PATH), PermissionError a file that is not executable (EACCES).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.events.records import LogLine

EXEC = "exception occurred while executing process"
_QUOTED = re.compile(r"'([^']+)'\s*$")
_WHY = {"FileNotFoundError": "there is no such program (it is not installed, or not on the PATH)",
        "PermissionError": "the file is not executable (permission denied)"}


def exec_failed(line: LogLine, after: Sequence[LogLine]) -> str | None:
    """"'scan_filter_node' could not be run: there is no such program (…)" when `line` is launch's word that it
    could not execute a process and one of the records `after` it is the error that said why; None otherwise."""
    if EXEC not in line.msg:
        return None
    # loaded here: every bring-up finding's line is asked, and the exception reader is wanted for few
    from hexar.explainers.stack.thrown import python_exception

    for later in after:
        exc = python_exception(later)
        if exc is not None and exc.name in _WHY:
            found = _QUOTED.search(exc.text)
            program = f"'{found[1]}'" if found else "its program"
            return f"{program} could not be run: {_WHY[exc.name]}"
    return None
