""""What skills do you have?", "what places do you know?", "what is navigate_to_room?": the skills and places of
the home-assistant application (its skill catalogue, which the plan check holds), with what the recording's plans
used of them. A recording of goals read from the logs holds no catalogue, and the answer says so, rather than
giving the task's finding or a list that is not this robot's."""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.plan_check import LOCATIONS
from hexar.explainers.recorded import join_words, place_name

_LEAD = r"^(and |so |but |ok |okay |now |then )?"
SKILLS = re.compile(
    _LEAD + r"(what|which) (skills|abilities|actions|capabilities) (do|did|have|can) you( have| got| use| know)?\b|"
    + _LEAD + r"(what|which) (skills|places|rooms|locations) (do|did|can) you (have|know|go to|drive to|visit)\b|"
    + _LEAD + r"where (all )?can you (go|drive)\W*$|" + _LEAD + r"what (can't|cannot|can not) you do\W*$|"
    # a skill's or place's name as a plan writes it, not any name a stack logs ("what is use_sim_time?")
    + _LEAD + r"what('s| is| was| does) (the |a |an )?(skill |place |room )?(?P<name>(navigate|ask|look|recommend|say|"
    r"explain|pick|place|move|follow|bring|go|find|fetch|deliver|open|grab|kitchen|dining|living|bed|bath)"
    r"(_[a-z]+)+)( mean| do)?\W*$")
# "can you open windows at all?", "are you even able to cook?": whether a skill of mine does it
ABLE = re.compile(r"^(and |so |but )?(can|could) you (even |actually )?(?P<verb>[a-z]+)( [a-z]+){0,3} at all\W*$|"
                  # "couldn't you have just picked it up yourself instead of giving up?"
                  r"^(and |so |but )?(couldn't|could|why couldn't|why didn't|can't) you (just )?(have )?(just )?"
                  r"(?P<verb3>[a-z]+?)(ed)? (it|that|them|the [a-z]+)( up)? (yourself|by yourself|on your own)\b|"
                  r"^(and |so |but )?(are|were) you (even |actually )?(able|capable) (to|of) (?P<verb2>[a-z]+)")
# What each skill of the catalogue does, as the robot says it (hexar_interfaces.md, "Skill catalogue").
_DOES = {"say": "say something aloud", "navigate_to_zone": "drive to one of my places",
         "navigate_to_pose": "drive to a position on my map",
         "ask_human_for_help": "find a person and ask them for help",
         "look_for_human": "look for a person", "recommend_pizza": "recommend a pizza from the ingredients you have",
         "explain": "explain what I did", "pick": "pick something up with my arm",
         "place": "put something down with my arm", "move_arm": "move my arm",
         "follow_joint_trajectory": "run a trajectory on my arm's controllers",
         "command_gripper": "open or close my gripper", "bring_up_controllers": "start my arm's controllers"}
_ARM = ("pick", "place", "move_arm", "follow_joint_trajectory", "command_gripper", "bring_up_controllers")
_HOME = ("say", "navigate_to_zone", "ask_human_for_help", "look_for_human", "recommend_pizza", "explain")


def _mine(log: EventLog) -> tuple[str, ...]:
    """The catalogue's skills this robot has: the home application's, and its arm's where a plan used the arm."""
    armed = any(run.skill in _ARM for t in log.tasks for run in t.skills)
    return _HOME + (("pick", "place") if armed else ())


def _evidence(task: Task) -> list[Evidence]:
    return [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created, item=task.instruction)]


def _able(verb: str, mine: tuple[str, ...], used: list[str]) -> str:
    """Whether a skill of mine does what the verb asked about says ("open"), and what a plan that asked for it got."""
    verb = verb.removesuffix("ing")
    have = [s for s in mine if s.split("_")[0] == verb or verb in _DOES[s].split()]
    if have:
        return "Yes: " + join_words([f"with {s} I {_DOES[s]}" for s in have]) + "."
    planned = [s for s in used if s.split("_")[0] == verb and s not in mine]
    said = f"No: none of my skills does that. My skills are {join_words(list(mine))}."
    if planned:
        said += (f" My recording's plan asked for {join_words([repr(s) for s in planned])}, which is not one of them, "
                 "so that plan was rejected before I started.")
    return said


def skills(question: str, log: EventLog, task: Task) -> Explanation:
    """The skills or places asked about, or what a skill or place name asked about is."""
    q = " ".join(question.lower().split())
    if all(t.derived for t in log.tasks):
        text = ("I can't tell: my recording holds no list of my skills or places, only goals that programs sent my "
                "stack, read from its logs.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    mine = _mine(log)
    used = list(dict.fromkeys(run.skill for t in log.tasks if not t.derived for run in t.skills))
    m = SKILLS.search(q)
    name = m.group("name") if m is not None else None
    places = join_words([place_name(p) for p in LOCATIONS])
    if name is not None:
        steps = [f"step {run.index + 1}" for run in task.skills if run.skill == name]
        asked = f" Step {steps[0].removeprefix('step ')} of my plan asked for it." if steps else ""
        if name in mine:
            text = f"'{name}' is one of my skills: with it I {_DOES[name]}.{asked}"
        elif name in LOCATIONS:
            text = f"'{name}' is one of my places: {place_name(name)}.{asked}"
        else:
            text = (f"'{name}' is none of my skills or places.{asked} My skills are {join_words(list(mine))}; my "
                    f"places are {places}.")
    elif (able := ABLE.search(q)) is not None:
        text = _able(able.group("verb") or able.group("verb2") or able.group("verb3"), mine, used)
    elif re.search(r"\b(places|rooms|locations|where)\b", q):
        went = list(dict.fromkeys(str(run.params["location"]) for t in log.tasks for run in t.skills
                                  if isinstance(run.params.get("location"), str)))
        text = f"I know {len(LOCATIONS)} places: {places}." + (
            f" My recording's plans named {join_words([repr(p) for p in went])}." if went else "")
    else:
        said = [f"{_DOES[s]} ({s})" for s in mine]
        text = f"My skills are to {join_words(said)}." + (
            f" My recording's plans named {join_words(used)}." if used else "")
        cannot = re.search(r"\b(can't|cannot|can not)\b", q) is not None
        if not any(s in _ARM for s in mine):
            limit = "I cannot manipulate objects: to fetch something I ask a person to put it on my tray."
            text = f"{limit} {text}" if cannot else f"{text} {limit}"
        elif cannot:
            text = f"I can do only what my skills do. {text}"
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=_evidence(task))
