"""'What else happened?' walks the task's findings in plan order, each naming its real goal."""

from __future__ import annotations

import re
from pathlib import Path

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.events import read_recording


def _walk(run: Path, first: str, turns: int = 6) -> list[str]:
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.ask(first)["thread"]
    answers: list[str] = []
    for _ in range(turns):
        answers.append(session.ask("what else happened?", thread=thread)["answer"])
        if answers[-1].startswith("Nothing else happened"):
            break
    return answers


def test_blocked_approach_is_not_the_kitchen(suite: Path) -> None:
    """The kitchen leg succeeded; the blocked trip was the approach to the person, told in the first answer."""
    answers = _walk(suite / "bagfile_14_1", "What happened?")
    assert answers[0].startswith("Step 1, going to the kitchen: I reached the kitchen")
    assert not any("couldn't reach the kitchen" in a for a in answers)
    assert any(a.startswith("Steps 3 (to go to the living room) and 4") for a in answers)
    assert answers[-1].startswith('Nothing else happened in your request "Bring me a coffee from the kitchen"')
    assert "task 2" in answers[-1]  # the robot's own recovery, named as such
    assert len(set(answers)) == len(answers)


def test_an_approach_inside_a_skill_names_the_person_and_coordinates(suite: Path) -> None:
    run = suite / "bagfile_17_1"
    goals = {m.group(0) for line in read_recording(run).logs
             if (m := re.match(r"Navigating to the person at \(-?[\d.]+, -?[\d.]+\)", line.msg))}
    answers = _walk(run, "What happened?")
    approach = [a for a in answers if "approach to the person at" in a]
    assert len(approach) == 1
    assert any(g.removeprefix("Navigating to ") in approach[0] for g in goals)
    assert "kitchen" not in approach[0] and "living room" not in approach[0]
    assert [a.split(",")[0] for a in answers if a.startswith("Step")] == ["Step 1", "Step 3", "Step 4"]


def test_nothing_else_is_said_plainly(suite: Path) -> None:
    answers = _walk(suite / "bagfile_1_1", "What happened?")
    assert answers == [answers[-1]] and answers[0].startswith("Nothing else happened")


def test_the_mismatch_is_a_finding_of_its_own(suite: Path) -> None:
    answers = _walk(suite / "bagfile_19_2", "Why did you stop talking in the middle?")
    assert any("What I said did not match your request" in a and "lasagne" in a for a in answers)


def test_the_recovery_after_an_invalid_plan_is_named_in_words(suite: Path) -> None:
    answers = _walk(suite / "bagfile_1_1", "What happened?")
    assert answers[-1].startswith('Nothing else happened in your request "Bring me a coffee from the kitchen"')
    assert "my own recovery task after task 1 had an invalid plan (task 2)" in answers[-1]
