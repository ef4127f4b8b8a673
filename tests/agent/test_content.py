"""Questions about what the robot did get answers from the recording, not the failure answer."""

from __future__ import annotations

from pathlib import Path

from hexar.agent.context import RunSettings
from hexar.agent.session import Session


def _ask(run: Path, *questions: str) -> list[dict[str, object]]:
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    return [session.ask(q, thread=thread) for q in questions]


def test_why_did_you_go_and_where_are_you(suite: Path) -> None:
    went, where, said = _ask(suite / "bagfile_14_1", "Why did you go to the kitchen?", "Where are you now?",
                             "What did you say?")
    assert str(went["answer"]).startswith('I went to the kitchen because step 1 of my plan for your request "Bring '
                                          'me a coffee from the kitchen" was to go there, and I got there.')
    assert "the person did not" not in str(went["answer"])
    # after the failure the robot's recovery drove it back: the last goal of the recording
    assert str(where["answer"]).startswith("I'm in the living room")
    assert "(-1.80, 0.60)" in str(where["answer"])
    assert str(said["answer"]).startswith("I didn't say anything for your request")
    assert 'in my recovery, I said "Sorry, I could not complete the task."' in str(said["answer"])


def test_a_place_the_plan_never_went(suite: Path) -> None:
    (went,) = _ask(suite / "bagfile_3_1", "Why did you go to the kitchen?")
    assert str(went["answer"]).startswith("I didn't go there for your request")
    assert "the dining room" in str(went["answer"])


def test_where_when_the_robot_never_moved(suite: Path) -> None:
    (where,) = _ask(suite / "bagfile_6_1", "Where are you now?")
    assert str(where["answer"]).startswith("My last goal was the kitchen, but I didn't get there")


def test_content_then_why_goes_deeper_on_it(suite: Path) -> None:
    said, why = _ask(suite / "bagfile_19_2", "Did you read me the right recipe?", "why?")
    assert str(said["answer"]).startswith("No. What I said did not match your request")
    assert why["intent"] == "deeper" and "Margherita" in str(why["answer"])
