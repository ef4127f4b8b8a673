""""What did they say?", "why did she say no?", "where was he?", "what was her name?": told from what the help skill
recorded of the person, and never more: no words, reasons, map position or name the recording does not hold."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.events import contract as c
from hexar.events import read_recording
from tests.agent.helpers import converse


@pytest.mark.parametrize(("question", "kind"), [
    ("what did they say?", "person"), ("why did she say no?", "person"), ("where was he?", "person"),
    ("what was her name?", "person"), ("who was that person?", "person"), ("what was their answer?", "person"),
    ("what did you ask her?", "talked"), ("what did you say to them?", "talked"),
    ("what did you say?", "said"), ("where were you?", None),
])
def test_questions_about_the_person_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def _recorded(run: Path, key: str) -> str:
    log = read_recording(run)
    return next(v for r in log.statuses[c.EPISODIC_MEMORY] for k, v in r.data_items() if k == key)


def test_a_person_who_declined_is_told_as_only_what_was_recorded(suite: Path) -> None:
    run = suite / "bagfile_15_1"
    assert _recorded(run, "user_accepted") == "False"
    said, why, name, where, asked = converse(run, "what did they say?", "why did they say no?",
                                             "what was her name?", "where was she?", "what did you ask her?")
    assert said["answer"] == "My recording holds only their yes or no, not their words: they declined."
    assert why["answer"] == "I can't tell why: my recording holds only that they declined, not their reasons."
    assert str(name["answer"]).startswith("My recording holds no name")
    assert where["answer"] == (f"I measured the person at {_recorded(run, 'person_distance')} m from me when I "
                               "detected them, but my recording holds no position for them on my map.")
    assert '("Could you please put the coffee on my tray?")' in str(asked["answer"])
    assert {e["item"].split(" = ")[0] for e in said["evidence"]} >= {"user_accepted"}  # type: ignore[union-attr]


def test_a_person_who_helped_and_one_never_found(suite: Path) -> None:
    (helped,) = converse(suite / "bagfile_10_1", "what did they say?")
    assert helped["answer"] == ("My recording holds only their yes or no, not their words: they agreed to help, and "
                                "then confirmed that they had helped.")
    (nobody,) = converse(suite / "bagfile_11_1", "what did they say?")
    assert nobody["answer"] == "I never detected anybody to ask, so my recording holds nothing of a person."
    (pizza,) = converse(suite / "bagfile_20_1", "what did they say?")
    assert pizza["answer"] == "I asked nobody for help in this task, so my recording holds nothing of a person."
