"""Causes a driver's decisive line states in standard words (explainers/stated_causes.py), on real rosbag2
recordings with a task on /task_info. The lines are real: the texts of glibc's strerror, of libfranka, of the UR
client library, of ros2_controllers, of rclcpp and MoveIt, printed as these programs print them."""

from __future__ import annotations

import json
import re
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from hexar.causes import vocabulary
from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import ERROR, FATAL, INFO, WARN
from hexar.explainers.base import Explanation
from hexar.explainers.stated_causes import phrases
from tests.explainers.helpers import T0, explain, write_lines

SOURCE = re.compile(r"\S+:\d+@[0-9a-f]{12}")


def _task(status: str, skill: str) -> dict[str, Any]:
    return {"instruction": "start the robot's drivers", "task_id": "0000000000000023", "task_status": "valid",
            "task_error_msg": "", "skill_sequence": [{"skill": skill, "params": {}, "status": status,
                                                      "error_msg": "The skill has been aborted" if status == "failed"
                                                      else ""}]}


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]], fails_at: float, explainer: str = "control",
             skill: str = "bring_up_controllers") -> Explanation:
    """The lines, and a one-step task that runs from 0 s and fails at `fails_at`."""
    b = BagBuilder()
    b.task_info(T0 - sec_ns(1), _task("waiting", skill))
    b.task_info(T0 - sec_ns(0.5), _task("Running", skill))
    b.task_info(T0 + sec_ns(fails_at), _task("failed", skill))
    return explain(write_lines(tmp_path, lines, b), explainer, "Why didn't that work?")[1]


def _claims(found: Explanation) -> set[str]:
    return {c for c in read_claims(found.text).affirmed if not c.startswith("claim.")}


def test_the_data_loads_every_pattern_compiles_and_every_cause_is_known() -> None:
    folder = resources.files("hexar.explainers.stack")
    errnos = json.loads(folder.joinpath("strerror.json").read_text("utf-8"))["errnos"]
    setup = json.loads(folder.joinpath("setup_phrases.json").read_text("utf-8"))["phrases"]
    assert {e["errno"] for e in errnos} >= {"EACCES", "EADDRINUSE", "ECONNREFUSED", "ENOENT", "EBUSY", "ETIMEDOUT"}
    assert "EPERM" not in {e["errno"] for e in errnos}  # healthy robots print it (no realtime priority)
    for e in errnos:
        re.compile(e["pattern"])
        assert e["cause"] is None or e["cause"] in vocabulary()
        assert e["source"].startswith("glibc/sysdeps/gnu/errlist.h:") and SOURCE.search(e["source"])
        assert re.search(e["pattern"], e["text"])  # the pattern finds its own strerror text
    for p in setup:
        re.compile(p["pattern"])
        kinds = {"version", "parameter", "device", "address", "manifest", "section", "simulation", "file"}
        assert p["kind"] in kinds and p["sources"]
        assert all(SOURCE.search(s) for s in p["sources"])
        if p["kind"] in ("device", "file"):  # their words state their cause (or none), told in the phrase's meaning
            assert (p["cause"] is None or p["cause"] in vocabulary()) and p["meaning"] and p["fix"]
            assert not read_claims(f"It failed because {p['meaning']}.").affirmed - {p["cause"]}
    assert len(phrases()) == len(errnos) + len(setup)
    # a meaning is told in the answer's own words: none of them may read as another cause
    for e in errnos:
        assert not read_claims(f"It failed because {e['meaning']}.").affirmed - {e["cause"]}


def test_permission_denied_on_a_drivers_fatal_line_is_the_devices_permission(tmp_path: Path) -> None:
    # hsr_ros2 hardware interface: no /dev/ path in the line, the strerror text says why
    found = _explain(tmp_path, [
        (0, "controller_manager", FATAL,
         "System cannot communicate with servo motors. Error message: Permission denied")], fails_at=1)
    assert found.causes == ["system.device_permission"]
    assert _claims(found) == {"system.device_permission"}
    assert "“[controller_manager] System cannot communicate with servo motors. Error message: Permission denied” " \
           "at 1.0 s" in found.text  # quoted with its node and its time after the task began
    assert "udev" in (found.fix or "")


def test_an_errno_printed_as_its_number_alone_states_its_cause(tmp_path: Path) -> None:
    # the micro-ROS agent's serial transport (TermiosAgentLinux.cpp) prints errno as a number: 13 is EACCES
    found = _explain(tmp_path, [
        (0, "micro_ros_agent", ERROR, "[1646397373.328044] error    | TermiosAgentLinux.cpp | init"
                                      "                     | open device error      | device: /dev/ttyACM0, "
                                      "errno: 13")], fails_at=1)
    assert found.causes == ["system.device_permission"]
    assert "udev" in (found.fix or "")


def test_an_errno_number_healthy_robots_print_or_of_no_known_errno_states_nothing(tmp_path: Path) -> None:
    # ros2_control_node.cpp:127@master on any machine without realtime rights: EPERM (1) is left out on purpose;
    # and 130 (ECANCELED here) is no errno of the mined table
    for msg in ("Could not enable FIFO RT scheduling policy: with error number <1>(Operation not permitted)",
                "open device error      | device: /dev/ttyACM0, errno: 130"):
        found = _explain(tmp_path / str(len(msg)), [(0, "controller_manager", ERROR, msg)], fails_at=1)
        assert "system.device_permission" not in found.causes
        assert found.causes == ["control.unexplained_failure"]


def test_address_in_use_in_an_exception_is_a_set_up_conflict_not_a_dead_process(tmp_path: Path) -> None:
    # Universal_Robots_Client_Library src/comm/tcp_server.cpp:168: the exception ros2_control_node dies of
    found = _explain(tmp_path, [
        (0, "ros2_control_node-1", INFO, "process started with pid [4242]\nterminate called after throwing an "
                                         "instance of 'std::system_error'\nwhat():  Failed to bind socket for port "
                                         "50003 to address. Reason: Address already in use"),
        (0.2, "ros2_control_node-1", ERROR, "process has died [pid 4242, exit code -6, cmd "
                                            "'/opt/ros/humble/lib/controller_manager/ros2_control_node --ros-args']")],
        fails_at=1)
    assert found.causes == ["control.configuration_error"]
    assert _claims(found) == {"control.configuration_error"}
    assert "another program already holds the network port" in found.text
    assert "“[ros2_control_node-1] Failed to bind socket for port 50003" in found.text


def test_a_library_version_the_robot_does_not_speak_is_a_hardware_interface_that_could_not_work(
        tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "FrankaHardwareInterface", FATAL,
         "libfranka: Incompatible library version (server version: 10, library version: 9). Please check "
         "https://frankaemika.github.io for system updates or choose a libfranka version that uses the server "
         "version 10 from the table at https://frankaemika.github.io/docs/compatibility.html .")], fails_at=1)
    assert found.causes == ["control.hardware_failure"]
    assert _claims(found) == {"control.hardware_failure"}
    assert "the version of my driver's library and the version of the robot's own software do not match" in found.text


def test_a_controllers_empty_joints_parameter_is_its_set_up(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Configuring controller 'velocity_controller'"),
        (0.1, "velocity_controller", ERROR, "'joints' parameter was empty"),
        (0.2, "controller_manager", ERROR,
         "After configuring, controller 'velocity_controller' is in state 'unconfigured' , expected inactive.")],
        fails_at=1, skill="follow_joint_trajectory")
    assert found.causes == ["control.configuration_error"]
    assert _claims(found) == {"control.configuration_error"}
    assert "'joints'" in found.text and "“[velocity_controller] 'joints' parameter was empty” at 1.1 s" in found.text


def test_a_robot_description_moveit_never_found_is_a_parameter_that_never_reached_it(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "hello_moveit", ERROR, "Could not find parameter robot_description and did not receive "
                                   "robot_description via std_msgs::msg::String subscription within 10.000000 "
                                   "seconds.")], fails_at=1, explainer="manipulation", skill="move_arm")
    assert found.causes == ["bringup.configuration_error"]
    assert _claims(found) == {"bringup.configuration_error"}


def test_no_such_file_names_candidates_and_claims_nothing(tmp_path: Path) -> None:
    # Universal_Robots_Client_Library src/rtde/rtde_client.cpp:702: strerror(ENOENT) behind the recipe's path
    found = _explain(tmp_path, [
        (0, "UR_Client_Library", ERROR, "Opening file '/opt/ur/resources/rtde_output_recipe.txt' failed with error: "
                                        "No such file or directory")], fails_at=1)
    assert found.causes == ["control.unexplained_failure"]
    assert _claims(found) == set()
    assert "“[UR_Client_Library] Opening file" in found.text and "at 1.0 s" in found.text
    assert "unplugged" in found.text and "wrong path" in found.text


def test_a_strerror_text_on_an_info_line_or_after_the_failure_is_not_claimed(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "v4l2_camera", INFO, "Cannot open '/dev/video0': 13, Permission denied"),
        (0.5, "controller_manager", ERROR, "Switch controller timed out after 5.000000 seconds!"),
        (2.0, "another_driver", FATAL, "System cannot communicate with servo motors. Error message: Permission "
                                       "denied")], fails_at=1)
    assert found.causes == ["control.controller_activation_failed"]
    assert "system.device_permission" not in _claims(found)


def test_an_undeclared_parameter_the_node_replaces_with_its_default_is_not_the_failure(tmp_path: Path) -> None:
    # gz_ros2_control gz_system.cpp:185: logged at ERROR, then the plugin goes on with its default
    found = _explain(tmp_path, [
        (0, "gz_ros2_control", ERROR, "Parameter 'hold_joints' not declared, with error parameter 'hold_joints' "
                                      "has not been declared"),
        (0.01, "gz_ros2_control", WARN, "Using default value: 1"),
        (0.5, "controller_manager", ERROR, "Switch controller timed out after 5.000000 seconds!")], fails_at=1)
    assert found.causes == ["control.controller_activation_failed"]


def test_a_failure_no_line_explains_names_its_node_time_and_candidates(tmp_path: Path) -> None:
    # an abort that says only that the arm did not follow: its words stay in the details, never in the sentence
    found = _explain(tmp_path, [
        (0, "scaled_joint_trajectory_controller", INFO, "Received new action goal"),
        (1.0, "scaled_joint_trajectory_controller", WARN, "Aborted due to state tolerance violation")],
        fails_at=1.5, skill="follow_joint_trajectory")
    assert found.causes == ["control.unexplained_failure"]
    assert "scaled_joint_trajectory_controller at 2.0 s" in found.text
    assert "It may be a controller's settings" in found.text and _claims(found) == set()


def test_an_exception_that_ended_a_process_is_read_for_its_cause(tmp_path: Path) -> None:
    # pluginlib's LibraryLoadException (class_loader_imp.hpp:541@rolling), printed by terminate behind the process's
    # name under an INFO line: its base class says whose plugin is not installed
    found = _explain(tmp_path, [
        (0, "ros2_control_node-1", INFO, "process started with pid [861]\nterminate called after throwing an "
                                         "instance of 'pluginlib::LibraryLoadException'\nwhat():  According to the "
                                         "loaded plugin descriptions the class ros2_control_demo_hardware/"
                                         "RRBotSystemPositionOnlyHardware with base class type "
                                         "hardware_interface::SystemInterface does not exist.")], fails_at=1)
    assert found.causes == ["control.configuration_error"]
    assert "not among the installed plugin descriptions" in found.text
    assert "hardware interface failed" not in found.text


def test_a_realtime_priority_the_os_refused_is_not_the_failure(tmp_path: Path) -> None:
    # kuka_drivers_core control_node.cpp:101-102@master: logged at ERROR on any machine without realtime rights,
    # and the driver goes on; EPERM is left out of the mined table for this reason
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR, "setscheduler error"),
        (0.01, "controller_manager", ERROR, "Operation not permitted"),
        (0.02, "controller_manager", WARN, "You can use the driver but scheduler priority was not set"),
        (0.5, "controller_manager", FATAL,
         "System cannot communicate with servo motors. Error message: Permission denied")], fails_at=1)
    assert found.causes == ["system.device_permission"]
    assert "1.5 s" in found.text  # the servo line, not the scheduler's


def test_the_original_error_of_a_failed_transition_is_its_why(tmp_path: Path) -> None:
    # rclcpp_lifecycle lifecycle_node_interface_impl.cpp: "Caught exception in callback for transition %d" then
    # "Original error: %s"; rclcpp's text for a statically typed parameter given no value
    found = _explain(tmp_path, [
        (0.0, "move_1", ERROR, "Caught exception in callback for transition 13"),
        (0.01, "move_1", ERROR, "Original error: Statically typed parameter 'waypoints' must be initialized."),
        (0.02, "move_1", WARN, "Error occurred while doing error handling.")], fails_at=1)
    assert found.causes == ["bringup.configuration_error"]
    assert "'waypoints' was empty or missing when move_1 needed it" in found.text
    assert "bringup.lifecycle_transition_failed" not in _claims(found)


def test_a_dynamixel_bus_error_on_a_drivers_error_line_is_its_device_exchange(tmp_path: Path) -> None:
    # DynamixelSDK protocol2_packet_handler.cpp:77 (COMM_PORT_BUSY), as dynamixel_hardware logs it, then its own
    # line; before, the answer was "my control logs do not show a cause I know"
    found = _explain(tmp_path, [
        (0, "ros2_control_node-4", ERROR, "[TxRxResult] Port is in use!"),
        (0.01, "ros2_control_node-4", ERROR, "groupSyncRead getdata failed")], fails_at=1)
    assert found.causes == ["control.hardware_failure"]
    assert _claims(found) == {"control.hardware_failure"}
    assert "“[ros2_control_node-4] [TxRxResult] Port is in use!” at 1.0 s" in found.text
    assert "another transfer was still using the port" in found.text
    # a servo that never answers (COMM_RX_TIMEOUT) has several causes (a baud rate or ID in the settings that is
    # not the servo's, no power, a loose cable): quoted with its candidates, none claimed
    silent = _explain(tmp_path / "silent", [
        (0, "DynamixelHardware", FATAL, "[TxRxResult] There is no status packet!")], fails_at=1)
    assert silent.causes == ["control.unexplained_failure"] and not _claims(silent)
    assert "“[DynamixelHardware] [TxRxResult] There is no status packet!” at 1.0 s" in silent.text
    assert "Its words say that no status packet came back from a Dynamixel servo" in silent.text
    assert "baud rate" in silent.text


def test_a_dynamixel_text_on_a_warning_states_nothing(tmp_path: Path) -> None:
    # a driver that retries logs the SDK's text at WARN and goes on: only an ERROR or FATAL line decides
    found = _explain(tmp_path, [
        (0, "dynamixel_hardware", WARN, "[TxRxResult] There is no status packet!"),
        (0.5, "controller_manager", ERROR, "Could not configure controller with name 'arm_controller'")], fails_at=1)
    assert "control.hardware_failure" not in found.causes


def test_a_parameter_type_exception_that_ended_move_group_is_its_configuration(tmp_path: Path) -> None:
    # rclcpp parameter_value.hpp:66@humble: ParameterTypeException names the two types, not the parameter;
    # move_group terminates with it when a Jazzy pipeline's planning_plugins is given as a string
    found = _explain(tmp_path, [
        (0, "move_group-1", INFO, "terminate called after throwing an instance of 'rclcpp::ParameterTypeException'"
                                  "\nwhat():  expected [string_array] got [string]")],
        fails_at=1, explainer="manipulation", skill="move_arm")
    assert found.causes == ["manipulation.configuration_error"]
    assert _claims(found) == {"manipulation.configuration_error"}
    assert "one of its parameters has a value of the wrong type (string_array expected, string given)" in found.text
    assert "“[move_group-1] expected [string_array] got [string]” at 1.0 s" in found.text
    assert "square brackets" in (found.fix or "")


# SICKAG/sick_scan_xd#287 (heldout4, spent): an empty udp_receiver_ip (sick_scan_services.cpp:546@2d4796699158);
# ros-drivers/ros2_ouster_drivers#38 (heldout5, spent): no lidar_ip parameter (ouster_driver.cpp:86@c0f5a174b846)
SICK = [(0.0, "sick_scan_xd", ERROR, "## ERROR SickScanServices::sendMultiScanStartCmd() failed: can't split ip "
         "address \"\" into 4 tokens, check ip address"),
        (0.0, "sick_scan_xd", ERROR, "## ERROR parsing ip address, check configuration of parameter \"hostname\" "
         "(launch file or commandline).")]
OUSTER = [(0.0, "OusterDriver", INFO, "Configuring Ouster driver node."),
          (0.1, "OusterDriver", FATAL, "Failed to get lidar or IMU IP address or hostname. An IP address for both are "
           "required!")]


@pytest.mark.parametrize("lines", [SICK, OUSTER], ids=["sick_empty_ip", "ouster_no_ip"])
def test_a_driver_that_was_given_no_address_is_a_parameter_that_never_reached_it(tmp_path: Path,
                                                                                   lines: list[Any]) -> None:
    found = _explain(tmp_path, lines, 0.5)
    assert found.causes == ["bringup.configuration_error"] and _claims(found) == {"bringup.configuration_error"}
    assert "had no IP address or host name to connect with" in found.text


def test_an_address_the_driver_was_given_is_no_missing_one(tmp_path: Path) -> None:
    # the same words with the address in them: it reached the driver (which then found it wrong)
    given = [(0.0, "sick_scan_xd", ERROR, "## ERROR SickScanServices::sendMultiScanStartCmd() failed: can't split ip "
              "address \"192.168.0\" into 4 tokens, check ip address")]
    found = _explain(tmp_path, given, 0.5)
    assert "had no IP address" not in found.text


def _real_module(tmp_path: Path, suite: str, ident: str) -> Explanation:
    from hexar.evals.real_modules import QUESTIONS, load_excerpts, write_recording
    from hexar.events import read_recording

    excerpt = next(e for e in load_excerpts(suite) if e.id == ident)
    return explain(read_recording(write_recording(excerpt, tmp_path / "run", task=False)), "control",
                   QUESTIONS["failed"])[1]


def test_a_line_whose_words_say_what_is_missing_is_not_told_as_no_cause_known(tmp_path: Path) -> None:
    # held-out set 29: "cannot open serial port: [Errno 2] No such file or directory: '/dev/ttyACM0'"
    found = _real_module(tmp_path, "real-modules-heldout29", "kilted-lifecycle-configure-serial-port-missing")
    assert found.text.startswith("Starting my drivers and controllers failed, and I can't tell why for sure. The first "
                                 "error was “[base_driver] "
                                 "cannot open serial port: [Errno 2] No such file or directory: '/dev/ttyACM0'”")
    assert "do not show a cause I know" not in found.text and "is not there" in found.text
    assert _claims(found) == set()


def test_a_first_line_that_only_tags_its_function_is_quoted_with_the_next(tmp_path: Path) -> None:
    # held-out set 3, livox_ros_driver2 issue 117: "LdsLidar *GetInstance\nparse summary info failed, can not open
    # file: path_default", the driver's config path left at its default
    found = _real_module(tmp_path, "real-modules-heldout3", "livox-ros-driver2-117-config-not-given")
    assert "“[unnamed node] LdsLidar *GetInstance parse summary info failed, can not open file: path_default”" in \
        found.text
    # the words read as a file it could not open (kind `file`), not as the port, cable or power of a device
    assert "Its words say that a file it was to read could not be opened" in found.text
    assert "baud" not in found.text and "cable" not in found.text and _claims(found) == set()
