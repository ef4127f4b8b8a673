"""The task a question names when a recording holds several: "why did the goal to (9, 4) fail?", "how long did the
second waypoint take?", "how long did the first two goals take each?". Without a name the latest task is meant."""

from __future__ import annotations

import re

from hexar.events.log import EventLog
from hexar.events.tasks import Task

# a goal's coordinates as people copy them from a log or a table: "(9, 4)", "(9.00, 4.00)", "to 9, 4"
_XY = re.compile(r"(?:\(|\b(?:to|at|goal|towards?) )\s*(-?\d+(?:\.\d+)?)\s*,\s*(-?\d+(?:\.\d+)?)\s*\)?")
_WHAT = r"(goal|waypoint|navigation|nav goal|trajectory|motion|move|errand|request|task|run|attempt)s?"
_NTH = {"first": 1, "1st": 1, "second": 2, "2nd": 2, "third": 3, "3rd": 3, "fourth": 4, "4th": 4, "fifth": 5,
        "5th": 5}
_ORDINAL = re.compile(r"\b(first|1st|second|2nd|third|3rd|fourth|4th|fifth|5th|last|final|previous|earlier)"
                      r"( [a-z_]+)? " + _WHAT + r"\b")
_COUNT = {"two": 2, "three": 3, "four": 4, "five": 5, "2": 2, "3": 3, "4": 4, "5": 5}
# "the first two waypoints", "each goal", "all the goals", "both goals"
_SEVERAL = re.compile(r"\b(first|last) (two|three|four|five|[2-5]) ([a-z_]+ )?" + _WHAT + r"\b|"
                      r"\b(each|every|all( the| of the)?|both)( [a-z_]+)? " + _WHAT + r"\b|"
                      # "which leg took the longest?" of a run of several goals compares them all
                      r"\b(which|what)( one)?( of (the|my|your)( [a-z0-9]+)?)? (leg|goal|waypoint|run|trip)s? "
                      r"(took|was) (the )?(longest|slowest|quickest|shortest|fastest)\b")
# close enough to be the same goal: logs print two decimals, people round
_SAME = 0.051


def _user(log: EventLog) -> list[Task]:
    return [t for t in log.tasks if not t.is_recovery]


def _goal_xy(task: Task) -> list[tuple[float, float]]:
    spots = []
    for run in task.skills:
        x, y = run.params.get("x"), run.params.get("y")
        if isinstance(x, (int, float)) and isinstance(y, (int, float)):
            spots.append((float(x), float(y)))
    return spots


def named_task(question: str, log: EventLog) -> Task | None:
    """The one task a question (lower case) names by its goal's coordinates or by its order, when the recording
    holds more than one; None when it names none (the default task is meant) or the name fits none."""
    tasks = _user(log)
    if len(tasks) < 2:
        return None
    for m in _XY.finditer(question):
        x, y = float(m.group(1)), float(m.group(2))
        named = [t for t in tasks if any(abs(x - gx) < _SAME and abs(y - gy) < _SAME for gx, gy in _goal_xy(t))]
        if named:
            return max(named, key=lambda t: t.last_update)
    nth = _ORDINAL.search(question)
    if nth is None or _SEVERAL.search(question):
        return None
    word = nth.group(1)
    if word in {"last", "final"}:
        return tasks[-1]
    if word in {"previous", "earlier"}:
        return tasks[-2]
    n = _NTH[word]
    return tasks[n - 1] if n <= len(tasks) else None


def named_tasks(question: str, log: EventLog) -> list[Task]:
    """The tasks a question (lower case) asks about together ("the first two waypoints", "each goal"), in order;
    empty when it asks about one."""
    tasks = _user(log)
    m = _SEVERAL.search(question)
    if m is None or len(tasks) < 2:
        return []
    if m.group(1):
        n = min(_COUNT[m.group(2)], len(tasks))
        return tasks[:n] if m.group(1) == "first" else tasks[-n:]
    return tasks


__all__ = ["named_task", "named_tasks"]
