"""The recorded items an answer cites, said as sentences: the first "why?" (agent/nodes.py's follow-up), and a
question that asks for a specific the finding leaves out ("which joint?", "by how much?", "what was the tolerance?"),
whose answer is in the lines the finding rests on."""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.explainers.base import Explanation
from hexar.render import clock

_SOURCE = {
    "/rosout": "my log", "launch.log": "my launch's log", "/task_info": "my task status",
    "/amcl_pose": "my localisation",
    "/joy_priority": "my joystick switch", "/power/is_charging": "my charger", "/diagnostics": "my diagnostics",
    "/episodic_memory": "my ask-for-help skill", "/skills/say/events": "my speech",
    "/skills/recommend_pizza/events": "my pizza recommender", "/parameter_events": "my nodes' parameters",
}
CITED = 3  # recorded items told at once: the explainers' strongest

# A question for one specific of a failure, which the finding's sentence leaves to the recorded lines.
SPECIFIC = re.compile(
    r"^(and |so |but |ok |okay )?(which|what) (joints?|controllers?|nodes?|plugins?|topics?|frames?|parameters?|"
    r"values?|error codes?|exceptions?|tolerances?|planners?|links?|files?|lines?|thresholds?|devices?|ports?|"
    r"interfaces?|trajector(y|ies)|critics?)\b(?! (can|could|should|do|does|would|will) (i|we|you) )|"
    r"^(and |so |but )?(by )?how (much|far off|big was the error)\W*$|"
    r"^(and |so |but )?how (old|stale|late|out of date) (was|were|is) (the|my|your) [a-z ]+\W*$|"
    r"^(and |so |but )?what (was|were) the (tolerances?|errors? values?|values?|limits?|thresholds?|exceptions?|"
    r"error codes?)\W*$")


def asks_specific(question: str) -> bool:
    return SPECIFIC.search(" ".join(question.lower().split())) is not None


def recorded(t: int, topic: str, item: str) -> str:
    source = _SOURCE.get(topic, topic)
    if item in {"data=True", "data=False"}:  # a recorded on/off flag
        return f"at {clock(t)} {source} was {'on' if item == 'data=True' else 'off'} ({topic})"
    # a logged message may end in a newline ("Known controllers and their joints:\n"): said without it
    return f"at {clock(t)} {source} recorded \"{' '.join(item.split())}\""


def cited(exps: Sequence[Explanation]) -> str:
    """'Here is what I recorded: at ... my log recorded "..."; ...' for the explainers' first CITED items (the
    strongest), told in the order they happened; '' when they cite none."""
    items = list(dict.fromkeys((ev.t, ev.topic, ev.item) for e in exps for ev in e.evidence if ev.item))
    said = [recorded(*ev) for ev in sorted(items[:CITED])]
    return ("Here is what I recorded: " + "; ".join(said) + ".") if said else ""
