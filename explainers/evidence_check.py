"""Does a cited evidence item really exist in the recording? Grading and tests use this, not string trust."""

from __future__ import annotations

import math
import re

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.explainers.base import Evidence

_PAIR = re.compile(r"([A-Za-z_][\w ]*?)\s*=\s*(\[[^\]]*\]|[^,;]+)")


def _same(recorded: str, cited: str) -> bool:
    recorded, cited = recorded.strip(), cited.strip()
    if recorded == cited or recorded.startswith(cited.rstrip(".")):
        return True
    try:
        return math.isclose(float(recorded), float(cited), rel_tol=0.01, abs_tol=0.01)
    except ValueError:
        return False


def _pairs(item: str) -> list[tuple[str, str]]:
    return [(k.strip().split(" ")[-1], v) for k, v in _PAIR.findall(item)]


def exists(log: EventLog, ev: Evidence) -> bool:
    """True when a message on `ev.topic` at exactly `ev.t` shows what `ev.item` says."""
    if ev.topic in c.LOG_SOURCES:
        return any(line.t == ev.t and line.origin == ev.topic and line.render() == ev.item for line in log.logs)
    if ev.topic == c.TASK_INFO:
        return any(u.t == ev.t and (ev.item in u.raw or ev.item == u.instruction or ev.item in u.task_error_msg)
                   for u in log.task_updates)
    if ev.topic == c.AMCL_POSE:
        cited = dict(_pairs(ev.item.replace(" ", ", ")))
        for p in log.poses:
            if p.t == ev.t:
                have = {"x": p.x, "y": p.y, "cov_xy": p.cov_xy, "cov_yaw": p.cov_yaw}
                return all(k not in have or _same(str(have[k]), v) for k, v in cited.items())
        return False
    if ev.topic in log.flags:
        return any(s.t == ev.t and str(s.value) in ev.item for s in log.flags[ev.topic])
    if ev.topic in log.statuses:
        pairs = _pairs(ev.item)
        for rec in log.statuses[ev.topic]:
            if rec.t != ev.t:
                continue
            values = dict(rec.values)
            if pairs and all(k in values and _same(values[k], v) for k, v in pairs):
                return True
            if rec.message and rec.message in ev.item and not pairs:
                return True
        return False
    return False
