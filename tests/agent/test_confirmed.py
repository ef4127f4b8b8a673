""""Were you charging?", "was your path blocked?": a yes-or-no question about one condition is answered "Yes." where
the explainer found it, "No." where it found nothing wrong, and with no yes or no where it found another problem."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.overview import confirmed
from hexar.agent.session import Session
from hexar.causes import BENIGN


def _ask(run: Path, question: str) -> str:
    return str(Session(RunSettings(recording=run, llm="none")).ask(question)["answer"])


@pytest.mark.parametrize(("run", "question", "lead"), [
    ("bagfile_7_3", "were you charging?", "Yes. I couldn't reach the kitchen because I was plugged into my charger"),
    ("bagfile_6_2", "were you in manual mode?", "Yes. I couldn't reach the dining room because my joystick"),
    ("bagfile_5_1", "was your path blocked?", "Yes. I couldn't reach the kitchen because something blocked my path"),
    ("bagfile_5_1", "wasn't something in the way?", "Yes. I couldn't reach the kitchen because something blocked"),
    ("bagfile_10_1", "was your path blocked?", "No. I reached the kitchen without any problem."),
    # another problem found: it is told, with no yes or no that nothing decided
    ("bagfile_7_3", "was your path blocked?", "I couldn't reach the kitchen because I was plugged into my charger"),
    # a recorded flag decides its own yes or no, and the problem found follows
    ("bagfile_6_2", "were you charging?", 'No: my charging flag (/power/is_charging) stayed off while I worked on '
                                          'your request "Could you bring me the book from the dining room?". I '
                                          "couldn't reach the dining room because my joystick"),
])
def test_a_condition_asked_about(suite: Path, run: str, question: str, lead: str) -> None:
    assert _ask(suite / run, question).startswith(lead)


def test_only_yes_or_no_questions_about_one_condition_get_a_lead() -> None:
    assert confirmed("why was your path blocked?", {"navigation.blocked_path"}, BENIGN) == ""
    assert confirmed("what happened?", {"navigation.blocked_path"}, BENIGN) == ""
    assert confirmed("was it blocked or were you charging?", {"navigation.blocked_path"}, BENIGN) == ""
    assert confirmed("was your path blocked?", {"navigation.blocked_path"}, BENIGN) == "Yes."


def test_did_you_finish_the_sentence_is_not_a_yes_or_no_on_the_task(suite: Path) -> None:
    """"Did you finish?" asks about the task; "did you finish the sentence?" about a sentence, which a task that
    failed at asking for help never spoke: no "No." taken from the task's outcome."""
    from hexar.agent.overview import yes_or_no

    assert yes_or_no("did you finish?", "failed") == "No." and yes_or_no("did you finish it?", "succeeded") == "Yes."
    assert yes_or_no("did you finish the sentence?", "failed") == ""
    assert not _ask(suite / "bagfile_16_1", "did you finish the sentence?").startswith("No.")


def test_a_question_that_finds_nothing_new_says_so_rather_than_repeating_as_news(arm: Path) -> None:
    from hexar.agent.nodes import SAID_BEFORE
    from hexar.evals.scenarios.arm import arm_recording_name

    run = arm / arm_recording_name("controllers_not_found", 1)
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    why, which, how = (str(session.ask(q, thread=thread)["answer"])
                       for q in ("why did it fail?", "which controller?", "how did it fail?"))
    assert "MoveIt found no controllers for my arm's joints" in why
    # "which controller?" asks for a specific the finding leaves to its lines: those, not the finding again
    assert which.startswith("Here is what I recorded: ") and "Unable to identify any set of controllers" in which
    assert "MoveIt found no controllers" not in which
    assert how == f"{SAID_BEFORE} {why}"
    # asked first, in a conversation of its own, it is no repetition: the finding, then its lines
    assert _ask(run, "which controller?") == f"{why} {which}"


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from hexar.evals.scenarios.arm import simulate_arm_suite

    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s == "controllers_not_found")
    return out
