"""A Python node's uncaught exception, as the console reader keeps it (stable API).

    python_exception(line) -> PyException | None
    thrown_words(line) -> str

CPython's default excepthook prints "Traceback (most recent call last):", the frames ("  File "…", line N, in f" and
the source line), then the exception's own line; the process then exits 1 (launch reports "process has died [… exit
code 1 …]"). events/console.py keeps that as one record whose first line is the exception's ("ValueError: min() arg is
an empty sequence", "rclpy._rclpy_pybind11.RCLError: failed to initialize rcl: …") and whose later lines are the
traceback. A traceback that a node logs on purpose (`logger.exception`) goes on after a log line of its own and is not
such a record.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from hexar.events.records import TRACEBACK, LogLine

_EXCEPTION = re.compile(r"^(?P<type>[A-Za-z_][\w.]*)(?::\s?(?P<text>.*))?$")
_FRAME = re.compile(r'^File "(?P<file>[^"]+)", line (?P<line>\d+), in (?P<function>\S+)$')
# a frame of the Python library or of an installed package is not where the node's own code went wrong
_LIBRARY = re.compile(r"/(site|dist)-packages/|/lib/python\d")


# rclpy's ActionServer._execute_goal (rclpy/action/server.py) catches what a goal's execute callback raises, logs
# "Error raised in execute callback: …", prints the traceback (traceback.print_exc) and aborts the goal ("Goal state
# not set, assuming aborted"): the exception ended that goal, not the process
_RCLPY_ACTION_SERVER = "rclpy/action/server.py"


_RCLPY_SAYS = {
    "Error raised in execute callback:": (
        "the goal's execute callback raised an exception; rclpy's action server caught it, printed its traceback and "
        "aborted the goal, and the node went on running"),
    "Goal state not set, assuming aborted.": (
        "the goal's execute callback ended without ending the goal (it called none of succeed(), abort() or "
        "canceled(), as when it raised an exception), so rclpy's action server aborted the goal itself"),
}


def rclpy_action_meaning(line: LogLine) -> str:
    """What rclpy's action server's own lines about a goal's execute callback mean (rclpy/action/server.py); ""
    for any other line."""
    return next((said for start, said in _RCLPY_SAYS.items() if line.msg.startswith(start)), "")


@dataclass(frozen=True)
class PyException:
    type: str  # the class as printed: "ValueError", "rclpy.exceptions.InvalidParameterTypeException"
    text: str  # its message, with the lines it went on over
    where: str  # the innermost frame of the node's own code: "tick (/home/robot/ws/scan_filter.py, line 12)"
    file: str = ""  # that frame's file: "/home/robot/ws/scan_filter.py"

    @property
    def name(self) -> str:
        return self.type.rsplit(".", 1)[-1]


def python_exception(line: LogLine) -> PyException | None:
    """The exception a record of an uncaught Python exception holds; None for any other line."""
    said, sep, frames = line.msg.partition(f"\n{TRACEBACK}")
    if not sep:
        return None
    head, _, more = said.partition("\n")
    m = _EXCEPTION.match(head.strip())
    if m is None:
        return None
    own = [f for f in (_FRAME.match(x.strip()) for x in frames.splitlines()) if f is not None]
    if any(f["file"].endswith(_RCLPY_ACTION_SERVER) and f["function"] == "_execute_goal" for f in own):
        return None  # rclpy caught it and printed it: its process goes on (see _RCLPY_ACTION_SERVER)
    mine = [f for f in own if not _LIBRARY.search(f["file"])] or own
    where = f"{mine[-1]['function']} ({mine[-1]['file']}, line {mine[-1]['line']})" if mine else ""
    text = " ".join([(m["text"] or "").strip(), *(x.strip() for x in more.splitlines() if x.strip())]).strip()
    return PyException(m["type"], text, where, mine[-1]["file"] if mine else "")


def exception_quoted(line: LogLine, exc: PyException, most: int = 200) -> str:
    """"“[node] its message”, raised in tick (…, line 12)": the exception's message as the log's words (hexar/claims.py
    reads no claim in quotes), and where the node's own code raised it."""
    where = f", raised in {exc.where}" if exc.where else ""
    return f"“[{line.name or 'unnamed node'}] {exc.text[:most]}”{where}"


def thrown_words(line: LogLine) -> str:
    """"an uncaught Python exception (InvalidParameterTypeException): “[node] Trying to set …”, raised in <module>
    (…, line 7)"."""
    exc = python_exception(line)
    if exc is None:
        return f"“{line.msg.splitlines()[0][:200]}”" if line.msg else ""
    return f"an uncaught Python exception ({exc.name}): {exception_quoted(line, exc)}"
