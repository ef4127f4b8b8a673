"""A controller manager whose cycles ran on a clock that did not advance.

With use_sim_time the controller manager triggers its cycles on the ROS clock ("Using ROS clock for triggering
controller manager cycles.", controller_manager.cpp:739@kilted; "Steady (Monotonic)" otherwise), which advances
only as /clock does. A switch of controllers is done by the update cycle; one that "timed out after N seconds"
(:2395) after that line is a cycle that never ran: nothing published /clock (no simulator, or one paused), so no
controller was activated. The same timeout on the steady clock stays the catalogue's activation failure.
"""

from __future__ import annotations

import re

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.module_wording import verbatim

CAUSE = "bringup.configuration_error"
_ROS_CLOCK = re.compile(r"^Using ROS clock for triggering controller manager cycles")
_TIMED_OUT = re.compile(r"^Switch controller timed out after")


def stalled(lines: list[LogLine]) -> tuple[LogLine, LogLine] | None:
    """(the ROS clock line, the first switch that timed out after it), else None."""
    clock = next((ln for ln in lines if _ROS_CLOCK.match(ln.msg)), None)
    if clock is None:
        return None
    timed_out = next((ln for ln in lines if ln.t >= clock.t and _TIMED_OUT.match(ln.msg)), None)
    return (clock, timed_out) if timed_out is not None else None


def answer(explainer: str, found: tuple[LogLine, LogLine]) -> Explanation:
    clock, timed_out = found
    return Explanation(
        explainer=explainer, causes=[CAUSE], confidence=0.8,
        evidence=[Evidence.of_log(CAUSE, clock), Evidence.of_log(CAUSE, timed_out)],
        text=("My controllers could not be started because my controller manager ran its cycles on simulated time "
              "(use_sim_time) and never received a clock: nothing published /clock, so no cycle ran and no switch "
              f"of controllers could complete: {verbatim(timed_out)}."),
        fix=("Start the simulator that publishes /clock (and unpause it), or run ros2_control_node without "
             "use_sim_time on a real robot."),
        details=["With use_sim_time the controller manager's update loop waits for /clock to advance."])
