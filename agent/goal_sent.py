""""Did a goal ever get sent, or was the navigation task never really started?": whether the recording shows the goal
itself, from how the task was found. A task of /task_info was given as recorded; a goal derived from Nav2's,
MoveIt's or the controllers' goal lines or action statuses shows its own start (the navigator's "Begin navigating
…", a server's "Received request", an accepted goal's status); one derived from errors alone ("no goal line",
events/nav_goals.py and arm_goals.py) shows none, and the answer says so, never that a goal was sent."""

from __future__ import annotations

import re

from hexar.agent.logs import line_evidence, quote
from hexar.events.log import EventLog
from hexar.events.records import ERROR, LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

SENT = re.compile(
    r"\b(did|was|were|has|had) (any |a |the |my |an )?(navigation |nav |nav2 |arm |moveit |trajectory )?"
    r"(goals?|task) (ever |actually |really |even )*(get |got |been |being )?(sent|received|arrived?|accepted|"
    r"came in|come in|given)\b|"
    r"\b(goal|task) (was |were )?never (really |actually |even )?(started|sent|received|given)\b")
_NONE = "no goal line"


def goal_sent_kind(q: str) -> str | None:
    return "goal_sent" if SENT.search(q) else None


def _begin(log: EventLog, task: Task) -> LogLine | None:
    """The goal line the derived task began with: a line of a catalogue's kind begin at the task's start."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit
    from hexar.explainers.navigation.catalogue import catalogue as nav2

    for line in log.logs:
        if line.t > task.created:
            break
        if line.t == task.created and any((e := cat.match(line.msg)) is not None and e.kind.startswith("begin")
                                          for cat in (nav2(), moveit(), control())):
            return line
    return None


def goal_sent(question: str, log: EventLog, task: Task) -> Explanation:
    """Whether the recording shows the task's goal sent, and by what."""
    run = task.skills[0] if task.skills else None
    via = str(run.params.get("derived_from", "")) if run is not None else ""
    if not task.derived:
        text = f"Yes: I was given the task \"{task.instruction}\" at {hms(task.created)} (my /task_info)."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence([], task))
    if _NONE in via:
        errors = [ln for ln in log.logs if ln.t >= task.created and ln.level >= ERROR][:1]
        text = ("No line of my log shows a goal sent or received (no navigator's \"Begin navigating …\", no action "
                "server's accepted goal, no goal status): I took the task from what my nodes logged, not from a "
                "goal")
        text += f"; its first error: {quote(errors, False, True)}." if errors else "."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence(errors, task))
    began = _begin(log, task)
    if began is not None:
        text = f"Yes: the goal came at {hms(began.t)}: {quote([began], False, False)}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence([began], task))
    if "status" in via.lower():
        text = f"Yes: the goal's action status shows it accepted at {hms(task.created)}."
    elif log.logs and task.created <= log.logs[0].t:
        text = ("My log shows the goal under way from its first line on, but not its start: it was sent before the "
                "recording began.")
    else:
        text = f"Yes: the goal began at {hms(task.created)}, as my log shows it."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=line_evidence([], task))


__all__ = ["SENT", "goal_sent", "goal_sent_kind"]
