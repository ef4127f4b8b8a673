""""And then?", "what did you do after that?": what the robot did after the task being talked about (its own
recovery, the next request), and "what tasks did you have?": the recording's tasks in order. Told from /task_info
(or the goals read from Nav2's logs), never from a failure nobody asked about."""

from __future__ import annotations

import re

from hexar.agent.content import task_name
from hexar.agent.measures import recorded_until
from hexar.agent.objects import step_place
from hexar.agent.overview import steps_summary
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.planner import step_outcome
from hexar.explainers.recorded import plan_words, sentence, step_ref

_LEAD = r"^(and |so |ok |okay |but )?"
AFTER = re.compile(
    _LEAD + r"(and )?then( what)?\W*$|"
    + _LEAD + r"what (did you do|happened|did you) (next|after( that| this| it)?|then|afterwards)\b|"
    + _LEAD + r"what (came|comes) (next|after)( that| this)?\W*$|"
    + _LEAD + r"(and )?after (that|this)\W*$")
TASKS = re.compile(
    _LEAD + r"(how many|what|which) (tasks|jobs|errands|requests) (did you (have|do|get|run)|were there|have you (had|"
    r"done))\b|" + _LEAD + r"what (was|were) (your|the) (first|second|third|last|other) (task|request|job)s?\b|"
    + _LEAD + r"(list|show me) (your|the|all) tasks\b")

_OUTCOME = {"succeeded": "done", "failed": "failed", "invalid": "rejected before it started",
            "canceled": "canceled", "running": "still under way when the recording ends",
            "waiting": "not started when the recording ends"}


def _ending(task: Task) -> str:
    failed = task.failed_skill
    if failed is not None:
        return f"failed at {step_ref(failed)}"
    return _OUTCOME.get(task.outcome, task.outcome)


_DID = {"succeeded": "and I did it", "failed": "and it failed", "invalid": "but it was rejected before it started",
        "canceled": "but it was canceled", "running": "and it was still under way when the recording ends",
        "waiting": "but it had not started when the recording ends"}


def _did(task: Task) -> str:
    """What a task did, briefly: each of its steps when it has several, else its one step and how it ended."""
    summary = steps_summary(task)
    if summary or not task.skills:
        return summary
    return sentence(f"My plan was to {plan_words(task)}, {_DID.get(task.outcome, task.outcome)}")


def next_task(log: EventLog, task: Task) -> Task | None:
    return min((t for t in log.tasks if t.order > task.order), key=lambda t: t.order, default=None)


def after(log: EventLog, task: Task, reason: Explanation | None = None) -> Explanation:
    """The next task of the recording after `task`, or that nothing came after it. `reason`: why the robot did the
    next task (the failure a recovery task recovers from), which "why?" then goes on to."""
    later = sorted((t for t in log.tasks if t.order > task.order), key=lambda t: t.order)
    name = task_name(task, log)
    if not later:
        end = hms(recorded_until(log, task))
        text = (f"Nothing more: {name} was the last task in my recording, which ends at {end} UTC." if
                task.outcome not in {"running", "waiting"} else
                f"Nothing more: {name} was still under way when my recording ends, at {end} UTC.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.last_update,
                                              item=f"task {task.order}: {_item(task, log)} {task.outcome}")])
    nxt = later[0]
    gap = (nxt.created - task.last_update) / 1e9
    when = "Right after that" if gap < 5 else f"{round(gap)} s later"
    text = f"{when}, I started on {task_name(nxt, log)}. {_did(nxt)}".strip()
    if len(later) > 1:
        text += f" {len(later) - 1} more task{'s' if len(later) > 2 else ''} came after it."
    evidence = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=nxt.created,
                         item=f"task {nxt.order}: {_item(nxt, log)}")]
    if reason is None:
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)
    return reason.model_copy(update={"text": text, "evidence": [*reason.evidence, *evidence],
                                     "details": [reason.text, *reason.details]})


def _item(task: Task, log: EventLog) -> str:
    return task.instruction or task_name(task, log)


def tasks(log: EventLog) -> Explanation:
    """Every task of the recording, in order, with how each ended."""
    listed = sorted(log.tasks, key=lambda t: t.order)
    parts = [f"{t.order}. {task_name(t, log)}, {_ending(t)}" for t in listed]
    head = "I had one task in this recording: " if len(listed) == 1 else \
        f"I had {len(listed)} tasks in this recording: "
    text = head + (parts[0].split(". ", 1)[1] if len(listed) == 1 else "; ".join(parts)) + "."
    if len(listed) > 1:
        text += " Ask me about one with \"what about task 2?\"."
    return Explanation(explainer="planner", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=t.created,
                                          item=f"task {t.order}: {_item(t, log)} {t.outcome}") for t in listed])


DOING = re.compile(
    # not "what were you doing standing in the kitchen for so long?", which asks where the time went (a measure)
    _LEAD + r"what were you (doing|up to|working on|in the middle of)( when| at the time| then| at that (time|point)|"
    r" before| right before)?\b(?![^?]*\b(so long|that long|such a long time|ages)\b)|"
    + _LEAD + r"what was happening when\b|"
    + _LEAD + r"what step (was it|were you|did (you|it) (fail|stop|give up))\b|"
    + _LEAD + r"(at )?which step (did it|did you) (fail|stop|give up)\b")


def doing(log: EventLog, task: Task) -> Explanation:
    """"What were you doing when it failed?": the step under way when the task failed (or when the recording
    ends, of a task still going), where the robot was for it and for how long."""
    failed = task.failed_skill
    going = next((r for r in task.skills if r.state == "running"), None)
    run = failed or going
    if run is None or (start := run.time_of("running")) is None:
        summary = steps_summary(task) or sentence(f"My plan was to {plan_words(task)}, {_DID.get(task.outcome, '')}")
        lead = "Nothing failed. " if task.outcome == "succeeded" else ""
        return Explanation(explainer="planner", text=f"{lead}{summary}".strip(), causes=["planner.plan_ok"],
                           evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created,
                                              item=task.instruction or task_name(task, log))])
    end = run.time_of("failed") or run.last_change if failed is not None else recorded_until(log, task)
    ran = duration(end - start)
    if failed is not None:
        text = (f"When it failed at {hms(end)} UTC, I was at {step_ref(run)}{step_place(task, run)}, "
                f"{ran} into it.")
    else:
        text = (f"At {hms(end)} UTC, when my recording ends, I was at {step_ref(run)}"
                f"{step_place(task, run)}, {ran} into it.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=h.t,
                                          item=f"step {run.index + 1}: {run.label()} {h.status.strip().lower()}")
                                 for h in run.history if h.status.strip().lower() in {"running", "failed"}])


PLAN = re.compile(
    _LEAD + r"what( is| was|'s| were) (your|the|my) (plan|steps|plan of action)\b(?! (for )?(tomorrow|next|now|"
    r"later|today))|"
    + _LEAD + r"what (were|are) you (supposed|meant|going|planning|trying|told) to do\b|"
    + _LEAD + r"what did you (plan|intend|mean) to do\b|"
    + _LEAD + r"(tell me|show me|list|give me) (your|the) (plan|steps)\b|"
    + _LEAD + r"how many steps (did|does|were|was|are) (there|it|you|your plan|the plan)( have| in (it|the plan))?\b")


_ONE_STEP = {"succeeded": "I did it.", "failed": "It failed.", "invalid": "It never started.",
             "canceled": "It was canceled.", "running": "It was still under way when the recording ends.",
             "waiting": "It had not started when the recording ends."}


def plan(log: EventLog, task: Task, counted: bool = False) -> Explanation:
    """"What was your plan?": the task's steps as planned (`counted`: how many first), then what became of them; a
    goal read from the logs is said to be no plan of the robot's own."""
    name = task_name(task, log)
    said = next((u for u in reversed(task.updates) if u.instruction == task.instruction), task.updates[-1])
    # a recovery task has no request: its first step's own words, as recorded, stand for it
    item = task.instruction or next((v for run in task.skills for v in run.params.values()
                                     if isinstance(v, str) and v), "")
    evidence = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=said.t, item=item)] if item else []
    if not task.skills:
        why = f": {task.error_msg}" if task.error_msg else ""
        text = f"I had no plan for {name}: it held no steps{why}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)
    if task.derived:
        text = (f"I had no plan of my own for {name}: it is a goal I read from my logs, to "
                f"{plan_words(task)}, {_DID.get(task.outcome, task.outcome)}.")
        return Explanation(explainer="planner", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                           evidence=evidence)
    n = len(task.skills)
    head = sentence(f"My plan for {name} had {n} step{'s' if n > 1 else ''}: {plan_words(task)}" if counted else
                    f"My plan for {name} was to {plan_words(task)}")
    if len(task.skills) == 1:
        rest = _ONE_STEP.get(task.outcome, "")
    elif all(r.state == "succeeded" for r in task.skills):
        rest = "I did every step."
    else:
        rest = steps_summary(task)
    if task.outcome == "invalid":
        rest += " " + sentence(f"My planner rejected it{': ' + task.error_msg.strip() if task.error_msg else ''}")
    # "why?" after it: the recorded request, then each step and what became of it
    return Explanation(explainer="planner", text=f"{head} {rest}".strip(), causes=["planner.plan_ok"],
                       evidence=evidence, details=[step_outcome(run) for run in task.skills])


# "What did I ask you?", "who gave you the task?": the request as the task status received it.
REQUEST = re.compile(
    _LEAD + r"what (did|have) (i|we) (ask|asked|tell|told|want|wanted)( of)?( you)?( to do| for)?\W*$|"
    + _LEAD + r"what (was|is) (my|our|the|your) (request|task|instruction|order|job|command)\W*$|"
    + _LEAD + r"(who|whom) (gave|sent|asked|told|ordered) (you|me)\b|" + _LEAD + r"who asked\b|"
    + _LEAD + r"when did (i|we|they|someone|anyone) (ask|tell|send|give) (you|me)\b")


def request(question: str, log: EventLog, task: Task) -> Explanation:
    """The request as received (its words and when), or that a goal read from the logs came with none; who asked is
    never recorded, and a question about it is told so."""
    q = " ".join(question.lower().split())
    who = re.search(r"\b(who|whom)\b", q) is not None
    evidence = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created, item=task.instruction)]
    if task.derived:
        text = (f"No one asked me in words that my recording holds: {task_name(task, log)} was read from the logs, "
                f"at {hms(task.created)} UTC; who sent it is not recorded.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence[:0])
    said = f'"{task.instruction}" at {hms(task.created)} UTC'
    text = (f"My recording does not say who asked: it holds the request {said}, as my task status received it."
            if who else f"You asked me {said}.")
    failed = task.failed_skill
    ended = f"failed at {step_ref(failed)}" if failed is not None else _ENDED.get(task.outcome, task.outcome)
    return Explanation(explainer="planner", text=f"{text} It {ended}.", causes=["planner.plan_ok"], evidence=evidence)


_ENDED = {"succeeded": "was done", "failed": "failed", "invalid": "was rejected before it started",
          "canceled": "was canceled", "running": "was still under way when the recording ends",
          "waiting": "had not started when the recording ends"}
