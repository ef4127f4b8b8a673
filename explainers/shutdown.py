"""Where a robot's stack began to shut down in its lines: what it prints on the way down is no cause of what
happened before (navigation and the module explainers alike)."""

from __future__ import annotations

import re

from hexar.events.records import LogLine

# A stack being stopped prints its own warnings and errors on the way down (a message filter dropping what came in
# as the transforms went away, launch escalating to SIGKILL and "process has died [..., exit code -9]"): none of it
# explains what happened before. Its beginning, by the lines that say so:
# - by their stamps, a node's own: rclcpp's when the node gets SIGINT or SIGTERM (signal_handler.cpp,
#   "signal_handler(signum=%d)" from Galactic on, "signal_handler(signal_value=%d)" in Foxy), and Nav2 servers' when
#   their contexts shut down (nav2_util lifecycle_node.cpp, "Running Nav2 LifecycleNode rcl preshutdown (%s)") from
#   the second server on: one server alone says it when it ends itself over an error of its own, which the others'
#   lines after it still tell about;
# - by their stamps too, where none of the others is there, a node's destructor, which runs only as its process ends
#   in order (rclcpp shut down, by a signal or by the program itself), after whatever the node logged of an error of
#   its own, and after the signal (so it is the last of these marks to come): rclcpp_lifecycle's
#   "LifecycleNode is not shut down: Node still in state(%u) in destructor" (lifecycle_node.cpp:159@rolling), Nav2's
#   "Destroying" (nav2_util lifecycle_node.cpp) and its lifecycle manager's "Destroying %s" (lifecycle_manager.cpp);
#   not "Destroying plugin ..." nor "Destroying bond ...", which a cleanup or deactivation at run time prints too;
# - by their place, launch's (it prints no stamp): Ctrl-C reaching it (launch_service.py, "user interrupted with
#   ctrl-c (SIGINT)") and its signal to a process it stops (execute_local.py, "sending signal '%s' to process[%s]"),
#   which a paste of a console's last lines may hold without the Ctrl-C above them.
CTRL_C = re.compile(r"^user interrupted with ctrl-c \(SIGINT\)")
SIGNALLED = re.compile(r"^signal_handler\((?:signum|signal_value)=(?:2|15)\)")
PRESHUTDOWN = re.compile(r"^Running Nav2 LifecycleNode rcl preshutdown \(")
DESTRUCTOR = re.compile(r"^(?:LifecycleNode is not shut down: Node still in state\(\d+\) in destructor|"
                        r"Destroying(?: [\w/]+)?)\s*$")
_BY_PLACE = re.compile(rf"{CTRL_C.pattern}|^sending signal '(?:SIGINT|SIGTERM|SIGKILL)' to process\[")


def before_shutdown(lines: list[LogLine]) -> list[LogLine]:
    """The lines before the stack began to shut down (all of them when it did not). A node's own line carries its
    stamp, so it decides by time; launch's have none, and a node's output that its pipe held back (a console is
    written as the buffers flush) can come after them though it was logged before, so launch's lines decide by their
    place only when no node printed its own."""
    marks = [ln.t for ln in lines if SIGNALLED.match(ln.msg)]
    servers: dict[str, int] = {}
    for ln in lines:
        if PRESHUTDOWN.match(ln.msg):
            servers.setdefault(ln.name, ln.t)
    if len(servers) > 1:
        marks.append(sorted(servers.values())[1])
    if marks:
        return [ln for ln in lines if ln.t < min(marks) and not _BY_PLACE.match(ln.msg)]
    stop = next((i for i, ln in enumerate(lines) if _BY_PLACE.match(ln.msg)), None)
    if stop is not None:
        return lines[:stop]
    # a destructor runs after the signal, as the node's process ends: the latest of these marks, used where none
    # of the others is there; its own stamp is kept, for what the node logged in the same instant came before it
    # (map_saver's "Failed to save the map: timeout", then its "Destroying", as it ends itself)
    ends = [ln.t for ln in lines if DESTRUCTOR.match(ln.msg)]
    return [ln for ln in lines if ln.t <= min(ends)] if ends else lines
