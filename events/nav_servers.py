"""Nav2 servers' own actions as tasks, beside the navigation goals of events/nav_goals.py.

A docking server's DockRobot goal ("Attempting to dock robot at …" to its success or abort,
explainers/navigation/docking.py) is a `dock_robot` step; the trip to the dock's staging pose that it sends
bt_navigator is part of it, not a task beside it. A behaviour server's goal ("Running spin" to "spin completed
successfully", its failure, cancel or abort, explainers/navigation/behaviors.py) that no navigation goal or docking
ran is a `run_behavior` step, as a program's spin(), backup() or driveOnHeading() asked for it; one inside a
navigation goal is that goal's recovery, which its own reading explains.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from hexar.events.records import LogLine

DOCK_SKILL = "dock_robot"
BEHAVIOR_SKILL = "run_behavior"
NO_GOAL_LINE = "Nav2 log (no goal line)"  # `derived_from` of a goal inferred from Nav2's activity alone


@dataclass
class Goal:
    start: int
    x: float | None
    y: float | None
    via: str
    end: int | None = None
    state: str = "running"
    error: str = ""
    lines: list[str] = field(default_factory=list)
    dock: str | None = None  # a DockRobot goal's dock id ("" for a dock given by its pose); None: a navigation goal
    behavior: str | None = None  # a behaviour server goal's behaviour (spin, backup, ...); None: no behaviour


def number(value: object) -> float | None:
    try:
        return float(str(value))
    except ValueError:
        return None


def _dockings(logs: list[LogLine]) -> list[Goal]:
    """The docking server's DockRobot goals: from "Attempting to dock robot at …" to its success or its abort (a
    new goal before either ends the one before, as preempted)."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.navigation.docking import ABORTED, BEGIN, DOCKED

    cat = catalogue()
    goals: list[Goal] = []
    for line in logs:
        msg = line.msg.strip()
        if line.name and cat.role(line.name) not in {"docking_server", None}:
            continue
        if (m := BEGIN.match(msg)) is not None:
            if goals and goals[-1].end is None:
                goals[-1].end, goals[-1].state = line.t, "canceled"
            goals.append(Goal(line.t, number(m["x"] or ""), number(m["y"] or ""), "Nav2 docking log",
                              dock=m["dock"] or ""))
        elif goals and goals[-1].end is None and (DOCKED.match(msg) or ABORTED.match(msg)):
            aborted = ABORTED.match(msg)
            goals[-1].end, goals[-1].state = line.t, "failed" if aborted else "succeeded"
            goals[-1].error = aborted["msg"] if aborted else ""
    return goals


def _behaviors(logs: list[LogLine]) -> list[Goal]:
    """The behaviour server's goals: from "Running <name>" to the line that ends it (a new goal before that ends
    the one before, as preempted)."""
    from hexar.explainers.navigation.behaviors import BEGIN, end_of
    from hexar.explainers.navigation.catalogue import catalogue

    cat = catalogue()
    goals: list[Goal] = []
    for line in logs:
        if line.name and cat.role(line.name) not in {"behavior_server", None}:
            continue
        if (m := BEGIN.match(line.msg.strip())) is not None:
            if goals and goals[-1].end is None:
                goals[-1].end, goals[-1].state = line.t, "canceled"
            goals.append(Goal(line.t, None, None, "Nav2 behaviour server log", behavior=m["name"]))
        elif goals and goals[-1].end is None and (end := end_of(line)) is not None and end[0] == goals[-1].behavior:
            goals[-1].end, goals[-1].state, goals[-1].error = line.t, end[1], end[2]
    return goals


def _inside(goal: Goal, others: list[Goal], last: int) -> bool:
    return any(o.start <= goal.start <= (o.end if o.end is not None else last) for o in others)


def with_server_goals(goals: list[Goal], logs: list[LogLine]) -> list[Goal]:
    """The navigation goals, the dockings and the behaviour goals no navigation goal or docking ran, in time order;
    without the trips a docking sent (those that began inside it), or a goal inferred from Nav2's activity alone
    where a docking or a behaviour goal shows what the robot did."""
    docks = _dockings(logs)
    last = max((ln.t for ln in logs), default=0)
    if docks:
        goals = [g for g in goals if g.via != NO_GOAL_LINE and not _inside(g, docks, last)] + docks
    shown = [g for g in goals if g.via != NO_GOAL_LINE]
    # navigation at work outside every goal shown: a goal whose begin and end the recording lacks, whose recoveries
    # the behaviours are
    from hexar.explainers.navigation.behaviors import navigating

    behaviors = [b for b in _behaviors(logs) if not _inside(b, shown, last)]
    if behaviors and any(navigating(ln) and not any(g.start <= ln.t <= (g.end if g.end is not None else last)
                                                    for g in shown) for ln in logs):
        behaviors = []
    if behaviors:
        goals = shown + behaviors
    return sorted(goals, key=lambda g: g.start)
