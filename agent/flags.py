""""Were you charging?", "was someone using the joystick?", "what is your speed limit?": answered from the recorded
flag or setting itself (/power/is_charging, /joy_priority, max_vel_x on /diagnostics) over the task's time, instead of
the task's finding with no answer to the question. A recording without it says so; it is never taken for "no"."""

from __future__ import annotations

import re
from typing import Literal

from hexar.agent.content import task_name
from hexar.agent.context import RunContext
from hexar.agent.measures import worked_until
from hexar.agent.overview import with_lead
from hexar.agent.probes import probe, with_failure
from hexar.agent.state import AgentState
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import BoolSample, duration, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.navigation.detectors import SPEED_KEY, status_item
from hexar.explainers.navigation.detectors import speed_limit as published_limit
from hexar.explainers.recorded import join_words

_LEAD = r"^(and |so |but |ok |okay )?"
# Per flag: how people ask about it, and how the answer names it.
_FLAGS: tuple[tuple[str, re.Pattern[str], str], ...] = (
    (c.IS_CHARGING, re.compile(
        _LEAD + r"(were|was|are|weren't|wasn't) you (still )?(charging|plugged in|on (the|your) (charger|dock)|"
        r"docked)\b|" + _LEAD + r"(was|were) (the|your) (charger|battery) (charging|plugged in|connected)\b|"
        + _LEAD + r"how long (were|was|have) you (been )?(charging|plugged in|on (the|your) (charger|dock)|docked)\b|"
        + _LEAD + r"when (did|were|was) (you|i|it|the robot) (get |got |being |be )?(unplugged|plugged in|"
                  r"disconnected|connected|charging|docked|undocked)\b"),
     "charging flag"),
    (c.JOY_PRIORITY, re.compile(
        _LEAD + r"(how long )?(was|were|is) (the |a |your )?(joystick|joypad|gamepad)( mode)? (on|in use|used|active|"
        r"holding|in control|connected)\b|"
        + _LEAD + r"(was|were|did) (someone|anyone|somebody|a person) (using|use|driving|drive|holding|hold) "
        r"(you|me|the robot)?( with)? ?(the |a )?(joystick|joypad|gamepad)\b|"
        + _LEAD + r"(were|was) you (in )?(joystick|manual) (mode|control)\b|"
        + _LEAD + r"who (was|is) (using|driving|holding|on|controlling( you with)?) (the |a |your )?"
                  r"(joystick|joypad|gamepad)\b|"
        + _LEAD + r"who (turned|switched|put) (on )?(the |your )?(joystick|manual mode|manual control)\b|"
        + _LEAD + r"when (was|did) (the |your )?(joystick|manual mode|manual control) (get |go )?(switched |turned )?"
                  r"(on|off|used|take over|took over)\b"),
     "joystick priority flag"),
)


Asked = Literal["yes_no", "timed", "who"]
_HOW_LONG = re.compile(r"\bhow long\b|^(\w+ )?when\b")  # asked for the flag's times, not a yes or no
_WHO = re.compile(r"^(\w+ )?who\b")
# The navigation explainer's cause for a flag that held while a goal did not complete (navigation/detectors.py).
FLAG_CAUSE = {c.IS_CHARGING: "navigation.charging", c.JOY_PRIORITY: "navigation.joystick"}


def flag_asked(q: str) -> str | None:
    """The flag topic a yes-or-no question (lower case, spaces collapsed) asks about, else None."""
    return next((topic for topic, pattern, _ in _FLAGS if pattern.search(q)), None)


def _evidence(s: BoolSample) -> Evidence:
    return Evidence(cause="planner.plan_ok", topic=s.topic, t=s.t, item=f"data={s.value}")


def flag(topic: str, log: EventLog, task: Task, asked: Asked = "yes_no") -> Explanation:
    """Yes (with when the flag on `topic` held), no, or that the recording holds no such flag; asked "timed", when
    and for how long it held, and asked "who", that a flag names nobody."""
    what = next(words for t, _, words in _FLAGS if t == topic)
    name = task_name(task, log)
    samples = sorted(log.flags.get(topic, []), key=lambda s: s.t)
    if not samples:
        text = f"I can't tell: my recording holds no {what} ({topic}) for {name}."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False)
    start = task.created
    end = worked_until(log, task)
    latched = [s for s in samples if s.t <= start][-1:]  # the value that held when the task began
    during = latched + [s for s in samples if start < s.t <= end]
    if not during:
        text = f"I can't tell: my {what} ({topic}) was first recorded after {name} ended, at {hms(samples[0].t)}."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False,
                           evidence=[_evidence(samples[0])])
    held = [s for s in during if s.value]
    if not held:
        lead = "Nobody, as far as my recording shows:" if asked == "who" else "No:"
        text = f"{lead} my {what} ({topic}) stayed off while I worked on {name}."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                           evidence=[_evidence(during[0]), *([_evidence(during[-1])] if len(during) > 1 else [])])
    off = next((s for s in during if not s.value and s.t > held[0].t), None)
    since = "when I began" if held[0] is during[0] and held[0].t <= start else f"at {hms(held[0].t)} UTC"
    until = f", until {hms(off.t)} UTC" if off is not None else ""
    held_when = f"my {what} ({topic}) was on from {since}{until}, while I worked on {name}"
    if asked == "timed":
        held_for = (off.t if off is not None else end) - max(held[0].t, start)
        whole = duration(end - start)
        text = f"M{held_when[1:]}: " + (f"the whole {whole} I worked on it." if duration(held_for) == whole else
                                        f"{duration(held_for)} of the {whole} I worked on it.")
    elif asked == "who":  # a flag is no person: who held the joystick is never recorded
        text = f"My recording does not say who: it holds only that {held_when}."
    else:
        text = f"Yes: {held_when}."
    evidence = [_evidence(held[0]), *([_evidence(off)] if off is not None else [])]
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], evidence=evidence)


def flag_answer(ctx: RunContext, state: AgentState, task: Task) -> Explanation:
    """The flag, yes or no, then the task's failure (whose evidence "why?" goes on to); where the failure's
    explainer blames that very flag, its answer, led by "Yes."."""
    q = " ".join(state["question"].lower().split())
    topic = flag_asked(q) or c.IS_CHARGING
    found = flag(topic, ctx.log, task, "timed" if _HOW_LONG.search(q) else "who" if _WHO.search(q) else "yes_no")
    name = ctx.registry.failure_explainer(task)
    failed = probe(ctx, name, state["question"], state["task_id"]) if name else None
    if failed is None:
        return found
    if found.text.startswith("Yes: ") and FLAG_CAUSE[topic] in failed.causes:  # only a yes-or-no is answered "Yes:"
        return failed.model_copy(update={"text": with_lead(failed.text, "Yes.")})
    # the flag decided the yes or no; what did stop me follows, as it would have been told
    told = with_failure(ctx, state, found, failed)
    return told.model_copy(update={"text": f"{found.text} {failed.text}"}) if found.enough_information else told


# "What is your speed limit?", "how fast can you go?": the controller's configured limit as the robot published it
# (the original HEXAR's /diagnostics key), not the speeds it drove at ("how fast were you going?", measures.py).
LIMIT = re.compile(
    _LEAD + r"what('s| is| was| were) (your|the|my) (speed limit|max(imum)? (speed|velocity)|velocity limit)s?\b|"
    + _LEAD + r"how fast (can|could|may|were) you (go|drive|move|allowed to (go|drive|move))\b|"
    + _LEAD + r"(what|which) speed (can|could|may) you\b")


def speed_limit(question: str, log: EventLog, task: Task) -> Explanation:
    """The speed limit published while the task ran (the one in force when it began, and any change after)."""
    name = task_name(task, log)
    limits = [(r, v) for r in log.statuses.get(c.DIAGNOSTICS, []) if (v := published_limit(r)) is not None]
    if not limits:
        text = f"I can't tell: my recording holds no speed limit ({SPEED_KEY} on {c.DIAGNOSTICS}) for {name}."
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False)
    end = worked_until(log, task)
    during = ([m for m in limits if m[0].t <= task.created][-1:] +
              [m for m in limits if task.created < m[0].t <= end])
    if not during:  # published only after the task: not the limit it worked under
        published, value = limits[0]
        text = (f"I can't tell: my speed limit ({SPEED_KEY} on {c.DIAGNOSTICS}) was first published at "
                f"{hms(published.t)} UTC, after {name} ended; it was {value:.2f} m/s then.")
        return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"], enough_information=False,
                           evidence=[Evidence(cause="planner.plan_ok", topic=c.DIAGNOSTICS, t=published.t,
                                              item=status_item(published, SPEED_KEY))])
    changes = [m for i, m in enumerate(during) if i == 0 or m[1] != during[i - 1][1]]
    first = f"{changes[0][1]:.2f} m/s"
    if len(changes) == 1:
        text = f"My speed limit was {first} while I worked on {name} ({SPEED_KEY} on {c.DIAGNOSTICS})."
    else:
        later = join_words([f"{v:.2f} m/s at {hms(r.t)} UTC" for r, v in changes[1:]])
        text = f"My speed limit changed while I worked on {name}: {first} at first, then {later} ({SPEED_KEY})."
    return Explanation(explainer="navigation", text=text, causes=["planner.plan_ok"],
                       evidence=[Evidence(cause="planner.plan_ok", topic=c.DIAGNOSTICS, t=r.t,
                                          item=status_item(r, SPEED_KEY)) for r, _ in changes[:4]])


# "What's your battery level?", "was your battery low?": HEXAR reads no battery state, only the charging flag.
BATTERY = re.compile(
    _LEAD + r"(what('s| is| was)|how('s| is| was)) (your|the|my) (battery|charge)( level| charge| state)?\b|"
    + _LEAD + r"how much (battery|charge|power) (do|did|does) (you|it) have\b|"
    + _LEAD + r"(was|is|were) (your|the) battery (low|empty|flat|dead|charged|full|ok|okay|running out)\b|"
    + _LEAD + r"(did|do) you (run out of|have( enough)?) (battery|power|charge)\b|"
    + _LEAD + r"(were|are) you (low on|out of|running out of) (battery|power|charge)\b")
BATTERY_TYPE = "sensor_msgs/msg/BatteryState"


def battery(question: str, log: EventLog, task: Task) -> Explanation:
    """That the battery's level is not something HEXAR reads (naming a recorded BatteryState topic it leaves
    aside), then what the charging flag shows."""
    held = [i for i in log.topics.values() if i.type == BATTERY_TYPE]
    if held:
        topics = join_words([f"{i.topic} ({i.count} messages)" for i in held])
        text = f"I can't tell my battery level: my recording holds {topics}, but I do not read its {BATTERY_TYPE}."
    else:
        text = f"I can't tell my battery level: my recording holds no battery state ({BATTERY_TYPE})."
    charging = flag(c.IS_CHARGING, log, task)
    # the flag's own yes or no answers "were you charging?", not this question
    flagged = re.sub(r"^(Yes|No): my ", "My ", charging.text)
    said = f"{text} {flagged}" if charging.enough_information else text
    return Explanation(explainer="navigation", text=said, causes=["planner.plan_ok"], enough_information=False,
                       evidence=charging.evidence)
