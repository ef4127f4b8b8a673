""""Is the arm broken?", "is it my fault?": a yes-or-no question about where a failure lies, answered from where its
cause lies (causes.yaml's `origin`) and then the failure as its explainer tells it, instead of the failure alone with
no answer to the question. The robot says only what its recording shows: a set-up problem is not a broken part, and
a person's doing is not told as the asker's."""

from __future__ import annotations

import re

from hexar.agent.content import task_name
from hexar.agent.context import RunContext
from hexar.agent.probes import finding
from hexar.agent.state import AgentState
from hexar.causes import BENIGN, vocabulary
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

_LEAD = r"^(and |so |but |ok |okay |then )?"
_THING = (r"(it|the robot|robot|something|anything|(the |my |your |its )?(arm|gripper|hand|base|wheels?|motors?|"
          r"robot|hardware|sensors?|camera|lidar|laser|speaker|battery|joints?|drivers?))")
_PART = r"(you|" + _THING + ")"  # "did you break anything?" asks about the house, not about the robot's parts
_BROKEN = (r"(broken|broke|damaged|faulty|defective|dead|bust(ed)?|kaput|out of order|malfunctioning|"
           r"not working( properly)?)")
BROKEN = re.compile(
    _LEAD + r"(is|are|was|were|has|have) " + _PART + r" (been )?(still )?" + _BROKEN + r"\b|"
    + _LEAD + r"(did|has|have) " + _THING + r" (break|broken|broke)( down)?\b|"
    + _LEAD + r"(is|was) (it|this|that) (a |an )?(hardware|mechanical|electrical) "
              r"(problem|issue|fault|failure|error)\b|"
    + _LEAD + r"(do|does|will) " + _PART + r" need (a |to be )?(repair(ed|ing|s)?|fix(ed|ing)|servic(e|ed|ing)|"
              r"replac(ed|ing))\b|"
    + _LEAD + r"(is|was) (there )?(something|anything) (broken|wrong) with " + _PART + r"\b|"
    + _LEAD + r"(are|were) you (ok|okay|alright|all right|fine|hurt|injured|unhurt|unharmed|in one piece)\W*$")
FAULT = re.compile(
    _LEAD + r"(is|was|it's|its) (it|this|that|all|everything)? ?(my|our) fault\b|"
    + _LEAD + r"(is|was) (it|this|that) (because of|down to) me\b|"
    + _LEAD + r"did (i|we) (do|make) (something|anything|a mistake|a thing) ?(wrong)?\b|"
    + _LEAD + r"(did|have) (i|we) (break|broken|mess(ed)? (it|up)|cause(d)? (it|this|that))\b|"
    + _LEAD + r"(whose|who's|who is|who was) (fault|to blame)\b|who (caused|is responsible for|was responsible for)\b|"
    + _LEAD + r"was (it|this|that) (someone|somebody|anyone)'?s fault\b|"
    # "should I phrase the book request differently next time?": whether the request was to blame
    + _LEAD + r"should (i|we) (have )?(phrase[d]?|word(ed)?|say|said|ask(ed)?|put) (it |that |my request |the [a-z]+ "
              r"request |my [a-z]+ request |the request )?differently\b")

LOST = re.compile(_LEAD + r"(did|were|was|are) (you|it|the robot) (get |getting )?(lost|confused about where)\b|"
                  + _LEAD + r"did (you|it|the robot) (know|lose track of) where (you|it) (were|was)\b")
# The causes that say I did not know where I was (navigation's localisation findings).
_LOST_CAUSES = frozenset({"navigation.poor_localisation", "navigation.off_costmap"})

# Per origin of the failure's cause: the answer's opening to each question, before the failure as told.
_IS_BROKEN = {
    "hardware": "Possibly: my recording shows a device of mine failing, which can be the device itself or only its "
                "cable, power or port; it cannot tell which.",
    "setup": "Nothing in my recording says a part of me is broken: what went wrong lies in how my software is set "
             "up, which is fixed without a repair.",
    "own": "No part of me is broken, as far as my recording shows: the mistake was my own.",
    "request": "No part of me is broken, as far as my recording shows: what you asked needs more than I can do.",
    "surroundings": "Nothing in my recording says a part of me is broken: what stopped me was around me.",
    "person": "Nothing in my recording says a part of me is broken: what stopped me was a person's doing.",
    "state": "Nothing in my recording says a part of me is broken.",
    "unknown": "I can't tell from my recording whether a part of me is broken.",
}
_IS_FAULT = {
    "person": "My recording shows what a person did, not who it was.",
    "request": "You did nothing wrong, as far as my recording shows, but what you asked needs more than I can do.",
    "own": "No: as far as my recording shows, the mistake was my own.",
}
_NOT_FAULT = "Nothing in my recording says you did anything wrong."


def health_kind(q: str) -> str | None:
    """'broken', 'fault' or 'lost' for a question (lower case, spaces collapsed) about where a failure lies."""
    if BROKEN.search(q):
        return "broken"
    if LOST.search(q):
        return "lost"
    return "fault" if FAULT.search(q) else None


def origin(found: Explanation) -> str:
    """Where the finding's causes lie: the first known origin among them ("my navigation to the person failed"
    lies where the blocked path that failed it lies), 'none' when nothing went wrong, else 'unknown'."""
    causes = [c for c in found.causes if c not in BENIGN]
    if not causes:
        return "none"
    known = vocabulary()
    return next((o for c in causes if c in known and (o := known[c].origin) != "unknown"), "unknown")


def health(ctx: RunContext, state: AgentState, task: Task, kind: str) -> Explanation:
    """The answer to "is the arm broken?", "is it my fault?" or "did you get lost?" (`kind`, see health_kind): where
    the failure's cause lies, then the failure (whose evidence "why?" goes on to). A task without a failure or a
    notable finding says that nothing went wrong."""
    broken = kind == "broken"
    found = finding(ctx, state)
    where = origin(found) if found is not None and found.enough_information else "unknown"
    if found is None or where == "none":
        ended = {"succeeded": "went without a problem", "running": "has gone without a problem so far"}.get(
            task.outcome, "shows no problem")
        lead = "Nothing went wrong" if kind == "fault" else "Nothing in my recording says so"
        text = f"{lead}: {task_name(task, ctx.log)} {ended}."
        return Explanation(explainer=found.explainer if found else "planner", text=text,
                           causes=list(found.causes) if found else ["planner.plan_ok"],
                           evidence=list(found.evidence) if found else [])
    if kind == "lost":
        opening = "Yes." if set(found.causes) & _LOST_CAUSES else "Nothing in my recording says I was lost."
    else:
        opening = _IS_BROKEN[where] if broken else _IS_FAULT.get(where, _NOT_FAULT)
    return found.model_copy(update={"text": f"{opening} {found.text}"})
