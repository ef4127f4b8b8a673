""""Did all the nav2 lifecycle nodes come up before the goal arrived?", "did everything come up?": whether the
bring-up finished, from the lifecycle managers' own words. Nav2's lifecycle manager logs "Managed nodes are active"
once every node it manages is active (nav2_lifecycle_manager/src/lifecycle_manager.cpp), and "Failed to bring up all
requested nodes" or "Failed to change state for node" when one was not; the mined Nav2 catalogue holds both. Where
neither was logged, the answer says the log does not show it, never that the nodes came up."""

from __future__ import annotations

import re

from hexar.agent.logs import line_evidence, quote
from hexar.events.log import EventLog
from hexar.events.records import LogLine, duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

ALL_UP = re.compile(
    r"^(and |so |but )?(did|have|had|were|are) (all|every)( of)? (the |my |your )?([a-z0-9_]+ ){0,2}"
    r"(nodes?|servers?)( \w+)? (come|came|get|got|start(ed)?|brought|go|went|become|became|been)"
    r"( up| active| started| configured)?\b|"
    r"^(and |so |but )?did (everything|the (whole |nav2 |navigation )?(stack|bring-?up)) (come up|start( up)?|"
    r"finish)\b|"
    # "did the lifecycle manager ever finish bringing up all the nav2 nodes?"
    r"\b(finish(ed)?|complete(d)?) (bringing up|the bring-?up|starting up)\b")
# the mined Nav2 catalogue's ids for the lifecycle manager's end of a bring-up
_DONE, _FAILED = "lm.active", "lm.bringup_failed"
_BEFORE = re.compile(r"\bbefore (the |my |a )?goal\b")


def all_up_kind(q: str) -> str | None:
    return "all_up" if ALL_UP.search(q) else None


def _said(line: LogLine) -> str | None:
    from hexar.explainers.navigation.catalogue import catalogue

    entry = catalogue().match(line.msg)
    return entry.id if entry is not None and entry.id in (_DONE, _FAILED) else None


def _begins(line: LogLine) -> bool:
    from hexar.explainers.navigation.catalogue import catalogue

    entry = catalogue().match(line.msg)
    return entry is not None and entry.kind == "begin"


def active_lines(log: EventLog) -> list[LogLine]:
    """The lifecycle managers' "Managed nodes are active" lines, in time order."""
    return [ln for ln in log.logs if _said(ln) == _DONE]


def all_up(question: str, log: EventLog, task: Task) -> Explanation:
    """Whether the lifecycle managers said their nodes came up, and when against the goal's start."""
    said = [(ln, kind) for ln in log.logs if (kind := _said(ln)) is not None]
    failed = [ln for ln, kind in said if kind == _FAILED]
    done = [ln for ln, kind in said if kind == _DONE]
    if failed and (not done or failed[-1].t > done[-1].t):
        text = f"No: my log shows a bring-up that failed: {quote(failed[:2], False, True)}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence(failed[:2], task))
    if not done:
        text = ("My log holds no lifecycle manager's word that its nodes are active (\"Managed nodes are active\") "
                "and none that a bring-up failed, so it does not show whether they all came up.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    first = done[0]
    text = f"Yes: {first.name or 'the lifecycle manager'} logged \"Managed nodes are active\" at {hms(first.t)}"
    if len(done) > 1:
        text += f" ({len(done)} times, the last at {hms(done[-1].t)})"
    if failed:
        text += f", after a bring-up that had failed ({quote(failed[:1], False, True)})"
    if _BEFORE.search(question.lower()):
        goal = next((ln for ln in log.logs if _begins(ln)), None)
        if goal is None:
            text += ("; my log holds no line of a goal arriving (Nav2's \"Begin navigating …\"), so I can't say "
                     "whether that was before one")
        else:
            gap = goal.t - done[-1].t
            text += (f", {duration(gap)} before the goal arrived" if gap >= 0 else
                     f", {duration(-gap)} after the goal arrived") + f" ({quote([goal], False, True)})"
    return Explanation(explainer="planner", text=text + ".", causes=["planner.plan_ok"],
                       evidence=line_evidence(done[-1:], task))


__all__ = ["ALL_UP", "all_up", "all_up_kind"]
