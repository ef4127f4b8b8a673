"""What an answer claims, read from its text alone, so that HEXAR's answers and the baselines' free text are
graded alike.

A cause is claimed when one of its vocabulary phrasings (hexar/causes.yaml) appears affirmed. Four rules keep
plain regex matching from misreading free text:
- denial: "there was no obstacle in my path", "I was well localised" or "the joystick was not engaged" mention a
  cause to rule it out. A negation or a healthy qualifier among the three words before the phrase (after the
  last connective of its clause, so "I didn't move because the joystick..." still affirms) or a "was not" right
  after it makes the match a denial.
- phrasings that carry their own negation ("cannot manipulate", "did not confirm") are already the negative
  statement of the cause: the words before them are not read as a denial.
- inverted phrasings: a few vocabulary patterns name the healthy state ("a stable detection", "knew where I
  was", "confirmed that they had") and state the cause only when negated, so for them the flip goes the other way.
- longest match: "no one confirmed" is a phrasing of `ask_human.not_confirmed`; the shorter "no one" inside it
  must not also count as `ask_human.nobody_detected`.
- a log line quoted verbatim, “[node] …”, is the log's words: none of them is the answer's claim; nor are the words
  of a qualified type name the answer cites ("opennav_docking::SimpleChargingDock").

Besides causes, three claims about the run that no cause id names but that annotators count as incorrect facts
when untrue: blaming the plan, saying the task failed, and saying nothing went wrong.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache

from hexar.causes import vocabulary

# Patterns (by their source text) whose plain form describes the healthy state.
INVERTED: frozenset[tuple[str, str]] = frozenset({
    ("ask_human.unstable_detection", "(stable|steady) detection"),
    ("navigation.poor_localisation", "(knew|know) where I (was|am)"),
    ("ask_human.not_confirmed", "confirm(ed)? (that )?(they|she|he|it) (had|was|were|finished|done)"),
})
NEGATION = re.compile(r"\b(no|not|never|without|nor|neither|nothing|none)\b|n't\b|\bcannot\b", re.I)
# "well localised", "within my 20-second limit": the phrase is there, the problem is not. Not for inverted phrasings.
HEALTHY = re.compile(r"\b(well|correctly|properly|accurately|good|fine|within)\b", re.I)
# A negation before the last of these words belongs to another statement: "I didn't move because the joystick...".
CONNECTIVE = re.compile(r"\b(because|since|as|so|due to|which|that|when|while|and|but|after|then)\b", re.I)
AFTER_DENIAL = re.compile(
    r"^\W*(\w+\W+){0,2}?(was|were|is|are|had been|has been)"
    r"(\s+not\b|n't\b|\s+(off|disabled|inactive|false|fine|ok|okay|good|normal|accurate)\b)",
    re.I,
)
# A log line an answer quotes verbatim, “[node] …” (explainers/module_explainer.py's verbatim): the log's words, not
# the answer's claim ("operation time out" on a lidar's line is no text-to-speech timeout).
QUOTED_LOG = re.compile(r"“\[[^\]\n]*\] [^”]*”")
# A qualified name the answer cites, a plugin or class type ("opennav_docking::SimpleChargingDock",
# "nav2_navfn_planner/NavfnPlanner"): its words name a thing, they state nothing ("Charging" is no charger)
QUALIFIED = re.compile(r"\b[A-Za-z_]\w*(?:::[A-Za-z_]\w*)+\b|\b[a-z_][a-z0-9_]*(?:/[A-Z]\w*)\b")
CLAUSE_END = re.compile(r"[.;:!?()\n]")
WINDOW_WORDS = 3

PLAN_BLAMED = "claim.plan_blamed"
TASK_FAILED = "claim.task_failed"
ALL_FINE = "claim.all_fine"
GENERIC: dict[str, re.Pattern[str]] = {
    PLAN_BLAMED: re.compile(
        r"\b(my|the) plan (was|is|had been) (incorrect|wrong|faulty|invalid|flawed|bad|mistaken|"
        r"not (correct|right|valid))|\b(incorrect|wrong|faulty|invalid|flawed|bad|mistaken) plan\b|"
        r"\bplan(ning)? (error|mistake|failure|fault)", re.I),
    TASK_FAILED: re.compile(
        r"\b(I|the task|it|the robot) (failed|could ?n[o']t|was unable|wasn't able|did ?n[o']t manage)( to)? "
        r"(complete|finish|do|reach|get|bring|deliver|make it)", re.I),
    # Only about the whole run: "nothing went wrong on the way to the kitchen" can be true of one step.
    ALL_FINE: re.compile(
        r"\b(nothing (went|was|had gone) wrong|everything (went|was|worked) (fine|well|ok|okay|smoothly|"
        r"as (planned|expected)))\b(?!\s+(on|with|during|while|when|in|at|for)\b)", re.I),
}


@dataclass(frozen=True)
class Match:
    claim: str
    start: int
    end: int
    affirmed: bool


@dataclass(frozen=True)
class Claims:
    """What a text affirms and what it only mentions to deny."""

    affirmed: frozenset[str]
    denied: frozenset[str]
    matches: tuple[Match, ...]

    @property
    def causes(self) -> frozenset[str]:
        return frozenset(c for c in self.affirmed if not c.startswith("claim."))

    @property
    def generic(self) -> frozenset[str]:
        return frozenset(c for c in self.affirmed if c.startswith("claim."))


@cache
def _patterns() -> tuple[tuple[str, re.Pattern[str], bool], ...]:
    out: list[tuple[str, re.Pattern[str], bool]] = []
    for cid, cause in vocabulary().items():
        for p in cause.patterns:
            out.append((cid, p, (cid, p.pattern) in INVERTED))
    out += [(cid, p, False) for cid, p in GENERIC.items()]
    return tuple(out)


def _clause_bounds(text: str, start: int, end: int) -> tuple[int, int]:
    left = max((m.end() for m in CLAUSE_END.finditer(text, 0, start)), default=0)
    right_m = CLAUSE_END.search(text, end)
    return left, right_m.start() if right_m else len(text)


def _negated(text: str, start: int, end: int, inverted: bool) -> bool:
    if not inverted and NEGATION.search(text[start:end]):
        return False  # the phrasing is itself the negative statement of the cause ("cannot manipulate")
    left, right = _clause_bounds(text, start, end)
    before = text[left:start]
    cut = list(CONNECTIVE.finditer(before))
    if cut:
        before = before[cut[-1].end():]
    window = " ".join(before.split()[-WINDOW_WORDS:])
    if NEGATION.search(window) or (not inverted and HEALTHY.search(window)):
        return True
    return bool(AFTER_DENIAL.search(text[end:right]))


def _raw_matches(text: str) -> Iterator[Match]:
    for cid, pattern, inverted in _patterns():
        for m in pattern.finditer(text):
            if m.end() == m.start():
                continue
            negated = _negated(text, m.start(), m.end(), inverted)
            yield Match(cid, m.start(), m.end(), negated if inverted else not negated)


def _shadowed(m: Match, others: list[Match]) -> bool:
    """Inside a longer phrase of another claim: that claim is what the words say."""
    return any(o.claim != m.claim and o.start <= m.start and m.end <= o.end and (o.end - o.start) > (m.end - m.start)
               for o in others)


def read_claims(text: str) -> Claims:
    text = QUOTED_LOG.sub(lambda m: " " * len(m[0]), text)  # same length: match offsets stay the answer's
    text = QUALIFIED.sub(lambda m: " " * len(m[0]), text)
    found = list(_raw_matches(text))
    kept = tuple(m for m in found if not _shadowed(m, found))
    affirmed = frozenset(m.claim for m in kept if m.affirmed)
    denied = frozenset(m.claim for m in kept if not m.affirmed) - affirmed
    return Claims(affirmed, denied, tuple(sorted(kept, key=lambda m: m.start)))
