"""The answer about a start derived from the logs (no /task_info, no goal): a start that completed is told as one
with nothing failed, its warnings as ones that only look like failures; a start that did not complete is never told
as a success or a failure; a failed one quotes its first error."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import ALL_FINE, TASK_FAILED, read_claims
from hexar.events.records import ERROR, FATAL, INFO, WARN
from hexar.explainers.base import Explanation
from hexar.explainers.bringup_answer import presumes_failure
from tests.explainers.helpers import explain, write_lines

# ros2_control's own lines: hardware_interface/src/resource_manager.cpp:88,120@humble,
# controller_manager/controller_manager/spawner.py:273@humble, controller_manager/src/controller_manager.cpp:3401@jazzy
LOADING = (0.0, "resource_manager", INFO, "Loading hardware 'RRBot'")
DONE = [(0.2, "resource_manager", INFO, "Successful initialization of hardware 'RRBot'"),
        (1.0, "spawner_joint_state_broadcaster", INFO, "Configured and activated joint_state_broadcaster")]
NO_CLOCK = (0.1, "controller_manager", WARN, "No clock received, using time argument instead! Check your node's "
            "clock configuration (use_sim_time parameter) and if a valid clock source is available")


# the controller manager's deprecation warning as a real console printed it (a spent module set's excerpt)
WARNED = (0.1, "controller_manager", WARN, "[Deprecated] Passing the robot description parameter directly to the "
          "control_manager node is deprecated. Use '~/robot_description' topic from 'robot_state_publisher' instead.")


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]], question: str) -> Explanation:
    task, found = explain(write_lines(tmp_path, lines), "control", question)
    assert task.derived and task.skills[0].skill == "bring_up_controllers"
    return found


def test_a_completed_start_says_nothing_failed_and_names_its_warning_as_only_looking_like_one(tmp_path: Path) -> None:
    found = _explain(tmp_path, [LOADING, NO_CLOCK, *DONE], "How did it go?")
    claims = read_claims(found.text).affirmed
    assert found.causes == ["control.nominal"] and "control.nominal" in claims
    assert ALL_FINE in claims and TASK_FAILED not in claims
    assert "Configured and activated joint_state_broadcaster" in found.text
    assert "No clock received" in found.text and "only looks like a failure" in found.text


def test_a_start_not_seen_complete_asked_why_it_failed_says_no_line_tells_why(tmp_path: Path) -> None:
    found = _explain(tmp_path, [LOADING, WARNED], "Why didn't that work?")
    claims = read_claims(found.text).affirmed
    assert found.causes == [] and not claims & {ALL_FINE, TASK_FAILED, "control.nominal"}
    assert found.text.startswith("My logs do not show why") and "Deprecated" in found.text


def test_a_start_that_never_had_its_clock_asked_why_it_failed_names_the_missing_clock(tmp_path: Path) -> None:
    # automaticaddison/yahboom_rosmaster#5 and xArm-Developer/xarm_ros2#114 (spent sets): Gazebo's clock was never
    # bridged to ROS, and the controller manager's no-clock warning was all the start printed
    found = _explain(tmp_path, [LOADING, NO_CLOCK], "Why didn't that work?")
    assert found.causes == ["bringup.configuration_error"]
    assert "never received a clock" in found.text and "No clock received" in found.text
    assert read_claims(found.text).affirmed - {TASK_FAILED} == {"bringup.configuration_error"}
    # the clock came after all: a controller came up after the warning
    found = _explain(tmp_path / "later", [LOADING, NO_CLOCK, *DONE], "Why didn't that work?")
    assert "never received a clock" not in found.text


def test_a_start_not_seen_complete_with_no_error_asked_how_it_went_says_nothing_went_wrong(tmp_path: Path) -> None:
    found = _explain(tmp_path, [LOADING, NO_CLOCK], "How did it go?")
    claims = read_claims(found.text).affirmed
    assert found.causes == ["control.nominal"] and {"control.nominal", ALL_FINE} <= claims
    assert TASK_FAILED not in claims
    # never told as a start that completed: the recording does not show that
    assert "ends before any line says the start completed" in found.text and "came up" not in found.text
    assert "“[resource_manager] Loading hardware 'RRBot'” at 0.0 s" in found.text
    assert "No clock received" in found.text and "only looks like a failure" not in found.text


def test_moveit_starting_alone_is_the_arms_motion_software_and_a_repeated_warning_is_quoted_once(
        tmp_path: Path) -> None:
    # moveit_servo's status text for HALT_FOR_SINGULARITY (moveit_ros/moveit_servo/include/moveit_servo/utils/
    # datatypes.hpp:68@main), said at every check while the arm stays there
    halt = "Very close to a singularity, emergency stop"
    found = _explain(tmp_path, [(0.0, "moveit_servo.utilities", WARN, halt),
                                (3.0, "moveit_servo.utilities", WARN, halt)], "How did it go?")
    claims = read_claims(found.text).affirmed
    assert found.causes == ["manipulation.nominal"] and "manipulation.nominal" in claims
    assert "control.nominal" not in claims and "my arm's motion software (MoveIt)" in found.text
    assert found.text.count(halt) == 1


@pytest.mark.parametrize(("question", "failed"), [
    ("Why didn't that work?", True), ("what went wrong", True), ("why did the arm stop?", True),
    ("Why does it fail to start?", True), ("How did it go?", False), ("What happened?", False),
    ("Did the controllers come up?", False)])
def test_which_questions_say_the_start_did_not_work(question: str, failed: bool) -> None:
    assert presumes_failure(question) is failed


def test_a_failed_start_quotes_its_first_error_and_never_says_it_went_fine(tmp_path: Path) -> None:
    driver = "ydlidar_ros2_driver_node"  # ydlidar_ros2_driver's own lines (a console of ydlidar_ros2#4)
    found = _explain(tmp_path, [(0.0, driver, INFO, "[YDLIDAR INFO] Current ROS Driver Version: 1.0.1"),
                                (2.6, driver, ERROR, "Unknown error")], "Why didn't that work?")
    assert found.text.startswith("Starting my drivers and controllers failed")
    assert "Unknown error" in found.text and ALL_FINE not in read_claims(found.text).affirmed


def _lone(tmp_path: Path, lines: list[tuple[float, str, int, str]], question: str = "Why didn't that work?"
          ) -> tuple[Explanation, set[str]]:
    """A recording of only these lines (no task, no goal), answered by control; its affirmed causes."""
    task, found = explain(write_lines(tmp_path, lines), "control", question)
    assert task.derived
    return found, set(read_claims(found.text).affirmed)


def test_a_drivers_lone_error_is_quoted_with_node_and_time_and_the_drivers_candidates(tmp_path: Path) -> None:
    # sllidar_ros2 src/sllidar_node.cpp:287@main: no line before it, no cause in its words
    found, claims = _lone(tmp_path, [(2.0, "sllidar_node", ERROR,
                                      "Error, cannot bind to the specified serial port /dev/ttyUSB0.")])
    assert found.text.startswith("Starting my drivers and controllers failed")
    assert ("“[sllidar_node] Error, cannot bind to the specified serial port /dev/ttyUSB0.” at 0.0 s"
            in found.text)
    assert "the port, address or baud rate it was given" in found.text and "a controller's settings" not in found.text
    assert found.causes == ["control.unexplained_failure"] and not {c for c in claims if not c.startswith("claim.")}
    assert ALL_FINE not in claims


def test_a_hardware_interfaces_lone_error_that_states_its_cause_names_it(tmp_path: Path) -> None:
    # libfranka src/exception.cpp:21 (IncompatibleVersionException), logged by franka_hardware under
    # "FrankaHardwareInterface" (franka_hardware_interface.cpp:405@humble)
    found, claims = _explain_lone_franka(tmp_path)
    assert found.causes == ["control.hardware_failure"] and "control.hardware_failure" in claims
    assert "“[FrankaHardwareInterface] libfranka: Incompatible library version" in found.text


def _explain_lone_franka(tmp_path: Path) -> tuple[Explanation, set[str]]:
    return _lone(tmp_path, [(0.0, "FrankaHardwareInterface", FATAL,
                             "libfranka: Incompatible library version (server version: 10, library version: 9). "
                             "Please check https://frankaemika.github.io for system updates or choose a libfranka "
                             "version that uses the server version 10 from the table at "
                             "https://frankaemika.github.io/docs/compatibility.html .")])


def test_a_lone_error_naming_a_parameter_names_that_parameters_candidates(tmp_path: Path) -> None:
    # robot_localization src/ros_robot_localization_listener.cpp:90-92@ros2
    found, claims = _lone(tmp_path, [(0.0, "robot_localization_listener_node", ERROR,
                                      "RosRobotLocalizationListener: Parameter filter_type invalid")])
    assert "“[robot_localization_listener_node] RosRobotLocalizationListener: Parameter filter_type invalid”" \
        in found.text
    assert "the value of the parameter it names" in found.text
    assert not {c for c in claims if not c.startswith("claim.")}


def test_a_controller_dropping_commands_is_told_as_not_active_claiming_no_cause_nor_outcome(tmp_path: Path) -> None:
    # diff_drive_controller/src/diff_drive_controller.cpp:466@jazzy
    line = (0.0, "diff_drive_controller", WARN, "Can't accept new commands. subscriber is inactive")
    for question in ("Why didn't that work?", "How did it go?"):
        found, claims = _lone(tmp_path / question[:3], [line], question)
        assert found.causes == ["control.unexplained_failure"] and claims == set()
        assert "“[diff_drive_controller] Can't accept new commands. subscriber is inactive” at 0.0 s" in found.text
        assert "it was not active when they came" in found.text
        assert "my logs do not show why it was not active" in found.text
        assert "list_controllers" in (found.fix or "")


def test_a_drivers_error_after_its_own_start_names_the_drivers_candidates_not_a_controllers(tmp_path: Path) -> None:
    driver = "ydlidar_ros2_driver_node"  # ydlidar_ros2_driver's own lines (a console of ydlidar_ros2#4)
    found, _ = _lone(tmp_path, [(0.0, driver, INFO, "[YDLIDAR INFO] Current ROS Driver Version: 1.0.1"),
                                (2.6, driver, ERROR, "Unknown error")])
    assert "the port, address or baud rate it was given" in found.text and "a controller's settings" not in found.text


def test_a_node_that_told_its_devices_firmware_is_a_driver_whose_error_fails_the_start(tmp_path: Path) -> None:
    # whatibroke.com's "Lidar Failing to Start" (spent held-out 20): rplidar_node, no "driver" in its name, named
    # its device's serial number and firmware before its error (the battery powering it had run flat)
    node = "rplidar_node"
    found, _ = _lone(tmp_path, [(0.0, node, INFO, "RPLIDAR S/N: CD8EED93C0EA98C7A0E69BF55D504560"),
                                (0.1, node, INFO, "Firmware Ver: 1.29"),
                                (2.6, node, ERROR, "Cannot start scan: '80008000'")])
    assert "“[rplidar_node] Cannot start scan: '80008000'”" in found.text
    assert "its cable, its power" in found.text and not read_claims(found.text).affirmed - {TASK_FAILED}


def test_asked_why_it_did_not_work_the_agent_tells_the_dropped_commands_not_the_plan(tmp_path: Path) -> None:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    # diff_drive_controller/src/diff_drive_controller.cpp:466@jazzy, the recording's only line
    log = write_lines(tmp_path, [(0.0, "diff_drive_controller", WARN,
                                  "Can't accept new commands. subscriber is inactive")])
    result = Session(RunSettings(recording=log.path, llm="none", phrase=False)).ask("Why didn't that work?")
    assert result["explainers"][:1] == ["control"] and "planner.plan_ok" not in result["causes"]
    assert "it was not active when they came" in result["answer"]


# controller_manager.cpp@jazzy: :759 as it starts, :770 once a second until a description arrives and loads
SUBSCRIBED = (0.0, "controller_manager", INFO, "Subscribing to '/robot_description' topic for robot description.")
WAITING = [(s, "controller_manager", WARN, "Waiting for data on 'robot_description' topic to finish initialization")
           for s in (1.0, 2.0)]


def test_a_start_whose_manager_subscribed_and_only_waited_never_got_its_description(tmp_path: Path) -> None:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    log = write_lines(tmp_path, [SUBSCRIBED, *WAITING])
    result = Session(RunSettings(recording=log.path, llm="none", phrase=False)).ask("Why didn't that work?")
    assert result["explainers"][:1] == ["control"] and result["causes"] == ["bringup.configuration_error"]
    assert "my robot description never reached my controller manager" in result["answer"]
    assert not {ALL_FINE, TASK_FAILED} & read_claims(result["answer"]).affirmed


def test_a_start_with_the_waiting_warning_alone_tells_both_readings_and_claims_no_cause(tmp_path: Path) -> None:
    found, claims = _lone(tmp_path, WAITING)
    assert found.causes == ["control.unexplained_failure"] and claims == set()
    assert "Either no description arrived" in found.text and "hardware that did not load" in found.text


def test_a_start_stopped_by_ctrl_c_is_no_failure_and_its_traceback_is_named(tmp_path: Path) -> None:
    """A real console: launch got Ctrl-C a moment after the start, and a Python node printed its KeyboardInterrupt
    traceback and died with exit code -2 on the way down. Nothing failed; asked what to change, the answer is how a
    Python node ends quietly."""
    from hexar.agent.context import RunSettings
    from hexar.agent.oneshot import OneShot
    from tests.agent.helpers import real_module_run

    run = real_module_run("kilted-bringup-ctrl-c-traceback", tmp_path / "run")
    ask = OneShot(RunSettings(recording=run, llm="none")).ask
    happened = ask("What happened?")
    text = str(happened["answer"])
    assert text.startswith("Starting my drivers and controllers went fine: my controllers were starting "
                           "without any problem when it was stopped from outside "
                           "(“[launch] user interrupted with ctrl-c (SIGINT)”")
    assert "odom_relay-2 printed on the way down is Python's KeyboardInterrupt" in text
    assert "failed because" not in text and happened["causes"] == ["control.nominal"]
    fix = str(ask("What should I change in odom_relay so it shuts down without a traceback?")["answer"])
    assert "`except (KeyboardInterrupt, ExternalShutdownException)` around `rclpy.spin(node)`" in fix


def test_an_error_before_ctrl_c_still_fails_the_start(tmp_path: Path) -> None:
    """Ctrl-C after the start had already failed ends nothing that was going well: the failure is told."""
    failed = (0.2, "resource_manager", ERROR, "Failed to initialize hardware 'RRBot'")
    stop = (0.5, "launch", WARN, "user interrupted with ctrl-c (SIGINT)")
    task, found = explain(write_lines(tmp_path, [LOADING, failed, stop]), "control", "What happened?")
    assert task.outcome == "failed" and "control.nominal" not in found.causes
    assert "stopped from outside" not in found.text


def test_a_hardware_that_came_up_is_not_told_as_controllers(tmp_path: Path) -> None:
    """A KUKA RSI driver's real console: the hardware activated, and no controller line follows."""
    from tests.agent.helpers import converse, real_module_run

    run = real_module_run("kuka-drivers-344-iiqka-rsi-stale-project-files", tmp_path / "run")
    (loaded,) = converse(run, "were any controllers loaded after the hardware came up?")
    text = str(loaded["answer"])
    assert "my hardware came up without any problem" in text and "my controllers came up" not in text
    assert text.endswith("My log names no controller being loaded or started.")


def test_a_process_that_aborted_on_its_only_line_failed_the_start(tmp_path: Path) -> None:
    """move_group's console holds only libstdc++'s "what():" and a backward-cpp stack trace (at INFO, as a console
    gives it): its start failed there, on the parameter of the wrong type the exception names."""
    from tests.agent.helpers import converse, real_module_run

    run = real_module_run("moveit2-pr2865-cached-ik-integer-parameter", tmp_path / "run")
    happened, crashed = converse(run, "What happened?", "did move_group crash or just log a warning?")
    assert "parameter 'robot_description_kinematics.robot.min_joint_config_distance' has a value of the wrong " \
           "type" in str(happened["answer"])
    assert "no line reports an error" not in str(happened["answer"])
    assert str(crashed["answer"]).endswith("holds \"what():\": its process aborted there.")


def test_a_hardware_plugin_that_pluginlib_cannot_load_is_the_arms_not_navigations(tmp_path: Path) -> None:
    """ros2_control_node's "terminate called … pluginlib::LibraryLoadException … with base class type
    hardware_interface::SystemInterface does not exist": the start failed, and no navigation goal is made of it."""
    from hexar.events import read_recording
    from tests.agent.helpers import real_module_run

    run = real_module_run("r2c-demos-62-hardware-package-missing", tmp_path / "run")
    task, found = explain(read_recording(run), "control", "What happened?")
    assert task.task_id.startswith("bringup-goal") and task.outcome == "failed"
    assert "the hardware plugin named in the ros2_control tag of the URDF is not among the installed plugin " \
           "descriptions" in found.text and "navigation" not in found.text
