"""Causes read from Nav2's own words (the message catalogue) and from odometry, for a goal that did not succeed.

Evidence decides: a cause is claimed only when lines (or recorded motion) that support it are in the window.
The explainer takes strong lines in the order of `ORDER` (a bring-up or TF fault explains the planner and
controller failures it causes; a goal outside the map explains the planner's "no valid path"); weak lines (e.g.
the TF message filter dropping scans, which many healthy robots print at start-up) count only when no strong
line supports any cause. `Failed to make progress` alone is reported as what it is: no progress, cause not
logged.
"""

from __future__ import annotations

from dataclasses import dataclass

from hexar.events.records import LogLine, OdomSample, TwistSample
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.catalogue import Entry

GOAL_UNREACHABLE = "navigation.goal_unreachable"
OFF_COSTMAP = "navigation.off_costmap"
TRANSFORM = "navigation.transform_error"
NOT_REACHING_BASE = "navigation.commands_not_reaching_base"
CONFIGURATION = "navigation.configuration_error"
COLLISION_AHEAD = "navigation.collision_ahead"
CONTROLLER = "navigation.controller_failure"
DOCKING = "navigation.docking_failure"
NO_PROGRESS = "navigation.no_progress"
BLOCKED = "navigation.blocked_path"
POOR_LOCALISATION = "navigation.poor_localisation"
START_IN_OBSTACLE = "navigation.start_in_obstacle"
BRINGUP = "navigation.bringup_failure"

# A node that never came up explains everything after it; then the stack's faults in the order in which one
# produces the next (a TF fault makes the planner and controller fail; a start on occupied cells or a goal outside
# the map makes planning fail).
ORDER = (BRINGUP, CONFIGURATION, TRANSFORM, POOR_LOCALISATION, OFF_COSTMAP, START_IN_OBSTACLE, GOAL_UNREACHABLE,
         DOCKING, BLOCKED, COLLISION_AHEAD, CONTROLLER, NOT_REACHING_BASE)
MAX_EVIDENCE = 4

# Motion thresholds for "commanded but did not move": Nav2's default progress checker wants 0.5 m in 10 s.
CMD_MIN = 0.05  # m/s or rad/s commanded
ODOM_STILL = 0.02  # m/s measured
MIN_COMMANDED_S = 3.0


@dataclass(frozen=True)
class Tagged:
    line: LogLine
    entry: Entry


def supporting(tagged: list[Tagged], cause: str, strength: str | None = None) -> list[LogLine]:
    return [t.line for t in tagged if t.entry.cause == cause and (strength is None or t.entry.strength == strength)]


def evidence(cause: str, lines: list[LogLine]) -> list[Evidence]:
    """The first and the last distinct supporting lines (a flood of one warning says as much as two copies)."""
    distinct = list({ln.msg: ln for ln in lines}.values())
    picks = distinct[:MAX_EVIDENCE - 1] + ([distinct[-1]] if len(distinct) >= MAX_EVIDENCE else [])
    return [Evidence.of_log(cause, ln) for ln in picks]


@dataclass(frozen=True)
class Stall:
    """Commanded motion that the odometry did not show."""

    commanded_s: float
    max_cmd: float
    max_odom: float
    first: TwistSample
    last: TwistSample
    odom: OdomSample


def stalled(cmds: list[TwistSample], odom: list[OdomSample]) -> Stall | None:
    """Commands above CMD_MIN for at least MIN_COMMANDED_S while every odometry sample of that time is still."""
    moving = [c for c in cmds if abs(c.vx) > CMD_MIN or abs(c.vy) > CMD_MIN or abs(c.wz) > CMD_MIN]
    if len(moving) < 2 or not odom:
        return None
    lo, hi = moving[0].t, moving[-1].t
    if (hi - lo) / 1e9 < MIN_COMMANDED_S:
        return None
    during = [o for o in odom if lo <= o.t <= hi]
    if len(during) < 2:
        return None
    fastest = max(during, key=lambda o: max(abs(o.vx), abs(o.wz)))
    speed = max(abs(fastest.vx), abs(fastest.wz))
    travelled = max(abs(o.x - during[0].x) + abs(o.y - during[0].y) for o in during)
    if speed > ODOM_STILL or travelled > 0.05:
        return None
    top = max(max(abs(c.vx), abs(c.vy), abs(c.wz)) for c in moving)
    return Stall((hi - lo) / 1e9, top, speed, moving[0], moving[-1], fastest)
