""""Where is the cup?", "did you drop it?": what the task's pick and place steps did with the object, on the arm's
recordings and on /task_info runs where the place failed or a trip failed after the pick."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.objects import object_asked
from hexar.evals.scenarios.arm import arm_recording_name, simulate_arm_suite
from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import read_recording
from tests.agent.helpers import converse

T0 = 1_741_600_000_000_000_000
PLAN = [("navigate_to_zone", {"location": "kitchen"}), ("pick", {"object": "red_mug"}),
        ("navigate_to_zone", {"location": "dining_room"}), ("place", {"object": "red_mug"}),
        ("say", {"input": "Here is your mug."})]


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s in {"nominal", "tolerance"})
    return out


def _fetch(tmp_path: Path, ends: list[str]) -> Path:
    """A fetch task's /task_info updates, step by step, each step ending as `ends` says (then the rest wait)."""
    b = BagBuilder()
    statuses = [("waiting", "")] * len(PLAN)
    t = T0

    def publish() -> None:
        b.task_info(t, {"instruction": "Bring me the red mug from the kitchen", "task_id": "T1",
                        "task_status": "valid", "task_error_msg": "",
                        "skill_sequence": [{"skill": s, "params": p, "status": st, "error_msg": em}
                                           for (s, p), (st, em) in zip(PLAN, statuses, strict=True)]})

    publish()
    for i, end in enumerate(ends):
        t += 1_000_000_000
        statuses[i] = ("Running", "")
        publish()
        t += 5_000_000_000
        if end != "Running":  # a step still under way when the recording ends
            statuses[i] = (end, "" if end == "succeeded" else "The skill has been aborted")
            publish()
    return b.write(tmp_path / "fetch")


def test_a_pick_that_failed_never_held_the_cup(arm: Path) -> None:
    where, dropped, kitchen = converse(arm / arm_recording_name("tolerance", 1), "where is the cup?",
                                       "did you drop it?", "where is the kitchen?")
    assert where["intent"] == "content"
    assert where["answer"].startswith("I never got hold of the cup: picking it up in the kitchen failed, so I did "
                                      "not carry it anywhere. Picking up the cup could not go on because my arm "
                                      "strayed from its planned trajectory")
    assert dropped["answer"].startswith("No. I never got hold of the cup")
    assert "I never got hold" not in kitchen["answer"]  # a place, not the task's object


def test_a_fetch_that_went_well_put_the_cup_down_where_it_was_to_go(arm: Path) -> None:
    where, picked, holding = converse(arm / arm_recording_name("nominal", 1), "Where's my cup?",
                                      "did you pick up the cup?", "what are you holding?")
    told = "I put the cup down in the dining room, after I picked it up in the kitchen."
    assert where["answer"] == told and picked["answer"] == f"Yes. {told}" and holding["answer"] == told


@pytest.mark.parametrize(("ends", "question", "said"), [
    (["succeeded", "succeeded", "succeeded", "failed"], "where is the red mug?",
     "I picked up the red mug in the kitchen, but putting it down in the dining room failed: my recording does "
     "not show whether I still hold it."),
    (["succeeded", "succeeded", "failed"], "do you still have the mug?",
     "Yes. I picked up the red mug in the kitchen and never got to put it down: step 3 (to go to the dining room) "
     "failed before that."),
    (["succeeded", "succeeded", "Running"], "what are you holding?",
     "I picked up the red mug in the kitchen and have not put it down yet."),
    (["failed"], "did you drop the mug?",
     "No. I never picked up the red mug: step 2 (to pick up the red mug) never started, because step 1 (to go to "
     "the kitchen) failed."),
])
def test_what_the_steps_say_became_of_the_object(tmp_path: Path, ends: list[str], question: str, said: str) -> None:
    (answer,) = converse(_fetch(tmp_path, ends), question)
    assert answer["answer"].startswith(said), answer["answer"]


@pytest.mark.parametrize(("question", "meant"), [
    ("where is the mug", "red_mug"), ("did you drop it?", "red_mug"), ("what were you carrying?", "red_mug"),
    ("where did you put the red mug?", "red_mug"), ("where is the kitchen?", None), ("where are you?", None),
    ("why did you stop?", None), ("did you drop the plate?", None), ("where is the mugrack?", None),
    ("did you get stuck?", None),
])
def test_which_questions_ask_about_the_tasks_object(tmp_path: Path, question: str, meant: str | None) -> None:
    task = read_recording(_fetch(tmp_path, ["succeeded"])).task()
    assert object_asked(question, task) == meant


def test_a_task_that_picks_nothing_has_no_object_to_ask_about(suite: Path) -> None:
    (answer,) = converse(suite / "bagfile_5_1", "where is the coffee?")
    assert answer["intent"] != "content" and "something blocked my path" in answer["answer"]


def test_an_object_is_named_by_whole_words(arm: Path) -> None:
    task = read_recording(arm / arm_recording_name("nominal", 1)).task()
    assert object_asked("where is the cup?", task) == "cup"
    assert object_asked("where is the cupboard?", task) is None
