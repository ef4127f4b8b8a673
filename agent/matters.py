""""Is the 'Map update loop missed its desired rate' warning anything to worry about?", "is the SHM error related to
the robot not moving?", "does rm-2 dying with exit code 1 matter?": whether the lines a developer names are what the
finding rests on, said first, before the finding and the lines themselves (agent/focus.py).

Said from what the recording shows, never from what such a line usually means: a goal that went through after the
line was not stopped by it; a failure whose evidence holds the line rests on it; one whose evidence does not, does
not rest on it (which the answer says as that, not as "unrelated"); a line after the failure came too late to cause
it."""

from __future__ import annotations

import re

from hexar.agent.focus import pointed_lines, with_repeats
from hexar.agent.measures import worked_until
from hexar.events.log import EventLog
from hexar.events.records import LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

_ASKED = re.compile(
    r"\b(anything|something) to (worry|be worried) about\b|\bshould i (worry|be worried|care)\b|"
    r"\b(is|are|was|were) [^?]{0,160}?\b(a problem|harmful|harmless|a concern|serious|dangerous|benign|"
    r"related to|connected to|linked to|to blame|the (root )?(cause|reason|culprit)|(just |only |merely )?(a |an )?"
    r"(side[- ]effect|knock[- ]on( effect)?|follow[- ]on( effect)?|consequence|symptom|noise)s?)\b|"
    r"\b(does|do|did) [^?]{0,160}?\b(matter|hurt|harm|have anything to do with|have to do with|cause (it|this|that|"
    r"the))\b|\bcan (i|it|this|that|these|those) be (safely )?ignored\b|\bcan i (safely )?ignore\b|"
    r"\bsafe to ignore\b|"
    # "is the inflation radius error what caused the planning failure?", "is X something I must handle as an error?"
    r"\b(is|are|was|were) [^?]{0,160}?\bwhat (caused|made|broke|stopped|killed)\b|"
    r"\b(handle|treat|count|see) (it |this |that |them |these |those )?as an? (error|failure|fault|bug)\b")
# what names a line: a quote, or the words for one
# ("the ROSInterruptException", "that RuntimeError": an exception by its class)
_NAMES_A_LINE = re.compile(r"['\"‘“]|\b(warn(ing)?s?|errors?|messages?|lines?|exit code|dying|died|dies|crash(ed|es)?|"
                           r"traceback|exception|fatal)\b|\b\w+(exception|error)s?\b")
_FINE = {"succeeded"}


def asks_matters(question: str) -> bool:
    """The question (any case) asks whether lines it names matter to what happened."""
    q = " ".join(question.lower().split())
    return _ASKED.search(q) is not None and _NAMES_A_LINE.search(q) is not None


def rests_on(line: LogLine, found: list[Explanation]) -> bool:
    """A finding's evidence holds the line (its time and words)."""
    words = " ".join(line.msg.split())[:60]
    return any(ev.t == line.t and words in " ".join(ev.item.split()) for e in found for ev in e.evidence)


def matters_lead(question: str, log: EventLog, task: Task, found: list[Explanation]) -> str:
    """The first sentence of the answer to "is this line a problem?": empty when the question names no line of
    the log or asks something else."""
    if not asks_matters(question):
        return ""
    end = worked_until(log, task)
    lines = pointed_lines(question, log, None, by_words=task.derived)
    if not lines:
        return ""
    named = lines[0]
    times = len(with_repeats([named], log))
    alike = f", the first of {times} alike" if times > 1 else ""
    when = f"the line you name ({named.name or 'a node'}, {hms(named.t)}{alike})"
    if task.outcome in _FINE:
        if named.t > end:
            return f"Not for this task: {when} came after it had already ended well."
        return f"Not for this task: it went through after {when}, so that line stopped nothing."
    if task.outcome == "canceled":
        return f"Not as a failure: the task was stopped from outside, not by {when}, and nothing failed before that."
    if task.outcome in {"running", "waiting"}:
        return f"It had not stopped the task when the recording ends: {when} came, and the task was still under way."
    if any(rests_on(ln, found) for ln in lines):
        # "a real bug or just a side effect?" asks two things: no bare yes for it
        yes = "" if re.search(r"\bor\b", question.lower()) else "Yes: "
        said = f"{yes}{when} is among the lines my finding below rests on."
        return said[:1].upper() + said[1:]
    if named.t > end + 1_000_000_000:  # a second: a failure's own lines come in the same moment as its end
        return f"Not as its cause: {when} came after the task had already ended, at {hms(end)}."
    if any(c.endswith(".unexplained_failure") for e in found for c in e.causes):
        # a finding that names no cause rests on no line that could rule this one out
        return f"I can't tell from my logs whether {when} is: my finding below names no cause for sure."
    return (f"My finding below does not rest on {when}: the lines it rests on are others, so the log does not show "
            "that line as the cause.")


__all__ = ["asks_matters", "matters_lead"]
