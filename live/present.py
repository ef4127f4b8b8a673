"""What a live answer says that an answer about a recorded run does not.

The explainers word their answers for a run that is over and kept on disk ("the recording does not show whether I
reached the goal"). A person asking the robot at home hears them while the robot is still at it: there is no
recording to them, a task that has not ended is going on now rather than cut off, and a question asked before
the robot was given any task deserves a spoken answer, not a developer's error that nobody hears.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from hexar.causes import BENIGN
from hexar.events.log import last_error
from hexar.events.records import LogLine
from hexar.events.tasks import Task
from hexar.live.contact import ENDED, Contact, annotate
from hexar.live.log import NS

# Longest phrases first: each later one would also match inside an earlier one's text.
_HEARD = tuple((re.compile(pattern, re.IGNORECASE), words) for pattern, words in (
    (r"\bas far as (?:the|this|my) recording shows\b", "as far as I heard"),
    (r"\bthat (?:the|this|my) recording shows\b", "that I heard of"),
    # a goal or a trip with no end yet, on a link that held (contact's note tells one that did not): under way
    (r"\bmy last goal was ([^;]+); (?:the|this|my) recording does not show whether I got there\b",
     r"I'm on my way to \1; I have not heard that I got there yet"),
    (r"\b(?:the|this|my) recording ends while I was still on my way\b", "I'm still on my way"),
    (r"\b(?:the|this|my) recording ends while\b", "the last I heard,"),
    (r"\bwhen (?:the|this|my) recording ends\b", "when I last heard of it"),
    (r"\b(?:the|this|my) recording ends\b", "what I have heard so far ends"),
    (r"\b(?:in|from) (?:the|this|my) recording\b", "in what I heard"),
    (r"\b(?:the|this|my) recording\b", "what I heard"),
))
# Quoted log lines and values are the robot's own words and stay as they were printed.
_QUOTED = re.compile(r'("[^"]*"|“[^”]*”)')


def heard_words(text: str) -> str:
    """The answer as the live node says it: "what I heard" where a recorded run's answer says "the recording",
    outside quotes, with a sentence's first letter kept capital."""
    parts = _QUOTED.split(text)
    for i in range(0, len(parts), 2):  # even parts lie outside quotes
        for pattern, words in _HEARD:
            parts[i] = pattern.sub(lambda m, w=words: _case(m.group(0), m.expand(w)), parts[i])
    return "".join(parts)


def _case(found: str, words: str) -> str:
    return words[0].upper() + words[1:] if found[:1].isupper() else words


def present(result: dict[str, Any], tasks: Iterable[Task], newest: int) -> None:
    """An answer about a task that has not ended, with no problem found and no hole in what the node heard
    (contact's note covers those): the robot is still at it, so it says where it is instead of "I don't have
    enough information", which for a run on disk means the recording stopped too early. An answer that already
    tells what the robot is doing (a benign cause: where it is going, its plan) is left as it is. `newest`: the
    robot's clock at the node's latest record."""
    task = next((t for t in tasks if t.task_id == result.get("task_id")), None)
    causes = list(result.get("causes") or ())
    if (task is None or task.outcome in ENDED or result.get("contact") or result.get("error")
            or any(cause not in BENIGN for cause in causes)):
        return
    if causes and result.get("enough_information") is not False:
        result["running"] = True
        return
    # a task derived from a Nav2 or MoveIt goal has no request of a person's, only the goal's own words
    what = f'your request "{task.instruction}"' if task.instruction.strip() and not task.derived else "it"
    running = next((r for r in task.skills if r.state == "running"), None)
    if running is None:
        lead = f"I'm still working on {what}: I haven't heard its first step start yet."
    else:
        from hexar.explainers.recorded import step_ref

        since = running.time_of("running") or running.last_change
        steps = f" of {len(task.skills)}" if len(task.skills) > 1 else ""
        ref = step_ref(running).replace(" (to", f"{steps} (to", 1)
        lead = f"I'm still working on {what}: I'm at {ref}, for {max(0, newest - since) / NS:.0f} s so far."
    if result.get("enough_information") is False:
        result["answer"] = f"{lead} Nothing I heard so far says anything went wrong."
    else:
        result["answer"] = f"{lead} {result['answer']}"
    result["running"] = True


def shape(result: dict[str, Any], tasks: list[Task], contact: Contact | None, newest: int) -> None:
    """An answer as a live page or node gives it: the holes in what was heard (live/contact.py), a task still
    going on told as such, and "what I heard" where an answer about a recorded run says "the recording"."""
    if contact is not None:
        annotate(result, tasks, contact)
    present(result, tasks, newest)
    if result.get("answer"):
        result["answer"] = heard_words(str(result["answer"]))


def no_task_yet(logs: Iterable[LogLine]) -> str:
    """The spoken answer to a question asked before the robot had any task the node heard of; the last error
    line it heard is quoted (never told as a cause), as the no-task error quotes it for a developer."""
    error = last_error(list(logs))
    said = "I haven't had a task since I started listening, so there is nothing I did that I can explain yet."
    if error:
        said += " The last error I heard " + error.removeprefix("; the last error it logged ") + "."
    return said


def no_task_answer(logs: Iterable[LogLine], error: Exception, thread: str | None) -> dict[str, Any]:
    """The whole answer to a question asked before any task: no_task_yet's words for the person, the developer's
    reason kept in "error", and no evidence."""
    return {"answer": no_task_yet(logs), "error": str(error), "no_task": True, "thread": thread, "evidence": []}


__all__ = ["heard_words", "no_task_answer", "no_task_yet", "present", "shape"]
