"""Plain facts about one plan step, read from the recording: where a trip went, what was said, what pizza
was recommended. `hexar inspect` shows them, and the agent answers content questions ("what did you say?",
"where are you now?") from them; no explainer verdict is involved.
"""

from __future__ import annotations

import itertools
import json
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import PoseSample, StatusRecord
from hexar.events.tasks import SkillRun, Task

NAV_SKILLS = ("navigate_to_zone", "navigate_to_pose", "dock_robot", "run_behavior")  # the steps that drive the base
_BEHAVIORS = {"spin": "turn in place", "backup": "back up", "back_up": "back up",
              "drive_on_heading": "drive straight ahead", "wait": "wait", "assisted_teleop": "drive by assisted teleop"}
# The steps HEXAR derives from Nav2's, MoveIt's and ros2_control's goals (events/nav_goals.py, arm_goals.py), as
# a person says them rather than as the skill's identifier ("step 1 (to move my arm)", not "(to move arm)").
_DERIVED_STEPS = {"navigate_to_pose": "drive to my goal", "dock_robot": "dock", "move_arm": "move my arm",
                  "follow_joint_trajectory": "follow a joint trajectory", "command_gripper": "move my gripper",
                  "bring_up_controllers": "bring up my drivers and controllers"}
_NAVIGATING_TO = re.compile(r"^Navigating to (.+?) at \((-?[\d.]+), (-?[\d.]+)\)")


def place_name(raw: object) -> str:
    """`dining_room` -> `the dining room`, as a person says it."""
    return f"the {str(raw).replace('_', ' ')}"


@dataclass(frozen=True)
class Utterance:
    """One `say`: what the robot was to say, how it ended, and what it got through before a cut."""

    text: str
    ended: str  # finished, timed_out or "" when the recording stops first
    spoken_s: float | None
    said: str | None
    t: int


@dataclass(frozen=True)
class Trip:
    """A navigation goal inside a skill (e.g. the approach to a person), named by the skill's own log line."""

    goal: str
    x: float
    y: float
    t: int

    def describe(self) -> str:
        return f"{self.goal} at ({self.x:.2f}, {self.y:.2f})"


def _statuses(log: EventLog, topic: str, window: tuple[int, int]) -> list[StatusRecord]:
    return log.view({topic}, window).statuses(topic)


def utterances(log: EventLog, window: tuple[int, int]) -> list[Utterance]:
    out: list[Utterance] = []
    records = [r for r in _statuses(log, c.SAY_EVENTS, window) if r.name in {c.SAY_STATUS_NAME, ""}]
    for i, r in enumerate(records):
        if r.message != "started":
            continue
        end = next((e for e in records[i + 1:] if e.message in {"finished", "timed_out", "started"}), None)
        if end is not None and end.message == "started":
            end = None
        spoken = end.get("spoken_s") if end is not None else None
        try:
            spoken_s = float(spoken) if spoken is not None else None
        except ValueError:
            spoken_s = None
        out.append(Utterance(r.get("text", "") or "", end.message if end else "", spoken_s,
                             end.get("text_said") if end else None, r.t))
    return out


def recommendation(log: EventLog, window: tuple[int, int]) -> tuple[str, list[str]] | None:
    """(recommended pizza, available ingredients) of the last recommendation in the window."""
    pizza: str | None = None
    available: list[str] = []
    for r in _statuses(log, c.PIZZA_EVENTS, window):
        if r.message == "request":
            try:
                raw = json.loads(r.get("available_ingredients", "[]") or "[]")
                available = [str(x) for x in raw] if isinstance(raw, list) else []
            except ValueError:
                available = []
        elif r.message == "recommendation":
            pizza = r.get("recommended_pizza")
    return (pizza, available) if pizza else None


def trips_inside(log: EventLog, window: tuple[int, int]) -> list[Trip]:
    """Goals that skills sent to the navigation themselves, in order."""
    out = []
    for line in log.view({c.ROSOUT}, window).logs():
        m = _NAVIGATING_TO.match(line.msg)
        if m:
            out.append(Trip(m.group(1), float(m.group(2)), float(m.group(3)), line.t))
    return out


def positions(log: EventLog, start: int | None = None, end: int | None = None
              ) -> tuple[list[tuple[int, float, float]], str]:
    """My position estimates (t, x, y) in [start, end] (open where None), in time order, and the topic they came
    from: /amcl_pose, or /odom in a window where no /amcl_pose was recorded."""
    def inside(t: int) -> bool:
        return (start is None or t >= start) and (end is None or t <= end)

    amcl = [(p.t, p.x, p.y) for p in log.poses if inside(p.t)]
    return (amcl, c.AMCL_POSE) if amcl else ([(o.t, o.x, o.y) for o in log.odometry if inside(o.t)], c.ODOM)


def last_pose(log: EventLog, until: int | None = None) -> PoseSample | None:
    poses = log.view({c.AMCL_POSE}, (log.start, until if until is not None else log.end)).poses()
    return poses[-1] if poses else None


def ask_human_outcome(log: EventLog, window: tuple[int, int]) -> str | None:
    keys = [k for r in _statuses(log, c.EPISODIC_MEMORY, window) for k, _ in r.data_items()]
    if "SkillSucceeded" in keys:
        return "got help"
    if "SkillFailed" in keys:
        return "did not get help"
    return None




def _clip(text: str, limit: int = 160) -> str:
    return text if len(text) <= limit else text[: limit - 3].rstrip() + "..."


def step_words(run: SkillRun, short: bool = False) -> str:
    """A plan step as a person says it: "go to the kitchen", "say 'Here is your coffee.'"."""
    p = run.params
    if run.skill in NAV_SKILLS and p.get("location"):
        return f"go to {place_name(p['location'])}"
    if run.skill == "ask_human_for_help":
        question = p.get("question")
        return f'ask someone for help ("{question}")' if question and not short else "ask someone for help"
    if run.skill == "say":
        text = str(p.get("input", ""))
        return "say the pizza I recommend" if text.startswith("?") else f'say "{_clip(text, 60)}"'
    if run.skill == "recommend_pizza":
        return "choose a pizza from the ingredients available"
    if run.skill == "run_behavior" and isinstance(name := p.get("behavior"), str):  # Nav2's behaviour server's
        return _BEHAVIORS.get(name.lower(), name.replace("_", " "))
    obj = p.get("object")
    if run.skill in {"pick", "place"} and isinstance(obj, str) and obj:
        return f"{'pick up' if run.skill == 'pick' else 'put down'} the {obj.replace('_', ' ')}"
    x, y = p.get("x"), p.get("y")
    if run.skill == "navigate_to_pose" and isinstance(x, int | float) and isinstance(y, int | float):
        return f"drive to ({float(x):.2f}, {float(y):.2f})"
    if run.skill == "dock_robot" and isinstance(dock := p.get("dock"), str) and dock:
        return f"dock at {dock}"
    return _DERIVED_STEPS.get(run.skill, run.skill.replace("_", " "))


def step_ref(run: SkillRun) -> str:
    """"step 2 (to ask someone for help)": a step named by its number and, briefly, what it was to do."""
    return f"step {run.index + 1} (to {step_words(run, short=True)})"


def path_length(points: Iterable[tuple[float, float]]) -> float:
    """Length of the path through (x, y) points in their order, in metres."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(points))


def join_words(words: list[str], last: str = "and") -> str:
    """"a", "a and b", "a, b and c" (or `last` = "or")."""
    return words[0] if len(words) == 1 else f"{', '.join(words[:-1])} {last} {words[-1]}"


def sentence(text: str) -> str:
    """End with one full stop, also after a quote that ends in its own (`say "Hi."`)."""
    return text if text.rstrip('"').endswith((".", "!", "?")) else text + "."


def plan_words(task: Task) -> str:
    steps = [step_words(r) for r in task.skills]
    if not steps:
        return "no steps at all"
    return steps[0] if len(steps) == 1 else ", ".join(steps[:-1]) + " and then " + steps[-1]


def step_facts(log: EventLog, task: Task, run: SkillRun) -> list[str]:
    """What this step did, in a few plain lines (empty when the recording shows nothing of its own)."""
    if not run.history:
        return []
    window = task.skill_window(run)
    facts: list[str] = []
    if run.skill == "say":
        for u in utterances(log, window):
            how = {"finished": "said in full", "timed_out": "cut off at the speech time limit"}.get(
                u.ended, "no end recorded")
            took = f", {u.spoken_s:.1f} s" if u.spoken_s is not None else ""
            said = "said the input above" if run.params.get("input") == u.text else f'said: "{_clip(u.text)}"'
            facts.append(f"{said} ({how}{took})")
            if u.said is not None:
                facts.append(f"got through {len(u.said.split())} of {len(u.text.split())} words")
    elif run.skill == "recommend_pizza":
        found = recommendation(log, window)
        if found is not None:
            facts.append(f"recommended: {found[0]}")
            if found[1]:
                facts.append("ingredients available: " + ", ".join(found[1]))
    elif run.skill == "ask_human_for_help":
        for trip in trips_inside(log, window):
            facts.append(f"approached {trip.describe()}")
        outcome = ask_human_outcome(log, window)
        if outcome:
            facts.append(outcome)
    return facts
