"""Answers to questions about what the robot did rather than what went wrong: where it went and why, where it
is now, and what it said (and whether that was what the person asked for). Read from the recording: the plan
and its instruction, the navigation goals, the last pose, the utterances.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.nav_servers import BEHAVIOR_SKILL
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import (
    NAV_SKILLS,
    Trip,
    Utterance,
    join_words,
    last_pose,
    place_name,
    plan_words,
    sentence,
    step_ref,
    step_words,
    trips_inside,
    utterances,
)
from hexar.explainers.tts import SAID_ANYTHING, WHOLE_MESSAGE, compare, first_sentence
from hexar.render import clock

# the label's tail a derived task's instruction carries in tables: "Run spin (derived from Nav2's behaviour server)"
_DERIVED = re.compile(r"\s*\(derived from [^)]*\)\s*$")


def task_name(task: Task, log: EventLog) -> str:
    """How to speak of a task: the request in quotes, a goal read from the logs, or the recovery it is."""
    if task.derived:  # a goal some program sent, read from the logs: nobody's request to me
        # "the goal to run spin": spoken, not the table's label "Run spin (derived from Nav2's behaviour server)"
        what = _DERIVED.sub("", task.instruction)
        if what.startswith("Navigate to "):
            where = what.removeprefix("Navigate to ")
            return "the navigation goal" if where == "an unrecorded goal" else f"the navigation goal to {where}"
        return f"the goal to {what[:1].lower()}{what[1:]}"
    if not task.is_recovery:
        return f'your request "{task.instruction}"'
    before = [t for t in log.tasks if t.order < task.order and not t.is_recovery]
    after = f" after task {before[-1].order} {_ENDED.get(before[-1].outcome, before[-1].outcome)}" if before else ""
    return f"my own recovery task{after}"


# how a task before a recovery ended, in words ("after task 1 failed", not "after task 1 invalid")
_ENDED = {"invalid": "had an invalid plan", "canceled": "was canceled",
          "succeeded": "succeeded", "failed": "failed"}


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


def _started(run: SkillRun) -> bool:
    return run.time_of("running") is not None or run.state in {"succeeded", "failed", "canceled"}


def _rank(run: SkillRun) -> int:
    """Which step answers "why did you go to X?" best: one that got there, then one that set off, then a plan."""
    return 0 if run.state == "succeeded" else 1 if _started(run) else 2


def trips_words(task: Task, capital: bool = False) -> str:
    """Where the task's plan took me, as it happened: reached, set off for but not reached, or never started.
    A step that only ever waited is no trip, whatever its status history holds."""
    reached: list[str] = []
    tried: list[str] = []
    going: list[str] = []
    never: list[str] = []
    for run in task.skills:
        loc = run.params.get("location")
        if run.skill in NAV_SKILLS and isinstance(loc, str):
            place = place_name(loc)
            (reached if run.state == "succeeded" else going if run.state == "running" else
             tried if _started(run) else never).append(place)
    parts = [f"I went to {join_words(reached)}"] if reached else []
    if going:  # no end yet: cut off on disk, or still under way when a live node is asked
        parts.append(f"the recording ends while I was still on my way to {join_words(going)}")
    if tried:
        parts.append(f"I tried to go to {join_words(tried)} but didn't get there")
    if never:
        parts.append(f"I never set off for {join_words(never)}")
    if not parts:
        return "I didn't drive anywhere"
    said = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + ", and " + parts[-1]
    return said[0].upper() + said[1:] if capital else said


_ASKED_PLACE = re.compile(r"\b(?:to|into|towards?)\s+(?:the\s+)?([a-z][a-z _]*?)\W*$")


def went(question: str, log: EventLog, task: Task) -> Explanation:
    """Why the robot went somewhere: the plan step that sent it there, and the request behind the plan.
    Only a step that reached its place is "I went"; one that set off and failed is "I tried to go"."""
    q = question.lower().replace("_", " ")
    matches = [(candidate, run) for candidate in [task, *(t for t in log.tasks if t is not task)]
               for run in candidate.skills
               if run.skill in NAV_SKILLS and isinstance(loc := run.params.get("location"), str)
               and re.search(rf"\b{re.escape(loc.replace('_', ' '))}\b", q)]
    if matches:
        # min() keeps the first of equal rank, so the task being discussed wins a tie
        candidate, run = min(matches, key=lambda m: _rank(m[1]))
        return _went_step(log, candidate, run, current=candidate is task)
    if _BACK.search(q):
        return _went_back(log, task)
    under_way = next((run for run in task.skills if run.skill in NAV_SKILLS and run.state == "running"), None)
    if under_way is not None and _ASKED_PLACE.search(q) is None and not any(w in q for w in ("person", "someone")):
        return _went_step(log, task, under_way, current=True)  # "where are you going?": the trip not over yet
    if "person" in q or "someone" in q or "them" in q:
        for run in task.skills:
            if run.skill == "ask_human_for_help" and _started(run):
                for trip in trips_inside(log, task.skill_window(run)):
                    verb = "tried to go" if _reached(log, trip) is False else "went"
                    return Explanation(
                        explainer="planner",
                        text=(f"I {verb} to {trip.describe()} because step {run.index + 1} of my plan was to "
                              f"{step_words(run)}, and I drive up to a person before I ask."),
                        causes=["planner.plan_ok"], evidence=_plan_evidence(task, run, "planner.plan_ok"))
    plan = sentence(f"My plan was to {plan_words(task)}")
    if not any(run.skill in NAV_SKILLS and _started(run) for run in task.skills):
        return Explanation(explainer="planner", text=f"I didn't drive anywhere for {task_name(task, log)}. {plan}",
                           causes=["planner.plan_ok"], evidence=_plan_evidence(task, None, "planner.plan_ok"))
    if any(word in q for word in ("why did you", "why have you", "why are you")):
        asked = _ASKED_PLACE.search(q)
        if asked is None and re.search(r"\bthere\b", q):
            # "why did you go there?" names no place: the last trip the robot set off on
            last = [run for run in task.skills if run.skill in NAV_SKILLS and _started(run)][-1]
            return _went_step(log, task, last, current=True)
        there = f"to the {asked.group(1)}" if asked else "there"
        text = (f"I did not go {there} for {task_name(task, log)}: no step of my plan went there. "
                f"{trips_words(task, capital=True)}. {plan}")
    else:
        text = f"For {task_name(task, log)}, {trips_words(task)}. {plan}"
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_plan_evidence(task, None, "planner.plan_ok"))


_BACK = re.compile(r"\b(go|went|drive|drove|come|came|head|headed|walk|walked|turn|turned) (back|home|around)\b")


def _went_back(log: EventLog, task: Task) -> Explanation:
    """"Why did you go back?": the last trip after the first one, of the task or of the recovery tasks right after
    it (a robot that fails drives back in its own recovery); a robot that made one trip or none went nowhere back."""
    trips = [(t, r) for t in [task, *later_recoveries(log, task)] for r in t.skills
             if r.skill in NAV_SKILLS and _started(r)]
    if len(trips) >= 2:
        owner, run = trips[-1]
        return _went_step(log, owner, run, current=owner is task)
    plan = sentence(f"My plan was to {plan_words(task)}")
    done = trips_words(task) if trips else "I didn't drive anywhere"
    return Explanation(explainer="planner", text=f"I didn't go back for {task_name(task, log)}: {done}. {plan}",
                       causes=["planner.plan_ok"], evidence=_plan_evidence(task, None, "planner.plan_ok"))


def later_recoveries(log: EventLog, task: Task) -> list[Task]:
    """The robot's own recovery tasks right after this one (they drive it back after a failure)."""
    out = []
    for later in sorted((t for t in log.tasks if t.order > task.order), key=lambda t: t.order):
        if not later.is_recovery:
            break
        out.append(later)
    return out


def _went_step(log: EventLog, task: Task, run: SkillRun, current: bool) -> Explanation:
    place = place_name(run.params.get("location"))
    where = "" if current else f" (task {task.order})"
    because = f"step {run.index + 1} of my plan for {task_name(task, log)}{where} was to go there"
    if run.state == "succeeded":
        lead = f"I went to {place} because {because}, and I got there."
    elif run.state == "running":
        lead = f"I set off for {place} because {because}, and the recording ends while I was still on my way."
    elif _started(run):
        ended = "the step was canceled" if run.state == "canceled" else "I didn't get there"
        lead = f"I tried to go to {place} because {because}, but {ended}."
    else:
        failed = task.failed_skill
        why = (f"{step_ref(failed)} failed first" if failed is not None
               else "that step never started")
        lead = f"I did not go to {place}: {because}, but {why}, so I never set off."
    text = lead + " " + sentence(f"The whole plan was to {plan_words(task)}")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_plan_evidence(task, run, "planner.plan_ok"),
                       details=[f"Step {run.index + 1} of task {task.order}, {step_words(run)}: {run.state}."])


def goal_place(run: SkillRun) -> tuple[str, str] | None:
    """Where a navigation step was sent, with the word that goes before it: ("in", "the kitchen") for a named place,
    ("at", "(1.00, 2.00) on my map") for a map position (a goal derived from Nav2); None for neither."""
    p = run.params
    if p.get("location"):
        return "in", place_name(p["location"])
    x, y = p.get("x"), p.get("y")
    if isinstance(x, int | float) and isinstance(y, int | float):
        return "at", f"({float(x):.2f}, {float(y):.2f}) on my map"
    return None


def _goal_words(run: SkillRun) -> str:
    """Where a navigation step was sent: a named place, a map position, or neither."""
    where = goal_place(run)
    return f"{where[0]} {where[1]}" if where is not None else "at a position the recording does not give"


def where(log: EventLog) -> Explanation:
    """Where the robot is at the end of the recording: its last goal, whether it got there, its last pose; with
    no pose recorded (an ordinary recording of only /rosout), that the position is not recorded."""
    goals: list[tuple[int, str, bool | None]] = []  # (when, "in the kitchen" / "by the person at ...", reached)
    for task in log.tasks:
        for run in task.skills:
            start = run.time_of("running")
            if start is None:
                continue
            if run.skill == BEHAVIOR_SKILL:  # a spin or a backup is sent nowhere: it has no place to reach
                goals.append((start, f"to {step_words(run, short=True)}", None))
            elif run.skill in NAV_SKILLS:
                goals.append((start, _goal_words(run), {"succeeded": True, "failed": False}.get(run.state)))
            inner = [] if run.skill in NAV_SKILLS else trips_inside(log, task.skill_window(run))
            goals += [(trip.t, "by " + trip.describe(), _reached(log, trip)) for trip in inner]
    pose = last_pose(log)
    at = f" My last recorded position is ({pose.x:.2f}, {pose.y:.2f}) on my map, at {clock(pose.t)}." \
        if pose is not None else f" My position is not recorded: this recording has no {c.AMCL_POSE} messages."
    evidence = [Evidence(cause="navigation.nominal", topic=c.AMCL_POSE, t=pose.t,
                         item=f"x = {pose.x:.2f}, y = {pose.y:.2f}")] if pose is not None else []
    if not goals:
        text = ("I didn't drive anywhere in this recording, so I'm where I started." + at if pose is not None else
                "I can't tell where I am: this recording holds neither my position (no "
                f"{c.AMCL_POSE} messages) nor a goal I was sent to.")
    else:
        _, goal, reached = max(goals, key=lambda g: g[0])
        target = goal.removeprefix("in ").removeprefix("by ").removeprefix("at ")
        if goal.startswith("to "):
            text = f"My last step was {goal}, which sends me to no place on my map." + at
        elif reached:
            text = f"I'm {goal}: that was the last place I drove to, and I got there." + at
        else:
            # a goal not reached says nothing of how far I got (a stack that never came up never moved me)
            text = (f"My last goal was {target}; the recording does not show whether I got there." if reached is None
                    else f"My last goal was {target}, but I didn't get there.") + at
    # where I am is told by a recorded position, or by a goal I got to
    reached_last = bool(goals) and max(goals, key=lambda g: g[0])[2] is True
    return Explanation(explainer="navigation", text=text, causes=["navigation.nominal"], evidence=evidence,
                       enough_information=pose is not None or reached_last)


def said(question: str, log: EventLog, task: Task, nothing: str | None = None) -> Explanation:
    """What the robot said for this task, and whether it was what the person asked for (`nothing`: the sentence
    for having said nothing, where another answer already named the task)."""
    spoken = utterances(log, (task.created, task.last_update))
    # "did you say it out loud?": yes or no first, then what (whether it was what was asked is compare()'s lead)
    yes_no = SAID_ANYTHING.match(" ".join(question.lower().split())) is not None
    if not spoken:
        later = [t for t in log.tasks if t.order > task.order and t.is_recovery]
        after = utterances(log, later[0].window()) if later else []
        extra = sentence(f' Afterwards, in my recovery, I said "{first_sentence(after[-1].text)}"') if after else ""
        none = nothing or f"{'No. ' if yes_no else ''}I didn't say anything for {task_name(task, log)}."
        return Explanation(explainer="text_to_speech", text=f"{none}{extra}", causes=["tts.completed"])
    last = spoken[-1]
    evidence = [Evidence(cause="tts.completed", topic=c.SAY_EVENTS, t=last.t, item=f"started: text = {last.text}")]
    if WHOLE_MESSAGE.search(q := " ".join(question.lower().split())):
        # "can you say the rest?" asks me to act, which HEXAR never does: it gives the words instead
        act = "I can't say it again from here: I only explain what I did. " if re.match(
            r"(\w+ )?(can|could|would|will) you\b", q) else ""
        return Explanation(explainer="text_to_speech", text=act + _whole(last), causes=["tts.completed"],
                           evidence=evidence)
    compared = compare(task.instruction, last.text, evidence, "" if yes_no else question) \
        if not task.is_recovery else None
    cut = " I was cut off before the end." if last.ended == "timed_out" else ""
    lead = ("Partly. " if cut else "Yes. ") if yes_no else ""
    if compared is not None:
        return compared.model_copy(update={"text": lead + compared.text + (cut if yes_no else "")}) if yes_no \
            else compared
    return Explanation(explainer="text_to_speech",
                       text=lead + sentence(f'I said "{first_sentence(last.text, 200)}"') + cut,
                       causes=["tts.completed"], evidence=evidence)


def _whole(last: Utterance) -> str:
    """The whole text of the last thing I was to say, and how far I got where I was cut off."""
    words = len(last.text.split())
    whole = f'The whole message was "{" ".join(last.text.split())}" ({words} words).'
    if last.ended != "timed_out":
        return whole + (" I said all of it." if last.ended == "finished" else
                        " My recording ends before it says whether I finished saying it.")
    if last.said:
        got = len(last.said.split())
        return whole + f' I was cut off after the first {got}, at "...{" ".join(last.said.split()[-6:])}".'
    return whole + " I was cut off before the end; my recording does not say how far I got."


def _how_it_ended(task: Task, log: EventLog) -> str:
    ended = {"succeeded": "was done", "failed": "failed", "invalid": "was rejected", "canceled": "was canceled"}.get(
        task.outcome, "was not over when the recording ends")
    name = task_name(task, log)
    return f"{name[0].upper()}{name[1:]} {ended}."


def read_only(kind: str, log: EventLog, task: Task) -> Explanation:
    """"Can you try again?", "what will you do next?", "will you remember this?", "are you sad?": the agent explains
    from the recording, never commands the robot and has no feelings, so it says so (with how the task ended)
    instead of answering with a failure nobody asked about."""
    now = _how_it_ended(task, log)
    if kind == "next":
        text = ("I can't tell what I will do next: I only explain what I have already done, from what I recorded. "
                + now)
    elif kind == "learn":
        text = ("Nothing I say here changes how I act next time: I only explain what I did, from my recording. "
                + now)
    elif kind == "feel":
        text = f"I have no feelings to tell you about: I can only explain what I did, from my recording. {now}"
    elif kind == "stop":
        text = ("I can't stop from here: here I only explain what I did, from my recording, and I send no commands. "
                f"To stop me now, press my emergency stop button. {now}")
    else:
        text = ("I can't do that here: here I only explain what I did, from my recording, and I don't act on "
                f"requests. {now} To have me try again, give me the task again as you usually do.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_plan_evidence(task, None, "planner.plan_ok"))


# What each module asked about does, as the robot says it did not, and the explainers whose steps count as it
# (a trajectory the controllers ran moved the arm as much as a MoveIt pick).
_DOES = {"pizza_recommender": ("recommend anything", "recommend a pizza", ("pizza_recommender",)),
         "ask_human_for_help": ("ask anyone for help", "ask someone for help", ("ask_human_for_help",)),
         "manipulation": ("use my arm", "use my arm", ("manipulation", "control"))}


def serving(module: str, candidates: list[str]) -> str | None:
    """The explainer of this task that answers about `module` (a trajectory task's arm is control's to tell)."""
    return next((name for name in _DOES[module][2] if name in candidates), None)


def steps_of(module: str, task: Task, explainers_of: Callable[[str], list[str]]) -> list[SkillRun]:
    names = set(_DOES[module][2])
    return [run for run in task.skills if names & set(explainers_of(run.skill))]


def started_step(module: str, task: Task, explainers_of: Callable[[str], list[str]]) -> SkillRun | None:
    """The first step of the task that `module` serves and that started, if any."""
    return next((run for run in steps_of(module, task, explainers_of) if _started(run)), None)


def ran(module: str, task: Task, explainers_of: Callable[[str], list[str]]) -> bool:
    """Whether a step of the task that `module` serves started."""
    return started_step(module, task, explainers_of) is not None


def asked_someone(step: SkillRun, found: Explanation) -> str:
    """"Who did you talk to?" of a task that ran its ask-for-help `step`: the step, then the first sentence of what
    that step's explainer found (whether I found the person, and what they said)."""
    return f"Step {step.index + 1} of my plan was to {step_words(step)}. {first_sentence(found.text, None)}"


def not_run(module: str, log: EventLog, task: Task, explainers_of: Callable[[str], list[str]]) -> Explanation:
    """"What did you recommend?" of a task whose plan had no such step, or never got to it: what the plan was and
    how far it got, and the task of this recording that did, if any; never another step's failure as the answer."""
    did, step, _ = _DOES[module]
    name = task_name(task, log)
    steps = steps_of(module, task, explainers_of)
    if steps:
        first = steps[0]
        failed = task.failed_skill
        why = (f"{step_ref(failed)} failed first" if failed is not None
               else {"canceled": "the task was canceled first", "invalid": "my plan was rejected before it started"}
               .get(task.outcome, "the recording ends before it started"))
        text = (f"I didn't {did} for {name}: step {first.index + 1} of my plan was to {step_words(first)}, "
                f"but I never got to it, because {why}.")
        evidence = _plan_evidence(task, first, "planner.plan_ok")
    else:
        text = (f"I didn't {did} for {name}: no step of my plan was to {step}. "
                f"{sentence(f'My plan was to {plan_words(task)}')} {_how_it_ended(task, log)}")
        evidence = _plan_evidence(task, None, "planner.plan_ok")
    others = [t for t in log.tasks if t is not task and ran(module, t, explainers_of)]
    if others:
        other = others[-1]
        text += f' In task {other.order}, {task_name(other, log)}, I did: ask "what about task {other.order}?".'
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)
