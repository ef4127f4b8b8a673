"""The robot's start as a task when a recording has no /task_info and no goal (events/bringup.py): failed at the first
decisive error, succeeded when ros2_control says the start completed, and no task where nothing starts."""

from __future__ import annotations

from pathlib import Path

from hexar.events.records import ERROR, INFO, WARN
from tests.explainers.helpers import T0, write_lines

# ros2_control's own lines (hardware_interface/src/resource_manager.cpp:88,111,120@humble;
# controller_manager/controller_manager/spawner.py:273@humble, which appends the controller's name)
START = [(0.0, "resource_manager", INFO, "Loading hardware 'RRBot'"),
         (0.1, "resource_manager", INFO, "Initialize hardware 'RRBot'"),
         (0.2, "resource_manager", INFO, "Successful initialization of hardware 'RRBot'"),
         (1.0, "spawner_joint_state_broadcaster", INFO, "Configured and activated joint_state_broadcaster")]
# controller_manager.cpp:3401@jazzy
NO_CLOCK = ("No clock received, using time argument instead! Check your node's clock configuration (use_sim_time "
            "parameter) and if a valid clock source is available")


def _tasks(tmp_path: Path, lines: list[tuple[float, str, int, str]]):  # type: ignore[no-untyped-def]
    return write_lines(tmp_path, lines).tasks


def _steps(tasks) -> list[tuple[str, str, str]]:  # type: ignore[no-untyped-def]
    return [(t.skills[0].skill, t.outcome, t.skills[0].error_msg) for t in tasks]


def test_a_start_ros2_control_says_completed_is_a_bring_up_that_succeeded(tmp_path: Path) -> None:
    assert _steps(_tasks(tmp_path, START)) == [("bring_up_controllers", "succeeded", "")]


def test_a_warning_on_the_way_does_not_fail_a_start_that_completed(tmp_path: Path) -> None:
    lines = [START[0], (0.05, "controller_manager", WARN, NO_CLOCK), *START[1:]]
    assert _steps(_tasks(tmp_path, lines)) == [("bring_up_controllers", "succeeded", "")]


def test_a_drivers_error_after_its_own_start_fails_the_bring_up_at_that_error(tmp_path: Path) -> None:
    # ydlidar_ros2_driver's own lines (a console of ydlidar_ros2#4): it started, then could not read the lidar
    lines = [(0.0, "ydlidar_ros2_driver_node", INFO, "[YDLIDAR INFO] Current ROS Driver Version: 1.0.1"),
             (2.6, "ydlidar_ros2_driver_node", ERROR, "Unknown error"),
             (2.7, "ydlidar_ros2_driver_node", INFO, "[YDLIDAR INFO] Now YDLIDAR is stopping")]
    tasks = _tasks(tmp_path, lines)
    assert _steps(tasks) == [("bring_up_controllers", "failed", "Unknown error")]
    assert tasks[0].created == T0  # the step began with the driver's start, so its lines are in the window


def test_an_error_after_the_start_completed_is_a_failure_never_a_success(tmp_path: Path) -> None:
    driver = "ydlidar_ros2_driver_node"
    lines = [*START, (1.5, driver, INFO, "[YDLIDAR INFO] Current ROS Driver Version: 1.0.1"),
             (2.0, driver, ERROR, "Unknown error")]
    assert _steps(_tasks(tmp_path / "a", lines)) == [("bring_up_controllers", "failed", "Unknown error")]
    # an error of a node the recording never saw start: not told as a failure of the start, nor as a success
    lines = [*START, (2.0, "moveit.ros.occupancy_map_monitor.middleware_handle", ERROR,
                      "No 3D sensor plugin(s) defined for octomap updates")]
    assert all(t.outcome != "succeeded" for t in _tasks(tmp_path / "b", lines))


def test_a_start_with_no_line_saying_it_completed_is_still_running(tmp_path: Path) -> None:
    assert _steps(_tasks(tmp_path, START[:2])) == [("bring_up_controllers", "running", "")]


def test_lines_of_a_node_that_starts_nothing_give_no_task(tmp_path: Path) -> None:
    # demo_nodes_cpp's talker (talker.cpp: "Publishing: '%s'"): no start of the robot's software, no error
    lines = [(0.0, "talker", INFO, "Publishing: 'Hello World: 1'"), (1.0, "talker", INFO,
                                                                     "Publishing: 'Hello World: 2'")]
    assert _tasks(tmp_path, lines) == []


def test_one_error_of_moveit_the_recording_never_saw_start_gives_no_task(tmp_path: Path) -> None:
    # moveit_ros occupancy_map_monitor's line, printed by healthy arms without a 3D sensor as well as broken ones
    lines = [(0.0, "moveit.ros.occupancy_map_monitor.middleware_handle", ERROR,
              "No 3D sensor plugin(s) defined for octomap updates")]
    assert _tasks(tmp_path, lines) == []


def test_a_nav2_robots_start_stays_navigations(tmp_path: Path) -> None:
    # lifecycle_manager's line (nav2_lifecycle_manager/src/lifecycle_manager.cpp) beside ros2_control's start
    lines = [*START, (3.0, "lifecycle_manager_navigation", INFO, "Managed nodes are active")]
    assert all(t.skills[0].skill != "bring_up_controllers" for t in _tasks(tmp_path, lines))


def test_a_hardware_plugin_that_aborts_while_loading_fails_the_start_though_nav2_shares_the_text(
        tmp_path: Path) -> None:
    # the resource manager's "Loading hardware" line with the abort of pluginlib's exception printed after it
    msg = ("Loading hardware 'ethercat_zeroerr'\nterminate called after throwing an instance of "
           "'pluginlib::LibraryLoadException'\n  what():  According to the loaded plugin descriptions the class "
           "ethercat_driver/EthercatDriver with base class type hardware_interface::SystemInterface does not exist.")
    [step] = _steps(_tasks(tmp_path, [(0.0, "resource_manager", INFO, msg)]))
    assert step[:2] == ("bring_up_controllers", "failed")


def test_a_behaviour_nodes_error_after_its_own_work_is_no_failed_start(tmp_path: Path) -> None:
    # turtlebot4_node's lines (turtlebot4 Ignition simulator notes): it undocked fine, then missed two services; it
    # neither drives a device nor is ros2_control's or MoveIt's, so no start is claimed to have failed
    node = "turtlebot4_node"
    lines = [(0.0, node, INFO, "Undocking"), (1.0, node, INFO, "undock goal accepted by server, waiting for result"),
             (11.0, node, INFO, "undock goal succeeded"),
             (31.2, node, ERROR, "Service oakd/start_camera unavailable."),
             (31.3, node, ERROR, "Service start_motor unavailable.")]
    assert _tasks(tmp_path, lines) == []
