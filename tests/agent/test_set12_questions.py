"""Questions of round 53's blind set (12) that the answers missed or got wrong, asked again of real consoles written
as recordings and of the simulated runs: whether every node came up, warnings of the bring-up alone, a goal MoveIt
ended without moving, a crash's stack trace, what a transition number is, a line's meaning from the finding, the time
to a line named by one word, a pleasantry before a question, a time of minutes asked with why, and a quoted line
that holds a parameter's name."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind, module_asked
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_all_nodes_came_up_before_the_goal(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-box-ahead", tmp_path / "run")
    (up,) = converse(run, "Did all the nav2 lifecycle nodes come up before the goal arrived?")
    assert str(up["answer"]) == (
        'Yes: lifecycle_manager_navigation logged "Managed nodes are active" at 01:38:23, 3 s before the goal arrived '
        '(at 01:38:26, bt_navigator (INFO) "Begin navigating from current location (2.00, 4.00) to (10.00, 4.00)").')


def test_a_bring_up_that_failed_is_no_and_no_goal_line_is_said(tmp_path: Path) -> None:
    failed = real_nav2_run("izzyboat-bt-task-navigator-settaskfailed-not-recognized-stale-build", tmp_path / "a")
    (no,) = converse(failed, "did everything come up?")
    assert str(no["answer"]).startswith('No: my log shows a bring-up that failed: at 22:13:20, lifecycle_manager-10 '
                                        '(ERROR) "Failed to change state for node: bt_task_navigator"')
    quiet = real_nav2_run("kilted-nav2-through-navigator-missing", tmp_path / "b")
    (unsure,) = converse(quiet, "Did all the nav2 lifecycle nodes come up before the goal arrived?")
    assert str(unsure["answer"]).endswith("my log holds no line of a goal arriving (Nav2's \"Begin navigating …\"), "
                                          "so I can't say whether that was before one.")


def test_warnings_of_the_bring_up_are_those_before_the_goal(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-box-ahead", tmp_path / "run")
    (warned,) = converse(run, "Any warnings during bring-up I should care about?")
    text = str(warned["answer"])
    assert text.startswith("Yes. My log holds 1 warning while I came up, before the navigation goal to (10.00, 4.00) "
                           "(01:38:20 to 01:38:26 UTC), from bt_navigator: at 01:38:21, \"error_code_name_prefixes")
    assert "controller_server" not in text  # its warnings came while it drove


def test_a_goal_moveit_met_without_moving_is_not_told_as_a_motion(tmp_path: Path) -> None:
    run = real_module_run("moveit2-3566-goal-already-satisfied-nominal", tmp_path / "run")
    moved, error = converse(run, "Did the arm actually move?",
                            'Is "Goal constraints are already satisfied" something I need to handle as an error?')
    assert str(moved["answer"]).startswith("I did not need to move my arm: it was already at the goal, so MoveIt had "
                                           "nothing to plan or execute and ended the goal as a success")
    assert "moved my arm as asked" not in str(moved["answer"])
    assert str(error["answer"]).startswith("Not for this task: it went through after the line you name")


def test_a_stack_trace_from_another_thread_is_a_failed_start(tmp_path: Path) -> None:
    run = real_module_run("r2cs-2320-jtc-segfault-joint-not-in-urdf", tmp_path / "run")
    (why,) = converse(run, "What caused the stack trace right after loading joint_trajectory_controller?")
    text = str(why["answer"])
    assert text.startswith("Starting my drivers and controllers failed")
    assert "no line reports an error" not in text


def test_a_transition_number_is_said_by_its_name(tmp_path: Path) -> None:
    run = real_nav2_run("nav2-4745-smac-hybrid-configure-bad-alloc", tmp_path / "run")
    (what,) = converse(run, "What is transition 10?")
    assert str(what["answer"]) == (
        "In planner_server's \"Caught exception in callback for transition 10\" at 09:20:01, transition 10 is the "
        "lifecycle transition the node's callback was running in: configure (lifecycle_msgs/msg/State's transition "
        "state 10; rclcpp_lifecycle numbers a callback's transition so).")


def test_a_real_console_numbers_activate_13_and_deactivate_14() -> None:
    from hexar.explainers.stack.bringup import TRANSITIONS

    # a real Nav2 console: "Caught exception in callback for transition 13", then "Failed to finish transition 3"
    assert TRANSITIONS[13] == TRANSITIONS[3] == "activate"
    assert TRANSITIONS[14] == TRANSITIONS[4] == "deactivate"


def test_the_time_to_a_line_named_by_one_word_after_the_first(tmp_path: Path) -> None:
    run = real_module_run("kilted-action-result-expired", tmp_path / "run")
    (gap,) = converse(run, "how long between goal accepted and the result coming back?")
    assert str(gap["answer"]).startswith("4.0 s passed from arm_commander's \"Goal accepted\" at 12:59:31 to "
                                         "arm_controller.action_server's \"Sending result response for unknown or "
                                         "expired goal ID")


def test_a_quoted_line_holding_a_parameter_name_is_not_a_parameter_question(tmp_path: Path) -> None:
    from hexar.evals.scenarios.arm import arm_recording_name, simulate_arm_suite

    simulate_arm_suite(tmp_path, only=lambda s, v: v == 1 and s == "controllers_not_found")
    run = tmp_path / arm_recording_name("controllers_not_found", 1)
    (asked,) = converse(run, 'What does "Unable to identify any set of controllers that can actuate the specified '
                             'joints" mean here? Is arm_controller not loaded?')
    assert str(asked["answer"]).startswith("I couldn't finish picking up the cup because MoveIt found no controllers "
                                           "for my arm's joints.")
    (values,) = converse(run, "what are the arm controller's joints?")
    assert "/arm_controller has joints = ['arm_1_joint'" in str(values["answer"])


def test_home_questions_after_a_pleasantry_and_minutes_asked_with_why(suite: Path) -> None:
    who, minute, standing = converse(suite / "bagfile_17_1", "Thanks for the coffee! Who put it on your tray?",
                                     "Why did it take you more than a minute to bring it?",
                                     "What were you doing standing in the kitchen for so long?")
    assert str(who["answer"]).startswith("My recording holds no name: I knew the person only as someone I detected")
    for told in (minute, standing):
        assert str(told["answer"]).startswith('Your request "Bring me a coffee from the kitchen" took 1 min 13 s')
        assert "step 2 (to ask someone for help) took 40 s" in str(told["answer"])


def test_the_ingredients_are_said_as_given_not_as_told(suite: Path) -> None:
    (had,) = converse(suite / "bagfile_20_1", "What did you see we had in the fridge?")
    assert str(had["answer"]).startswith("The ingredients I was given as available were ham, basil, capers")


@pytest.mark.parametrize(("question", "kind"), [
    ("Why did it take you more than a minute to bring it?", "long"),
    ("What were you doing standing in the kitchen for so long?", "long"),
    ("Why did it take you so long?", None),  # why it was slow: the explainers'
    ("What were you doing when it failed?", "doing"),
    ("Thanks for the coffee! Who put it on your tray?", "person"),
    ("Did all the nav2 lifecycle nodes come up before the goal arrived?", "all_up"),
    ("Which of the three legs took the longest, and why?", "long"),
    ("What is transition 10?", "means"),
])
def test_kinds(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_rate_that_dropped_is_no_arm_question() -> None:
    assert module_asked("The planner loop dropped to about 3.3 Hz. Is the planner overloaded?") is None
    assert module_asked("why did you drop the cup?") == "manipulation"


def test_a_line_no_catalogue_explains_means_what_the_finding_rests_on_it(tmp_path: Path) -> None:
    run = real_nav2_run("opennav-docking-99-docking-server-reconfigure-crash", tmp_path / "run")
    (means,) = converse(run, "what does 'Caught exception in callback for transition 10' mean?")
    assert str(means["answer"]).startswith(
        "My catalogues hold no meaning of their own for docking_server's \"Caught exception in callback for "
        "transition 10\" at 22:13:20, but my finding rests on it: I couldn't reach my goal because my navigation "
        "stack was misconfigured and a node of it never came up: docking_server stopped in a lifecycle transition")


def test_whether_a_line_caused_it_and_slash_joined_words(tmp_path: Path) -> None:
    wide = real_nav2_run("kilted-nav2-amcl-robot-too-wide", tmp_path / "a")
    (caused,) = converse(wide, "Is the inflation radius error (0.550 smaller than inscribed radius 0.598) what caused "
                               "the planning failure?")
    assert str(caused["answer"]).startswith("I can't tell from my logs whether the line you name "
                                            "(global_costmap.global_costmap, 02:38:13) is")
    saver = real_nav2_run("nav2-3048-galactic-gmapping-map-volatile-map-saver-durability-qos", tmp_path / "b")
    (related,) = converse(saver, "Are the free/occupied threshold warnings related to the failure?")
    assert str(related["answer"]).startswith("My finding below does not rest on the line you name (map_saver, "
                                             "08:48:21)")
