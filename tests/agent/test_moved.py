"""'Did the robot move at all?': from my positions where the recording holds them, else from the lines that hand a
path or a trajectory to a controller, else that no such line is there; a plan that never started did not move."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


@pytest.mark.parametrize(("question", "kind"), [
    ("Did the robot move at all before the goal failed?", "moved"), ("did the arm move at all?", "moved"),
    ("Did the trajectory ever get sent to the controller?", "moved"), ("did you move at all?", "moved"),
    ("why didn't you move?", None),  # why is the explainers'
])
def test_whether_it_moved_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_goal_planning_refused_handed_nothing_to_the_controller(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("kilted-nav2-goal-off-map", tmp_path / "run"),
                        "Did the robot move at all before the goal failed?")
    assert asked["answer"] == ("No line of my log hands a path or a trajectory to a controller before the navigation "
                               "goal to (16.00, 4.00) failed, so most likely I did not move; my recording holds no "
                               "position of mine to confirm it.")


def test_a_path_handed_to_the_controller_is_quoted_with_its_count(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("warehouse-waypoint-tb3-single-goal-succeeded", tmp_path / "run"),
                        "did the robot move at all?")
    assert str(asked["answer"]).startswith(
        'A motion was handed to my controllers for the navigation goal to (-2.75, -2.81): at 05:30:34, '
        'controller_server "Received a goal, begin computing control effort."; at 05:30:36, controller_server '
        '"Passing new path to controller." (5 times).')


def test_an_arm_whose_state_was_never_fetched_got_no_trajectory(tmp_path: Path) -> None:
    (asked,) = converse(real_module_run("mogi-simple-arm-move-group-without-sim-time", tmp_path / "run"),
                        "Did the trajectory ever get sent to the controller?")
    assert str(asked["answer"]).startswith("No line of my log hands a path or a trajectory to a controller before the "
                                           "goal to move the arm failed")


def test_home_runs_answer_from_the_plan_and_the_positions(suite: Path) -> None:
    (never,) = converse(suite / "bagfile_1_2", "did you move at all?")
    assert never["answer"] == ('No: no step of your request "Could you bring me the book from the dining room?" '
                               "started, so I did not move.")
    (drove,) = converse(suite / "bagfile_14_2", "did you move at all?")
    assert str(drove["answer"]).startswith('For your request "Could you bring me the book from the dining room?", I '
                                           "drove about 6.3 m")


def test_an_excerpt_that_shows_no_end_claims_no_absence_of_motion(tmp_path: Path) -> None:
    # ifra_srrc issue 3: MoveIt's "The complete state of the robot is not yet known" warnings alone, a goal with no end
    (asked,) = converse(real_module_run("ifra-srrc-3-missing-fixed-joints-nominal", tmp_path / "run"),
                        "did the arm move actually complete?")
    assert str(asked["answer"]).endswith("and my recording holds no position of mine, so it does not show that I "
                                         "moved.")


def test_a_backup_drives_the_base_itself_so_no_controller_line_is_looked_for(tmp_path: Path) -> None:
    # blind set 28: a backup toward a box exits at once with "Collision Ahead - Exiting DriveOnHeading"
    (asked,) = converse(real_nav2_run("kilted-nav2-backup-toward-box", tmp_path / "run"),
                        "Did the robot move at all during the backup before it stopped?")
    assert str(asked["answer"]).endswith("the goal to run backup drives my base without handing a path to a "
                                         "controller, so it does not show how far I moved.")
