"""The chain of evidence on recordings written with rosbags from REAL lines (each cited): a node that never came up
before the goal, the stack's own layers (rcl, rclcpp_lifecycle, launch, tf_help), symptoms never told as causes
(a planner that found no path, a behaviour's "Collision Ahead" after no progress, planning retries on a slow run),
and the fallback that quotes the decisive unknown error with its node and time."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.causes import stated_causes
from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, FATAL, INFO, WARN
from hexar.explainers.base import Context, Explanation
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.detectors import BLOCKED, MOVING_OBSTACLES, NOMINAL, UNEXPLAINED
from tests.events.helpers import task_msg

T0 = 1_700_000_000_000_000_000
Line = tuple[str, int, str]
BEGIN: Line = ("bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
FAILED: Line = ("bt_navigator", ERROR, "Goal failed")
SUCCEEDED: Line = ("bt_navigator", INFO, "Goal succeeded")


def _explain(tmp_path: Path, before: list[Line], during: list[Line], end: Line | None = FAILED,
             question: str = "Why didn't you get there?", begin: Line = BEGIN) -> Explanation:
    """Bring-up lines, then a task whose goal runs `during` and ends with `end` (None: no end, no task)."""
    b = BagBuilder()
    for i, (name, level, msg) in enumerate(before):
        b.log(T0 + sec_ns(0.1 * (i + 1)), name, level, msg)
    t = T0 + sec_ns(5)
    task = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    if end is not None:
        b.task_info(t, task_msg("t1", "go to the door", task))
    for i, (name, level, msg) in enumerate([begin, *during, *([end] if end else [])]):
        b.log(t + sec_ns(0.1 + i), name, level, msg)
    done = t + sec_ns(2 + len(during))
    state = "succeeded" if end is SUCCEEDED else "failed"
    if end is not None:
        b.task_info(done, task_msg("t1", "go to the door", [(*task[0][:2], state, "")]))
    log = read_recording(b.write(tmp_path / "bag"))
    return NavigationExplainer().explain(question, Context.for_task(log, log.task()))


def _quoted(answer: Explanation, msg: str) -> bool:
    return any(e.topic == "/rosout" and msg in e.item for e in answer.evidence)


# turtlebot/turtlebot4#341: the planner server's params file did not parse (rcl), so it never started.
PARAMS: list[Line] = [
    ("rcl", ERROR, "Failed to parse global arguments"),
    ("", ERROR, "terminate called after throwing an instance of 'rclcpp::exceptions::RCLInvalidROSArgsError'\n"
     "what():  failed to initialize rcl: Couldn't parse params file: '--params-file /tmp/launch_params_pl1tbamm'. "
     "Error: Cannot have a value before ros__parameters at line 85, at ./src/parse.c:805")]
# turtlebot/turtlebot4#632 (Jazzy): the controller server's process died (exit code -4).
DIED: list[Line] = [
    ("controller_server-1", ERROR, "process has died [pid 6474, exit code -4, cmd '/opt/ros/jazzy/lib/"
     "nav2_controller/controller_server --ros-args --log-level info --params-file /tmp/launch_params_di0ju_uk']."),
]
# turtlebot/turtlebot4#591 (corpus tb4-591-jazzy-no-footprint): configure threw in the controller server.
THREW: list[Line] = [
    ("controller_server", ERROR, "Caught exception in callback for transition 10"),
    ("controller_server", ERROR, "Original error: Considering footprint in collision checking but no robot "
     "footprint provided in the costmap."),
    ("lifecycle_manager_navigation", ERROR, "Failed to change state for node: controller_server"),
    ("lifecycle_manager_navigation", ERROR, "Failed to bring up all requested nodes. Aborting bringup."),
]
# what the navigator then says (nav2_behavior_tree bt_action_node.hpp@humble: "\"%s\" action server not available
# after waiting for %.2fs")
UNAVAILABLE: list[Line] = [("bt_navigator_navigate_to_pose_rclcpp_node", WARN,
                            "\"compute_path_to_pose\" action server not available after waiting for 1.00s")]


def test_a_params_file_rcl_could_not_parse_is_a_bringup_failure(tmp_path: Path) -> None:
    answer = _explain(tmp_path, PARAMS, UNAVAILABLE)
    assert answer.causes == [g.BRINGUP]
    assert "never came up" in answer.text and "could not parse its parameters file" in answer.text
    assert stated_causes(answer.text) >= {g.BRINGUP}
    assert _quoted(answer, "Couldn't parse params file")


def test_a_process_that_died_names_the_node_and_exit_code(tmp_path: Path) -> None:
    answer = _explain(tmp_path, DIED, UNAVAILABLE)
    assert answer.causes == [g.BRINGUP]
    assert "the process of controller_server died (exit code -4)" in answer.text
    assert _quoted(answer, "process has died [pid 6474, exit code -4")


def test_a_configure_callback_that_threw_is_the_node_not_brought_up(tmp_path: Path) -> None:
    answer = _explain(tmp_path, THREW, UNAVAILABLE)
    # both ids, each with the lines: a configuration error that kept a node from coming up
    assert answer.causes == [g.CONFIGURATION, g.BRINGUP]
    assert {e.cause for e in answer.evidence} == {g.CONFIGURATION, g.BRINGUP}
    assert "never came up: controller_server stopped in a lifecycle transition" in answer.text
    assert "no robot footprint provided in the costmap" in answer.text
    assert stated_causes(answer.text) >= {g.CONFIGURATION, g.BRINGUP}
    assert _quoted(answer, "Caught exception in callback for transition 10")


# ros-navigation/navigation2#1948-style: a BT node library that bt_navigator cannot load at configure (the
# Nav2 catalogue's bt.plugin_load), then the lifecycle manager aborts the bring-up.
PLUGIN: list[Line] = [
    ("bt_navigator", ERROR, "Original error: Could not load library: /opt/ros/humble/lib/"
     "libnav2_compute_path_to_pose_action_bt_node.so: undefined symbol: _ZTIN2BT14CoroActionNodeE"),
    ("lifecycle_manager_navigation", ERROR, "Failed to change state for node: bt_navigator"),
]


def test_a_plugin_that_cannot_be_loaded_is_a_configuration_error_and_a_node_that_never_came_up(
        tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], PLUGIN)
    assert answer.causes == [g.CONFIGURATION, g.BRINGUP]
    assert stated_causes(answer.text) >= {g.CONFIGURATION, g.BRINGUP}
    assert _quoted(answer, "Could not load library")


def test_a_process_that_died_with_no_error_before_says_the_logs_do_not_show_why(tmp_path: Path) -> None:
    answer = _explain(tmp_path, DIED, UNAVAILABLE)
    assert "nothing in my logs says why it died" in answer.text
    answer = _explain(tmp_path / "b", [("controller_server", ERROR, "Original error: Considering footprint in "
                                        "collision checking but no robot footprint provided in the costmap."),
                                       *DIED], UNAVAILABLE)
    assert "nothing in my logs says why it died" not in answer.text


def test_a_process_whose_last_words_are_an_uncaught_exception_is_not_told_as_dying_for_no_reason(
        tmp_path: Path) -> None:
    # ros-navigation/navigation2#904 (blind set 3): bt_navigator's libstdc++ terminate handler, then launch's death
    thrown = [("bt_navigator", INFO, "terminate called after throwing an instance of "
               "'rclcpp_action::exceptions::UnknownGoalHandleError'"),
              ("bt_navigator-13", ERROR, "process has died [pid 664, exit code -6, cmd '/opt/ros/humble/lib/"
               "nav2_bt_navigator/bt_navigator --ros-args']."),
              ]
    answer = _explain(tmp_path, thrown, UNAVAILABLE)
    assert answer.causes[0] == g.BRINGUP
    assert "UnknownGoalHandleError'', an exception nothing caught, which ends a program" in answer.text
    assert "nothing in my logs says why it died" not in answer.text


def test_a_program_the_loader_could_not_start_is_a_process_that_died_with_the_loaders_reason(tmp_path: Path) -> None:
    # turtlebot/turtlebot4_simulator#14: glibc's "symbol lookup error" (elf/dl-lookup.c:808) on amcl's stderr
    lost = ("/opt/ros/galactic/lib/nav2_amcl/amcl: symbol lookup error: /opt/ros/galactic/lib/libamcl_core.so: "
            "undefined symbol: _ZN9nav2_amcl20LikelihoodFieldModelC1EddddmP5map_t")
    answer = _explain(tmp_path, [("amcl-37", INFO, lost)], UNAVAILABLE)
    assert answer.causes[0] == g.BRINGUP and g.BRINGUP in stated_causes(answer.text)
    assert "the process of amcl died (symbol lookup error: " in answer.text
    assert "libamcl_core.so needs nav2_amcl::LikelihoodFieldModel::LikelihoodFieldModel(…)" in answer.text
    assert "nothing in my logs says why it died" not in answer.text


def test_tf_help_dropped_by_the_filter_is_still_read(tmp_path: Path) -> None:
    # pf-robotics/kachaka-api#106's shape: nav_2d_utils' tf_help logs under its own logger (role tf), which the
    # log filter does not keep; its "Transform data too old" (tf_help.cpp:70@humble) still decides
    answer = _explain(tmp_path, [], [("tf_help", ERROR, "Transform data too old when converting from odom to map"),
                                     ("tf_help", ERROR, "Data time: 1721806792s 88418722ns, Transform time: "
                                      "1721806791s 859294000ns")])
    assert answer.causes[0] == g.TRANSFORM and _quoted(answer, "Transform data too old")


def test_a_stack_brought_up_again_afterwards_is_no_bringup_failure(tmp_path: Path) -> None:
    healthy = [("lifecycle_manager_navigation", INFO, "Managed nodes are active")]
    answer = _explain(tmp_path, THREW + healthy, [("controller_server", ERROR, "Failed to make progress")])
    assert g.CONFIGURATION not in answer.causes and g.BRINGUP not in answer.causes


def test_tf_help_transform_too_old_is_a_transform_error(tmp_path: Path) -> None:
    # the example: nav_2d_utils tf_help.cpp:70@humble "Transform data too old when converting from %s to %s"
    answer = _explain(tmp_path, [], [("controller_server", ERROR,
                                      "Transform data too old when converting from odom to map"),
                                     ("controller_server", ERROR, "Failed to make progress")])
    assert answer.causes == [g.TRANSFORM] and _quoted(answer, "Transform data too old")


def test_rpp_collision_ahead_is_a_collision_check_not_a_controller_failure(tmp_path: Path) -> None:
    # heldout nav2-3115-humble-rpp-false-collision's line
    answer = _explain(tmp_path, [], [("controller_server", WARN,
                                      "RegulatedPurePursuitController detected collision ahead!")])
    assert answer.causes == [g.COLLISION_AHEAD]
    assert g.CONTROLLER not in stated_causes(f"{answer.text} {answer.fix}")
    assert "footprint" in (answer.fix or "")


# heldout tutorials-108-gps-goal-off-costmap's planner lines without the line that said why
NO_PATH: list[Line] = [
    ("planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50."),
    ("planner_server", WARN, "Planning algorithm GridBased failed to generate a valid path to (-693.34, 1110546.90)"),
    ("planner_server", WARN, "[compute_path_to_pose] [ActionServer] Aborting handle."),
]


def test_a_planner_that_never_found_a_path_is_a_symptom_with_candidates(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], NO_PATH)
    assert answer.causes == [UNEXPLAINED]
    said = stated_causes(answer.text)
    assert BLOCKED not in said and g.GOAL_UNREACHABLE not in said and g.START_IN_OBSTACLE not in said
    assert "can't tell why" in answer.text and "occupied cells" in answer.text
    assert "What tells them apart" in (answer.fix or "")


def test_a_planner_that_lost_a_path_it_had_is_a_blocked_way(tmp_path: Path) -> None:
    planned = [("controller_server", INFO, "Received a goal, begin computing control effort."),
               ("controller_server", INFO, "Passing new path to controller."),
               ("controller_server", ERROR, "Failed to make progress")]
    assert _explain(tmp_path, [], planned + NO_PATH).causes == [BLOCKED]


def test_collision_ahead_in_a_backup_after_no_progress_is_not_the_cause(tmp_path: Path) -> None:
    # the case: no progress first, then the backup recovery's collision checker (drive_on_heading.hpp:167)
    lines = [("controller_server", ERROR, "Failed to make progress"),
             ("behavior_server", INFO, "Running backup"),
             ("behavior_server", WARN, "Collision Ahead - Exiting DriveOnHeading")]
    answer = _explain(tmp_path, [], lines)
    assert answer.causes == [g.NO_PROGRESS]
    assert g.COLLISION_AHEAD not in stated_causes(answer.text)


# sllidar_ros2's driver error (sllidar_node.cpp, RCLCPP_ERROR "Error, operation time out. RESULT_OPERATION_TIMEOUT! ")
LIDAR: Line = ("sllidar_node", ERROR, "Error, operation time out. RESULT_OPERATION_TIMEOUT! ")
# turtlebot4_node's error when a service it calls is missing (GNagahashi/study-ros2 jungle/tb4_memo.md, TurtleBot 4)
CAMERA: Line = ("turtlebot4_node", ERROR, "Service oakd/start_camera unavailable.")


@pytest.mark.parametrize("during", [[CAMERA, ("controller_server", ERROR, "Failed to make progress")], [CAMERA]],
                         ids=["no_progress", "unexplained"])
def test_the_decisive_unknown_error_is_quoted_with_node_and_time(tmp_path: Path, during: list[Line]) -> None:
    answer = _explain(tmp_path, [], during)
    assert answer.causes in ([g.NO_PROGRESS], [UNEXPLAINED])
    assert "the last error before I gave up came from turtlebot4_node: 'Service oakd/start_camera unavailable." \
        in answer.text
    assert " UTC)" in answer.text and "do not show why" not in answer.text
    assert _quoted(answer, "oakd/start_camera")


def test_an_error_that_reads_as_another_cause_is_told_by_node_and_time_only(tmp_path: Path) -> None:
    # "operation time out" reads as a text-to-speech timeout (hexar/causes.yaml): quoted in the sentence, the answer
    # would claim a cause nothing found; it names the node and the time, and the line stays in the evidence
    answer = _explain(tmp_path, [], [LIDAR, ("controller_server", ERROR, "Failed to make progress")])
    assert answer.causes == [g.NO_PROGRESS]
    assert "the last error before I gave up came from sllidar_node (at " in answer.text
    assert "operation time out" not in answer.text and stated_causes(answer.text) <= {g.NO_PROGRESS}
    assert _quoted(answer, "RESULT_OPERATION_TIMEOUT")


def test_without_any_error_the_answer_stays_honest(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [])
    assert answer.causes == [UNEXPLAINED] and "do not show why" in answer.text


def test_a_slow_run_with_planning_retries_is_not_people_moving(tmp_path: Path) -> None:
    retries = [*NO_PATH[:2], ("behavior_server", INFO, "Running spin"),
               ("global_costmap.global_costmap", INFO, "Received request to clear entirely the global_costmap"),
               ("controller_server", INFO, "Passing new path to controller.")]
    answer = _explain(tmp_path, [], retries, end=SUCCEEDED, question="Why did it take so long?")
    assert MOVING_OBSTACLES not in answer.causes
    assert MOVING_OBSTACLES not in stated_causes(answer.text)
    assert "took longer" in answer.text and "can't tell what was in the way" in answer.text


def test_without_a_goal_end_the_last_error_is_still_quoted(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [LIDAR], end=None)
    assert answer.causes == [UNEXPLAINED]
    assert answer.text.startswith("The recording does not show whether my navigation")
    assert "the last error my logs show came from sllidar_node" in answer.text


def test_a_recording_of_a_stack_that_never_came_up_has_a_task_to_explain(tmp_path: Path) -> None:
    # no /task_info and no goal: the bring-up error itself is the navigation that failed (events.nav_goals)
    b = BagBuilder()
    for i, (name, level, msg) in enumerate(DIED):
        b.log(T0 + sec_ns(i), name, level, msg)
    log = read_recording(b.write(tmp_path / "bag"))
    task = log.task()
    assert task.derived and task.skills[0].state == "failed"
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, task))
    assert answer.causes == [g.BRINGUP] and "controller_server died" in answer.text


# ros-navigation/navigation2's system tests (nav2_system_tests, test_bt_navigator): a controller working, no goal
# line recorded (controller_server.cpp@humble: "Passing new path to controller.").
QUIET: list[Line] = [("controller_server", INFO, "Passing new path to controller."),
                     ("controller_server", INFO, "Passing new path to controller.")]


def _without_task(tmp_path: Path, lines: list[Line]) -> Explanation:
    b = BagBuilder()
    for i, (name, level, msg) in enumerate(lines):
        b.log(T0 + sec_ns(i), name, level, msg)
    log = read_recording(b.write(tmp_path / "bag"))
    return NavigationExplainer().explain("How did the navigation go?", Context.for_task(log, log.task()))


def test_a_stack_that_ran_without_a_goal_line_or_a_warning_is_told_as_it_ran(tmp_path: Path) -> None:
    answer = _without_task(tmp_path, QUIET)
    assert answer.causes == [NOMINAL]
    assert "controller_server logged its work" in answer.text and "does not show whether I reached one" in answer.text
    assert _quoted(answer, "Passing new path to controller")


def test_a_warning_of_the_stack_is_no_quiet_run(tmp_path: Path) -> None:
    answer = _without_task(tmp_path, [*QUIET, ("controller_server", WARN, "Control loop missed its desired rate "
                                               "of 20.0000Hz")])
    assert NOMINAL not in answer.causes


def _task_only(tmp_path: Path, lines: list[Line], state: str) -> Explanation:
    """A /task_info navigation step that ends in `state`, with `lines` in its window and no Nav2 goal line."""
    b = BagBuilder()
    task = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    b.task_info(T0, task_msg("t1", "go to the door", task))
    for i, (name, level, msg) in enumerate(lines):
        b.log(T0 + sec_ns(0.5 + i), name, level, msg)
    b.task_info(T0 + sec_ns(1 + len(lines)), task_msg("t1", "go to the door", [(*task[0][:2], state, "")]))
    log = read_recording(b.write(tmp_path / "bag"))
    question = "Why didn't you get there?" if state == "failed" else "How did the navigation go?"
    return NavigationExplainer().explain(question, Context.for_task(log, log.task()))


# ROBOTIS-GIT/turtlebot3#945 (Humble): launch could not parse the params file it substitutes, so nothing started.
LAUNCH: list[Line] = [("launch", ERROR, "Caught exception in launch (see debug for traceback): while parsing a block "
                       "mapping\n  in \"/opt/ros/humble/share/turtlebot3_navigation2/param/waffle.yaml\", line 2, "
                       "column 3\nexpected <block end>, but found '<block mapping start>'")]


def test_an_exception_in_launch_is_a_stack_that_never_came_up(tmp_path: Path) -> None:
    answer = _task_only(tmp_path, LAUNCH, "failed")
    assert answer.causes == [g.BRINGUP]
    assert "my launch stopped with an error before it had started my navigation nodes" in answer.text
    assert "waffle.yaml\", line 2, column 3" in answer.text
    assert stated_causes(answer.text) >= {g.BRINGUP}


# Kinovarobotics/ros2_kortex#216 (an arm's launch, no Nav2 in it): launch refused a parameter before any node ran.
ARM_LAUNCH: list[Line] = [("launch", ERROR, "Caught exception in launch (see debug for traceback): Invalid parameter "
                           "\"isaac_joint_commands\"")]


def test_a_launch_that_names_no_navigation_is_not_told_as_the_navigations(tmp_path: Path) -> None:
    """The same failure, but nothing in the recording names Nav2: the answer says no node came up, not that the
    navigation's did not (the robot may be an arm)."""
    answer = _task_only(tmp_path, ARM_LAUNCH, "failed")
    assert answer.causes == [g.BRINGUP]
    assert "because my nodes never came up: my launch stopped with an error before it had started any of my nodes" \
        in answer.text
    assert "navigation" not in answer.text


# TheWindISeek/tianracer_ros2_ws docs/NAV2_ERRORS_AND_SOLUTIONS.md: nav2_costmap_2d's inflation layer rejects the
# configured radius (ERROR), pasted cut short after "of your footprint".
INFLATION: list[Line] = [("local_costmap.local_costmap", ERROR, "The configured inflation radius (0.050) is smaller "
                          "than the computed inscribed radius (0.186) of your footprint")]


def test_a_parameter_a_nav2_node_rejects_is_a_configuration_error_quoted(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [*INFLATION, ("controller_server", ERROR, "Failed to make progress")])
    assert answer.causes[0] == g.CONFIGURATION
    assert "misconfigured" in answer.text and "inflation radius (0.050) is smaller" in answer.text
    assert stated_causes(answer.text) <= {g.CONFIGURATION, g.BRINGUP}


# turtlebot/turtlebot4#188 (corpus tb4-188): rviz's tf2_ros message filter drops scans waiting for a transform
# (tf2_ros/message_filter.h: "discarding message because the queue is full"), logged at INFO.
DROPS: list[Line] = [("rviz2", INFO, "Message Filter dropping message: frame 'rplidar_link' at time 1685961755.735 "
                      "for reason 'discarding message because the queue is full'")] * 2


def test_message_filter_drops_on_a_failed_goal_are_navigation_evidence(tmp_path: Path) -> None:
    answer = _task_only(tmp_path, DROPS, "failed")
    assert answer.enough_information and answer.causes == [g.TRANSFORM]
    assert _quoted(answer, "discarding message because the queue is full")


def test_a_step_reported_succeeded_with_no_warning_is_a_normal_trip(tmp_path: Path) -> None:
    # the Nav2 docs' vector object tutorial: nodes loaded into the container, nothing else logged
    loaded = [("launch_ros.actions.load_composable_nodes", INFO,
               "Loaded node '/vector_object_server' in container 'nav2_container'")]
    answer = _task_only(tmp_path, loaded, "succeeded")
    assert answer.causes == [NOMINAL] and "without any problem" in answer.text
    failed = _task_only(tmp_path / "f", loaded, "failed")
    assert not failed.enough_information and not stated_causes(failed.text)


def test_a_stack_error_alone_without_any_goal_is_not_read_as_a_failed_goal(tmp_path: Path) -> None:
    # ros-navigation/navigation2#4660: an empty source frame during SLAM while the robot navigates normally
    # (nav2_util robot_utils.cpp transformPoseInTargetFrame); no goal line, no /task_info
    answer = _without_task(tmp_path, [("transformPoseInTargetFrame", ERROR, "Failed to transform from  to base_link")])
    assert g.TRANSFORM not in answer.causes and g.TRANSFORM not in stated_causes(answer.text)


def test_rpp_collision_check_says_the_logs_do_not_show_what_it_saw(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [("controller_server", WARN,
                                      "RegulatedPurePursuitController detected collision ahead!")])
    assert "My logs do not say what it saw there" in answer.text
    assert stated_causes(answer.text) == {g.COLLISION_AHEAD}


def test_a_process_that_died_during_the_goal_is_not_told_as_never_having_come_up(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], DIED)
    assert answer.causes == [g.BRINGUP]
    assert "because the process of controller_server died (exit code -4)" in answer.text
    assert "never came up" not in answer.text


# corpus nav2-1876's costmap line (costmap_2d_ros.cpp:281@humble: on_activate loops, logging it, until the transform
# exists), then the lifecycle manager's "Managed nodes are active" (lifecycle_manager.cpp:288@humble).
WAITED: list[Line] = [
    ("global_costmap.global_costmap", INFO, "Timed out waiting for transform from base_link to map to become "
     "available, tf error: Invalid frame ID \"map\" passed to canTransform argument target_frame - frame does not "
     "exist")]
ACTIVE: Line = ("lifecycle_manager_navigation", INFO, "Managed nodes are active")


def test_a_transform_wait_that_bringup_got_past_is_not_the_cause(tmp_path: Path) -> None:
    stuck = [("controller_server", ERROR, "Failed to make progress")]
    answer = _explain(tmp_path, [*WAITED, ACTIVE], stuck)
    assert answer.causes == [g.NO_PROGRESS] and g.TRANSFORM not in stated_causes(answer.text)
    # without the bring-up finishing after it, the same wait is what held the navigation
    answer = _explain(tmp_path / "b", [], [*WAITED, *stuck])
    assert answer.causes == [g.TRANSFORM]


def test_a_died_process_is_told_with_what_it_last_logged(tmp_path: Path) -> None:
    # ros-navigation/docs.nav2.org's backtrace guide: the planner server's last line, then launch reports it dead
    lines = [("planner_server", INFO, "Computing path to goal...."),
             ("planner_server-13", ERROR, "process has died [pid 165734, exit code -11, cmd '/opt/overlay_ws/src/"
              "navigation2/install/nav2_planner/lib/nav2_planner/planner_server --ros-args -r __node:=planner_server']."
              )]
    answer = _explain(tmp_path, [], lines)
    assert answer.causes == [g.BRINGUP]
    assert ("the process of planner_server died (exit code -11) right after it logged 'Computing path to goal....'; "
            "nothing in my logs says why it died") in answer.text
    assert _quoted(answer, "Computing path to goal")


def test_a_component_container_that_died_is_told_with_the_last_line_of_a_node_it_may_host(tmp_path: Path) -> None:
    # Nav2's bring-up composes its servers into one component_container_isolated (engdiegomaia/toradex-demo-aquila-
    # am69-ros2, docs/results/ml35-regressao-navegacao.md: route_server crashed configuring its ReroutingService)
    lines = [("route_server", INFO, "Created route operation ReroutingService of type nav2_route::ReroutingService"),
             ("route_server", INFO, "Configuring Rerouting service operation."),
             ("component_container_isolated-4", ERROR, "process has died [pid 40, exit code -11, ...]")]
    answer = _explain(tmp_path, [], lines)
    assert answer.causes == [g.BRINGUP]
    assert ("the process of component_container_isolated died (exit code -11) right after route_server logged "
            "'Configuring Rerouting service operation.'") in answer.text
    # a process of one node is still told only with that node's own lines
    other = [("route_server", INFO, "Configuring Rerouting service operation."), *DIED]
    assert "right after" not in _explain(tmp_path / "b", [], other).text


# nav2_collision_monitor/src/collision_monitor_node.cpp:619@jazzy (WARN, one message over three literals)
INVALID_SOURCE: Line = ("collision_monitor", WARN, "Robot to stop due to invalid source. Either due to data not "
                        "published yet, or to lack of new data received within the sensor timeout, or if impossible "
                        "to transform data to base frame")


def test_a_collision_monitor_stop_for_a_source_without_data_is_no_collision_ahead(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [INVALID_SOURCE, ("controller_server", ERROR, "Failed to make progress")])
    assert answer.causes == [g.NO_PROGRESS]
    assert "one of its sensor sources gave no valid data" in answer.text
    assert stated_causes(answer.text) <= {g.NO_PROGRESS}
    # a polygon stop (collision_monitor_node.cpp:464@humble) is one
    answer = _explain(tmp_path / "b", [], [("collision_monitor", INFO, "Robot to stop due to PolygonStop polygon"),
                                           ("controller_server", ERROR, "Failed to make progress")])
    assert answer.causes == [g.COLLISION_AHEAD]


# No goal line, no /task_info, no error: what a warning alone may claim.
def test_a_background_warning_with_no_goal_is_quoted_not_read_as_a_cause(tmp_path: Path) -> None:
    # dot-Ahope/jupiter_ws_ros2's guide (Humble): a global-costmap warning the guide calls harmless
    # (obstacle_layer.cpp:637@humble)
    origin = ("Sensor origin at (-0.03, 0.00) is out of map bounds (-0.03, -1.50) to (2.55, 3.13). The costmap cannot "
              "raytrace for it.")
    answer = _without_task(tmp_path, [("global_costmap.global_costmap", WARN, origin)])
    assert answer.causes == [UNEXPLAINED] and not stated_causes(answer.text) - {UNEXPLAINED}
    assert "the last warning my logs show came from global_costmap.global_costmap" in answer.text
    assert "does not show whether" in answer.text


def test_a_server_that_says_why_it_fails_decides_without_a_goal(tmp_path: Path) -> None:
    # the planner server's own words (navfn_planner.cpp:253@humble, reference/nav2_log_messages.md)
    answer = _without_task(tmp_path, [("planner_server", WARN, "The goal sent to the planner is off the global "
                                       "costmap. Planning will always fail to this goal.")])
    assert answer.causes == [g.GOAL_UNREACHABLE]


def test_a_server_that_reports_a_state_without_a_goal_is_hedged_not_a_mere_warning(tmp_path: Path) -> None:
    # ros-navigation/navigation2#3230 (corpus): the planner server's own words (navfn_planner.cpp:223@humble) say
    # the start was off the costmap, not why (states.py): the state with its candidates, not the last warning
    answer = _without_task(tmp_path, [("planner_server", WARN, "Cannot create a plan: the robot's start position is "
                                       "off the global costmap. Planning will always fail, are you sure the robot has "
                                       "been properly localized?")])
    assert answer.causes == [UNEXPLAINED] and "outside its bounds" in answer.text
    assert stated_causes(answer.text) == set() and "last warning" not in answer.text


def test_a_transform_lookup_off_by_more_than_a_second_is_a_clock_fault(tmp_path: Path) -> None:
    # create-robot (Foxy): tf2_echo on a real robot with use_sim_time set (sim time 0.2 s, data at wall time)
    answer = _without_task(tmp_path, [("tf2_echo", INFO, "Waiting for transform map ->  base_footprint: Lookup would "
                                       "require extrapolation into the past.  Requested time 0.200000 but the earliest "
                                       "data is at time 1619986346.813953, when looking up transform from frame "
                                       "[base_footprint] to frame [map]")])
    assert answer.causes == [g.TRANSFORM]


# nav2_costmap_2d/src/costmap_2d_ros.cpp:285-306@jazzy: the costmap waits for its transform in on_activate, then fails
# the transition; nav2_lifecycle_manager then aborts the bring-up (lines of a Jazzy run whose initial pose came late)
TF_WAIT = ("global_costmap.global_costmap", INFO, "Timed out waiting for transform from base_link to map to become "
           "available, tf error: Invalid frame ID \"map\" passed to canTransform argument target_frame - frame does "
           "not exist")
TF_ABORT: list[Line] = [
    TF_WAIT, TF_WAIT,
    ("global_costmap.global_costmap", ERROR, "Failed to activate global_costmap because transform from base_link to "
     "map did not become available before timeout"),
    ("lifecycle_manager_navigation", ERROR, "Failed to change state for node: planner_server"),
    ("lifecycle_manager_navigation", ERROR, "Failed to bring up all requested nodes. Aborting bringup.")]


def test_a_costmap_that_could_not_activate_for_want_of_a_transform_is_a_transform_error(tmp_path: Path) -> None:
    found = _explain(tmp_path, TF_ABORT, [])
    assert found.causes == [g.TRANSFORM]
    assert stated_causes(found.text) == {g.TRANSFORM}  # the aborted start is its consequence, no second cause
    assert "the transform from base_link to map" in found.text and "start was aborted" in found.text
    assert _quoted(found, "Timed out waiting for transform") and _quoted(found, "Failed to activate global_costmap")


def test_a_node_that_failed_its_transition_with_no_transform_wait_stays_a_bring_up_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, TF_ABORT[3:], [])
    assert g.TRANSFORM not in found.causes and found.causes


# nav2_collision_monitor/src/collision_monitor_node.cpp:642,647@jazzy: approach (a slow-down), then release
APPROACH: Line = ("collision_monitor", INFO, "Robot to approach for 1.200000 seconds away from collision")
RELEASE: Line = ("collision_monitor", INFO, "Robot to continue normal operation")


def test_a_collision_monitor_that_slowed_the_robot_and_let_it_go_leaves_a_reached_goal_normal(tmp_path: Path) -> None:
    found = _explain(tmp_path, [], [APPROACH, RELEASE], end=SUCCEEDED, question="How did it go?")
    assert found.causes == [NOMINAL]
    assert "stopped me" not in found.text


def test_a_slow_down_during_recoveries_after_a_failed_plan_is_not_why_the_goal_failed(tmp_path: Path) -> None:
    # nav2_navfn_planner (jazzy) fails from an occupied start; the tree's IsGoalNearby warns "Path is empty"
    # (is_goal_nearby_condition.cpp:46@main) under bt_navigator's logger; recoveries run with the monitor slowing them
    found = _explain(tmp_path, [], [
        ("planner_server", WARN, "GridBased plugin failed to plan from (1.00, 1.00) to (-1.50, 1.50): \"Failed to "
                                 "create plan with tolerance of: 0.500000\""),
        ("bt_navigator_navigate_to_pose_rclcpp_node", WARN, "Path is empty"),
        ("behavior_server", INFO, "Running backup"), APPROACH,
        ("behavior_server", WARN, "backup failed:Exceeded time allowance before reaching the DriveOnHeading goal - "
                                  "Exiting DriveOnHeading")])
    assert "navigation.collision_ahead" not in found.causes
    assert "navigation.controller_failure" not in found.causes


# nav2_planner/src/planner_server.cpp:122@jazzy (f4108e5b1), in on_configure, then FAILURE: the planner's plugin
# parameter was not set (nav2_util/include/nav2_util/node_utils.hpp:264-265@jazzy), so the server never came up
NO_PLANNER_PLUGIN: list[Line] = [
    ("planner_server", FATAL, "'plugin' param not defined for GridBased"),
    ("planner_server", FATAL, "Failed to create global planner. Exception: No 'plugin' param for param ns!")]
# nav2_docking/opennav_docking/src/dock_database.cpp:156,42@jazzy: DockDatabase::initialize fails, and with it the
# docking server's on_configure (docking_server.cpp:92-94@jazzy); no docking was ever asked for
NO_DOCK_PLUGINS: list[Line] = [
    ("docking_server", ERROR, "Charging dock plugins not given!"),
    ("docking_server", ERROR, "An error occurred while getting the dock plugins!")]


@pytest.mark.parametrize("lines", [NO_PLANNER_PLUGIN, NO_DOCK_PLUGINS], ids=["planner", "docking"])
def test_a_server_that_could_not_create_its_plugins_at_configure_never_came_up(tmp_path: Path,
                                                                               lines: list[Line]) -> None:
    # the lines as a recording that starts at the goal shows them (no lifecycle manager line after them)
    found = _explain(tmp_path, [], lines)
    assert set(found.causes) == {g.CONFIGURATION, g.BRINGUP}
    assert stated_causes(found.text) == {g.CONFIGURATION, g.BRINGUP}
    assert "navigation.docking_failure" not in found.causes  # the docking server's set-up, not a docking
    assert "never came up" in found.text


def test_a_server_that_failed_its_configure_before_the_goal_explains_the_failed_goal(tmp_path: Path) -> None:
    # the FATAL at bring-up, before the goal, with no lifecycle manager line after it (as pasted, abridged)
    found = _explain(tmp_path, NO_PLANNER_PLUGIN[1:], UNAVAILABLE)
    assert set(found.causes) == {g.CONFIGURATION, g.BRINGUP}
    assert "planner_server" in found.text and "never came up" in found.text
    assert _quoted(found, "Failed to create global planner")


def test_lines_the_filter_does_not_read_are_quoted_not_denied(tmp_path: Path) -> None:
    # ozkannceylan/amr-agent (blind8.yaml): amcl's message filter dropping every scan at INFO, with no goal and no
    # error (tf2_ros message_filter.h@humble "Message Filter dropping message: frame '%s' at time %.3f for reason
    # '%s'"): not a cause on its own, but it was recorded, so the answer must not say that nothing was
    drop = ("Message Filter dropping message: frame 'nav_lidar_link' at time 27.260 for reason 'discarding message "
            "because the queue is full'")
    found = _without_task(tmp_path, [("amcl", INFO, drop)])
    assert "Nothing from my navigation system was recorded" not in found.text
    assert drop in found.text and "amcl" in found.text
    assert not stated_causes(found.text)


def test_a_slow_trip_with_no_speed_figures_is_still_answered_in_a_sentence(tmp_path: Path) -> None:
    # NachtaktiverHalbaffe/Autonomous-Ape's troubleshooting page (blind9.yaml): the local costmap waiting for odom
    # at start-up, which the page calls normal; the recording has no odometry, and Humble's begin line no start, so
    # there is no speed to give
    waited = ("Timed out waiting for transform from base_link to odom to become available, tf error: Invalid frame "
              "ID \"odom\" passed to canTransform argument target_frame - frame does not exist")
    found = _explain(tmp_path, [("turtle1.local_costmap.local_costmap", INFO, waited),
                                ("lifecycle_manager_navigation", INFO, "Managed nodes are active")],
                     [], SUCCEEDED, "Why did it take so long to get there?",
                     ("bt_navigator", INFO, "Begin navigating from current location to (1.00, 2.00)"))
    assert found.text == "I reached my goal without any problem; my recording has no figures of how fast I went."
    assert "navigation.nominal" in stated_causes(found.text)


def test_a_failed_plan_while_the_goal_still_runs_at_the_end_is_no_goal_missed(tmp_path: Path) -> None:
    # the tugbot phase-3 notes (blind7.yaml): a far frontier goal, one failed plan, recoveries, then the controller
    # took a new path; the recording (no task, no end line) stops there, so it does not show whether it got there
    found = _explain(tmp_path, [], [
        ("planner_server", ERROR, 'GridBased plugin failed to plan from (0.00, 0.00) to (1.00, 2.00): "Failed to '
                                  'create plan with tolerance of: 0.500000"'),
        ("planner_server", ERROR, "[compute_path_to_pose] [ActionServer] Aborting handle."),
        ("behavior_server", INFO, "Running spin"),
        ("controller_server", INFO, "Received a goal, begin computing control effort.")], None,
        "Why did it take so long to get there?")
    assert found.text.startswith("The recording ends before my navigation to my goal finished, so it does not "
                                 "show whether I got there; on the way my planner could not compute a route to it "
                                 "(1 time), and I can't tell why")
    assert "claim.task_failed" not in read_claims(found.text).affirmed


# The daifuku Pi4 reproduction notes (blind10.yaml, spent): emcl2's map -> odom froze, the controller could not place
# the robot on the plan, and its goal checker said "Reached the goal!" 0.2 s after the 44 m path came in.
LOST: Line = ("controller_server", WARN, "Unable to transform robot pose into global plan's frame")
REACHED: Line = ("controller_server", INFO, "Reached the goal!")
RECEIVED: Line = ("controller_server", INFO, "Received a goal, begin computing control effort.")


def test_a_goal_judged_reached_right_after_the_pose_was_lost_is_not_a_clean_reach(tmp_path: Path) -> None:
    found = _explain(tmp_path, [], [RECEIVED, LOST, REACHED], SUCCEEDED)
    assert found.causes == [g.TRANSFORM]
    assert found.text.startswith("Nav2 logged my goal as reached, but I can't be sure I got there: on the line "
                                 "before, my controller said 'Unable to transform robot pose into global plan's "
                                 "frame'")
    assert "navigation.nominal" not in stated_causes(found.text)
    assert _quoted(found, "Reached the goal!")


def test_a_pose_lost_and_found_again_before_the_reach_is_a_clean_reach(tmp_path: Path) -> None:
    # the controller worked again after the warning (it passed on a new path) before it judged the goal reached
    found = _explain(tmp_path, [], [RECEIVED, LOST, ("controller_server", INFO, "Passing new path to controller."),
                                    REACHED], SUCCEEDED)
    assert found.causes == [NOMINAL]


# blind set 5's nav2-guide-fork-run3 (Jazzy), its three error lines alone: the global costmap's activation gave up on
# its transform (costmap_2d_ros.cpp:306@jazzy) and the lifecycle manager aborted the bring-up; no "Timed out waiting
# for transform" line before them
NO_TRANSFORM_IN_TIME: list[Line] = [
    ("global_costmap.global_costmap", ERROR, "Failed to activate global_costmap because transform from base_link to "
                                             "map did not become available before timeout"),
    ("lifecycle_manager_nav2", ERROR, "Failed to change state for node: planner_server"),
    ("lifecycle_manager_nav2", ERROR, "Failed to bring up all requested nodes. Aborting bringup."),
]


def test_a_costmap_whose_activation_names_the_transform_it_lacked_is_a_transform_error(tmp_path: Path) -> None:
    answer = _explain(tmp_path, NO_TRANSFORM_IN_TIME, UNAVAILABLE)
    assert answer.causes == [g.TRANSFORM]
    assert "waited for the transform from base_link to map until its time ran out" in answer.text
    assert stated_causes(answer.text) == {g.TRANSFORM}


def test_a_stack_seen_only_as_it_is_taken_down_is_not_told_as_having_run_normally() -> None:
    # the last lines of blind set 20's map-missing console before rclcpp's signal_handler: Nav2's own teardown words
    from hexar.events.records import LogLine
    from hexar.explainers.navigation.chain import ran_quietly

    down = [LogLine(T0, INFO, "planner_server", "Destroying bond (planner_server) to lifecycle manager."),
            LogLine(T0 + 1, INFO, "map_server", "Running Nav2 LifecycleNode rcl preshutdown (map_server)"),
            LogLine(T0 + 2, INFO, "global_costmap.global_costmap", "Destroying"),
            LogLine(T0 + 3, INFO, "bt_navigator-6", "process has finished cleanly [pid 796]")]
    assert ran_quietly(down) is None
    # the same stack seen at work says so
    worked = [LogLine(T0, INFO, "planner_server", "Configuring"), *down]
    told = ran_quietly(worked)
    assert told is not None and told[0].startswith("As far as my recording shows, my navigation went normally")
