"""Questions about nothing the robot did ("what is the capital of France?") are refused with the reason, and
questions about HEXAR itself ("what can you do?") are answered by what it does, never with the task's finding."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from hexar.agent.classifier import examples
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.agent.topic import ABOUT_ME, OFF_TOPIC, about_me, off_topic, recording_words
from hexar.cli import main
from hexar.evals.cases import cases
from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import read_recording

T0 = 1_741_600_000_000_000_000
OFF = ["what is the capital of France?", "tell me a joke", "what's the weather like?", "who is the president",
       "what is the population of germany", "how tall is mount everest", "play some music"]
PHRASINGS = yaml.safe_load((Path(__file__).parent / "data" / "question_phrasings.yaml").read_text(encoding="utf-8"))


def _ask(run: Path, *questions: str) -> list[dict[str, Any]]:
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    return [session.ask(q, thread=thread) for q in questions]


def test_every_question_people_ask_about_the_robot_is_on_topic() -> None:
    asked = {c.question for c in cases()} | {q for qs in examples().values() for q in qs}
    asked |= {q for q, _, _ in PHRASINGS["accepted"]}
    asked |= {"why?", "and then?", "wher is my cofee", "what if I had no basil?", "why not a Hawaiian?",
              "how long did it take?", "did you drop it?", "where did you go?", "who did you talk to?"}
    assert [q for q in asked if off_topic(q)] == []


@pytest.mark.parametrize("question", OFF)
def test_a_question_about_the_world_is_off_topic(question: str) -> None:
    assert off_topic(question) and not about_me(question)


def test_a_thing_the_recording_names_is_on_topic(tmp_path: Path) -> None:
    b = BagBuilder()
    b.task_info(T0, {"instruction": "Fetch the screwdriver from the workshop", "task_id": "T1", "task_status": "valid",
                     "task_error_msg": "", "skill_sequence": [
                         {"skill": "navigate_to_zone", "params": {"location": "workshop"}, "status": "succeeded",
                          "error_msg": ""},
                         {"skill": "pick", "params": {"object": "torque_wrench"}, "status": "failed",
                          "error_msg": "The skill has been aborted"}]})
    run = b.write(tmp_path / "fetch")
    words = recording_words(read_recording(run).tasks)
    assert off_topic("where is the screwdriver?") and off_topic("why no wrench?")
    assert not off_topic("where is the screwdriver?", words) and not off_topic("why no wrench?", words)
    (answer,) = _ask(run, "where is the torque wrench?")
    assert answer["intent"] != "offtopic" and answer["error"] == "", answer


def test_off_topic_is_refused_without_the_tasks_finding_and_the_talk_goes_on(suite: Path) -> None:
    first, off, why = _ask(suite / "bagfile_5_1", "Why didn't you bring me the coffee?",
                           "what is the capital of France?", "why?")
    assert "something blocked my path" in str(first["answer"])
    assert off["intent"] == "offtopic" and off["answer"] == OFF_TOPIC and off["explainers"] == []
    assert "is not about anything I did" in str(off["error"]) and "blocked" not in str(off["answer"])
    # the refusal does not cut the conversation: "why?" still goes deeper on the blocked path
    assert why["route"] == "followup" and "Failed to make progress" in str(why["answer"]), why["answer"]


def test_ask_refuses_off_topic_with_one_error_line(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["ask", str(suite / "bagfile_10_1"), "tell me a joke", "--llm", "none"])
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert code != 0 and captured.out == "" and "\n" not in err and "Traceback" not in err
    assert err.startswith("ERROR: 'tell me a joke' is not about anything I did"), err
    assert "reached the kitchen" not in err


@pytest.mark.parametrize("question", ["what can you do?", "who are you?", "help", "what can I ask you?",
                                      "who made you"])
def test_a_question_about_hexar_is_answered_by_what_it_does(suite: Path, question: str) -> None:
    (answer,) = _ask(suite / "bagfile_5_1", question)
    assert answer["intent"] == "about" and answer["error"] == "" and answer["answer"] == ABOUT_ME
    assert answer["explainers"] == [] and answer["causes"] == []


def test_what_can_you_do_about_it_is_still_a_fix(suite: Path) -> None:
    first, fix = _ask(suite / "bagfile_5_1", "Why didn't you bring me the coffee?", "what can you do about it?")
    assert not about_me("what can you do about it?")
    assert fix["intent"] == "helped" and fix["answer"] != ABOUT_ME and "blocked" in str(first["answer"])


@pytest.mark.parametrize(("question", "start"), [
    ("what is a costmap?", "A costmap is the grid map my navigation plans on"),
    ("What does AMCL mean?", "AMCL (adaptive Monte Carlo localisation)"),
    ("whats use_sim_time", "use_sim_time is a ROS 2 parameter"),
    ("what is MoveIt?", "MoveIt is the ROS 2 software that plans my arm's motions"),
    ("what does the controller do?", "A controller turns a planned motion into commands"),
])
def test_a_word_of_the_answers_is_defined(suite: Path, question: str, start: str) -> None:
    first, meant, why = _ask(suite / "bagfile_8_1", "what happened?", question, "why?")
    assert "not sure where I was on my map" in str(first["answer"])
    assert meant["intent"] == "about" and str(meant["answer"]).startswith(start) and meant["error"] == ""
    assert meant["explainers"] == [] and meant["causes"] == []
    # the definition does not cut the conversation: "why?" still goes deeper on the first answer
    assert why["route"] == "followup" and str(why["answer"]).startswith("Here is what I recorded")


def test_every_glossary_entry_loads_and_no_known_question_is_taken_for_a_definition() -> None:
    from hexar.agent.topic import _glossary, defined

    terms = _glossary()
    assert len(terms) >= 30 and all(len(meaning.split()) >= 10 for meaning in terms.values())
    for term in terms:
        assert defined(f"what is {term}?") == terms[term]
    asked = {c.question for c in cases()} | {q for qs in examples().values() for q in qs}
    asked |= {q for q, _, _ in PHRASINGS["accepted"]} | {"what did the controllers do?", "what is the plan?",
                                                         "what is the problem?", "what was your plan?"}
    assert [q for q in asked if defined(q)] == []
