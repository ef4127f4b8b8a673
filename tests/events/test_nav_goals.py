"""Tasks derived from Nav2 goals on recordings without /task_info (sqlite3 and mcap), from the log lines of
several distros, from the NavigateToPose status topic and from /goal_pose; old-shape recordings unchanged."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.events.errors import NoTaskError
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Context
from hexar.explainers.navigation import NavigationExplainer
from tests.events.helpers import T0, two_skill_task

# bt_navigator's begin/end wording per distro (shared reference nav2_log_messages.md; Foxy bt_navigator.cpp;
# Kilted/main bt_action_server_impl.hpp:470).
HUMBLE = ("Begin navigating from current location (0.00, 0.00) to (2.50, 1.00)", "Goal failed")
FOXY = ("Begin navigating from current location to (2.50, 1.00)", "Navigation failed")
KILTED = ("Begin navigating from current location (0.00, 0.00) to (2.50, 1.00)",
          "Goal failed error_code:104 error_msg:'Failed to make progress'")


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
@pytest.mark.parametrize(("logger", "wording"), [("bt_navigator", HUMBLE), ("bt_navigator", FOXY),
                                                  ("robot1.bt_navigator", KILTED)])
def test_goals_from_nav2_lines(tmp_path: Path, storage: str, logger: str, wording: tuple[str, str]) -> None:
    b = BagBuilder()
    b.log(T0, logger, INFO, wording[0])
    b.log(T0 + sec_ns(20), "controller_server", ERROR, "Failed to make progress")
    b.log(T0 + sec_ns(30), logger, ERROR, wording[1])
    b.log(T0 + sec_ns(40), logger, INFO, "Begin navigating from current location (2.40, 1.00) to (0.00, 3.00)")
    b.log(T0 + sec_ns(60), logger, INFO, "Goal succeeded")
    log = read_recording(b.write(tmp_path / "bag", storage=storage))  # type: ignore[arg-type]
    first, second = log.tasks
    assert first.derived and first.outcome == "failed" and second.outcome == "succeeded"
    assert first.skills[0].skill == "navigate_to_pose"
    assert (first.skills[0].params["x"], first.skills[0].params["y"]) == (2.5, 1.0)
    assert first.window() == (T0, T0 + sec_ns(30))
    assert log.task().task_id == second.task_id


def _status_array(t: int, goals: list[tuple[int, int]]) -> object:
    ty = TYPESTORE.types
    stamp = ty["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)
    return ty["action_msgs/msg/GoalStatusArray"](status_list=[
        ty["action_msgs/msg/GoalStatus"](
            goal_info=ty["action_msgs/msg/GoalInfo"](
                goal_id=ty["unique_identifier_msgs/msg/UUID"](uuid=np.full(16, gid, dtype=np.uint8)), stamp=stamp),
            status=status)
        for gid, status in goals])


def test_goals_from_the_action_status_and_goal_pose(tmp_path: Path) -> None:
    ty = TYPESTORE.types
    b = BagBuilder()
    header = ty["std_msgs/msg/Header"](stamp=ty["builtin_interfaces/msg/Time"](sec=T0 // 10**9, nanosec=0),
                                       frame_id="map")
    pose = ty["geometry_msgs/msg/Pose"](position=ty["geometry_msgs/msg/Point"](x=3.0, y=-1.0, z=0.0),
                                        orientation=ty["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    b.raw(T0, "/goal_pose", "geometry_msgs/msg/PoseStamped", ty["geometry_msgs/msg/PoseStamped"](header=header,
                                                                                                 pose=pose))
    status = "/navigate_to_pose/_action/status"
    b.raw(T0 + sec_ns(1), status, "action_msgs/msg/GoalStatusArray", _status_array(T0 + sec_ns(1), [(7, 2)]))
    b.raw(T0 + sec_ns(9), status, "action_msgs/msg/GoalStatusArray", _status_array(T0 + sec_ns(9), [(7, 6)]))
    log = read_recording(b.write(tmp_path / "bag"))
    (task,) = log.tasks
    assert task.derived and task.outcome == "failed"
    # only the pose topic gives no goal without status; with the status, the status decides the outcome
    only_pose = BagBuilder(messages=[m for m in b.messages if m[1] == "/goal_pose"])
    (goal,) = read_recording(only_pose.write(tmp_path / "pose")).tasks
    assert goal.skills[0].params["x"] == 3.0 and goal.outcome == "running"


def test_recording_with_task_info_keeps_its_tasks(tmp_path: Path) -> None:
    b = BagBuilder()
    two_skill_task(b, T0, "a1", fail_second=False)
    b.log(T0 + sec_ns(2), "bt_navigator", INFO, HUMBLE[0])
    log = read_recording(b.write(tmp_path / "bag"))
    assert [t.task_id for t in log.tasks] == ["a1"] and not log.tasks[0].derived


def test_nav2_nodes_at_work_without_a_goal_line_are_a_navigation_still_running(tmp_path: Path) -> None:
    # ros-navigation/docs.nav2.org#404's planner_server bring-up (planner_server.cpp@galactic: "Configuring"), and
    # a node that is not Nav2's beside it
    b = BagBuilder()
    b.log(T0, "planner_server", INFO, "Creating")
    b.log(T0 + sec_ns(1), "planner_server", INFO, "Configuring")
    b.log(T0 + sec_ns(2), "minimal_publisher", INFO, "Publishing: 'Hello, world! 0'")
    task = read_recording(b.write(tmp_path / "bag")).task()
    assert task.derived and task.skills[0].state == "running"


def test_the_controllers_reached_line_with_no_name_is_a_navigation_that_reached_its_goal(tmp_path: Path) -> None:
    # ganapetya forklift MPC notes (blind10, spent): a custom controller's own lines, then the controller server's
    # "Reached the goal!" (controller_server.cpp:411@humble) pasted without its logger
    b = BagBuilder()
    b.log(T0, "", INFO, "P5 curvature speed limit active: max_v 0.450 -> 0.080")
    b.log(T0 + sec_ns(1), "", INFO, "Reached the goal!")
    log = read_recording(b.write(tmp_path / "bag"))
    task = log.task()
    assert task.derived and task.skills[0].skill == "navigate_to_pose"
    found = NavigationExplainer().explain("How did the navigation go?", Context.for_task(log, task))
    assert found.causes == ["navigation.nominal"] and found.text.startswith("I reached my goal")


def test_no_nav2_activity_still_no_task(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "minimal_publisher", INFO, "Publishing: 'Hello, world! 0'")
    log = read_recording(b.write(tmp_path / "bag"))
    with pytest.raises(NoTaskError, match="no task to explain"):
        log.task()


# turtlebot/turtlebot4_simulator#14 (Galactic): amcl's program could not start, the dynamic loader said why on its
# stderr (glibc elf/dl-lookup.c:808 "symbol lookup error"), pasted with launch's process prefix and no level
AMCL_LOADER = ("/opt/ros/galactic/lib/nav2_amcl/amcl: symbol lookup error: /opt/ros/galactic/lib/libamcl_core.so: "
               "undefined symbol: _ZN9nav2_amcl20LikelihoodFieldModelC1EddddmP5map_t")


def test_a_nav2_program_the_loader_could_not_start_is_a_failed_navigation(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "amcl-37", INFO, AMCL_LOADER)
    task = read_recording(b.write(tmp_path / "bag")).task()
    assert task.derived and task.skills[0].skill != "bring_up_controllers" and task.outcome == "failed"


def test_a_bring_up_error_about_a_node_that_is_not_nav2s_makes_no_navigation_goal(tmp_path: Path) -> None:
    # launch_ros/actions/lifecycle_node.py:123@rolling about a lidar driver (tof-imager-ros #3)
    b = BagBuilder()
    b.log(T0, "launch_ros.actions.lifecycle_node", ERROR,
          "Failed to make transition 'TRANSITION_CONFIGURE' for LifecycleNode '/tof_imager'")
    tasks = read_recording(b.write(tmp_path / "bag")).tasks
    assert all(t.skills[0].skill == "bring_up_controllers" for t in tasks)


# blind set 21's amcl-base-frame-wrong (the real kilted Nav2 run here): the global costmap waits for a transform that
# never comes, a goal is refused while the stack is not up, and Ctrl-C takes the stack down with errors of its own
WAITING = ("Timed out waiting for transform from base_footprint to map to become available, tf error: Invalid frame ID "
           "\"base_footprint\" passed to canTransform argument target_frame - frame does not exist")
DOWN = [("global_costmap.global_costmap", ERROR, "Caught exception in callback for transition 13"),
        ("rclcpp_lifecycle", WARN, "LifecycleNode is not shut down: Node still in state(1) in destructor"),
        ("planner_server-4", ERROR, "process has died [pid 28735, exit code -6, cmd '/opt/ros/kilted/lib/nav2_planner/"
                                    "planner_server --ros-args -r __node:=planner_server']."),
        ("lifecycle_manager_navigation", ERROR, "Failed to bring up all requested nodes. Aborting bringup.")]


@pytest.mark.parametrize("refused", [False, True])
def test_errors_a_stack_prints_as_it_is_stopped_end_no_goal(tmp_path: Path, refused: bool) -> None:
    b = BagBuilder()
    for k in range(4):
        b.log(T0 + sec_ns(k * 0.5), "global_costmap.global_costmap", INFO, WAITING)
    if refused:  # simple_action_server.hpp:155@kilted, at INFO: the goal ended there
        b.log(T0 + sec_ns(2.2), "bt_navigator", INFO, "Action server is inactive. Rejecting the goal.")
    b.log(T0 + sec_ns(2.5), "rclcpp", INFO, "signal_handler(signum=2)")
    for k, (name, level, msg) in enumerate(DOWN):
        b.log(T0 + sec_ns(3 + k * 0.1), name, level, msg)
    task = read_recording(b.write(tmp_path / "bag")).task()
    assert task.derived and task.outcome == ("failed" if refused else "running")
    # the same lines without the signal handler's: the first destructor begins the way down, by its stamp
    b = BagBuilder()
    for k in range(4):
        b.log(T0 + sec_ns(k * 0.5), "global_costmap.global_costmap", INFO, WAITING)
    for k, (name, level, msg) in enumerate(DOWN[1:]):
        b.log(T0 + sec_ns(3 + k * 0.1), name, level, msg)
    assert read_recording(b.write(tmp_path / "bag2")).task().outcome == "running"
