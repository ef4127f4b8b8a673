"""The LLM judge against a fake TextModel (the API boundary); no Ollama server is needed."""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

from hexar.evals.cases import Case, cases
from hexar.evals.judge import Judge, Verdict, agreement, rubric
from hexar.explainers.base import TextModel
from hexar.explainers.errors import ModelError


class FakeJudgeModel:
    """Replies with a fixed text and records what it was asked."""

    name = "fake:judge"

    def __init__(self, reply: str = "", fail: bool = False) -> None:
        self.reply = reply
        self.fail = fail
        self.seen: list[tuple[list[dict[str, str]], Mapping[str, Any] | None]] = []

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        self.seen.append(([dict(m) for m in messages], schema))
        if self.fail:
            raise ModelError("ollama at http://127.0.0.1:11434 failed: connection refused")
        return self.reply


def case7() -> Case:
    return next(c for c in cases() if c.id == "7.1.generic")


def test_fake_is_a_text_model() -> None:
    assert isinstance(FakeJudgeModel(), TextModel)


def test_verdict_and_prompt() -> None:
    model = FakeJudgeModel(json.dumps({"root_cause": 1, "incorrect_facts": 0, "reason": "states charging"}))
    verdict = Judge(model).grade(case7(), "I was on my charger.")
    assert verdict == Verdict(True, False, "states charging")
    messages, schema = model.seen[0]
    assert messages[0] == {"role": "system", "content": rubric()}
    assert "docked on its charger" in messages[1]["content"] and "I was on my charger." in messages[1]["content"]
    assert schema is not None and set(schema["required"]) == {"root_cause", "incorrect_facts", "reason"}


def test_reply_in_a_code_fence() -> None:
    model = FakeJudgeModel('```json\n{"root_cause": "1", "incorrect_facts": "1", "reason": "x"}\n```')
    assert Judge(model).grade(case7(), "a") == Verdict(True, True, "x")


def test_unusable_replies_become_errors_not_grades() -> None:
    assert Judge(FakeJudgeModel("I think it is fine")).grade(case7(), "a").error
    partial = Judge(FakeJudgeModel('{"root_cause": 2, "incorrect_facts": 0}')).grade(case7(), "a")
    assert partial.root_cause is None and partial.incorrect_facts is False
    down = Judge(FakeJudgeModel(fail=True)).grade(case7(), "a")
    assert down.root_cause is None and "connection refused" in down.error


def test_agreement_counts_disagreements_like_annotators() -> None:
    grades = {"root_cause": True, "incorrect_facts": False}
    rows = [("a", grades, Verdict(True, False)), ("b", grades, Verdict(False, False)),
            ("c", grades, Verdict(None, None))]
    by_label = {a.label: a for a in agreement(rows)}
    assert (by_label["root_cause"].judged, by_label["root_cause"].disagreements) == (2, 1)
    assert by_label["root_cause"].cases == ("b",) and by_label["root_cause"].rate == 0.5
    assert by_label["incorrect_facts"].disagreements == 0
