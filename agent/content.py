"""Answers to questions about what the robot did rather than what went wrong: where it went and why, where it
is now, and what it said (and whether that was what the person asked for). Read from the recording: the plan
and its instruction, the navigation goals, the last pose, the utterances.
"""

from __future__ import annotations

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import (
    NAV_SKILLS,
    Trip,
    last_pose,
    place_name,
    plan_words,
    sentence,
    step_words,
    trips_inside,
    utterances,
)
from hexar.explainers.tts import compare, first_sentence
from hexar.render import clock


def task_name(task: Task, log: EventLog) -> str:
    """How to speak of a task: the request in quotes, or the recovery it is."""
    if not task.is_recovery:
        return f'your request "{task.instruction}"'
    before = [t for t in log.tasks if t.order < task.order and not t.is_recovery]
    after = f" after task {before[-1].order} {before[-1].outcome}" if before else ""
    return f"my own recovery task{after}"


def _plan_evidence(task: Task, run: SkillRun | None, cause: str) -> list[Evidence]:
    t = run.time_of("running") if run is not None else None
    item = f"step {run.index + 1}: {run.label()} {run.state}" if run is not None else task.instruction
    return [Evidence(cause=cause, topic=c.TASK_INFO, t=t or task.created, item=item)]


def _reached(log: EventLog, trip: Trip) -> bool | None:
    for line in log.view({c.ROSOUT}, (trip.t, log.end)).logs():
        if line.msg.startswith("Goal succeeded"):
            return True
        if line.msg.startswith(("Goal failed", "Goal canceled")):
            return False
    return None


def went(question: str, log: EventLog, task: Task) -> Explanation:
    """Why the robot went somewhere: the plan step that sent it there, and the request behind the plan."""
    q = question.lower()
    for candidate in [task, *(t for t in log.tasks if t is not task)]:
        for run in candidate.skills:
            loc = run.params.get("location")
            if run.skill in NAV_SKILLS and isinstance(loc, str) and loc.replace("_", " ") in q.replace("_", " "):
                return _went_step(log, candidate, run, current=candidate is task)
    if "person" in q or "someone" in q or "them" in q:
        for run in task.skills:
            if run.skill == "ask_human_for_help" and run.history:
                for trip in trips_inside(log, task.skill_window(run)):
                    return Explanation(
                        explainer="planner",
                        text=(f"I went to {trip.describe()} because step {run.index + 1} of my plan was to "
                              f"{step_words(run)}, and I drive up to a person before I ask."),
                        causes=["planner.plan_ok"], evidence=_plan_evidence(task, run, "planner.plan_ok"))
    trips = [r for r in task.skills if r.skill in NAV_SKILLS and r.history]
    if not trips:
        return Explanation(explainer="planner", text=sentence(f"I didn't drive anywhere for {task_name(task, log)}: "
                                                               f"my plan was to {plan_words(task)}"),
                           causes=["planner.plan_ok"], evidence=_plan_evidence(task, None, "planner.plan_ok"))
    if any(word in q for word in ("why did you go", "why did you drive", "why did you come")):
        named = " and ".join(place_name(r.params.get("location")) for r in trips)
        text = sentence(f"I didn't go there for {task_name(task, log)}; I went to {named}, because my plan was "
                        f"to {plan_words(task)}")
        return Explanation(explainer="planner", text=text,
                           causes=["planner.plan_ok"], evidence=_plan_evidence(task, trips[0], "planner.plan_ok"))
    return _went_step(log, task, trips[0], current=True)


def _went_step(log: EventLog, task: Task, run: SkillRun, current: bool) -> Explanation:
    place = place_name(run.params.get("location"))
    outcome = {"succeeded": "and I got there", "failed": "but I didn't get there",
               "running": "and I was still on my way"}.get(run.state, "but that step never started")
    where = "" if current else f" (task {task.order})"
    text = (f"I went to {place} because step {run.index + 1} of my plan for {task_name(task, log)}{where} was "
            f"to go there, {outcome}. " + sentence(f"The whole plan was to {plan_words(task)}"))
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_plan_evidence(task, run, "planner.plan_ok"),
                       details=[f"{task.task_id}: {run.label()} {run.state}"])


def where(log: EventLog) -> Explanation:
    """Where the robot is at the end of the recording: its last goal, whether it got there, its last pose."""
    goals: list[tuple[int, str, bool | None]] = []  # (when, "in the kitchen" / "by the person at ...", reached)
    for task in log.tasks:
        for run in task.skills:
            start = run.time_of("running")
            if start is None:
                continue
            if run.skill in NAV_SKILLS and run.params.get("location"):
                goals.append((start, "in " + place_name(run.params["location"]),
                              {"succeeded": True, "failed": False}.get(run.state)))
            inner = [] if run.skill in NAV_SKILLS else trips_inside(log, task.skill_window(run))
            goals += [(trip.t, "by " + trip.describe(), _reached(log, trip)) for trip in inner]
    pose = last_pose(log)
    at = f" My last recorded position is ({pose.x:.2f}, {pose.y:.2f}) on my map, at {clock(pose.t)}." \
        if pose is not None else ""
    evidence = [Evidence(cause="navigation.nominal", topic=c.AMCL_POSE, t=pose.t,
                         item=f"x = {pose.x:.2f}, y = {pose.y:.2f}")] if pose is not None else []
    if not goals:
        text = "I didn't drive anywhere in this recording, so I'm where I started." + at
    else:
        _, goal, reached = max(goals, key=lambda g: g[0])
        if reached:
            text = f"I'm {goal}: that was the last place I drove to, and I got there." + at
        else:
            target = goal.removeprefix("in ").removeprefix("by ")
            text = (f"My last goal was {target}; the recording does not show whether I got there." if reached is None
                    else f"My last goal was {target}, but I didn't get there, so I'm somewhere on the way.") + at
    return Explanation(explainer="navigation", text=text, causes=["navigation.nominal"], evidence=evidence)


def said(question: str, log: EventLog, task: Task) -> Explanation:
    """What the robot said for this task, and whether it was what the person asked for."""
    spoken = utterances(log, (task.created, task.last_update))
    if not spoken:
        later = [t for t in log.tasks if t.order > task.order and t.is_recovery]
        after = utterances(log, later[0].window()) if later else []
        extra = sentence(f' Afterwards, in my recovery, I said "{first_sentence(after[-1].text)}"') if after else ""
        return Explanation(explainer="text_to_speech", text=f"I didn't say anything for {task_name(task, log)}.{extra}",
                           causes=["tts.completed"])
    last = spoken[-1]
    evidence = [Evidence(cause="tts.completed", topic=c.SAY_EVENTS, t=last.t, item=f"started: text = {last.text}")]
    compared = compare(task.instruction, last.text, evidence, question) if not task.is_recovery else None
    if compared is not None:
        return compared
    cut = " I was cut off before the end." if last.ended == "timed_out" else ""
    return Explanation(explainer="text_to_speech", text=f'I said "{first_sentence(last.text, 200)}".{cut}',
                       causes=["tts.completed"], evidence=evidence)
