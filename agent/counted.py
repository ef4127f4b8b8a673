""""How many times was a new path passed to the controller before 'Reached the goal!'?", "how many times did it
brake before the ctrl-c?": how often the log holds the line the question describes, counted from the log, within
the bounds the question sets (before or after a moment it names, agent/between.py's way of finding one)."""

from __future__ import annotations

import re

from hexar.agent.between import moment, moment_said
from hexar.agent.focus import ranked_lines
from hexar.events.log import EventLog
from hexar.events.records import hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation

_ASKED = re.compile(r"^(and |so |but )?how (many times|often) (was|were|did|does|do|has|had|is)\b")
_BOUND = re.compile(r"\b(before|until|till|after|since) (?P<moment>.+)$")


def count_asked(q: str) -> bool:
    """The question (lower case) asks how often something was logged."""
    return _ASKED.search(q) is not None


def counted(question: str, log: EventLog, task: Task) -> Explanation | None:
    """How many times the line the question describes was logged (within its bounds); None where no line fits."""
    q = " ".join(question.lower().split())
    bound = _BOUND.search(q)
    what = q[: bound.start()] if bound else q
    since, until, said = None, None, ""
    if bound is not None:
        at = moment(bound["moment"].strip(" ?.!,"), log, task)
        if at is not None:
            t = at if isinstance(at, int) else at.t
            since, until = (None, t) if bound.group(1) in {"before", "until", "till"} else (t, None)
            said = f" {bound.group(1)} {moment_said(at, 80)}"
    found = [ln for ln in ranked_lines(what, log, None if until is None else until - 1, by_words=True, least=1,
                                       slack=0) if since is None or ln.t > since]
    if not found:
        return None
    top = found[0]
    same = [ln for ln in log.logs if ln.name == top.name and ln.msg == top.msg
            and (until is None or ln.t < until) and (since is None or ln.t > since)]
    n = len(same)
    span = f"at {hms(same[0].t)}" if n == 1 else f"from {hms(same[0].t)} to {hms(same[-1].t)}"
    text = (f"{n} time{'s' if n != 1 else ''}{said}: {top.name or 'a node'} logged "
            f"\"{' '.join(top.msg.split())[:160]}\" {span}.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", ln) for ln in same[:3]])


__all__ = ["count_asked", "counted"]
