"""The navigation explainer's log filter.

Kept: every line the Nav2 message catalogue recognises by its text (whatever its logger: namespaced,
Foxy/Galactic names, `*_rclcpp_node` helpers, `DWBLocalPlanner`, TF helpers, or a logger we never heard of),
the other lines of loggers whose Nav2 role is known, the navigation skills' lines, and warnings and errors of
loggers with no known role (an unknown logger's decisive line reaches the LLM even when the catalogue lacks it).
Dropped: lines holding a known noise substring that the catalogue gives no cause, and a line equal to the
previous kept line of the same logger (Nav2 repeats e.g. `Passing new path to controller.` at every 1 Hz replan;
one copy says as much as twenty).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import TYPE_CHECKING

from hexar.events.records import WARN, LogLine
from hexar.explainers.navigation.catalogue import Entry, catalogue
from hexar.explainers.stack.bringup import client_gave_up

if TYPE_CHECKING:
    from hexar.explainers.navigation.detectors import Run

# The loggers of the original HEXAR filter (hexar_interfaces.md); roles now cover their other spellings.
NAV2_LOGGERS: frozenset[str] = frozenset({
    "amcl", "global_costmap.global_costmap", "local_costmap.local_costmap", "behavior_server",
    "planner_server", "controller_server", "bt_navigator",
})
SKILL_LOGGERS: frozenset[str] = frozenset({"skill_navigate_to_zone", "skill_navigate_to_pose"})
KEPT_LOGGERS: frozenset[str] = NAV2_LOGGERS | SKILL_LOGGERS
# Roles whose every line is worth reading; TF helpers and map servers only through recognised lines.
KEPT_ROLES: frozenset[str] = frozenset({
    "bt_navigator", "planner_server", "controller_server", "behavior_server", "costmap", "amcl",
    "collision_monitor", "docking_server", "smoother_server", "velocity_smoother", "waypoint_follower",
})
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

# nav2_behavior_tree/plugins/condition/is_goal_nearby_condition.cpp:46@main: the behaviour tree's condition warns
# "Path is empty" under bt_navigator's logger when the planner gave it no path; the controller's own "Path is
# empty." (nav2_controller/src/controller_server.cpp:631@jazzy) is thrown by the controller server
_TREE_NO_PATH = re.compile(r"^Path is empty$")

def kept(line: LogLine) -> tuple[bool, Entry | None]:
    """Whether the line is worth reading, and its catalogue entry."""
    cat = catalogue()
    entry = cat.match(line.msg)
    if is_noise(line.msg):
        return False, entry
    if entry is not None or line.name in KEPT_LOGGERS:
        return True, entry
    role = cat.role(line.name)
    if role is None and line.level >= WARN:
        return True, entry  # a warning of a logger we never heard of may be the decisive line: never drop it unread
    return role in KEPT_ROLES, entry


def filter_logs(lines: Iterable[LogLine]) -> list[LogLine]:
    """The lines worth reading, in time order."""
    return [line for line, _ in tag_logs(lines)]


def tag_logs(lines: Iterable[LogLine]) -> list[tuple[LogLine, Entry | None]]:
    """The lines worth reading, with what the catalogue says of each."""
    out: list[tuple[LogLine, Entry | None]] = []
    previous: dict[str, str] = {}
    seen: list[LogLine] = []
    for line in lines:
        keep, entry = kept(line)
        seen.append(line)
        if entry is not None and entry.id == "launch.process_died" and client_gave_up(line, seen):
            entry = None  # a spawner that found no controller manager: read, never a node that failed to come up
        if entry is not None and entry.id == "ctrl.carrot" and _TREE_NO_PATH.match(line.msg) \
                and catalogue().role(line.name) == "bt_navigator":
            entry = None  # the tree's IsGoalNearby found no path (no plan was made), not a controller that failed
        # each "Failed to make progress" is one aborted FollowPath, so its copies count; other repeats say nothing new
        if not keep or (previous.get(line.name) == line.msg and (entry is None or entry.kind != "progress")):
            continue
        previous[line.name] = line.msg
        out.append((line, entry))
    return out


def weak_noise(lines: Iterable[LogLine]) -> list[tuple[LogLine, Entry]]:
    """Noise lines the catalogue still counts as weak evidence (e.g. the TF message filter dropping scans)."""
    cat = catalogue()
    out = []
    for line in lines:
        if is_noise(line.msg):
            entry = cat.match(line.msg)
            if entry is not None and entry.cause is not None:
                out.append((line, entry))
    return out


# tf2_ros's MessageFilter logs every message it drops at INFO (signalFailure, RCLCPP_INFO "Message Filter dropping
# message: frame '%s' at time %.3f for reason '%s'", tf2_ros/include/tf2_ros/message_filter.h:708@rolling,
# :706@humble) and warns only when more than 95% of the messages of a 15 s period were dropped (checkFailures,
# "Dropped %.2f%% of messages so far", :611-623@rolling). A few INFO drops are routine (a scan older than the
# transform cache at start-up); many of them, or any at WARN and above, are a transform fault.
_DROP = "Message Filter dropping message"
MANY_DROPS = 10


def routine_drops(noise: list[tuple[LogLine, Entry]], run: Run) -> list[tuple[LogLine, Entry]]:
    """The noise lines that are evidence for this run: INFO message-filter drops only on a goal that failed or
    never ended (a stalled one), from the goal's begin line on where the window shows it (the start-up's drops,
    before the transform cache filled, are routine), or in numbers; a goal that succeeded or that the window does
    not show is not explained by a few routine drops."""
    drops = [ln for ln, _ in noise if _DROP in ln.msg and ln.level < WARN]
    if len(drops) >= MANY_DROPS:
        return noise
    stalled = run.outcome == "unknown" and run.begin is not None
    if run.outcome == "failed" or stalled:
        since = run.begin.t if run.begin is not None else None
        return [(ln, e) for ln, e in noise
                if since is None or ln.t >= since or not (_DROP in ln.msg and ln.level < WARN)]
    return [(ln, e) for ln, e in noise if not (_DROP in ln.msg and ln.level < WARN)]


