""""Did you hit anything?", "what was in the way?": questions about what the robot's recording cannot hold (a touch,
what an obstacle was). Said so first, then the finding that the recording does support, instead of that finding
as if it answered them."""

from __future__ import annotations

import re

from hexar.agent.content import task_name
from hexar.agent.context import RunContext
from hexar.agent.places import where_failed
from hexar.agent.probes import finding
from hexar.agent.state import AgentState
from hexar.causes import BENIGN
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

_LEAD = r"^(and |so |but |ok |okay )?"
CONTACT = re.compile(_LEAD + r"(did|have) (you|the arm|your arm|the gripper|the robot) (hit|bump(ed)? into|run into|"
                     r"ran into|crash(ed)? into|collide with|"
                     r"touch|knock(ed)? (over|into)|drive into|drove into) (anything|something|anyone|someone|"
                     r"somebody|anybody|it|that|a [a-z]+|the [a-z]+)\b")
WHAT_BLOCKED = re.compile(_LEAD + r"what (was|were|is) (in (the|your|my) way|blocking (you|your path|the way|the "
                          r"path)|the (obstacle|obstruction|blockage))\b|"
                          + _LEAD + r"what (blocked|stopped) (you|your path|the way|the path)\b|"
                          + _LEAD + r"what (was|is) (ahead of|in front of) (you|me|the robot)\b|"
                          + _LEAD + r"what (kind of|sort of)? ?(obstacle|thing|object) (was it|blocked you)\b|"
                          + _LEAD + r"(was|is) (the|a) door (closed|shut|open|locked)\b|"
                          + _LEAD + r"where (was|is|were|are) (the|that|this) (obstacles?|obstructions?|blockages?|"
                          r"things? in (the|your|my) way)\b")
# The findings that tell of a collision check stopping me: the nearest the recording comes to a touch.
_CHECKED = frozenset({"navigation.collision_ahead"})


def unseen_kind(q: str) -> str | None:
    """'contact' or 'blocked' for a question (lower case, spaces collapsed) the recording cannot answer itself."""
    if CONTACT.search(q):
        return "contact"
    return "blocked" if WHAT_BLOCKED.search(q) else None


def unseen(ctx: RunContext, state: AgentState, task: Task, kind: str) -> Explanation:
    """What the recording cannot show (`kind`, see unseen_kind), then the task's failure (or its notable finding) as
    its explainer tells it."""
    found = finding(ctx, state)
    q = state["question"].lower()
    door = kind == "blocked" and re.search(r"\bdoor\b", q) is not None
    where = kind == "blocked" and not door and re.match(r"(\w+ )?where\b", q) is not None
    if kind == "contact":
        opening = "I can't tell: my recording holds no bumper or contact sensor."
        if found is not None and set(found.causes) & _CHECKED:
            opening += " What it holds is that a collision check stopped me first."
    elif door:
        opening = ("I can't tell whether a door was closed: my recording holds no camera image or door sensor, only "
                   "what my navigation logged.")
    else:
        opening = (f"I can't tell {'where' if where else 'what'} it was: my recording holds no camera image or object "
                   "detection, only what my navigation logged.")
    if found is None or set(found.causes) <= BENIGN:
        named = task_name(task, ctx.log)
        ended = " went without a problem." if task.outcome == "succeeded" else " shows no problem in my recording."
        if kind == "blocked" and not door:
            opening = "My recording shows nothing in my way."
        text = f"{opening} {named[0].upper()}{named[1:]}{ended}"
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    if where:  # the nearest the recording comes: where I was when it failed
        at = where_failed(state["question"], ctx.log, task)
        if at.enough_information:
            return found.model_copy(update={"text": f"{opening} {found.text} {at.text}",
                                            "evidence": [*found.evidence, *at.evidence]})
    return found.model_copy(update={"text": f"{opening} {found.text}"})
