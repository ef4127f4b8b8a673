"""The navigation explainer's log filter, as the original HEXAR defines it (hexar_interfaces.md).

Kept: lines of the Nav2 loggers and of the navigation skills. Dropped: lines holding a known noise substring,
and a line equal to the previous kept line of the same logger (Nav2 repeats e.g. `Passing new path to
controller.` at every 1 Hz replan; one copy says as much as twenty).
"""

from __future__ import annotations

from collections.abc import Iterable

from hexar.events.records import LogLine

NAV2_LOGGERS: frozenset[str] = frozenset({
    "amcl", "global_costmap.global_costmap", "local_costmap.local_costmap", "behavior_server",
    "planner_server", "controller_server", "bt_navigator",
})
SKILL_LOGGERS: frozenset[str] = frozenset({"skill_navigate_to_zone", "skill_navigate_to_pose"})
KEPT_LOGGERS: frozenset[str] = NAV2_LOGGERS | SKILL_LOGGERS
NOISE: tuple[str, ...] = (
    "KeepoutFilter",
    "SpeedFilter",
    "missed its desired rate",
    "Client requested to cancel the goal. Cancelling",
    "Goal was canceled. Stopping the robot",
    "The /scan observation buffer has not been updated",
    "Message Filter dropping message",
    "Optimizer reset",
)


def is_noise(msg: str) -> bool:
    return any(pattern in msg for pattern in NOISE)


def filter_logs(lines: Iterable[LogLine]) -> list[LogLine]:
    """The lines worth reading, in time order."""
    kept: list[LogLine] = []
    previous: dict[str, str] = {}
    for line in lines:
        if line.name not in KEPT_LOGGERS or is_noise(line.msg):
            continue
        if previous.get(line.name) == line.msg:
            continue
        previous[line.name] = line.msg
        kept.append(line)
    return kept
