"""Where a robot's stack began to shut down in its lines: what it prints on the way down is no cause of what
happened before (navigation and the module explainers alike)."""

from __future__ import annotations

import re

from hexar.events.records import LogLine

# A stack being stopped prints its own warnings and errors on the way down (a message filter dropping what came in
# as the transforms went away, launch escalating to SIGKILL and "process has died [..., exit code -9]"): none of it
# explains what happened before. Launch's own line when Ctrl-C reaches it (launch_service.py, "user interrupted
# with ctrl-c (SIGINT)"), and rclcpp's when a node gets SIGINT or SIGTERM (signal_handler.cpp,
# "signal_handler(signum=%d)" from Galactic on, "signal_handler(signal_value=%d)" in Foxy), begin it.
CTRL_C = re.compile(r"^user interrupted with ctrl-c \(SIGINT\)")
SIGNALLED = re.compile(r"^signal_handler\((?:signum|signal_value)=(?:2|15)\)")


def before_shutdown(lines: list[LogLine]) -> list[LogLine]:
    """The lines before the stack began to shut down (all of them when it did not). A node's own signal_handler line
    carries its stamp, so it decides by time; launch's line has none, and a node's output that its pipe held back
    (a console is written as the buffers flush) can come after it though it was logged before, so launch's line
    decides by its place only when no node printed its own."""
    signalled = next((ln for ln in lines if SIGNALLED.match(ln.msg)), None)
    if signalled is not None:
        return [ln for ln in lines if ln.t < signalled.t and not CTRL_C.match(ln.msg)]
    stop = next((i for i, ln in enumerate(lines) if CTRL_C.match(ln.msg)), None)
    return lines if stop is None else lines[:stop]
