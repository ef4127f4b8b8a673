"""Nav2 servers' own actions as tasks, beside the navigation goals of events/nav_goals.py.

A docking server's DockRobot goal ("Attempting to dock robot at …" to its success or abort,
explainers/navigation/docking.py) is a `dock_robot` step; the trip to the dock's staging pose that it sends
bt_navigator is part of it, not a task beside it. A behaviour server's goal ("Running spin" to "spin completed
successfully", its failure, cancel or abort, explainers/navigation/behaviors.py) that no navigation goal or docking
ran is a `run_behavior` step, as a program's spin(), backup() or driveOnHeading() asked for it; one inside a
navigation goal is that goal's recovery, which its own reading explains.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace

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


@dataclass(frozen=True)
class Span:
    """One goal of a Nav2 server, read from its lines: the line that began it, the line that ended it (None while it
    ran on), and how it ended."""

    begin: LogLine
    end: LogLine | None = None
    state: str = "running"
    error: str = ""


Begins = Callable[[LogLine], bool]
Ends = Callable[[LogLine, LogLine], tuple[str, str] | None]  # (begin, line): (state, error) if `line` ends it


def spans(logs: list[LogLine], role: str, begins: Begins, ends: Ends) -> list[Span]:
    """A server's goals in `logs`, from a line `begins` reads to one `ends` reads for it (the server's lines, or an
    unknown logger's); a new goal before that ends the one before, as preempted."""
    from hexar.explainers.navigation.catalogue import catalogue

    cat = catalogue()
    out: list[Span] = []
    for line in logs:
        if line.name and cat.role(line.name) not in {role, None}:
            continue
        if begins(line):
            if out and out[-1].end is None:
                out[-1] = replace(out[-1], end=line, state="canceled")
            out.append(Span(line))
        elif out and out[-1].end is None and (ended := ends(out[-1].begin, line)) is not None:
            out[-1] = replace(out[-1], end=line, state=ended[0], error=ended[1])
    return out


def _goal(span: Span, via: str, xy: tuple[float | None, float | None] = (None, None), dock: str | None = None,
          behavior: str | None = None) -> Goal:
    return Goal(span.begin.t, *xy, via, span.end.t if span.end is not None else None, span.state, span.error,
                dock=dock, behavior=behavior)


def _dockings(logs: list[LogLine]) -> list[Goal]:
    """The docking server's DockRobot goals: from "Attempting to dock robot at …" to its success or its abort."""
    from hexar.explainers.navigation import docking

    goals = []
    for span in spans(logs, "docking_server", docking.begins, docking.ends):
        m = docking.BEGIN.match(span.begin.msg.strip())
        assert m is not None
        xy = number(m["x"] or ""), number(m["y"] or "")
        goals.append(_goal(span, "Nav2 docking log", xy, dock=m["dock"] or ""))
    return goals


def _behaviors(logs: list[LogLine]) -> list[Goal]:
    """The behaviour server's goals: from "Running <name>" to the line that ends it."""
    from hexar.explainers.navigation import behaviors

    return [_goal(span, "Nav2 behaviour server log", behavior=behaviors.name_of(span.begin))
            for span in spans(logs, "behavior_server", behaviors.begins, behaviors.ends)]


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
