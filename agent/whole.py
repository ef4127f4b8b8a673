"""Questions about a recording that holds no task: no /task_info, no goal and no start of the robot read from its
logs. Such a recording is refused for what needs a task ("what happened?", "why did it fail?": the one-line "no task
to explain" error), but what it did record answers a question about that: the lines of a moment, a node, a topic,
the nodes' parameters, and the lines a developer's question points at ("why does it say class ... does not
exist?"). Those are answered over the whole recording (events/tasks.py, WHOLE), saying that it holds no task.
"""

from __future__ import annotations

from hexar.agent.focus import pointed_lines, with_repeats
from hexar.agent.logs import line_evidence, quote
from hexar.agent.matters import asks_matters
from hexar.agent.parameters import asks_parameters
from hexar.events.log import EventLog
from hexar.events.records import ERROR, duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

# the content kinds a recording answers without a task (agent/kinds.py): what it holds, not what a task did
RECORDING_WIDE = frozenset({"at_time", "node_status", "all_up", "unnamed", "recorded", "clock", "topic_data", "nodes",
                            "plugins", "mentions", "logs", "between", "count", "means"})
NO_TASK = ("My recording holds no task of mine (no /task_info, no goal, no start of my drivers or controllers in its "
           "logs), so I can't tell what I was doing")


def answerable(question: str, kind: str | None, log: EventLog) -> bool:
    """Whether a question can be answered from a recording with no task: its kind is the recording's, it asks for
    parameters, or it points at log lines."""
    return kind in RECORDING_WIDE or asks_parameters(question, log) or \
        bool(pointed_lines(question, log, by_words=True))


def lines_answer(question: str, log: EventLog, task: Task) -> Explanation:
    """The lines the question points at, said as what the log holds of it, with no task to explain."""
    lines = pointed_lines(question, log, by_words=True)
    if not lines:
        return Explanation.not_enough("planner", f"{NO_TASK}, and no line of my log names what you asked.")
    shown = with_repeats(lines, log)
    text = f"{NO_TASK}, but my log says of what you asked: {quote(shown, False, True)}."
    if asks_matters(question):  # "are these warnings harmful?": what came after them, with no task to judge by
        last = max(shown, key=lambda ln: ln.t)
        errors = [ln for ln in log.logs if ln.t > last.t and ln.level >= ERROR]
        after = ("and holds no error after it" if not errors else
                 f"and the first error after it is {quote(errors[:1], False, True)}")
        text += (f" The last of them came at {hms(last.t)}; my log goes on for {duration(log.end - last.t)} after it "
                 f"without another, {after}.")
    return Explanation(explainer="planner", causes=["planner.plan_ok"], evidence=line_evidence(shown, task),
                       text=text)
