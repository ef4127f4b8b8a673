"""Questions a developer asks of a real recording (rosbags files written from real Nav2 and module excerpts, tasks
derived from their logs) and of the simulated arm, answered from what the logs hold: the named thing's lines, a
sensor the log never names, the staleness of a state, whether a goal was reached, and a request to install."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.agent.overview import asks_fix
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse, real_module_run, real_nav2_run


@pytest.mark.parametrize(("question", "kind"), [
    ("what is the initial pose?", "mentions"), ("is odometry published?", "topic_data"),
    ("is the lidar working?", "mentions"), ("what resource?", "mentions"), ("was the simulation paused?", "mentions"),
    ("did you reach the goal or not?", None), ("how far was the collision?", None),
    ("what was ahead of you?", "blocked"), ("did the arm hit something?", "contact"),
])
def test_kinds(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_goal_reached_or_not_is_the_goal_s_outcome(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("nav2-1367-reached-goal-but-navigation-failed", tmp_path / "run"),
                        "did you reach the goal or not?")
    # the log's own "Reached the goal!" is told beside the failure: the question's words point at it
    assert asked["answer"] == ("No. My navigation to the goal at (0.58, -0.55) failed, but my navigation logs do not "
                               'show why. What my log says of it: at 22:13:20, controller_server (INFO) "Reached the '
                               'goal!".')


def test_a_sensor_the_log_names_and_one_it_never_does(tmp_path: Path) -> None:
    (odom,) = converse(real_nav2_run("tb3-ue-37-no-odom-published", tmp_path / "odom"), "is odometry published?")
    assert str(odom["answer"]).startswith(
        "My recording holds no /odom: it has only /rosout, so whether anything was published on /odom it cannot "
        "tell. My log names odometry in 1 line up to the end of the navigation goal: at 14:21:47, "
        'local_costmap.local_costmap (INFO) "Timed out waiting for transform from base_link to odom to become '
        "available")
    (lidar,) = converse(real_nav2_run("tb4-318-lidar-create3-clock", tmp_path / "lidar"), "is the lidar working?")
    text = str(lidar["answer"])
    # no line names it, and a sensor is no setting: nothing said of parameter files
    assert text.startswith("I can't tell: no line of my log (/rosout) up to the end of the navigation goal names "
                           "lidar. My navigation to my goal did not finish")
    assert "ros2 param" not in text


def test_a_resource_conflict_is_quoted(tmp_path: Path) -> None:
    (asked,) = converse(real_module_run("moveit2-2698-dual-arm-resource-conflict", tmp_path / "run"), "what resource?")
    assert "\"Resource conflict for controller 'both_arm_controller'. Command interface 'robot_joint1_l/position' " \
           "is already claimed.\"" in str(asked["answer"])


def test_how_old_the_state_was_quotes_the_state_monitor(tmp_path: Path) -> None:
    simulate_arm_suite(tmp_path, only=lambda s, v: v == 2 and s == "stale_state")
    (asked,) = converse(tmp_path / "armfile_stale_state_2", "how old was the joint state?")
    text = str(asked["answer"])
    assert text.startswith("I couldn't finish picking up the apple because the joint states MoveIt received were "
                           "older than the time it asked for")
    assert "latest received state has time" in text


def test_install_is_a_fix_question() -> None:
    assert asks_fix("how do I install it?") and asks_fix("how can we install the navfn planner")



def test_a_path_found_invalid_and_an_optimiser_reset_are_tries(tmp_path: Path) -> None:
    run = real_nav2_run("nav2-guide-fork-run4-mppi-soft-reset-path-invalid-replanned-succeeded", tmp_path / "run")
    (why,) = converse(run, "why did you replan?")
    assert why["answer"] == (
        "For step 1 (to drive to (-1.50, 1.50)), my path was found to cross an obstacle in my costmap once, so I "
        "planned a new one and my controller started its trajectory optimisation over twice, and the step went "
        "through in the end.")


def test_quality_asked_as_good_flips_the_yes_or_no(tmp_path: Path, suite: Path) -> None:
    (nominal,) = converse(real_nav2_run("kilted-nav2-amcl-nominal", tmp_path / "run"), "was localization good?")
    assert str(nominal["answer"]).startswith("Yes. I reached the goal at (10.00, 4.00) without any problem.")
    good, poor = converse(suite / "bagfile_8_1", "was localization good?", "was your localization poor?")
    assert str(good["answer"]).startswith("No. I reached the kitchen, but slowly and unsteadily")
    assert str(poor["answer"]).startswith("Yes. I reached the kitchen, but slowly and unsteadily")


def test_start_up_lines_give_way_to_warnings_and_data_dropped_is_no_arm(tmp_path: Path) -> None:
    (plugin,) = converse(real_nav2_run("kilted-nav2-smoother-plugin-misspelt", tmp_path / "sm"),
                         "what is the plugin called?")
    assert str(plugin["answer"]).startswith("My log names plugin in 1 line at warning or error level (20 more at info "
                                            "level) up to the end of the navigation goal: at 09:48:48, smoother_server "
                                            '(FATAL) "Failed to create smoother.')
    (dropped,) = converse(real_nav2_run("roverrobotics-19-ekf-wall-time-slam-drops-sim-scans", tmp_path / "rr"),
                          "why are scans dropped?")
    assert "arm" not in str(dropped["answer"])
    assert "Message Filter dropping message" in str(dropped["answer"])


@pytest.mark.parametrize(("question", "kind"), [
    ("did any /scan get published before the error?", "topic_data"),
    ("was any cmd_vel actually sent to the base?", "topic_data"),
    ("were joint_states actually coming in during the pick?", "topic_data"),
    ("did docking_server ever get a BatteryState message?", "topic_data"),
    ("was odom from rtabmap updating during this?", "topic_data"), ("is there anything on /tf?", "topic_data"),
    ("did the wheels move?", None), ("what topics did you record?", "recorded"),
])
def test_whether_data_flowed_on_a_topic_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_whether_data_flowed_is_answered_from_the_recordings_topics(tmp_path: Path, suite: Path) -> None:
    (scan,) = converse(real_module_run("ldlidar-9-wrong-tty-device", tmp_path / "lidar"),
                       "did any /scan get published before the error?")
    assert scan["answer"] == ("My recording holds no /scan: it has only /rosout, so whether anything was published "
                              "on /scan it cannot tell.")
    (pose, charging) = converse(suite / "bagfile_7_1", "was any amcl_pose published?",
                                "were the joint states updating?")
    assert str(pose["answer"]).startswith("My recording holds ")
    assert "messages on /amcl_pose (geometry_msgs/msg/PoseWithCovarianceStamped)" in str(pose["answer"])
    assert str(charging["answer"]).startswith("My recording holds no /joint_states: it has only /amcl_pose, ")


def test_a_wait_a_log_line_times_itself_is_told_with_the_recorded_times(tmp_path: Path) -> None:
    run = real_module_run("doc-moveit2-tutorials-first-project-no-robot-description", tmp_path / "run")
    (waited,) = converse(run, "how long did it wait for robot_description before failing?")
    assert str(waited["answer"]).endswith(
        'My log states how long itself: "Could not find parameter robot_description and did not receive '
        'robot_description via std_msgs::msg::String subscription within 10.000000 seconds." (hello_moveit, '
        "21:08:24).")


@pytest.mark.parametrize(("question", "kind"), [
    ("did anything arrive on /joint_states in this bag?", "topic_data"),
    ("was the base moving at all? any cmd_vel or odom in this bag?", "topic_data"),
    ("were there any WARN or ERROR lines at all in this run?", "logs"),
    ("how many times did it warn?", "logs"), ("how many spin recoveries ran before it gave up?", "tried"),
])
def test_set_five_questions_find_their_answers(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_how_often_a_node_warned_is_counted(tmp_path: Path) -> None:
    run = real_module_run("ifra-srrc-3-missing-fixed-joints-nominal", tmp_path / "run")
    (warned,) = converse(run, "how many times did it warn, and did it ever stop?")
    assert str(warned["answer"]).startswith("My log holds 3 warnings while I worked on the goal to move the arm")
    assert str(warned["answer"]).endswith('"The complete state of the robot is not yet known. Missing BASE_TF_joint, '
                                          'TCP_joint" (3 times).')


def test_where_it_was_is_read_from_nav2_s_own_line_without_a_pose_topic(tmp_path: Path) -> None:
    run = real_nav2_run("mowgli-306-kilted-goal-outside-costmap", tmp_path / "run")
    (where,) = converse(run, "where was the robot when it tried to plan?")
    assert str(where["answer"]).startswith("My recording holds no position (/amcl_pose or /odom), but my log states "
                                           'one: at 22:13:20, planner_server "GridBased plugin failed to plan from '
                                           "(4.12, 14.97) to (-15.42, -9.71)")
    assert str(where["answer"]).endswith("I was at (4.12, 14.97) on my map then, as step 1 (to drive to my goal) "
                                         "failed.")


def test_warnings_or_errors_asked_together_are_counted_together(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-ekf-nominal", tmp_path / "run")
    (both,) = converse(run, "were there any WARN or ERROR lines at all in this run?")
    assert str(both["answer"]).startswith("Yes. My log holds 2 errors or warnings while I worked on the navigation "
                                          "goal to (10.00, 4.00)")


def test_how_long_after_launch_is_told_against_the_logs_first_line(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-through-pose-off-map", tmp_path / "run")
    (asked, when) = converse(run, "How many seconds after launch did the goal fail?", "when did the goal fail?")
    assert str(asked["answer"]).startswith("I started on the navigation goal to (16.00, 4.00) at 07:39:53 UTC, and it "
                                           "ended when step 1")
    assert str(asked["answer"]).endswith("I began 4 s after my log's first line (07:39:49, launch: \"All log files "
                                         "can be found below /home/robot/ws/.ros/log/2026-11-30-07-39-49-803\").")
    assert "after my log's first line" not in str(when["answer"])  # only asked after launch
