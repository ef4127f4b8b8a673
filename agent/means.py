""""What does 'Sequences cannot be key' mean here?", "what does can't compare times with different time sources
mean?": what a line of the log means, from the catalogues mined from the sources that log it (Nav2's, ros2_control's,
MoveIt's) and the readings the explainers make of a line's own numbers or words; where none holds a meaning, the
answer says so and quotes the line, never a guess."""

from __future__ import annotations

import re

from hexar.agent.focus import pointed_lines
from hexar.agent.matters import rests_on
from hexar.events.log import EventLog
from hexar.events.records import LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.stack.bringup import TRANSITIONS
from hexar.explainers.stack.signals import ended_by

_ASKED = re.compile(r"^(and |so |but )?what (does|do|did|is) (the |that |this |a |an )?.+? (mean|means|meant|indicate|"
                    r"signify)\b|^(and |so )?what('s| is) the meaning of\b")
# "why did controller_server crash with 'double free or corruption'?": what the quoted last words mean
# (not "why did controller_server abort with 'Failed to make progress'?": a goal's abort, which the finding explains)
_CRASHED_WITH = re.compile(r"^(and |so |but )?why did .{1,60}? (crash|die|segfault)(ed)? (with|on|after "
                           r"printing|printing|saying)\b.*['\"“]")
# glibc's malloc_printerr texts (malloc/malloc.c): its allocator found the heap corrupted and aborts the process
_GLIBC_HEAP = re.compile(r"double free or corruption|malloc\(\): |free\(\): invalid|realloc\(\): invalid|"
                         r"munmap_chunk\(\): invalid pointer|"
                         r"corrupted (size vs\. prev_size|double-linked list|top size)")
_HEAP = ("glibc's memory allocator found the process's heap corrupted (memory freed twice, or written past what was "
         "allocated) and aborted the process (SIGABRT, exit code -6): a memory bug in that program or in a library or "
         "plugin it loaded. The line does not say where; a backtrace does (run the node under gdb, or read its core "
         "dump)")
# the mined catalogues' word for an entry no rule classified: no meaning to tell
_UNCLASSIFIED = "(no cause assigned)"


# "what is transition 10?": the lifecycle transition a line names by its number
_TRANSITION = re.compile(r"^(and |so )?what('s| is| was| does| do) (the |that |this )?transition (?P<n>\d+)\b")
# "what does exit code -8 mean?": launch's word for how a process ended
_EXIT_CODE = re.compile(r"^(and |so )?what('s| is| was| does| do) (an? |the |that |this )?exit code (?P<code>-?\d+)\b")
_ON_REQUEST = {2: "SIGINT (Ctrl-C, or launch stopping it)", 15: "SIGTERM (a request to stop, as a shutdown sends)"}


def means_asked(q: str) -> bool:
    """The question (lower case) asks what something it names means ("what does that mean?" asks of the answer)."""
    if _TRANSITION.search(q) or _EXIT_CODE.search(q) or _CRASHED_WITH.search(q):
        return True
    if "?" in q.rstrip(" ?"):
        return False  # "what does X mean? did controller_server die?": two questions, the finding answers both
    return _ASKED.search(q) is not None and re.search(
        r"\bwhat (does|did) (that|this|the|it)( (error|warning|line|message|log|finding|answer))? mean\W*$", q) is None


def _meaning(line: LogLine) -> str:
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit
    from hexar.explainers.navigation.catalogue import catalogue as nav
    from hexar.explainers.stack.middleware import fastdds_meaning
    from hexar.explainers.stack.thrown import rclpy_action_meaning
    from hexar.explainers.stack_causes import mixed_clocks

    mixed = mixed_clocks(line)
    if mixed is not None:
        return mixed
    if (dds := fastdds_meaning(line)):
        return dds
    if _GLIBC_HEAP.search(line.msg):
        return _HEAP
    if (rclpy := rclpy_action_meaning(line)):
        return rclpy
    for cat in (nav(), control(), moveit()):
        entry = cat.match(line.msg)
        if entry is not None and entry.meaning and _UNCLASSIFIED not in entry.meaning:
            return entry.meaning
    return ""


def means(question: str, log: EventLog, task: Task, found: Explanation | None = None) -> Explanation | None:
    """What the line the question points at means; None when it points at no line. `found`: the task's finding,
    which tells what a line it rests on means where no catalogue does."""
    q = " ".join(question.lower().split())
    if _TRANSITION.search(q) or _EXIT_CODE.search(q):
        return _number(q, log)
    lines = pointed_lines(question, log, None, by_words=True)
    if not lines:
        return None
    said = [(ln, m) for ln in lines if (m := _meaning(ln))]
    if not said:
        rested = [ln for ln in lines if found is not None and found.causes and rests_on(ln, [found])]
        ln = (rested or lines)[0]
        quoted = f"\"{' '.join(ln.msg.split())[:160]}\""
        line = f"{ln.name or 'a node'}'s {quoted} at {hms(ln.t)}"
        evidence = [Evidence.of_log("planner.plan_ok", ln)]
        if rested and found is not None:
            # "Parameter 'version' is not set. Please update your URDF": the finding's reading of it
            text = f"My catalogues hold no meaning of their own for {line}, but my finding rests on it: {found.text}"
            return found.model_copy(update={"text": text, "evidence": [*evidence, *found.evidence]})
        text = (f"My catalogues of the stack's log lines hold no meaning for {line}, so I can't tell more than its "
                "own words.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False,
                           evidence=evidence)
    ln, meaning = said[0]
    text = f"That line ({ln.name or 'a node'}, {hms(ln.t)}: \"{' '.join(ln.msg.split())[:160]}\") means: {meaning}."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", ln)])


def _transition(n: int, log: EventLog) -> Explanation | None:
    """What "transition N" of the log's lines is: a transition state a callback ran in (10 and up), or a
    transition asked of the node."""
    line = next((ln for ln in log.logs if re.search(rf"\btransition {n}\b", ln.msg)), None)
    if line is None or n not in TRANSITIONS:
        return None
    name = TRANSITIONS[n]
    what = (f"the lifecycle transition the node's callback was running in: {name} (lifecycle_msgs/msg/State's "
            f"transition state {n}; rclcpp_lifecycle numbers a callback's transition so)" if n >= 10 else
            f"the lifecycle transition asked of the node: {name} (lifecycle_msgs/msg/Transition id {n})")
    said = f"\"{' '.join(line.msg.split())[:120]}\""
    text = f"In {line.name or 'a node'}'s {said} at {hms(line.t)}, transition {n} is {what}."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", line)])


def _exit_code(code: int, log: EventLog) -> Explanation | None:
    """What launch's "exit code N" of a process's death line says of how it ended."""
    line = next((ln for ln in log.logs if re.search(rf"exit code {code}\b", ln.msg)), None)
    if line is None:
        return None
    said = f"\"{' '.join(line.msg.split())[:100]}\""
    where = f"In {line.name or 'a node'}'s {said} at {hms(line.t)}, exit code {code}"
    signal = ended_by(line.msg)
    if signal is not None:
        text = (f"{where} is signal {signal.number} ({signal.name}), negated: the process {signal.happened}. "
                f"{signal.fix}")
    elif -code in _ON_REQUEST:
        text = f"{where} is signal {-code}, negated: the process was stopped by {_ON_REQUEST[-code]}."
    elif code < 0:
        text = f"{where} is signal {-code}, negated: a signal ended the process."
    else:
        ended = "no error" if code == 0 else "an error, which its lines before it may say"
        text = f"{where} is the program's own: it returned {code} as it ended ({ended})."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", line)])


def _number(q: str, log: EventLog) -> Explanation | None:
    """What the exit code or transition number the question (lower case) asks about means; None for neither."""
    if (code := _EXIT_CODE.search(q)) is not None:
        return _exit_code(int(code["code"]), log)
    if (asked := _TRANSITION.search(q)) is not None:
        return _transition(int(asked["n"]), log)
    return None


def means_lead(question: str, log: EventLog) -> str:
    """What a number the question's first part asks about means ("what does exit code -8 mean? is it my BT?"), said
    before the finding that answers the rest; "" when it asks of none."""
    q = " ".join(question.lower().split())
    if "?" not in q.rstrip(" ?"):
        return ""
    found = _number(q, log)
    return found.text if found is not None else ""


__all__ = ["means", "means_asked", "means_lead"]
