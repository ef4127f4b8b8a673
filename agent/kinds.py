"""The content questions answered from the recording alone ("how far did you drive?", "what was your plan?",
"where is the kitchen?"), each kind by one function of (question, log, task); the content node (agent/nodes.py)
answers the kinds that also ask an explainer itself (the errors, a flag, a try again, what I was doing)."""

from __future__ import annotations

import re
from collections.abc import Callable

from hexar.agent import content, measures, sequence
from hexar.agent.all_up import all_up
from hexar.agent.between import before_one, between
from hexar.agent.counted import counted
from hexar.agent.flags import battery, speed_limit
from hexar.agent.focus import with_pointed
from hexar.agent.goal_sent import goal_sent
from hexar.agent.logs import nodes, stated_spans
from hexar.agent.means import means
from hexar.agent.mentions import mentions
from hexar.agent.moved import moved
from hexar.agent.named_task import named_tasks
from hexar.agent.node_status import node_status
from hexar.agent.person import person
from hexar.agent.places import at_place, goal, place, reached, when_at, where_failed
from hexar.agent.plugins import plugins
from hexar.agent.recording import clock, recorded, topic_data
from hexar.agent.skills import skills
from hexar.agent.step_status import step_status
from hexar.agent.unnamed import unnamed
from hexar.agent.window import at_time
from hexar.events.log import EventLog
from hexar.events.records import duration, hms
from hexar.events.tasks import WHOLE, Task
from hexar.explainers.base import Explanation

Answer = Callable[[str, EventLog, Task], Explanation]


def _with_spans(told: Explanation, log: EventLog, task: Task) -> Explanation:
    return told.model_copy(update={"text": told.text + stated_spans(log, task)})


def _topic_data(question: str, log: EventLog, task: Task) -> Explanation:
    """What the recording holds on the topics asked about; where it holds none, the log lines that name the thing
    ("Timed out waiting for transform from base_link to odom") say what the topic cannot."""
    told = topic_data(question, log, task)
    if told.enough_information:
        return told
    pointed = with_pointed(told.text, question, log, task)  # "Received amcl_pose": the topic's name in a line
    if pointed != told.text:
        return told.model_copy(update={"text": pointed})
    named = mentions(question, log, task)
    if not named.enough_information:
        return told
    return told.model_copy(update={"text": f"{told.text} {named.text}", "evidence": [*named.evidence, *told.evidence]})


_AFTER_LAUNCH = re.compile(r"\bafter (the |my )?(launch|start|starting|bring-?up|startup)\b")


def _after_launch(question: str, told: Explanation, log: EventLog, task: Task) -> Explanation:
    """'How many seconds after launch did the goal fail?': the task's times, and how long after the log's first
    line (launch's, at the bring-up) it began."""
    first = log.logs[0] if log.logs else None
    if first is None or not _AFTER_LAUNCH.search(question.lower()) or first.t > task.created:
        return told
    said = f"{first.name or 'a node'}: \"{' '.join(first.msg.split())[:80]}\""
    return told.model_copy(update={"text": f"{told.text} I began {duration(task.created - first.t)} after my log's "
                                           f"first line ({hms(first.t)}, {said})."})


def _between(question: str, log: EventLog, task: Task) -> Explanation:
    """The time between two moments the question names by their lines; where the log names either of them in no
    line, the task's times (of a recording with no task, what its log says of the things named)."""
    found = between(question, log, task)
    if found is not None:
        return found
    return mentions(question, log, task) if task.task_id == WHOLE else _long(question, log, task)


def _means(question: str, log: EventLog, task: Task) -> Explanation:
    """What the line the question points at means; where it points at none, what the log says of the things it
    names."""
    return means(question, log, task) or mentions(question, log, task)


def _counted(question: str, log: EventLog, task: Task) -> Explanation:
    """How often the line the question describes was logged; where no line fits, what the log says of the things
    the question names."""
    return counted(question, log, task) or mentions(question, log, task)


def _long(question: str, log: EventLog, task: Task) -> Explanation:
    """The task's time and its steps'; of several tasks asked about together ("the first two waypoints"), each
    task's time."""
    several = named_tasks(question.lower(), log)
    if several:
        return measures.long_each(log, several)
    if before_one(" ".join(question.lower().split())):  # "how long was it stuck before the first planning error?"
        found = between(question, log, task)
        if found is not None:
            return found
    return _with_spans(measures.long(log, task), log, task)


FROM_RECORDING: dict[str, Answer] = {
    "where": lambda q, log, task: content.where(log),
    "failed_at": where_failed,
    "goal": goal,
    "reached": reached,
    "went": content.went,
    "far": lambda q, log, task: measures.far(log, task, q),
    "fast": lambda q, log, task: measures.fast(log, task),
    "start": lambda q, log, task: measures.start(log, task),
    "long": _long,
    "when": lambda q, log, task: _after_launch(q, when_at(q, log, task), log, task),
    "at_place": at_place,
    "route": lambda q, log, task: measures.far(log, task),
    "tasks": lambda q, log, task: sequence.tasks(log),
    "request": sequence.request,
    "place": place,
    "person": person,
    "limit": speed_limit,
    "battery": battery,
    "plan": lambda q, log, task: sequence.plan(log, task, counted="how many" in q.lower()),
    "nodes": nodes,
    "plugins": plugins,
    "said": content.said,
    "clock": clock,
    "recorded": recorded,
    "topic_data": _topic_data,
    "at_time": at_time,
    "node_status": node_status,
    "all_up": all_up,
    "goal_sent": goal_sent,
    "unnamed": unnamed,
    "moved": moved,
    "skills": skills,
    "step": step_status,
    "between": _between,
    "count": _counted,
    "means": _means,
}
