"""An optional LLM judge (`--judge ollama:MODEL`), graded with evals/data/judge_rubric.md.

It is reported beside the deterministic graders, never instead of them; where the two differ, the report counts
the disagreement as the paper counts disagreement between its human annotators.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass
from importlib import resources
from typing import Any

from hexar.causes import vocabulary
from hexar.evals.cases import Case
from hexar.explainers.base import TextModel
from hexar.explainers.errors import ModelError

SCHEMA: dict[str, Any] = {
    "type": "object",
    "properties": {
        "root_cause": {"type": "integer", "enum": [0, 1]},
        "incorrect_facts": {"type": "integer", "enum": [0, 1]},
        "reason": {"type": "string"},
    },
    "required": ["root_cause", "incorrect_facts", "reason"],
}
LABELS = ("root_cause", "incorrect_facts")
JUDGE_TOKENS = 160


def rubric() -> str:
    return resources.files("hexar.evals").joinpath("data/judge_rubric.md").read_text(encoding="utf-8")


def rubric_hash() -> str:
    return hashlib.sha256(rubric().encode("utf-8")).hexdigest()[:12]


@dataclass(frozen=True)
class Verdict:
    root_cause: bool | None
    incorrect_facts: bool | None
    reason: str = ""
    error: str = ""

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


def _parse(raw: str) -> Verdict:
    found = re.search(r"\{.*\}", raw, re.S)  # tolerate prose or code fences around the object
    if found is None:
        return Verdict(None, None, error=f"no JSON in the judge's reply: {raw[:80]!r}")
    try:
        data = json.loads(found.group(0))
    except ValueError as err:
        return Verdict(None, None, error=f"unreadable judge reply: {err}")
    labels: dict[str, bool | None] = {}
    for key in LABELS:
        value = data.get(key)
        labels[key] = bool(int(value)) if value in (0, 1, "0", "1", True, False) else None
    return Verdict(labels["root_cause"], labels["incorrect_facts"], str(data.get("reason", ""))[:300])


class Judge:
    def __init__(self, model: TextModel, rubric_text: str | None = None) -> None:
        self.model = model
        self.name = model.name
        self.rubric = rubric_text or rubric()

    def prompt(self, case: Case, answer: str) -> str:
        s = case.scenario
        also = "; ".join(vocabulary()[c].means for c in s.also if c in vocabulary()) or "none"
        return "\n".join([
            f"Scenario: {s.category}, module {s.module}",
            f"Instruction: {s.variants[case.variant - 1].instruction}",
            f"Question: {case.question}",
            f"Ground-truth root cause: {s.root_cause}",
            f"Also true of the run: {also}",
            f"Explanation to grade: {answer or '(no answer)'}",
        ])

    def grade(self, case: Case, answer: str) -> Verdict:
        messages = [{"role": "system", "content": self.rubric}, {"role": "user", "content": self.prompt(case, answer)}]
        try:
            raw = self.model.chat(messages, schema=SCHEMA, max_tokens=JUDGE_TOKENS)
        except ModelError as err:
            return Verdict(None, None, error=str(err))
        return _parse(raw)


@dataclass(frozen=True)
class Agreement:
    label: str
    judged: int
    disagreements: int
    cases: tuple[str, ...]

    @property
    def rate(self) -> float:
        return self.disagreements / self.judged if self.judged else 0.0

    def as_dict(self) -> dict[str, Any]:
        return {"label": self.label, "judged": self.judged, "disagreements": self.disagreements,
                "rate": self.rate, "cases": list(self.cases)}


def agreement(rows: Iterable[tuple[str, Mapping[str, Any], Verdict]]) -> list[Agreement]:
    """Judge versus graders per label over (case key, grades, verdict) rows; unusable verdicts are skipped."""
    out: list[Agreement] = []
    items = list(rows)
    for label in LABELS:
        judged = [(key, grades[label], getattr(verdict, label)) for key, grades, verdict in items
                  if getattr(verdict, label) is not None]
        differ = tuple(key for key, ours, theirs in judged if bool(ours) != theirs)
        out.append(Agreement(label, len(judged), len(differ), differ))
    return out
