"""The cause vocabulary shared by the faithfulness guard and the eval graders, and the causes that say nothing went
wrong, which the router, the guard, the step-by-step walk and fleet triage all read."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from importlib import resources

from hexar.fastyaml import load

# What an explainer reports when nothing went wrong in its module: never a failure's cause, never a finding worth
# a look in a fleet report, never a problem the person has "already heard".
NOTHING_WRONG = frozenset({"planner.plan_ok", "navigation.nominal", "manipulation.nominal", "control.nominal",
                           "ask_human.succeeded", "tts.completed"})
# The figures of a run that went fine (its speed over the distance, the words said as asked): benign wherever a
# nominal cause is, but the router still lets an explainer that found them answer a question about them.
FIGURES_OF_SUCCESS = frozenset({"navigation.nominal_speed", "tts.utterance_matches"})
BENIGN = NOTHING_WRONG | FIGURES_OF_SUCCESS
# Where a cause can lie (causes.yaml's `origin`).
ORIGINS = ("hardware", "setup", "own", "request", "surroundings", "person", "state", "unknown", "none")


@dataclass(frozen=True)
class Cause:
    id: str
    means: str
    patterns: tuple[re.Pattern[str], ...]
    origin: str
    implies: tuple[str, ...] = ()

    @property
    def module(self) -> str:
        return self.id.split(".", 1)[0]

    def stated_in(self, text: str) -> bool:
        return any(p.search(text) for p in self.patterns)


@cache
def vocabulary() -> dict[str, Cause]:
    text = resources.files("hexar").joinpath("causes.yaml").read_text(encoding="utf-8")
    raw = load(text)
    return {
        cid: Cause(cid, entry["means"], tuple(re.compile(p, re.I) for p in entry["patterns"]), entry["origin"],
                   tuple(entry.get("implies", ())))
        for cid, entry in raw.items()
    }


def stated_causes(text: str) -> set[str]:
    """Every known cause whose phrasing appears in `text`."""
    return {cid for cid, cause in vocabulary().items() if cause.stated_in(text)}
