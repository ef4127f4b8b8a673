"""The robot's start as a task when a recording has no /task_info and no goal (events/bringup.py): failed at the first
decisive error, succeeded when ros2_control says the start completed, and no task where nothing starts."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder
from hexar.events.errors import NoTaskError
from hexar.events.records import ERROR, FATAL, INFO, WARN
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


# ros2_control_demos ros2_control_demo_hardware/src/rrbot_system_position_only.cpp:56-59@foxy: the demo's hardware
# interface, logging under its class name, refuses a joint whose command interface is not a position one
WRONG_INTERFACE = "Joint 'joint1' have velocity command interfaces found. 'position' expected."
# sllidar_ros2 src/sllidar_node.cpp:287@main (node "sllidar_node", :59): the lidar's serial port could not be opened
NO_PORT = "Error, cannot bind to the specified serial port /dev/ttyUSB0."
# sllidar_node.cpp:180@main, "Failed to start motor: %08x" with SL_RESULT_OPERATION_TIMEOUT (0x80008000)
MOTOR = "Failed to start motor: 80008000"
# diff_drive_controller/src/diff_drive_controller.cpp:466@jazzy: a velocity command came while it was not active
INACTIVE = "Can't accept new commands. subscriber is inactive"


def test_a_hardware_interfaces_lone_error_fails_the_start_at_that_error(tmp_path: Path) -> None:
    lines = [(0.0, "RRBotSystemPositionOnlyHardware", FATAL, WRONG_INTERFACE)]
    tasks = _tasks(tmp_path, lines)
    assert _steps(tasks) == [("bring_up_controllers", "failed", WRONG_INTERFACE)]
    assert tasks[0].created == T0


def test_a_drivers_identical_lone_errors_fail_the_start_at_the_first(tmp_path: Path) -> None:
    # no line of the driver before its error, and a node name that does not say "driver": the serial port it names
    # tells that it drives a device
    lines = [(s, "sllidar_node", ERROR, NO_PORT) for s in (1.0, 2.0, 3.0)]
    tasks = _tasks(tmp_path, lines)
    assert _steps(tasks) == [("bring_up_controllers", "failed", NO_PORT)]
    assert tasks[0].created == T0 + 1_000_000_000


def test_a_lone_error_naming_a_parameter_fails_that_nodes_start(tmp_path: Path) -> None:
    # robot_localization src/ros_robot_localization_listener.cpp:90-92@ros2, in its listener node
    # (robot_localization_listener_node.cpp:48)
    msg = "RosRobotLocalizationListener: Parameter filter_type invalid"
    lines = [(0.0, "robot_localization_listener_node", ERROR, msg)]
    assert _steps(_tasks(tmp_path, lines)) == [("bring_up_controllers", "failed", msg)]


def test_a_controller_dropping_commands_because_it_is_inactive_is_a_start_not_seen_complete(tmp_path: Path) -> None:
    lines = [(0.0, "diff_drive_controller", WARN, INACTIVE)]
    assert _steps(_tasks(tmp_path / "a", lines)) == [("bring_up_controllers", "running", "")]
    # after a start that completed, the same line (a controller deactivated since, or never activated) is no success
    lines = [*START, (5.0, "diff_drive_controller", WARN, INACTIVE)]
    assert _steps(_tasks(tmp_path / "b", lines)) == [("bring_up_controllers", "running", "")]


def test_a_recording_with_nothing_started_says_what_it_looked_for(tmp_path: Path) -> None:
    # no /rosout line (the robot's pose only), and a lone warning of a driver (no error, no refusal): no start to tell
    b = BagBuilder()
    b.pose(T0, 1.0, 2.0, 0.0, 0.01, 0.01, 0.01)
    for name, lines, builder in (("quiet", [], b), ("warning", [(0.0, "sllidar_node", WARN, MOTOR)], None)):
        log = write_lines(tmp_path / name, lines, builder)
        assert log.tasks == []
        with pytest.raises(NoTaskError) as err:
            log.task()
        assert str(err.value).startswith("no task to explain:")
        for looked_for in ("/task_info", "Nav2 navigation goal", "MoveIt or arm controller goal",
                           "start of the robot's drivers or controllers"):
            assert looked_for in str(err.value)



def test_a_drivers_own_lines_without_an_error_are_no_task_its_error_after_them_is(tmp_path: Path) -> None:
    # the UR driver's client library, logged under "UR_Client_Library:" (ur_robot_driver/src/urcl_log_handler.cpp:59
    # @humble), as pasted in Universal_Robots_ROS2_Driver#1308: the robot asked for its program, nothing said more
    lines = [(0.0, "UR_Client_Library:", INFO, "Robot requested program"),
             (0.1, "UR_Client_Library:", INFO, "Sent program to robot")]
    assert _tasks(tmp_path / "a", lines) == []
    # Universal_Robots_Client_Library src/rtde/rtde_client.cpp:702: strerror(ENOENT) behind the recipe's path
    msg = "Opening file '/opt/ur/resources/rtde_output_recipe.txt' failed with error: No such file or directory"
    assert _steps(_tasks(tmp_path / "b", [*lines, (1.0, "UR_Client_Library:", ERROR, msg)])) == [
        ("bring_up_controllers", "failed", msg)]


def test_a_lone_error_naming_a_device_fails_that_nodes_start(tmp_path: Path) -> None:
    # bluespace-ai/bluespace_ai_xsens_ros_mti_driver#1 (heldout9.yaml), as its console printed it: the Xsens driver's
    # node found no MTi device (it could not open /dev/ttyUSB0), before any other line of it
    msg = "No MTi device found."
    assert _steps(_tasks(tmp_path, [(0.0, "xsens_mti_node", ERROR, msg)])) == [("bring_up_controllers", "failed", msg)]
