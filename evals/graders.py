"""Deterministic graders of the paper's metrics, over an answer's text (any method) and, where a method has them,
its structured causes (HEXAR only; reported beside the text grade, never instead of it).

- root cause identified: the text affirms the ground-truth cause (vocabulary phrasings, hexar/causes.yaml).
- incorrect facts: the text affirms a claim that is false of this run: a cause other than the truth and the
  causes `also` true of it (another module's, or another cause of the same module), blaming the plan when the
  plan was fine, saying the task failed when it succeeded, or saying nothing went wrong when something did.
- explanation accuracy: root cause and no incorrect facts.
- explainer selection (HEXAR): the first explainer the agent used is the scenario's explainer.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from hexar.causes import vocabulary
from hexar.claims import ALL_FINE, PLAN_BLAMED, TASK_FAILED, Claims, read_claims
from hexar.evals.cases import Case

# Paper Table I categories whose task completed (possibly slowly or awkwardly).
SUCCEEDED_CATEGORIES = frozenset({"Normal/Successful", "Sub-Optimal Behaviour", "Social Norm Violation"})
# Speed figures are true of any run that moved; what would be false ("nothing went wrong") is `claim.all_fine`.
NEVER_FALSE = frozenset({"navigation.nominal_speed"})
# Consequences true of every run of a cause, which scenarios.yaml's `also` does not list: a noisy detection
# made the approach poor (scenario 18's ground truth says "so it approached them poorly").
@dataclass(frozen=True)
class Truth:
    """What is true of one case, from evals/data/scenarios.yaml."""

    cause: str
    also: frozenset[str]
    module: str
    explainer: str
    category: str

    @classmethod
    def of(cls, case: Case) -> Truth:
        s = case.scenario
        also = frozenset(s.also)
        return cls(s.cause, also, s.module, s.explainer, s.category)

    @property
    def succeeded(self) -> bool:
        return self.category in SUCCEEDED_CATEGORIES

    def is_false(self, claim: str) -> bool:
        """Whether affirming `claim` states something untrue of this run."""
        if claim == PLAN_BLAMED:
            return self.module != "planning"
        if claim == TASK_FAILED:
            return self.succeeded
        if claim == ALL_FINE:
            return self.category != "Normal/Successful"
        if claim in NEVER_FALSE:
            return False
        return claim in vocabulary() and claim != self.cause and claim not in self.also

    def false_claims(self) -> list[str]:
        """This scenario's list of claims that would be incorrect facts, derived from the vocabulary."""
        return sorted(c for c in [*vocabulary(), PLAN_BLAMED, TASK_FAILED, ALL_FINE] if self.is_false(c))


@dataclass(frozen=True)
class Graded:
    """The answer of one method to one case, as the graders see it."""

    text: str
    causes: Sequence[str] | None = None
    explainers: Sequence[str] | None = None


@dataclass(frozen=True)
class Grades:
    root_cause: bool
    incorrect_facts: bool
    accuracy: bool
    selection: bool | None
    claims: tuple[str, ...]
    false_claims: tuple[str, ...]
    structured: dict[str, bool] | None = field(default=None)

    def as_dict(self) -> dict[str, Any]:
        return {
            "root_cause": self.root_cause, "incorrect_facts": self.incorrect_facts, "accuracy": self.accuracy,
            "selection": self.selection, "claims": list(self.claims), "false_claims": list(self.false_claims),
            "structured": self.structured,
        }


class RootCauseGrader:
    name = "root_cause"

    def grade(self, truth: Truth, claims: Claims) -> bool:
        return truth.cause in claims.affirmed


class IncorrectFactsGrader:
    name = "incorrect_facts"

    def false_claims(self, truth: Truth, claims: Claims) -> tuple[str, ...]:
        return tuple(sorted(c for c in claims.affirmed if truth.is_false(c)))

    def grade(self, truth: Truth, claims: Claims) -> bool:
        return bool(self.false_claims(truth, claims))


class SelectionGrader:
    name = "selection"

    def grade(self, truth: Truth, explainers: Sequence[str] | None) -> bool | None:
        if explainers is None:
            return None
        return bool(explainers) and explainers[0] == truth.explainer


class StructuredGrader:
    """The same two metrics over the cause ids a method returned, for methods that return them."""

    name = "structured"

    def grade(self, truth: Truth, causes: Sequence[str] | None) -> dict[str, bool] | None:
        if causes is None:
            return None
        root = truth.cause in causes
        wrong = any(truth.is_false(c) for c in causes)
        return {"root_cause": root, "incorrect_facts": wrong, "accuracy": root and not wrong}


class Grader:
    """All metrics of one answer."""

    def __init__(self) -> None:
        self.root = RootCauseGrader()
        self.incorrect = IncorrectFactsGrader()
        self.selection = SelectionGrader()
        self.structured = StructuredGrader()

    def grade(self, truth: Truth, answer: Graded) -> Grades:
        claims = read_claims(answer.text)
        root = self.root.grade(truth, claims)
        false = self.incorrect.false_claims(truth, claims)
        return Grades(
            root_cause=root,
            incorrect_facts=bool(false),
            accuracy=root and not false,
            selection=self.selection.grade(truth, answer.explainers),
            claims=tuple(sorted(claims.affirmed)),
            false_claims=false,
            structured=self.structured.grade(truth, answer.causes),
        )


def grade(case: Case, answer: Graded) -> Grades:
    return Grader().grade(Truth.of(case), answer)
