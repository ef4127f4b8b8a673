""""What happened at 10:33:12?", "nothing was logged between 11:14:46 and 11:15:33: what was the robot doing?",
"follow_path aborted at 21:20:46 but the goal only failed at 21:21:00, what ran in between?": a developer replaying a
run asks about a moment or a span of it by the log's own clock. The answer is what the recording holds then: the
log lines in that span (a moment: the two seconds around it), and where none was logged, that, with the last line
before and the first after, since a silent span is itself what the developer noticed. Times are UTC, as every
answer gives them; a time of day is placed on the recording's day (or the next, for a recording past midnight).
"""

from __future__ import annotations

import re
from datetime import UTC, datetime, timedelta

from hexar.agent.logs import line_evidence, quote
from hexar.events.log import EventLog
from hexar.events.records import WARN, LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation

_TIME = r"\b([01]?\d|2[0-3]):([0-5]\d)(?::([0-5]\d)(?:\.(\d{1,9}))?)?\b"
# a question that names a time of day and asks what happened or went on then
AT_TIME = re.compile(r"\b(what|why|anything|which|who|did|was|were)\b.*" + _TIME + r"|" + _TIME +
                     r".*\b(what|why|anything|which|happen\w*|going on|doing|ran|logged)\b|"
                     r"^(and |so |then )?(at|around|between|after|before) " + _TIME)
_AROUND_S = 1.0  # a moment asked about: the lines this many seconds either side of it


def window_kind(q: str) -> str | None:
    return "at_time" if AT_TIME.search(q) else None


def _times(question: str, log: EventLog) -> list[tuple[int, int]]:
    """The times of day a question names, each as (its nanosecond stamp on the recording's clock, how long it
    lasts: a second when it names seconds, else a minute)."""
    day = datetime.fromtimestamp(log.start // 1_000_000_000, tz=UTC).replace(hour=0, minute=0, second=0)
    found = []
    for m in re.finditer(_TIME, question):
        h, mi, s, frac = int(m.group(1)), int(m.group(2)), int(m.group(3) or 0), m.group(4) or "0"
        at = day + timedelta(hours=h, minutes=mi, seconds=s)
        t = int(at.timestamp()) * 1_000_000_000 + int(frac.ljust(9, "0")[:9])
        if t < log.start - 3_600_000_000_000:  # a recording past midnight: the next day's time
            t += 86_400_000_000_000
        found.append((t, 1_000_000_000 if m.group(3) is not None else 60_000_000_000))
    return sorted(found)


def _at(ln: LogLine) -> str:
    return f'{hms(ln.t)}, {ln.name or "a node"} "{" ".join(ln.msg.split())[:160]}"'


def at_time(question: str, log: EventLog, task: Task) -> Explanation:
    """The log lines in the span a question names, or that none was logged then and what came either side."""
    times = _times(question, log)
    if not times:
        return Explanation.not_enough("planner", "I could not read a time of day in that question.")
    (first, length), (last, _) = times[0], times[-1]
    around = int(_AROUND_S * 1e9)
    if first == last:
        start, end, said, what = first - around, first + length + around, f"at {hms(first)}", hms(first)
    else:  # between the two moments, neither included: "nothing was logged between" asks about the silence
        start, end = first + length, last - 1
        said, what = f"between {hms(first)} and {hms(last)}", f"{hms(first)} to {hms(last)}"
    if end < log.start or start > log.end:
        return Explanation.not_enough(
            "planner", f"My recording does not cover {what} UTC: it runs from {hms(log.start)} to {hms(log.end)}.")
    lines = [ln for ln in log.logs if start <= ln.t <= end]
    if first == last and any(not first <= ln.t < first + length for ln in lines):
        said = f"within {_AROUND_S:g} s of {hms(first)}"  # the moment's neighbours too: not said to be at it
    if not lines:
        before = next((ln for ln in reversed(log.logs) if ln.t < start), None)
        after = next((ln for ln in log.logs if ln.t > end), None)
        text = f"My log holds no line {said}."
        if before is not None:
            text += f" The last one before came at {_at(before)}"
            text += f"; the next at {_at(after)}." if after is not None else "; none came after."
        elif after is not None:
            text += f" The first one after came at {_at(after)}."
        shown = [ln for ln in (before, after) if ln is not None]
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=[Evidence.of_log("planner.plan_ok", ln) for ln in shown])
    routine = len(lines)
    loud = [ln for ln in lines if ln.level >= WARN]
    shown = loud or lines
    routine -= len(shown)
    more = f" ({routine} more at info level)" if loud and routine else ""
    text = (f"My log holds {len(lines)} line{'s' if len(lines) > 1 else ''} {said}{more}: "
            f"{quote(shown, False, True)}.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=line_evidence(shown, task))
