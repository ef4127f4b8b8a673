"""The new navigation causes on recordings written with rosbags from REAL Nav2 lines (each cited), with and
without /task_info, plus /cmd_vel and /odom evidence for commands that never reach the base."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hexar.causes import stated_causes
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Context
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.catalogue import catalogue
from hexar.explainers.navigation.detectors import BLOCKED, UNEXPLAINED
from tests.events.helpers import task_msg

T0 = 1_700_000_000_000_000_000
Line = tuple[str, int, str]

# (corpus id or source, expected cause, lines as (logger, level, msg)): messages verbatim from the threads.
CASES: list[tuple[str, str, list[Line]]] = [
    # evals/data/real_nav2/corpus.yaml nav2-3230-tb3-off-costmap (ros-navigation/navigation2#3230, galactic): two
    # lines that report the robot outside the costmap and no line that says why (localisation, TF, costmap size):
    # told as the state with its candidates (states.py), no cause claimed
    ("nav2-3230", UNEXPLAINED, [
        ("nav2_costmap_2d", WARN, "Robot is out of bounds of the costmap!"),
        ("planner_server", WARN, "Cannot create a plan: the robot's start position is off the global costmap. "
         "Planning will always fail, are you sure the robot has been properly localized?")]),
    # coverage-64-goal-outside-bounds (open-navigation/opennav_coverage#64)
    ("coverage-64", g.GOAL_UNREACHABLE, [
        ("planner_server", WARN, 'GridBased plugin failed to plan from (0.00, -0.01) to (-105.92, 39.25): '
         '"Goal Coordinates of(-105.918845, 39.251424) was outside bounds"')]),
    # nav2-3746-sim-time-extrapolation (ros-navigation/navigation2#3746): an unknown TF-helper logger
    ("nav2-3746", g.TRANSFORM, [
        ("transformPoseInTargetFrame", ERROR, "Extrapolation Error looking up target frame: Lookup would require "
         "extrapolation into the future.  Requested time 1691424773.212782 but the latest data is at time "
         "3617.600000, when looking up transform from frame [map] to frame [odom]"),
        ("planner_server", WARN, "Could not transform the start or goal pose in the costmap frame")]),
    # rbvogui-20-dwb-not-installed (namespaced logger `robot.controller_server`)
    ("rbvogui-20", g.CONFIGURATION, [
        ("robot.controller_server", 50, "Failed to create controller. Exception: According to the loaded plugin "
         "descriptions the class dwb_core::DWBLocalPlanner with base class type nav2_core::Controller does not "
         "exist.")]),
    # neo-sim2-19-spin-collision-ahead (Foxy/Galactic `recoveries_server`)
    ("neo-sim2-19", g.COLLISION_AHEAD, [
        ("recoveries_server", INFO, "Attempting spin"),
        ("recoveries_server", WARN, "Collision Ahead - Exiting Spin"),
        ("controller_server", ERROR, "Failed to make progress")]),
    # nav2-451-goaldist-unreachable-area (`DWBLocalPlanner`'s own logger)
    ("nav2-451", g.CONTROLLER, [
        ("DWBLocalPlanner", ERROR, "No valid trajectories out of 399! "),
        ("DWBLocalPlanner", ERROR, "1.00:   GoalDist/Trajectory Hits Unreachable Area.")]),
    # shared reference nav2_log_messages.md: docking_server.cpp:184@jazzy
    ("nav2_log_messages.md docking_server", g.DOCKING, [
        ("docking_server", ERROR, "Failed to dock, all retries have been used")]),
]


def _bag(lines: list[Line], with_task: bool, end: str | None = "Goal failed") -> BagBuilder:
    b = BagBuilder()
    t = T0 + sec_ns(1)
    task = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    if with_task:
        b.task_info(t, task_msg("t1", "go to the door", task))
    b.log(t + sec_ns(0.1), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    for i, (name, level, msg) in enumerate(lines):
        b.log(t + sec_ns(1 + i), name, level, msg)
    done = t + sec_ns(2 + len(lines))
    if end is not None:
        b.log(done, "bt_navigator", ERROR, end)
    if with_task:
        b.task_info(done + sec_ns(0.1), task_msg("t1", "go to the door", [(*task[0][:2], "failed", "")]))
    return b


def _explain(tmp_path: Path, b: BagBuilder, name: str, storage: str = "sqlite3") -> tuple[list[str], str]:
    log = read_recording(b.write(tmp_path / name, storage=storage))  # type: ignore[arg-type]
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    return answer.causes, f"{answer.text} {answer.fix}"


@pytest.mark.parametrize(("source", "cause", "lines"), CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("with_task", [True, False])
def test_each_new_cause_from_real_lines(tmp_path: Path, source: str, cause: str, lines: list[Line],
                                        with_task: bool) -> None:
    causes, _ = _explain(tmp_path, _bag(lines, with_task), "bag")
    # a configuration error that kept a node from coming up is told as a bring-up failure too (issue 20)
    assert causes in ([cause], [cause, g.BRINGUP] if cause == g.CONFIGURATION else [cause]), source


def test_goal_outside_the_map_is_not_an_obstacle(tmp_path: Path) -> None:
    causes, text = _explain(tmp_path, _bag(CASES[1][2], True), "bag")
    assert causes == [g.GOAL_UNREACHABLE]
    assert "pick a reachable goal" in text and "Clear the way" not in text


def test_failed_to_make_progress_alone_is_no_progress_never_blocked(tmp_path: Path) -> None:
    # corpus hsr-14-failed-to-make-progress: the controller gave up and nothing says why
    lines: list[Line] = [("controller_server", INFO, "Passing new path to controller."),
                         ("controller_server", ERROR, "Failed to make progress"),
                         ("controller_server", WARN, "[follow_path] [ActionServer] Aborting handle.")]
    causes, text = _explain(tmp_path, _bag(lines, True), "bag")
    assert causes == [g.NO_PROGRESS] and BLOCKED not in causes
    assert "nothing in my logs says why" in text and "cmd_vel reaches the base" in text
    assert "obstacle" not in text.lower().split("checks")[0]


def test_a_line_of_an_unknown_logger_still_reaches_the_detectors(tmp_path: Path) -> None:
    # corpus outdoor-example-3-tf-unconnected: the TF message arrives under a logger nobody lists
    lines: list[Line] = [("my_custom_wrapper_node", WARN, "Could not find a connection between 'odom' and "
                          "'base_link' because they are not part of the same tree.Tf has two or more unconnected "
                          "trees.")]
    assert catalogue().role("my_custom_wrapper_node") is None
    causes, _ = _explain(tmp_path, _bag(lines, True), "bag")
    assert causes == [g.TRANSFORM]


def _twist(vx: float) -> object:
    v3 = TYPESTORE.types["geometry_msgs/msg/Vector3"]
    return TYPESTORE.types["geometry_msgs/msg/Twist"](linear=v3(x=vx, y=0.0, z=0.0), angular=v3(x=0.0, y=0.0, z=0.0))


def _odom(t: int, x: float, vx: float) -> object:
    ty = TYPESTORE.types
    pose = ty["geometry_msgs/msg/Pose"](position=ty["geometry_msgs/msg/Point"](x=x, y=0.0, z=0.0),
                                       orientation=ty["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    header = ty["std_msgs/msg/Header"](stamp=ty["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9),
                                       frame_id="odom")
    return ty["nav_msgs/msg/Odometry"](
        header=header, child_frame_id="base_link",
        pose=ty["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.zeros(36)),
        twist=ty["geometry_msgs/msg/TwistWithCovariance"](twist=_twist(vx), covariance=np.zeros(36)))


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_commands_not_reaching_base_needs_cmd_vel_and_still_odometry(tmp_path: Path, storage: str) -> None:
    # corpus nav2-4027-cmd-vel-not-set: the controller kept commanding, the robot never moved
    lines: list[Line] = [("controller_server", INFO, "Received a goal, begin computing control effort."),
                         ("controller_server", ERROR, "Failed to make progress")]
    b = _bag(lines, True)
    for i in range(40):
        t = T0 + sec_ns(1.2 + i * 0.1)
        b.raw(t, "/cmd_vel", "geometry_msgs/msg/Twist", _twist(0.26))
        b.raw(t, "/odom", "nav_msgs/msg/Odometry", _odom(t, 0.0, 0.0))
    causes, text = _explain(tmp_path, b, "bag", storage)
    assert causes == [g.NOT_REACHING_BASE]
    assert "check that cmd_vel reaches the base" in text.lower()
    # the same goal where odometry shows motion: no such claim, only the honest no-progress finding
    moving = _bag(lines, True)
    for i in range(40):
        t = T0 + sec_ns(1.2 + i * 0.1)
        moving.raw(t, "/cmd_vel", "geometry_msgs/msg/Twist", _twist(0.26))
        moving.raw(t, "/odom", "nav_msgs/msg/Odometry", _odom(t, 0.026 * i, 0.26))
    assert _explain(tmp_path, moving, "moving", storage)[0] == [g.NO_PROGRESS]


def test_a_goal_reached_late_because_the_collision_monitor_held_the_robot(tmp_path: Path) -> None:
    # corpus mowgli-159-collision-monitor-stop: the collision monitor held the robot 414 s, then let it go on
    b = BagBuilder()
    t = T0 + sec_ns(1)
    step = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    b.task_info(t, task_msg("t1", "mow the strip", step))
    b.log(t + sec_ns(0.1), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    b.log(t + sec_ns(5), "collision_monitor", INFO, "Robot to stop due to PolygonStop polygon")
    b.log(t + sec_ns(419), "collision_monitor", INFO, "Robot to continue normal operation")
    b.log(t + sec_ns(430), "bt_navigator", INFO, "Goal succeeded")
    b.task_info(t + sec_ns(430.1), task_msg("t1", "mow the strip", [(*step[0][:2], "succeeded", "")]))
    log = read_recording(b.write(tmp_path / "bag"))
    answer = NavigationExplainer().explain("Why did it take so long to get there?", Context.for_task(log, log.task()))
    assert answer.causes == [g.COLLISION_AHEAD]
    assert "collision monitor stopped me for 414 s" in answer.text


DWB_HITS: list[Line] = [  # corpus tb4-679 / nav2-3807: DWB's debug lines, verbatim
    ("DWBLocalPlanner", ERROR, "No valid trajectories out of 419! "),
    ("DWBLocalPlanner", ERROR, "1.00: BaseObstacle/Trajectory Hits Obstacle."),
]


def test_dwb_obstacle_critic_is_a_blocked_path_only_when_the_controller_gave_up(tmp_path: Path) -> None:
    # tb4-679-humble-trajectory-hits-obstacle: then "Controller patience exceeded" and the goal failed
    gave_up = [*DWB_HITS, ("controller_server", ERROR, "Controller patience exceeded")]
    assert _explain(tmp_path, _bag(gave_up, True), "gave_up")[0] == [BLOCKED]
    # nav2-3807-dwb-no-valid-trajectories: the controller keeps driving; its trajectories were the trouble
    going = [*DWB_HITS, ("controller_server", INFO, "Passing new path to controller.")]
    assert _explain(tmp_path, _bag(going, True), "going")[0] == [g.CONTROLLER]


def test_a_crashed_nav2_process_is_a_bring_up_failure(tmp_path: Path) -> None:
    # corpus nav2-4380-humble-mppi-sigill-arm-binaries (gdb's report, an unknown logger)
    lines: list[Line] = [("gdb", ERROR, 'Thread 1 "controller_serv" received signal SIGILL, Illegal instruction.')]
    assert _explain(tmp_path, _bag(lines, False), "bag")[0] == [g.CONFIGURATION, g.BRINGUP]


def test_a_docking_failure_is_not_worded_as_charging(tmp_path: Path) -> None:
    from hexar.causes import stated_causes

    # corpus mowgli-486-dock-charge-timeout
    lines: list[Line] = [("docking_server", WARN, "Docking failed, will retry: Timed out waiting for charge to start"),
                         ("docking_server", ERROR, "Timed out resetting dock approach")]
    causes, text = _explain(tmp_path, _bag(lines, True), "bag")
    assert causes == [g.DOCKING]
    assert g.DOCKING in stated_causes(text) and "navigation.charging" not in stated_causes(text)


def _no_task(tmp_path: Path, lines: list[tuple[float, str, int, str]], question: str) -> tuple[list[str], str]:
    b = BagBuilder()
    for s, logger, level, msg in lines:
        b.log(T0 + sec_ns(s), logger, level, msg)
    log = read_recording(b.write(tmp_path / "bag"))
    answer = NavigationExplainer().explain(question, Context.for_task(log, log.task()))
    return answer.causes, answer.text


def test_a_stop_seen_while_the_goal_still_runs_is_not_called_a_failed_goal(tmp_path: Path) -> None:
    # corpus mowgli-159-collision-monitor-stop: no goal line, no /task_info, the robot resumed after 414 s
    causes, text = _no_task(tmp_path, [(1, "collision_monitor", INFO, "Robot to stop due to PolygonStop polygon"),
                                       (415, "collision_monitor", INFO, "Robot to continue normal operation")],
                            "Why did it take so long?")
    assert causes == [g.COLLISION_AHEAD]
    assert "couldn't reach" not in text and "does not show whether I got there" in text


_STUCK_THEN_REACHED = [
    (1, "bt_navigator", INFO, "Begin navigating from current location (-4.03, -2.64) to (-4.00, 2.70)"),
    (2, "controller_server", INFO, "Received a goal, begin computing control effort."),
    (12, "controller_server", ERROR, "Failed to make progress"),
    (12.1, "controller_server", WARN, "[follow_path] [ActionServer] Aborting handle."),
    (13, "local_costmap.local_costmap", INFO, "Received request to clear entirely the local_costmap"),
    (23, "controller_server", ERROR, "Failed to make progress"),
    (24, "global_costmap.global_costmap", INFO, "Received request to clear entirely the global_costmap"),
    (34, "controller_server", ERROR, "Failed to make progress"),
    (44, "controller_server", ERROR, "Failed to make progress"),
    (45, "behavior_server", INFO, "Running spin"),
    (50, "behavior_server", INFO, "spin completed successfully")]


def test_a_goal_the_controller_reached_after_progress_failures_is_reached_late_not_given_up(tmp_path: Path) -> None:
    # blind7 pinklab-openarm-rack-aisle (Jazzy, no navigator end, no /task_info): four progress failures, a spin,
    # then the controller's "Reached the goal!" (controller_server.cpp): the goal was reached, each failure counted
    causes, text = _no_task(tmp_path, [*_STUCK_THEN_REACHED, (70, "controller_server", INFO, "Reached the goal!")],
                            "Why did it take so long to get there?")
    assert causes == [UNEXPLAINED]
    assert text.startswith("I reached my goal, but it took longer") and "gave up" not in text
    assert "4 times" in text and "can't tell what was in the way" in text


def test_an_error_after_the_controller_reached_leaves_the_end_unknown(tmp_path: Path) -> None:
    causes, text = _no_task(tmp_path, [*_STUCK_THEN_REACHED, (70, "controller_server", INFO, "Reached the goal!"),
                                       (71, "controller_server", ERROR, "Failed to make progress")],
                            "Why did it take so long to get there?")
    # a progress failure after the controller's "Reached the goal!" belongs to a later goal, which gave up
    assert causes == [g.NO_PROGRESS] and "I reached" not in text and "gave up" in text


def test_a_short_collision_monitor_hold_is_not_worded_as_0_s(tmp_path: Path) -> None:
    b = BagBuilder()
    t = T0 + sec_ns(1)
    step = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    b.task_info(t, task_msg("t1", "mow the strip", step))
    b.log(t + sec_ns(5), "collision_monitor", INFO, "Robot to stop due to PolygonStop polygon")
    b.log(t + sec_ns(5.3), "collision_monitor", INFO, "Robot to continue normal operation")
    b.log(t + sec_ns(20), "bt_navigator", INFO, "Goal succeeded")
    b.task_info(t + sec_ns(20.1), task_msg("t1", "mow the strip", [(*step[0][:2], "succeeded", "")]))
    log = read_recording(b.write(tmp_path / "bag"))
    text = NavigationExplainer().explain("Why were you slow?", Context.for_task(log, log.task())).text
    assert "stopped me for less than a second" in text and "0 s" not in text


def test_amcl_waiting_for_an_initial_pose_is_a_symptom_told_with_its_two_readings(tmp_path: Path) -> None:
    # corpus tb4-318-lidar-create3-clock: AMCL's own warning (amcl_node.cpp:926@humble), verbatim, with a failed goal
    # on /task_info; the thread's cause was the lidar's and the base's clocks disagreeing, not a missing pose: the
    # warning alone is no localisation finding, the answer says what it means and what would tell the two apart
    b = BagBuilder()
    t = T0 + sec_ns(1)
    step = [("navigate_to_pose", {"x": 1.0, "y": 2.0}, "Running", "")]
    b.task_info(t, task_msg("t1", "go to the dock", step))
    for k in range(3):
        b.log(t + sec_ns(1 + 2 * k), "amcl", WARN,
              "AMCL cannot publish a pose or update the transform. Please set the initial pose...")
    b.task_info(t + sec_ns(9), task_msg("t1", "go to the dock", [(*step[0][:2], "failed", "aborted")]))
    log = read_recording(b.write(tmp_path / "bag"))
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    assert answer.causes == [UNEXPLAINED]
    assert "AMCL kept saying it cannot publish a pose until an initial pose is set" in answer.text
    assert "do not show why" in answer.text and stated_causes(answer.text) <= {UNEXPLAINED}
    assert "initial pose" in (answer.fix or "") and "clocks" in (answer.fix or "")


def test_no_progress_says_how_long_the_recorded_position_stood_still(tmp_path: Path) -> None:
    b = BagBuilder()
    t = T0 + sec_ns(1)
    step = [("navigate_to_pose", {"x": 5.0, "y": 0.0}, "Running", "")]
    b.task_info(t, task_msg("t1", "go to the door", step))
    b.log(t + sec_ns(0.1), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (5.00, 0.00)")
    for i in range(100):  # 5 Hz: drives 0.4 m/s for 5 s up to x = 2.0, then stands there (1 cm jitter)
        x = min(0.08 * i, 2.0) + (0.01 * (i % 2) if i > 25 else 0.0)
        b.pose(t + sec_ns(0.5 + i * 0.2), x, 0.0, 0.0, 0.01, 0.01, 0.01)
    b.log(t + sec_ns(20.5), "controller_server", ERROR, "Failed to make progress")
    b.log(t + sec_ns(21), "bt_navigator", ERROR, "Goal failed")
    b.task_info(t + sec_ns(21.1), task_msg("t1", "go to the door", [(*step[0][:2], "failed", "aborted")]))
    log = read_recording(b.write(tmp_path / "bag"))
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    assert answer.causes == [g.NO_PROGRESS]
    # the last pose farther than 0.5 m from where it stood: x = 1.44 at 4.1 s; the failure at 20.5 s
    assert "made no progress for 16 s (my recorded position stayed within 0.5 m" in answer.text


def _timed(lines: list[tuple[float, str, int, str]]) -> BagBuilder:
    """A failed goal with its lines at the given seconds after the goal began (real Nav2 lines come in bursts)."""
    b = BagBuilder()
    t = T0 + sec_ns(1)
    b.log(t, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    for at, name, level, msg in lines:
        b.log(t + sec_ns(at), name, level, msg)
    b.log(t + sec_ns(max(at for at, *_ in lines) + 1), "bt_navigator", ERROR, "Goal failed")
    return b


STAMPED_EARLY = (  # blind3 tb4-530 (turtlebot/turtlebot4#530), amcl's line verbatim
    "amcl", INFO, "Message Filter dropping message: frame 'rplidar_link' at time 1738229894.744 for reason 'the "
    "timestamp on the message is earlier than all the data in the transform cache'")
PATIENCE = ("controller_server", ERROR, "Controller patience exceeded")


def test_obstacle_critic_after_data_stamped_before_its_transforms_is_told_as_that_doubt(tmp_path: Path) -> None:
    hits = [(116.0, *DWB_HITS[1]), (116.001, *DWB_HITS[0]), (116.002, *PATIENCE)]
    causes, text = _explain(tmp_path, _timed([(0.0, *STAMPED_EARLY), *hits]), "skew")
    assert causes == [g.TRANSFORM]
    assert "may not have been a real obstacle" in text and "chrony" in text
    assert BLOCKED not in stated_causes(text) and g.TRANSFORM in stated_causes(text)
    # the same critic with no such drop, or with one only after it, is an obstacle on the way
    assert _explain(tmp_path, _timed(hits), "plain")[0] == [BLOCKED]
    assert _explain(tmp_path, _timed([*hits, (117.0, *STAMPED_EARLY)]), "later")[0] == [BLOCKED]
    # a drop at start-up, before the goal began, is none of this goal's data: robots print a few then
    assert _explain(tmp_path, _timed([(-5.0, *STAMPED_EARLY), *hits]), "startup")[0] == [BLOCKED]


def test_that_doubt_with_no_end_of_the_goal_recorded_claims_no_goal_missed(tmp_path: Path) -> None:
    b = BagBuilder()
    t = T0 + sec_ns(1)
    b.log(t, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    for at, name, level, msg in [(0.0, *STAMPED_EARLY), (116.0, *DWB_HITS[1]), (116.001, *DWB_HITS[0]),
                                 (116.002, *PATIENCE)]:
        b.log(t + sec_ns(at), name, level, msg)
    causes, text = _explain(tmp_path, b, "cut")  # the recording stops before any line ends the goal
    assert causes == [g.TRANSFORM]
    assert text.startswith("The recording ends before my navigation to my goal finished, so it does not show "
                           "whether I got there; on the way my controller found that every trajectory would hit")
    assert "may not have been a real obstacle" in text


PLANNER_GAVE_UP = [  # blind7 rafism-notes (TurtleBot 3, goal sent outside the map), verbatim
    ("planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50."),
    ("planner_server", WARN, "Planning algorithm GridBased failed to generate a valid path to (-4.12, 4.78)"),
]


def test_controller_rejections_right_after_the_planner_gave_up_are_not_a_cause(tmp_path: Path) -> None:
    planner = [(0.0, *PLANNER_GAVE_UP[0]), (0.0001, *PLANNER_GAVE_UP[1])]
    dwb = [(0.043, *DWB_HITS[0]), (0.0431, *DWB_HITS[1]),
           (0.0432, "controller_server", WARN, "[follow_path] [ActionServer] Aborting handle.")]
    causes, text = _explain(tmp_path, _timed([*planner, *dwb]), "rafism")
    assert causes == [UNEXPLAINED] and "my planner could not compute a route" in text
    assert not stated_causes(text) & {BLOCKED, g.CONTROLLER}
    # the controller's own trouble when the planner had not just given up
    later = [(at + 10.0, *rest) for at, *rest in dwb]
    assert _explain(tmp_path, _timed([*planner, *later]), "later")[0] == [BLOCKED]


def test_optimizer_failing_after_a_start_on_occupied_cells_is_not_the_controllers_fault(tmp_path: Path) -> None:
    # blind5 mirte (inflation radius below the inscribed radius), the planner's and MPPI's lines verbatim
    lethal = (0.0, "planner_server", ERROR,
              "GridBased: failed to create plan, invalid use: Starting point in lethal space! Cannot create feasible "
              "plan..")
    mppi = (0.1, "controller_server", ERROR, "Optimizer fail to compute path")
    causes, text = _explain(tmp_path, _timed([lethal, mppi]), "lethal")
    assert causes == [UNEXPLAINED] and "reported the cells under me as occupied" in text
    assert g.CONTROLLER not in stated_causes(text)
    assert _explain(tmp_path, _timed([mppi]), "mppi")[0] == [g.CONTROLLER]


def test_transform_errors_right_after_the_planner_gave_up_do_not_explain_its_failure(tmp_path: Path) -> None:
    # blind13 NavGreen wp10: the planner found no path, then the controller's extrapolation errors a second later
    planner = [(2.0, "planner_server", WARN, "GridBased: failed to create plan, no valid path found."),
               (2.0001, "planner_server", WARN,
                "Planning algorithm GridBased failed to generate a valid path to (5.50, 0.00)")]
    tf = (3.0, "controller_server", ERROR, "Extrapolation Error looking up target frame: Lookup would require "
          "extrapolation into the future. from frame [map] to frame [odom]")
    causes, text = _explain(tmp_path, _timed([*planner, tf]), "after")
    assert causes == [UNEXPLAINED] and "my planner could not compute a route" in text
    assert g.TRANSFORM not in stated_causes(text)
    # the same error before the planner gave up, or long after it, is still the transform's
    assert _explain(tmp_path, _timed([(1.0, *tf[1:]), *planner]), "before")[0] == [g.TRANSFORM]
    assert _explain(tmp_path, _timed([*planner, (12.0, *tf[1:])]), "later")[0] == [g.TRANSFORM]


def test_a_failed_planning_attempt_is_counted_once_though_it_logs_two_lines(tmp_path: Path) -> None:
    # navigation2's planner plugin and planner server each log one line per failed attempt (blind13 NavGreen wp10)
    attempt = [(0.0, "planner_server", WARN, "GridBased: failed to create plan, no valid path found."),
               (0.0001, "planner_server", WARN,
                "Planning algorithm GridBased failed to generate a valid path to (5.50, 0.00)")]
    causes, text = _explain(tmp_path, _timed(attempt), "one")
    assert causes == [UNEXPLAINED] and "my planner could not compute a route to it (1 time)" in text
    again = [(at + 1.0, *rest) for at, *rest in attempt]
    assert "could not compute a route to it (2 times)" in _explain(tmp_path, _timed([*attempt, *again]), "two")[1]
