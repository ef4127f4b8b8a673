""""What does 'Sequences cannot be key' mean here?", "what does can't compare times with different time sources
mean?": what a line of the log means, from the catalogues mined from the sources that log it (Nav2's, ros2_control's,
MoveIt's) and the readings the explainers make of a line's own numbers or words; where none holds a meaning, the
answer says so and quotes the line, never a guess."""

from __future__ import annotations

import re

from hexar.agent.focus import pointed_lines
from hexar.events.log import EventLog
from hexar.events.records import LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation

_ASKED = re.compile(r"^(and |so |but )?what (does|do|did|is) (the |that |this |a |an )?.+? (mean|means|meant|indicate|"
                    r"signify)\b|^(and |so )?what('s| is) the meaning of\b")
# the mined catalogues' word for an entry no rule classified: no meaning to tell
_UNCLASSIFIED = "(no cause assigned)"


def means_asked(q: str) -> bool:
    """The question (lower case) asks what something it names means ("what does that mean?" asks of the answer)."""
    if "?" in q.rstrip(" ?"):
        return False  # "what does X mean? did controller_server die?": two questions, the finding answers both
    return _ASKED.search(q) is not None and re.search(
        r"\bwhat (does|did) (that|this|the|it)( (error|warning|line|message|log|finding|answer))? mean\W*$", q) is None


def _meaning(line: LogLine) -> str:
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit
    from hexar.explainers.navigation.catalogue import catalogue as nav
    from hexar.explainers.stack_causes import mixed_clocks

    mixed = mixed_clocks(line)
    if mixed is not None:
        return mixed
    for cat in (nav(), control(), moveit()):
        entry = cat.match(line.msg)
        if entry is not None and entry.meaning and _UNCLASSIFIED not in entry.meaning:
            return entry.meaning
    return ""


def means(question: str, log: EventLog, task: Task) -> Explanation | None:
    """What the line the question points at means; None when it points at no line."""
    lines = pointed_lines(question, log, None, by_words=True)
    if not lines:
        return None
    said = [(ln, m) for ln in lines if (m := _meaning(ln))]
    if not said:
        ln = lines[0]
        text = (f"My catalogues of the stack's log lines hold no meaning for {ln.name or 'a node'}'s "
                f"\"{' '.join(ln.msg.split())[:160]}\" at {hms(ln.t)}, so I can't tell more than its own words.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False,
                           evidence=[Evidence.of_log("planner.plan_ok", ln)])
    ln, meaning = said[0]
    text = f"That line ({ln.name or 'a node'}, {hms(ln.t)}: \"{' '.join(ln.msg.split())[:160]}\") means: {meaning}."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence.of_log("planner.plan_ok", ln)])


__all__ = ["means", "means_asked"]
