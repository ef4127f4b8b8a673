""""What skills do you have?", "what places do you know?", "what is navigate_to_room?": the home application's
catalogue (hexar_interfaces.md) and what the recording's plans named of it; a recording of goals read from the logs
says it holds no such list."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals import real_nav2
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse


@pytest.mark.parametrize(("question", "kind"), [
    ("what skills do you have?", "skills"), ("what places do you know?", "skills"), ("where can you go?", "skills"),
    ("what is navigate_to_room?", "skills"), ("what does ask_human_for_help do?", "skills"),
    ("what is use_sim_time?", "mentions"), ("what can you do?", None), ("where did you go?", "went"),
])
def test_skills_and_places_are_their_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_skill_the_planner_made_up_is_said_to_be_none_of_mine(suite: Path) -> None:
    made_up, real, listed = converse(suite / "bagfile_1_1", "what is navigate_to_room?", "what is navigate_to_zone?",
                                     "what skills do you have?")
    assert made_up["answer"] == (
        "'navigate_to_room' is none of my skills or places. Step 1 of my plan asked for it. My skills are say, "
        "navigate_to_zone, ask_human_for_help, look_for_human, recommend_pizza and explain; my places are the "
        "kitchen, the dining room and the living room.")
    assert str(real["answer"]).startswith("'navigate_to_zone' is one of my skills: with it I drive to one of my "
                                          "places.")
    text = str(listed["answer"])
    assert "find a person and ask them for help (ask_human_for_help)" in text
    assert text.endswith("I cannot manipulate objects: to fetch something I ask a person to put it on my tray.")


def test_places_and_an_arm_s_skills(suite: Path, tmp_path: Path) -> None:
    (places,) = converse(suite / "bagfile_2_1", "what places do you know?")
    assert places["answer"] == ("I know 3 places: the kitchen, the dining room and the living room. My recording's "
                                "plans named 'kitchen_counter' and 'living_room'.")
    simulate_arm_suite(tmp_path, only=lambda s, v: v == 1 and s == "nominal")
    (arm,) = converse(tmp_path / "armfile_nominal_1", "what skills do you have?")
    assert "pick something up with my arm (pick)" in str(arm["answer"])
    assert "cannot manipulate" not in str(arm["answer"])


def test_goals_read_from_the_logs_hold_no_skill_list(tmp_path: Path) -> None:
    case = next(e for e in real_nav2.corpus() if e.id == "tb4-591-jazzy-no-footprint")
    (asked,) = converse(real_nav2.write_recording(case, tmp_path / "run", task=False), "what skills do you have?")
    assert asked["answer"] == ("I can't tell: my recording holds no list of my skills or places, only goals that "
                               "programs sent my stack, read from its logs.")


def test_whether_i_can_do_something_at_all_is_answered_from_my_skills(suite: Path) -> None:
    """"Can you open windows at all?" after a plan that asked for open_window: no skill of mine does it, and that
    is why the plan was rejected; "are you able to say things?" is yes, with the skill."""
    (windows,) = converse(suite / "bagfile_4_1", "Can you open windows at all?")
    assert str(windows["answer"]).startswith("No: none of my skills does that. My skills are say, navigate_to_zone")
    assert "My recording's plan asked for 'open_window', which is not one of them, so that plan was rejected before " \
           "I started." in str(windows["answer"])
    (say,) = converse(suite / "bagfile_4_1", "are you able to say things?")
    assert say["answer"] == "Yes: with say I say something aloud."
