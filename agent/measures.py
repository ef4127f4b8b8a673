"""Answers to "how far did you drive?", "how long did it take?" and "when did you get there?": figures read from
the recording (the plan's status times and the robot's poses), not a finding about what went wrong.

Distances are the length of the path the robot's own position estimate (/amcl_pose, else /odom) traced while a
step ran, so a badly localised robot's jumps count too: the answers say "about".
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from hexar.agent.content import later_recoveries, task_name
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import calendar_day, duration, hms
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import NAV_SKILLS, join_words, path_length, place_name, positions, step_ref, step_words


@dataclass(frozen=True)
class _Step:
    run: SkillRun
    start: int
    end: int
    metres: float | None  # None: no position recorded while it ran


def _points(log: EventLog, start: int, end: int) -> list[tuple[float, float]]:
    """My position estimate in [start, end]: /amcl_pose, or /odom without it."""
    return [(x, y) for _, x, y in positions(log, start, end)[0]]


def _path(log: EventLog, start: int, end: int) -> float | None:
    """Length of the path my position estimate traced in [start, end]."""
    points = _points(log, start, end)
    return path_length(points) if points else None


def _steps(log: EventLog, task: Task) -> list[_Step]:
    """The steps that started, with when they ran and how far I moved meanwhile."""
    out = []
    for run in task.skills:
        start = run.time_of("running")
        if start is None:
            continue
        # a step still under way ran until the recording's last word on its task, not only to its start
        end = max(recorded_until(log, task) if run.state == "running" else run.last_change, start)
        out.append(_Step(run, start, end, _path(log, start, end)))
    return out


def recorded_until(log: EventLog, task: Task) -> int:
    """When the recording stops telling about a task still under way: its end, past the task's last update."""
    return max(task.last_update, log.end)


def worked_until(log: EventLog, task: Task) -> int:
    """The end of a task's time: its last update, or for one still under way the recording's end."""
    return recorded_until(log, task) if task.outcome in {"running", "waiting"} else task.last_update


def _goal(run: SkillRun) -> str:
    loc = run.params.get("location")
    if isinstance(loc, str) and loc:
        return place_name(loc)
    x, y = run.params.get("x"), run.params.get("y")
    if isinstance(x, int | float) and isinstance(y, int | float):
        return f"my goal at ({float(x):.2f}, {float(y):.2f})"
    return "my goal"


def _evidence(task: Task, runs: list[SkillRun]) -> list[Evidence]:
    return [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=run.last_change,
                     item=f"step {run.index + 1}: {run.label()} {run.state}") for run in runs] or \
        [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created, item=task.instruction)]


# "how far away was the dining room?" of a task that never went there: the place asked about, not the whole errand
_FAR_PLACE = re.compile(r"\bhow far (?:away )?(?:is|was) (?:the|your) ([a-z][a-z ]*?)(?: from (?:here|you|me))?\W*$")
_NOT_A_PLACE = frozenset({"trip", "drive", "way", "path", "route", "goal", "errand", "task", "distance"})


# Nav2's lines that state where the robot was: bt_navigator's "Begin navigating from current location (x, y) to
# ..." and the planner's "... failed to plan from (x, y) to (x, y)"
STATED_AT = re.compile(r"(?:from current location|failed to plan from) \((-?\d+(?:\.\d+)?), (-?\d+(?:\.\d+)?)\)")


def _stated_far(log: EventLog, task: Task) -> str:
    """Without positions, what Nav2's own lines say of where I set off and where I was last while the task ran:
    the straight line between them (the path driven is not in them)."""
    end = worked_until(log, task)
    said = [(ln, m) for ln in log.logs if task.created <= ln.t <= end and (m := STATED_AT.search(ln.msg))]
    if len(said) < 2:
        return ""
    (first, a), (last, b) = said[0], said[-1]
    x0, y0, x1, y1 = float(a[1]), float(a[2]), float(b[1]), float(b[2])
    gap = math.hypot(x1 - x0, y1 - y0)
    return (f" My log states where I was, though: at {hms(first.t)} at ({x0:.2f}, {y0:.2f}) "
            f"({first.name or 'a node'}), and at {hms(last.t)} at ({x1:.2f}, {y1:.2f}) ({last.name or 'a node'}: "
            f"\"{' '.join(last.msg.split())[:100]}\"), {gap:.1f} m apart in a straight line; the path I drove is not "
            "in those lines.")


def far(log: EventLog, task: Task, question: str = "", asked: str = "far") -> Explanation:
    """How far I drove for the task, leg by leg; of a place the question names, that trip alone. `asked` ("far" or
    "fast") is what a recording without positions cannot tell."""
    q = _norm(question)
    named = named_trip(q, log, task) if q else None
    if named is not None:
        return _far_to(log, *named)
    other = _FAR_PLACE.search(q)
    if other is not None and other.group(1) not in _NOT_A_PLACE:
        place, name = f"the {other.group(1)}", task_name(task, log)
        text = f"No step of my plan for {name} went to {place}, so my recording has no distance to it."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                           evidence=_evidence(task, []), enough_information=False)
    steps = _steps(log, task)
    moved = [s for s in steps if s.metres is not None and s.metres >= 0.05]
    name = task_name(task, log)
    evidence = _evidence(task, [s.run for s in steps])
    if not steps:
        why = "my plan was rejected before I started" if task.outcome == "invalid" else "none of its steps started"
        return Explanation(explainer="navigation", text=f"I didn't drive anywhere for {name}: {why}.",
                           causes=["planner.plan_ok"], evidence=evidence)
    if not any(s.metres is not None for s in steps):
        drove = any(s.run.skill in NAV_SKILLS for s in steps)
        text = (f"I can't tell how {asked} I drove for {name}: this recording holds no position of mine "
                f"(no {c.AMCL_POSE} or {c.ODOM} messages) while it ran.{_stated_far(log, task)}" if drove else
                f"I didn't drive anywhere for {name}.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], evidence=evidence,
                           enough_information=not drove)
    if not moved:
        return Explanation(explainer="navigation", text=f"I didn't drive anywhere for {name}.",
                           causes=["planner.plan_ok"], evidence=evidence)
    total = sum(s.metres or 0.0 for s in moved)
    parts = [f"{s.metres or 0.0:.1f} m {_during(s.run)} ({duration(s.end - s.start)})" for s in moved]
    head = f"For {name}, I drove about {total:.1f} m"
    # each leg says how long it took; one span over all of them would count the steps between them as driving
    text = f"{head}: {join_words(parts)}." if len(moved) > 1 else \
        f"{head} in {duration(moved[0].end - moved[0].start)}, {_during(moved[0].run)}."
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=_evidence(task, [s.run for s in moved]),
                       details=["Distances are the path my position estimate traced, so they include its jumps."])


def _far_to(log: EventLog, owner: Task, run: SkillRun) -> Explanation:
    """"How far away was the kitchen?": the way I drove there and, as the crow flies, how far I ended up from where
    I set off. The recording holds no map of its places, so it is the way taken, not the place's own distance."""
    place, start = _goal(run), run.time_of("running")
    lead = "In my own recovery task, " if owner.is_recovery else ""
    if start is None:
        text = f"I never set off for {place}, so my recording has no distance to it: {_never_set_off(log, owner, run)}"
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                           evidence=_evidence(owner, []), enough_information=False)
    end = max(recorded_until(log, owner) if run.state == "running" else run.last_change, start)
    points = _points(log, start, end)
    if not points:
        text = (f"I can't tell how far {place} was: my recording holds no position of mine (no {c.AMCL_POSE} or "
                f"{c.ODOM} messages) while I drove there.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                           evidence=_evidence(owner, [run]), enough_information=False)
    driven, across = path_length(points), math.dist(points[0], points[-1])
    took = duration(end - start)
    if run.state == "succeeded":
        text = (f"{lead}I drove about {driven:.1f} m to get to {place}, in {took}; where I got to was about "
                f"{across:.1f} m in a straight line from where I set off.")
    else:
        ended = "and the recording ends before I got there" if run.state == "running" else "and I did not get there"
        text = (f"{lead}I drove about {driven:.1f} m towards {place} in {took}, {ended}; I was then about "
                f"{across:.1f} m in a straight line from where I set off.")
    return Explanation(explainer="navigation", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                       evidence=_evidence(owner, [run]),
                       details=["Distances are the path my position estimate traced, so they include its jumps."])


def fast(log: EventLog, task: Task) -> Explanation:
    """My average speed on each leg I drove: the path my positions traced over the time the step ran."""
    steps = [s for s in _steps(log, task) if s.metres is not None and s.metres >= 0.05 and s.end > s.start]
    if not steps:
        return far(log, task, asked="fast")  # nothing driven, or no positions: what "how far" says of it
    name = task_name(task, log)
    parts = [f"{(s.metres or 0.0) / ((s.end - s.start) / 1e9):.2f} m/s {_during(s.run)} "
             f"({s.metres or 0.0:.1f} m in {duration(s.end - s.start)})" for s in steps]
    text = f"For {name}, I drove at about {join_words(parts)}, on average."
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=_evidence(task, [s.run for s in steps]),
                       details=["Speeds are averages over each step: the path my position estimate traced, divided "
                                "by the step's time, stops included."])


def start(log: EventLog, task: Task) -> Explanation:
    """Where I was when I set off on the task's first step (or, when none started, when I was asked)."""
    first = next((r for r in task.skills if r.time_of("running") is not None), None)
    at = first.time_of("running") if first is not None else None
    t = at if at is not None else task.created
    before, source = positions(log, None, t)
    after, later = positions(log, t + 1, log.end)
    pose, topic = (before[-1], source) if before else (after[0], later) if after else (None, source)
    name = task_name(task, log)
    when = f"when I set off on {step_ref(first)}" if first is not None else f"when I got {name}"
    if pose is None:
        text = f"I can't tell where I was {when}: my recording holds no position of mine ({c.AMCL_POSE} or {c.ODOM})."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                           evidence=_evidence(task, [first] if first else []), enough_information=False)
    pt, x, y = pose
    which = "my last position recorded before then" if before else "the first position recorded after then"
    text = f"{when[0].upper()}{when[1:]}, I was at ({x:.2f}, {y:.2f}) on my map: {which}, at {hms(pt)} UTC. "
    arrived = _arrived_before(log, t, (x, y))
    if arrived is not None:
        owner, run = arrived
        text += (f"That is {_goal(run)}, where {step_ref(run)} of {task_name(owner, log)} had taken me at "
                 f"{hms(run.last_change)}.")
    else:
        text += "I can't say which room that is: I know rooms only as the places my plan's steps name."
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=[*_evidence(task, [first] if first else []),
                                 Evidence(cause="planner.plan_ok", topic=topic, t=pt, item=f"x={x:.2f} y={y:.2f}")])


# How near the last place I got to my position must be for "where did you start?" to name that place: a trip that
# ended there, not one I drove away from since.
SAME_PLACE_M = 1.0


def _arrived_before(log: EventLog, t: int, at: tuple[float, float]) -> tuple[Task, SkillRun] | None:
    """The last trip to a named place that got there before `t`, when my position at `t` is still there."""
    done = [(task, r) for task in log.tasks for r in task.skills if r.skill in NAV_SKILLS and r.state == "succeeded"
            and r.last_change <= t and isinstance(r.params.get("location"), str)]
    if not done:
        return None
    owner, run = max(done, key=lambda m: m[1].last_change)
    there = positions(log, None, run.last_change)[0]
    return (owner, run) if there and math.dist(there[-1][1:], at) <= SAME_PLACE_M else None


def _during(run: SkillRun) -> str:
    """What a distance was driven for: "to go to the kitchen", "during step 2, to ask someone for help"."""
    if run.skill not in NAV_SKILLS:
        return f"during step {run.index + 1}, to {step_words(run, short=True)}"
    return f"to {step_words(run, short=True)}" + (", and I did not get there" if run.state == "failed" else "")


def _ended(task: Task) -> str:
    failed = task.failed_skill
    if failed is not None:
        return f"it ended when {step_ref(failed)} failed"
    if task.outcome == "succeeded":
        return "I finished it"
    if task.outcome == "invalid":
        return "my plan for it was rejected before it started"
    return "it was canceled"


def _span(ns: int) -> str:
    """duration(), with milliseconds under half a second: "how quickly did the goal fail?" of a goal rejected
    20 ms after it came is not answered "less than a second"."""
    if ns >= 500_000_000:
        return duration(ns)
    return f"{ns / 1e6:.0f} ms" if ns >= 1_000_000 else "less than a millisecond"


def long(log: EventLog, task: Task, lead_with_times: bool = False) -> Explanation:
    steps = _steps(log, task)
    span = _span(worked_until(log, task) - task.created)
    ended = _ended(task)
    name = task_name(task, log)
    if task.outcome in {"running", "waiting"}:
        text = (f"{name[0].upper()}{name[1:]} was not over when the recording ends, {span} after it began at "
                f"{hms(task.created)} UTC.")
    elif task.outcome == "invalid":
        text = f"My plan for {name} was rejected at once, at {hms(task.created)} UTC, before I started anything."
        said = next(((r, t) for t in later_recoveries(log, task) for r in t.skills if r.skill == "say"
                     and r.time_of("running") is not None), None)
        if said is not None:  # "how long before you told me?": the recovery's words are when the person heard it
            spoke = said[0].time_of("running") or said[0].last_change
            text += (f" I told you at {hms(spoke)} UTC, {duration(spoke - task.created)} after that: "
                     f"\"{said[0].params.get('input', '')}\".")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=_evidence(task, []))
    elif lead_with_times:
        text = f"I started on {name} at {hms(task.created)} UTC, and {ended} at {hms(task.last_update)}, {span} later."
    else:
        when = (f"at {hms(task.created)} UTC" if hms(task.created) == hms(task.last_update)
                else f"from {hms(task.created)} to {hms(task.last_update)} UTC")
        text = f"{name[0].upper()}{name[1:]} took {span}, {when}; {ended}."
    if steps:
        each = "; ".join(f"{step_ref(s.run)} had run for {_span(s.end - s.start)} when the recording ends"
                         if s.run.state == "running" else f"{step_ref(s.run)} took {_span(s.end - s.start)}"
                         for s in steps)
        text += f" {each[0].upper()}{each[1:]}."
        most = max(steps, key=lambda s: s.end - s.start)  # "why did it take so long?": where the time went
        if len(steps) > 1 and 2 * (most.end - most.start) > sum(s.end - s.start for s in steps):
            text += f" Most of that time went to {step_ref(most.run)}."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_evidence(task, [s.run for s in steps]))


def long_each(log: EventLog, tasks: list[Task]) -> Explanation:
    """"How long did the first two waypoints take each?": each task's time, in order, in one sentence each."""
    said = []
    for task in tasks:
        name = task_name(task, log)
        if task.outcome in {"running", "waiting"}:
            said.append(f"{name[0].upper()}{name[1:]} was not over when the recording ends, "
                        f"{_span(worked_until(log, task) - task.created)} after it began at {hms(task.created)} UTC.")
        else:
            said.append(f"{name[0].upper()}{name[1:]} took {_span(worked_until(log, task) - task.created)}, from "
                        f"{hms(task.created)} to {hms(task.last_update)} UTC; {_ended(task)}.")
    if len(tasks) > 1:  # "which leg took the longest?"
        longest = max(tasks, key=lambda t: worked_until(log, t) - t.created)
        said.append(f"The longest was {task_name(longest, log)}.")
    return Explanation(explainer="planner", text=" ".join(said), causes=["planner.plan_ok"],
                       evidence=[e for t in tasks for e in _evidence(t, [s.run for s in _steps(log, t)])])


def _trips(log: EventLog, task: Task) -> tuple[list[tuple[Task, SkillRun]], list[tuple[Task, SkillRun]]]:
    """The task's trips, and those of the recovery tasks after it."""
    return ([(task, r) for r in task.skills if r.skill in NAV_SKILLS],
            [(t, r) for t in later_recoveries(log, task) for r in t.skills if r.skill in NAV_SKILLS])


def named_trip(q: str, log: EventLog, task: Task) -> tuple[Task, SkillRun] | None:
    """The trip to a place the question names: one that got there, then one that set off (a recovery that drove
    there answers for the request)."""
    trips, after = _trips(log, task)
    named = [(t, r) for t, r in trips + after if isinstance(loc := r.params.get("location"), str)
             and re.search(rf"\b{re.escape(loc.replace('_', ' '))}\b", q)]
    if not named:
        return None
    return min(named, key=lambda m: 0 if m[1].state == "succeeded" else 1 if m[1].time_of("running") else 2)


def _norm(question: str) -> str:
    return " ".join(question.lower().replace("_", " ").split())


def _never_set_off(log: EventLog, owner: Task, run: SkillRun) -> str:
    failed = owner.failed_skill
    why = f"{step_ref(failed)} failed first" if failed is not None and failed.index < run.index else "it never started"
    return f"that was step {run.index + 1} of {task_name(owner, log)}, and {why}."


def trip_asked(q: str, log: EventLog, task: Task) -> tuple[Task, SkillRun] | None:
    """The trip a "when" question is about: a place it names, the way back ("get back", "return": the last trip,
    also a recovery's), or "get there"/"arrive": the last trip that got there, else the last that set off."""
    named = named_trip(q, log, task)
    if named is not None:
        return named
    trips, after = _trips(log, task)
    if re.search(r"\b(get|got|come|came) back\b|\breturn", q):
        return (trips + after)[-1] if trips + after else None
    if re.search(r"\b(get|got) there\b|\barriv|\breach", q) and trips:
        return ([(t, r) for t, r in trips if r.state == "succeeded"] or
                [(t, r) for t, r in trips if r.time_of("running") is not None] or trips)[-1]
    return None


_DATED = re.compile(r"\b(day|date|happen|take place|recorded|recording|run)\b|^(and |so |ok |okay )?when was")


def _on(t: int) -> str:
    """"On Monday 10 March 2025.": the day of a time on the robot's clock, in UTC."""
    day = calendar_day(t)
    if day is None:
        return "My clock was a simulator's, which starts at zero, so my recording gives no calendar day."
    return f"On {day}."


def when(question: str, log: EventLog, task: Task) -> Explanation:
    """A trip the question asks about (see trip_asked): its times; otherwise the task's (with its day when the
    question asks when it all happened)."""
    q = _norm(question)
    asked = trip_asked(q, log, task)
    if asked is None:
        timed = long(log, task, lead_with_times=True)
        if _DATED.search(q) is None:
            return timed
        return timed.model_copy(update={"text": f"{_on(task.created)} {timed.text}"})
    owner, run = asked
    start = run.time_of("running")
    place = _goal(run)
    lead = "In my own recovery task, " if owner is not task else ""
    if start is None:
        text = f"I never set off for {place}: {_never_set_off(log, owner, run)}"
    elif run.state == "succeeded":
        text = (f"{lead}I got to {place} at {hms(run.last_change)} UTC, {duration(run.last_change - start)} after I "
                f"set off at {hms(start)}.")
    elif run.state == "failed":
        text = (f"{lead}I never got to {place}: I set off at {hms(start)} UTC and gave up at {hms(run.last_change)}, "
                f"{duration(run.last_change - start)} later.")
    else:
        text = f"{lead}I set off for {place} at {hms(start)} UTC; the recording ends before I got there."
    text = text[0].upper() + text[1:]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                       evidence=_evidence(owner, [run] if start is not None else []))
