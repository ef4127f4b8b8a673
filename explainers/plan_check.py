"""Deterministic plan validation against the robot's skill catalogue and the person's request.

Used by the planner explainer and by the agent's failure check, so it must stay cheap and model-free.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

LOCATIONS = ("kitchen", "dining_room", "living_room")
# skill -> mandatory parameters (hexar_interfaces.md, "Skill catalogue of the home-assistant application")
CATALOGUE: dict[str, tuple[str, ...]] = {
    "say": ("input",),
    "navigate_to_zone": ("location",),
    # Nav2's own NavigateToPose goal (modules.toml maps it to the navigation explainer): recordings of ordinary
    # Nav2 robots and tasks derived from their goals carry it with coordinates, not a place name.
    "navigate_to_pose": (),
    "ask_human_for_help": ("question",),
    "look_for_human": ("patterns",),
    "recommend_pizza": (),
    "explain": ("question",),
    # a mobile manipulator's arm (modules.toml: manipulation, control); tasks derived from MoveIt's and the
    # controllers' goals carry the last three
    "pick": ("object",),
    "place": ("object",),
    "move_arm": (),
    "follow_joint_trajectory": (),
    "command_gripper": (),
    "bring_up_controllers": (),
}
# Skills that get an object into the robot's hands: a person's help, or its own arm.
FETCHING = ("ask_human_for_help", "pick")
# skill -> parameters it may carry besides the mandatory ones: a NavigateToPose goal's pose.
OPTIONAL: dict[str, tuple[str, ...]] = {"navigate_to_pose": ("x", "y", "yaw", "frame_id", "source")}
# Actions that need arms or hands; the robot can only move, talk, look and ask people.
MANIPULATION_VERBS = frozenset(
    [
        "open",
        "close",
        "shut",
        "wash",
        "clean",
        "cook",
        "bake",
        "boil",
        "fry",
        "water",
        "fold",
        "cut",
        "chop",
        "slice",
        "pour",
        "lift",
        "push",
        "pull",
        "pick",
        "grab",
        "throw",
        "iron",
        "vacuum",
        "mop",
        "sweep",
        "tidy",
        "repair",
        "fix",
        "unlock",
        "lock",
        "plug",
        "unplug",
        "turn",
        "switch",
        "press",
        "hang",
        "feed",
        "dust",
        "scrub",
        "wipe",
        "stir",
        "mix",
        "peel",
        "hand",
        "make",
        "build",
        "assemble",
        "load",
        "unload",
        "empty",
        "fill",
    ]
)
_POLITE = re.compile(r"^(please|could you|can you|would you|will you|kindly|hey robot|robot)[, ]+", re.I)
_ROOM_WORDS = {"kitchen": "kitchen", "dining room": "dining_room", "living room": "living_room"}
_BRING = re.compile(r"\b(bring|fetch|get me|carry)\b", re.I)
_TELL = re.compile(r"\b(tell|say|remind|inform|deliver|read|let \w+ know)\b", re.I)
_PIZZA = re.compile(r"\bpizza\b", re.I)


@dataclass(frozen=True)
class Finding:
    cause: str
    step: int | None
    message: str


def requested_action(instruction: str) -> str:
    """The first word of an imperative request, after politeness ('Could you open...' -> 'open')."""
    text = instruction.strip().lower()
    while (m := _POLITE.match(text)) is not None:
        text = text[m.end() :]
    words = re.findall(r"[a-z']+", text)
    return words[0] if words else ""


def mentioned_rooms(instruction: str) -> list[str]:
    low = instruction.lower()
    return [loc for phrase, loc in _ROOM_WORDS.items() if phrase in low]


def _step_findings(index: int, skill: str, params: Mapping[str, object]) -> list[Finding]:
    if skill not in CATALOGUE:
        close = difflib.get_close_matches(skill, CATALOGUE, n=1, cutoff=0.4)
        hint = f" (did the planner mean {close[0]!r}?)" if close else ""
        msg = f"step {index + 1} uses the skill {skill!r}, which I don't have{hint}"
        return [Finding("planner.invalid_skill", index, msg)]
    out = []
    for name in CATALOGUE[skill]:
        if name not in params or params[name] in (None, "", []):
            out.append(
                Finding(
                    "planner.invalid_parameter", index, f"step {index + 1} ({skill}) is missing its {name!r} parameter"
                )
            )
    unknown = sorted(set(params) - set(CATALOGUE[skill]) - set(OPTIONAL.get(skill, ())) - {"value"})
    for name in unknown:
        out.append(
            Finding(
                "planner.invalid_parameter",
                index,
                f"step {index + 1} ({skill}) has a parameter {name!r} that the skill does not take",
            )
        )
    if skill == "navigate_to_zone" and "location" in params:
        loc = params["location"]
        if not isinstance(loc, str):
            out.append(
                Finding(
                    "planner.invalid_parameter",
                    index,
                    f"step {index + 1} gives the location as {loc!r}, which is not a place name",
                )
            )
        elif loc not in LOCATIONS:
            out.append(
                Finding(
                    "planner.invalid_parameter",
                    index,
                    f"step {index + 1} sends me to {loc!r}, which is not one of my places ({', '.join(LOCATIONS)})",
                )
            )
    return out


def _fulfilment(instruction: str, plan: Sequence[tuple[str, Mapping[str, object]]]) -> list[Finding]:
    skills = [s for s, _ in plan]
    visits = [(i, p.get("location")) for i, (s, p) in enumerate(plan) if s == "navigate_to_zone"]
    out: list[Finding] = []
    rooms = mentioned_rooms(instruction)
    visited = list(dict.fromkeys(str(loc) for _, loc in visits if loc))
    for room in rooms:
        if room not in visited:
            went = " and the ".join(loc.replace("_", " ") for loc in visited) or "nowhere"
            went = f"the {went}" if visited else went
            out.append(
                Finding(
                    "planner.plan_not_fulfilling_request",
                    None,
                    f"the request is about the {room.replace('_', ' ')}, but the plan goes to {went}",
                )
            )
    if _BRING.search(instruction):
        if not any(s in skills for s in FETCHING):
            out.append(
                Finding(
                    "planner.plan_not_fulfilling_request",
                    None,
                    "the plan never asks anyone to put the object on my tray",
                )
            )
        else:
            ask = min(skills.index(s) for s in FETCHING if s in skills)
            if not any(i > ask for i, _ in visits):
                out.append(
                    Finding(
                        "planner.plan_not_fulfilling_request",
                        ask,
                        "the plan never brings the object back to you after picking it up",
                    )
                )
    elif _TELL.search(instruction) and "say" not in skills:
        out.append(Finding("planner.plan_not_fulfilling_request", None, "the plan never says anything"))
    elif _TELL.search(instruction) and visits and skills.index("say") < visits[-1][0]:
        out.append(Finding("planner.plan_not_fulfilling_request", None, "the plan speaks before it reaches the person"))
    if _PIZZA.search(instruction) and "recommend_pizza" not in skills:
        out.append(Finding("planner.plan_not_fulfilling_request", None, "the plan never recommends a pizza"))
    return out


def check_plan(instruction: str, plan: Sequence[tuple[str, Mapping[str, object]]]) -> list[Finding]:
    """Problems of `plan` (skill, params) for `instruction`, most fundamental first.

    A request beyond the robot's abilities explains every other problem of its plan, so it is reported alone.
    """
    action = requested_action(instruction)
    if action in MANIPULATION_VERBS:
        return [
            Finding(
                "planner.request_beyond_capabilities",
                None,
                f"you asked me to {action} something, and I cannot manipulate objects",
            )
        ]
    steps = [f for i, (skill, params) in enumerate(plan) for f in _step_findings(i, skill, params)]
    if steps:
        return steps
    return _fulfilment(instruction, plan) if instruction.strip() else []
