""""Where is the kitchen?": a room the robot knows only as a place its plans name, so the answer is where it was
when a trip there got there (its position estimate then), or that no trip of the recording did. Never a map
position the recording does not hold."""

from __future__ import annotations

import re

from hexar.agent.content import goal_place, task_name, trips_words, where
from hexar.agent.measures import STATED_AT, named_trip, trip_asked, when
from hexar.agent.overview import with_lead
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import LogLine, hms
from hexar.events.tasks import SkillRun, Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import NAV_SKILLS, join_words, place_name, positions, step_ref

# The rooms of a home people ask about; a place a plan names is matched by its own words (recording-independent
# here, so that "where is the coffee?" stays a question for the explainers).
_ROOMS = (r"kitchen|living ?room|dining ?room|bed ?room|bath ?room|office|hall|hallway|garage|garden|"
          r"lounge|pantry|study|entrance|corridor|laundry( room)?|toilet|charging (station|dock)|dock|charger")
PLACE = re.compile(r"^(and |so |ok |okay |but )?where('s| is| was) (the |my |your )?(?P<place>" + _ROOMS + r")\W*$")


def place_asked(q: str) -> str | None:
    """The room a "where is the kitchen?" names (lower case, spaces collapsed), else None."""
    m = PLACE.search(q)
    return m.group("place") if m is not None else None


def _key(name: str) -> str:
    return re.sub(r"[\s_]+", "", name.lower())


def _trips_to(log: EventLog, room: str) -> list[tuple[Task, SkillRun]]:
    return [(task, r) for task in log.tasks for r in task.skills if r.skill in NAV_SKILLS
            and _key(str(r.params.get("location", ""))) == _key(room)]


_NOT_THERE = {"failed": "failed", "running": "was still under way when my recording ends", "canceled": "was canceled"}


def place(question: str, log: EventLog, task: Task) -> Explanation:
    """Where I was when a trip got to the room asked about, or why I can't tell."""
    room = place_asked(" ".join(question.lower().split())) or ""
    trips = _trips_to(log, room)
    got = [(t, r) for t, r in trips if r.state == "succeeded"]
    if not trips:
        text = (f"I can't tell: no step of any plan in my recording went to the {room}, and I know rooms only as "
                "the places my plans name.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False)
    owner, run = (got or trips)[-1]
    name = place_name(run.params.get("location"))
    if not got:
        ended = _NOT_THERE.get(run.state, "never started")
        step = step_ref(run)
        text = (f"I can't tell: I never got to {name} in my recording, so I have no position for it. "
                f"{step[0].upper()}{step[1:]} of {task_name(owner, log)} {ended}.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False,
                           evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=run.last_change,
                                              item=owner.instruction)] if owner.instruction else [])
    at = [p for p in log.poses if p.t <= run.last_change]
    if not at:
        text = (f"I got to {name} at {hms(run.last_change)} UTC ({step_ref(run)} of {task_name(owner, log)}), but my "
                f"recording holds no position of mine ({c.AMCL_POSE}) to say where on my map that is.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False)
    pose = at[-1]
    text = (f"When I got to {name} at {hms(run.last_change)} UTC, for {step_ref(run)} of {task_name(owner, log)}, I "
            f"was at ({pose.x:.2f}, {pose.y:.2f}) on my map. I know {name} only as a place my plan names, so that is "
            "where I stopped for it, not the room's outline.")
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=c.AMCL_POSE, t=pose.t,
                                          item=f"x = {pose.x:.2f}, y = {pose.y:.2f}")])


# "Where were you when it failed?": the position at the failure, not at the recording's end.
FAILED_AT = re.compile(
    r"\b(where were you|what was (your|the robot's|its|the robot) (position|pose|location))( exactly)? "
    r"(when|as|at the (time|moment)) (it|you|the task|that|this|the step|your task) ?(failed|stopped|gave up|went "
    r"wrong|happened|aborted|crashed|broke down)\b|"
    r"\bwhere (was|were) (the robot|you|it|i) when (it|you|the robot|the planner) (tried|was trying|were trying) to "
    r"(plan|move|drive|dock)\b|"
    # "where was the robot when planning to (9, 4) failed?"
    r"\bwhere (was|were) (the robot|you|it|i|the base)( exactly)? when ([a-z0-9_(),.]+ ){1,6}"
    r"(failed|aborted|gave up|stopped|went wrong|crashed)\b")


def logged_position(log: EventLog, until: int) -> tuple[LogLine, float, float] | None:
    """The last line up to `until` that states the robot's position, with that position (its map's frame)."""
    for ln in reversed(log.logs):
        m = STATED_AT.search(ln.msg) if ln.t <= until else None
        if m is not None:
            return ln, float(m.group(1)), float(m.group(2))
    return None


def where_failed(question: str, log: EventLog, task: Task) -> Explanation:
    """The last position recorded up to the moment the task failed (its failed step's last change), or where the
    robot is at the end of a task that did not fail."""
    failed = task.failed_skill
    when = failed.last_change if failed is not None else task.last_update if task.outcome == "failed" else None
    if when is None:
        told = where(log)
        return told.model_copy(update={"text": f"Nothing failed in {task_name(task, log)}. {told.text}"})
    what = f"{step_ref(failed)} failed" if failed is not None else f"{task_name(task, log)} failed"
    before, topic = positions(log, None, when)
    if not before:
        stated = logged_position(log, when)
        if stated is not None:  # no pose topic, but Nav2's own line says where it started from
            ln, x, y = stated
            then = f"as {what}" if when - ln.t < 1_000_000_000 else f"before {what} at {hms(when)} UTC"
            quoted = " ".join(ln.msg.split())[:160]
            text = (f"My recording holds no position ({c.AMCL_POSE} or {c.ODOM}), but my log states one: at "
                    f'{hms(ln.t)}, {ln.name or "a node"} "{quoted}": I was at ({x:.2f}, {y:.2f}) on my map then, '
                    f"{then}.")
            return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                               evidence=[Evidence.of_log("planner.plan_ok", ln)])
        text = (f"I can't tell: my recording holds no position ({c.AMCL_POSE} or {c.ODOM}) up to when {what}, at "
                f"{hms(when)} UTC.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False)
    t, x, y = before[-1]
    frame = "on my map" if topic == c.AMCL_POSE else f"by my odometry ({topic})"
    text = f"When {what}, at {hms(when)} UTC, my last recorded position was ({x:.2f}, {y:.2f}) {frame}, at {hms(t)}."
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=topic, t=t, item=f"x = {x:.2f}, y = {y:.2f}")])


# "What was your goal?", "where was the goal?": the goals my steps were sent to, as the recording gives them.
GOAL = re.compile(r"^(and |so |but |ok |okay )?(what|where) (was|were|is|are) (your|the|my|its) (navigation )?"
                  r"(goals?|goal poses?|goal positions?|targets?|destinations?)( (coordinates|pose|position))?\W*$|"
                  r"^(and |so )?what (were|are) the (goal|target) (coordinates|poses?|positions?)\W*$|"
                  # "which goal was the robot navigating to when this happened?"
                  r"^(and |so )?(which|what) (goal|target|destination) (was|were|is) (the robot|it|you) (navigating|"
                  r"driving|heading|going|trying to (reach|get to))\b")
_OUTCOME = {"succeeded": "I got there", "failed": "I didn't get there", "running": "I was still on my way",
            "canceled": "it was canceled"}


def goal(question: str, log: EventLog, task: Task) -> Explanation:
    """Each navigation step's goal (a named place, a map position, or that the recording does not give it) and
    whether I got there; a task without a trip is told by its request."""
    name = task_name(task, log)
    trips = [r for r in task.skills if r.skill in NAV_SKILLS]
    if not trips:
        text = f"My goal was {name}; none of its steps sent me anywhere."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"])
    goals, unknown = [], []
    for run in trips:
        outcome = _OUTCOME.get(run.state, "I never set off") if run.time_of("running") is not None else \
            "I never set off"
        sent = goal_place(run)
        if sent is not None:
            goals.append(f"{sent[1]} ({outcome})")
        else:
            source = run.params.get("derived_from")
            unknown.append(f"My recording does not give my goal{' for ' + step_ref(run) if len(trips) > 1 else ''}"
                           + (f": I know of it only from the {source}" if isinstance(source, str) else "")
                           + f". {outcome[0].upper()}{outcome[1:]}.")
    said = f"my goal{'s were' if len(goals) > 1 else ' was'} {join_words(goals)}." if goals else ""
    # a goal read from the logs is named by its position already ("the navigation goal to (0.58, -0.55)")
    said = (said[0].upper() + said[1:] if task.derived else f"For {name}, {said}") if said else ""
    text = " ".join(([said] if said else []) + unknown)
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=r.last_change,
                                          item=f"step {r.index + 1}: {r.label()} {r.state}") for r in trips])


# "Did you reach the kitchen?", "did you get there?": yes or no from the trip's own outcome, with its times.
REACHED = re.compile(r"^(and |so |but |ok |okay )?(did|have) (you|the robot|it) (ever )?(reach|reached|get to|got to|"
                     r"make it to|made it to|arrive (at|in)|arrived (at|in)|get into|go into|go to|drive to|"
                     # "did the robot end up back in the dining room after the failure?"
                     r"(go|get|come|drive|make it|end up) back (to|in|at|into)|"
                     r"end up (at|in))( the| your| my)? "
                     # "did you reach the goal?" asks whether the task was done (overview.yes_or_no)
                     r"(?!((the|your|my) )?(goals?|destination|target|end|it|that)( or not)?\W*$)"
                     # "did you go to the wrong room?" asks about the plan, "... to the person?" about the help skill
                     r"(?!((the|your|my|a|an) )?(wrong|right|correct|same|other|another|person|people|someone|"
                     r"somebody|anyone|human|them|"
                     r"him|her)\b)"
                     # "did the robot reach its frontier goal?" asks whether the goal was reached, not a place
                     r"(?!([a-z]+ ){0,3}(goals?|destinations?|targets?|waypoints?)\b)"
                     r"(?P<place>[a-z][a-z ]*?)( (after|once|when) [a-z ]+)?\W*$|"
                     r"^(and |so |but |ok |okay )?(did|have) you (ever )?(get|got|make it|made it|arrive|arrived) "
                     r"(there|back)\W*$")


_ROOM = re.compile(r"\b(?P<room>" + _ROOMS + r")\b")
# "What did you do in the kitchen?": the steps between getting to a place and setting off from it.
AT_PLACE = re.compile(r"^(and |so |but |ok |okay )?what (did you do|happened) (in|at) (the |my |your )?"
                      r"(?P<room>" + _ROOMS + r")\W*$")
# "What path did you take?", "which way did you go?": the legs I drove, in order, with their lengths.
ROUTE = re.compile(r"^(and |so |but |ok |okay )?(what|which) (path|route|way) did you (take|follow|go|drive|use)\b|"
                   # "did you go the wrong way?" asks for a judgement the legs do not give: the finding's
                   r"^(and |so |but |ok |okay )?which way did you (go|come|drive)\b")


def at_place(question: str, log: EventLog, task: Task) -> Explanation:
    """The steps I ran at the place asked about: from the step that got me there to the next step that drove."""
    q = " ".join(question.lower().replace("_", " ").split())
    m = AT_PLACE.search(q)
    room = m["room"] if m is not None else "place"
    trip = named_trip(q, log, task)
    if trip is None or trip[1].state != "succeeded":  # never went there, or never got there: when_at says which
        return when_at(f"when did you reach the {room}?", log, task)
    owner, run = trip
    after = owner.skills[run.index + 1:]
    there = []
    for step in after:
        if step.skill in NAV_SKILLS:
            break
        there.append(step)
    place = place_name(str(run.params.get("location", "")))
    arrived = f"I got to {place} at {hms(run.last_change)} UTC"
    if not there:
        nxt = f"; I went on to step {after[0].index + 1} at once" if after else ", and that was the end of my plan"
        text = f"Nothing there but arrive: {arrived}{nxt}."
    else:
        done = [f"{step_ref(s)}, which {_STEP_ENDED.get(s.state, s.state)}" for s in there]
        text = f"{arrived}; there I ran {join_words(done)}."
    ev = [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=s.last_change, item=f"step {s.index + 1}: "
                   f"{s.label()} {s.state}") for s in [run, *there]]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=ev)


_STEP_ENDED = {"succeeded": "went as planned", "failed": "failed", "canceled": "was canceled",
               "waiting": "never started", "running": "was still under way when my recording ends"}


def when_at(question: str, log: EventLog, task: Task) -> Explanation:
    """"When did you reach the kitchen?": a room no trip went to is said so, not answered with the last trip that
    got somewhere (measures.when's "when did you arrive?"); any other question is measures.when's."""
    q = " ".join(question.lower().replace("_", " ").split())
    room = _ROOM.search(q)
    if room is None or named_trip(q, log, task) is not None:
        return when(question, log, task)
    text = f"No step of {task_name(task, log)} went to the {room['room']}. {trips_words(task, capital=True)}."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"])


def reached(question: str, log: EventLog, task: Task) -> Explanation:
    """"Yes."/"No." and the trip's times for the place asked about; a place no trip went to is said so, with where
    the trips did go."""
    q = " ".join(question.lower().replace("_", " ").split())
    m = REACHED.search(q)
    # a place named ("did you reach the kitchen?") is that place's trip or none, never the last trip that got there
    asked = named_trip(q, log, task) if m is not None and m["place"] else trip_asked(q, log, task)
    if asked is None:
        place = m["place"] if m is not None and m["place"] else "there"
        text = f"No: no step of {task_name(task, log)} went to the {place}. {trips_words(task, capital=True)}."
        if place == "there":
            text = f"No step of {task_name(task, log)} went anywhere. {trips_words(task, capital=True)}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"])
    told = when(question, log, task)
    lead = {"succeeded": "Yes.", "failed": "No.", "canceled": "No."}.get(asked[1].state, "")
    if asked[1].time_of("running") is None:
        lead = "No."
    return told.model_copy(update={"text": with_lead(told.text, lead)}) if lead else told
