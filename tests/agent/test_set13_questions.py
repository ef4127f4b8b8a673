"""Questions of round 53's blind set 13 that the answers missed or got wrong, asked again of real consoles written as
recordings and of the simulated runs: a span whose first moment says "was", an identifier inside a longer one,
whether a line is a side effect and how many like it, planner failures NavFn and Smac word as "failed to create
plan, …", lines that name no node, whether someone gave the robot what it brought, and the time at a place."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_a_span_from_a_moment_said_with_was(tmp_path: Path) -> None:
    run = real_module_run("kilted-control-traj-stamp-past", tmp_path / "run")
    (gap,) = converse(run, "How long after arm_controller was activated did the goal arrive?")
    # not from "arm_controllers.yaml" in joint_state_broadcaster's arguments: the identifier stands alone
    assert str(gap["answer"]).startswith("1.1 s passed from controller_manager's \"Activating controllers: [ "
                                         "arm_controller ]\" at 13:52:56 to the goal's start at 13:52:57.")


def test_a_side_effect_question_and_how_many_alike(tmp_path: Path) -> None:
    run = real_module_run("kilted-control-base-no-position-state", tmp_path / "run")
    (knock,) = converse(run, "Are all the \"Can't accept new commands. subscriber is inactive\" warnings just a "
                             "knock-on effect, and how many are there?")
    assert str(knock["answer"]).startswith("Not as its cause: the line you name (diff_drive_controller, 07:07:57, the "
                                           "first of 30 alike) came after the task had already ended, at 07:07:56.")


def test_each_failed_to_create_plan_line_is_a_try(tmp_path: Path) -> None:
    run = real_nav2_run("navgreen-iter23-wp15-start-in-lethal-space-aborted", tmp_path / "run")
    (tries,) = converse(run, "how many times did it retry planning?")
    assert str(tries["answer"]) == ("For step 1 (to drive to (5.50, -2.20)), my planner failed to find a path 4 times, "
                                    "and the step was still going when the recording ends.")


def test_lines_that_name_no_node_are_said_by_whose_words_they_are(tmp_path: Path) -> None:
    run = real_nav2_run("forklift-mpc-foxy-sparse-90-turn-no-feasible-command", tmp_path / "run")
    (whose,) = converse(run, "Which node logged these lines? They have no name.")
    text = str(whose["answer"])
    assert "(ERROR) \"Action server failed while executing action callback: \"ForkliftMpcController found no " \
           "collision-free\" names no node; its words are what nav2_util logs (nav2_ros_common/include/" \
           "nav2_ros_common/simple_action_server.hpp:267@main)" in text
    assert "no catalogue of mine holds its words, so I can't tell whose code wrote it" in text
    assert text.endswith("2 more lines name no node.")


def test_someone_gave_it_or_not(suite: Path) -> None:
    (gave,) = converse(suite / "bagfile_10_2",
                       "Did you actually find the book yourself or did someone give it to you?")
    assert str(gave["answer"]) == ("Someone gave it to me: I asked a person for help, and they agreed to help, and "
                                   "then confirmed that they had helped; no step of my plan had me take it myself.")
    (no,) = converse(suite / "bagfile_15_2", "did someone give you the book?")
    assert str(no["answer"]).startswith("Not as far as my recording shows: I asked a person for help, and they "
                                        "declined")


@pytest.mark.parametrize(("question", "kind"), [
    ("Why did it take you so long in the dining room before you came back?", "long"),
    ("that took almost a minute and a half, what were you waiting for?", "long"),
    ("Which node threw this? The log line has no node name.", "unnamed"),
    ("Which node logged these lines? They have no name.", "unnamed"),
    ("which node failed?", "logs"),
    ("Did you actually find the book yourself or did someone give it to you?", "person"),
])
def test_kinds(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_whether_the_lifecycle_manager_finished_bringing_up(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-amcl-scan-frame-unknown", tmp_path / "run")
    (up,) = converse(run, "Did the lifecycle manager ever finish bringing up all the nav2 nodes?")
    assert str(up["answer"]).startswith("No: my log shows a bring-up that failed: at 02:35:55, "
                                        "lifecycle_manager_navigation (ERROR) \"Failed to change state for node: "
                                        "planner_server.")


def test_an_exit_code_is_said_by_its_signal(tmp_path: Path) -> None:
    run = real_nav2_run("nav2-3508-humble-bt-navigator-died-custom-bt", tmp_path / "run")
    (both,) = converse(run, "What does exit code -8 mean? Is it a problem with my custom BT xml?")
    text = str(both["answer"])
    assert text.startswith("In bt_navigator-28's \"process has died [pid 81493, exit code -8,")
    assert "exit code -8 is signal 8 (SIGFPE), negated: the process ended on an arithmetic error (a division by " \
           "zero)." in text
    # the rest of the question is the finding's
    assert "I couldn't reach my goal because the process of bt_navigator died (exit code -8)" in text
    (alone,) = converse(run, "what is exit code -8?")
    assert str(alone["answer"]).startswith("In bt_navigator-28's")
    assert content_kind("what does exit code -6 mean?") == "means"


def test_a_start_state_moveit_passed_on_to_its_planner_is_no_failure_claimed(tmp_path: Path) -> None:
    from hexar.evals import real_modules

    (case,) = [e for k in real_modules.FILES for e in real_modules.load_excerpts(k)
               if e.id == "agx-arm-ros-teach-open-hand-errors-then-plan-succeeds"]
    run = tmp_path / "run"
    real_modules.write_recording(case, run, task=False)  # the task read from its logs: it has not ended
    (how,) = converse(run, "Did the planning request end up succeeding or did it fail?")
    text = str(how["answer"])
    assert text.startswith("The recording ends before my arm's motion finished. On the way, MoveIt found my start "
                           "state in collision and passed the request on to its planner anyway")
    assert "could not begin" not in text and "couldn't finish" not in text


def test_spans_named_with_one_end_or_a_subject_of_their_own(tmp_path: Path) -> None:
    stuck = real_nav2_run("navgreen-iter23-wp15-start-in-lethal-space-aborted", tmp_path / "a")
    (before,) = converse(stuck, "How long was the robot stuck before the first planning error?")
    assert str(before["answer"]).startswith("38.7 s passed from the goal's start at 00:55:47 to planner_server-13's "
                                            "\"Planning algorithm GridBased failed to generate a valid path")
    up = real_module_run("kilted-control-state-no-initial-value", tmp_path / "b")
    (bringup,) = converse(up, "How long did bringup take from launch until the arm_controller was active?")
    assert str(bringup["answer"]).startswith("1.6 s passed from launch's \"All log files can be found below")
    keepout = real_nav2_run("kilted-nav2-keepout-start", tmp_path / "c")
    (ran,) = converse(keepout, "did the recovery behaviors run before the goal was aborted, and how many?")
    assert str(ran["answer"]).startswith("For step 1 (to drive to (9.00, 4.00)), I ran 8 recoveries (3 spins, 3 waits "
                                         "and 2 backups)")


def test_a_controller_failure_names_the_critics_dwb_logged(tmp_path: Path) -> None:
    run = real_nav2_run("nav2-520-dwb-all-trajectories-oscillating", tmp_path / "run")
    (why,) = converse(run, "Why did DWB reject all 399 trajectories?")
    assert str(why["answer"]) == ("I couldn't reach my goal because my controller failed to compute velocity commands "
                                  "to follow the path. DWB's critics rejected the trajectories it sampled, by share: "
                                  "Oscillation 100% (\"Trajectory is oscillating\").")


def test_an_exception_named_by_its_class_is_a_line_asked_about(tmp_path: Path) -> None:
    run = real_module_run("kilted-rate-sleep-after-shutdown", tmp_path / "run")
    (either,) = converse(run, "Is the ROSInterruptException a real bug or just a side effect of the e-stop shutting "
                              "things down?")
    # two things asked: no bare "yes" before the finding
    assert str(either["answer"]).startswith("The line you name (a node, 13:47:57) is among the lines my finding below "
                                            "rests on.")


def test_dwb_critics_are_read_from_every_line_and_a_zero_share_is_left_out(tmp_path: Path) -> None:
    run = real_nav2_run("oliwall-arm-sweep-dwb-refuses-scan-pose-inside-inflation", tmp_path / "run")
    (what,) = converse(run, "what happened?")
    text = str(what["answer"])
    assert "DWB's critics rejected the trajectories it sampled, by share: RotateToGoal 100% (\"Nonrotation command " \
           "near goal\")." in text
    assert "BaseObstacle" not in text  # 0.00: it rejected none
