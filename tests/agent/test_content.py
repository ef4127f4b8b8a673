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
    assert str(went["answer"]).startswith("I did not go to the kitchen for your request")
    assert "I went to the dining room and the living room" in str(went["answer"])


def test_only_a_reached_place_is_where_i_went(suite: Path) -> None:
    """bagfile_5_1 stops on the way to the kitchen: the later steps only ever waited, so no answer may say the robot
    went to the living room, and a room in no step is not answered with rooms it never reached."""
    living, dining, kitchen, anywhere = _ask(suite / "bagfile_5_1", "Why did you go to the living room?",
                                             "Why did you go to the dining room?", "Why did you go to the kitchen?",
                                             "Where did you go?")
    assert str(living["answer"]).startswith("I did not go to the living room: step 3 of my plan")
    assert "step 1 (to go to the kitchen) failed first, so I never set off" in str(living["answer"])
    assert str(dining["answer"]).startswith("I did not go to the dining room for your request")
    assert "I tried to go to the kitchen but didn't get there, and I never set off for the living room" in \
        str(dining["answer"])
    assert str(kitchen["answer"]).startswith("I tried to go to the kitchen because step 1")
    for answer in (living, dining, kitchen, anywhere):
        assert "I went to" not in str(answer["answer"]), answer["answer"]


def test_a_recovery_trip_counts_where_the_request_never_went(suite: Path) -> None:
    """bagfile_14_1: the request never got to the living room, the recovery task drove there."""
    (went,) = _ask(suite / "bagfile_14_1", "Why did you go to the living room?")
    assert str(went["answer"]).startswith("I went to the living room because step 1 of my plan for my own recovery "
                                          "task after task 1 failed (task 2)")


def test_where_when_the_robot_never_moved(suite: Path) -> None:
    (where,) = _ask(suite / "bagfile_6_1", "Where are you now?")
    assert str(where["answer"]).startswith("My last goal was the kitchen, but I didn't get there")


def test_content_then_why_goes_deeper_on_it(suite: Path) -> None:
    said, why = _ask(suite / "bagfile_19_2", "Did you read me the right recipe?", "why?")
    assert str(said["answer"]).startswith("No. What I said did not match your request")
    assert why["intent"] == "deeper" and "Margherita" in str(why["answer"])
