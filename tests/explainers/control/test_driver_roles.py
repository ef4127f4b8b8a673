"""Drivers' own errors read by where they are logged (explainers/control/driver_roles.py): the mined catalogue
places real driver strings in their hardware_interface callbacks, and the control explainer answers recordings of
those lines with what the place supports, and no more. Each line's format is the driver's (cited); the values in
it are ones a robot would print."""

from __future__ import annotations

import json
import re
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from hexar.causes import vocabulary
from hexar.claims import read_claims
from hexar.events.records import ERROR, FATAL, INFO, WARN, LogLine
from hexar.explainers.base import Explanation
from hexar.explainers.control.catalogue import catalogue
from hexar.explainers.control.driver_roles import role_of
from hexar.explainers.logcause import read
from tests.explainers.helpers import explain, write_lines

GOAL = (0.0, "joint_trajectory_controller", INFO, "Received new action goal")
# Kinova's kortex_driver/src/hardware_interface.cpp:215@main logs "Kortex exception: " << ex.what(); the Kortex
# API's text of a device error as Kinovarobotics/ros_kortex#341 shows it
KORTEX = "Kortex exception: Device error, Error sub type=ROBOT_IN_FAULT => <srv: 2, fct: 48, msgType: 3>"


def _raw() -> dict[str, Any]:
    text = resources.files("hexar.explainers.control").joinpath("ros2_control_catalogue.json").read_text("utf-8")
    return dict(json.loads(text))


def _row(text: str) -> dict[str, Any]:
    return next(m for m in _raw()["messages"] if m["text"] == text)


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]]) -> Explanation:
    return explain(write_lines(tmp_path, lines), "control", "Why didn't the arm move?")[1]


def test_the_mined_roles_load_compile_and_name_known_causes() -> None:
    raw = _raw()
    known = vocabulary()
    assert {r["cause"] for r in raw["hardware_roles"].values()} - {None} <= set(known)
    placed = [m for m in raw["messages"] if "functions" in m]
    assert len({m["source"].split("/")[0] for m in placed}) >= 8  # UR, Kinova, KUKA (two), Franka, Robotiq, ...
    for m in placed:
        assert m["functions"] and (m["hw_role"] is None or m["hw_role"] in raw["hardware_roles"])
        re.compile(m["pattern"])
        assert re.match(r"[\w/.+-]+:\d+@[\w.]+", m["source"])


@pytest.mark.parametrize(("text", "functions", "source"), [
    ("Robot ip is empty!", ["on_init"], "ros2_kortex/kortex_driver/src/hardware_interface.cpp:101@main"),
    ("Kortex exception:", ["on_init", "write"], "ros2_kortex/kortex_driver/src/hardware_interface.cpp:215@main"),
    ("Can't start joint based controller while twist controller is running!", ["prepare_command_mode_switch"],
     "ros2_kortex/kortex_driver/src/hardware_interface.cpp:574@main"),
    ("Could not send command to controller", ["write"],
     "kuka_drivers/kuka_sunrise_fri_driver/src/hardware_interface.cpp:321@humble"),
    ("Could not initialize TCP connection to controller", ["on_configure"],
     "kuka_drivers/kuka_sunrise_fri_driver/src/hardware_interface.cpp:102@humble"),
    ("Cannot connect to the Robotiq gripper", ["on_configure"],
     "ros2_robotiq_gripper/robotiq_driver/src/hardware_interface.cpp:161@humble"),
    ("Could not connect to robot", ["on_init"],
     "franka_ros2/franka_hardware/src/franka_hardware_interface.cpp:387@humble"),
    ("Unable to read from hardware...", ["read"],
     "Universal_Robots_ROS2_Driver/ur_robot_driver/src/hardware_interface.cpp:969@humble"),
    ("MuJoCo model file '…' does not exist!", ["on_init"],
     "mujoco_ros2_control/mujoco_ros2_control/src/mujoco_system_interface.cpp:305@main"),
])
def test_real_driver_strings_are_placed_in_the_callbacks_that_log_them(text: str, functions: list[str],
                                                                       source: str) -> None:
    row = _row(text)
    assert row["functions"] == functions
    assert row["source"].startswith(source)


def test_a_drivers_error_with_a_rule_of_its_own_keeps_the_rules_cause() -> None:
    # kortex_driver/src/hardware_interface.cpp:101@main, a curated rule of scripts/modules_mining.yaml
    line = read([LogLine(0, ERROR, "KortexMultiInterfaceHardware", "Robot ip is empty!")], [catalogue()])[0]
    assert line.cause == "bringup.configuration_error" and role_of(line) is None
    warning = read([LogLine(0, WARN, "URPositionHardwareInterface", "Unable to read from hardware...")],
                   [catalogue()])[0]
    assert role_of(warning) is None  # only an ERROR or FATAL is read by its place


def test_a_read_error_is_the_hardware_failing_to_exchange_with_its_device(tmp_path: Path) -> None:
    # ur_robot_driver/src/hardware_interface.cpp:1086@main, inside read()
    found = _explain(tmp_path, [GOAL, (1.0, "URPositionHardwareInterface", ERROR, "Unable to read from hardware...")])
    assert found.causes == ["control.hardware_failure"]
    assert "hardware interface failed" in found.text and "read()" in found.text
    assert "not why" in found.text and "error report" in (found.fix or "")
    assert read_claims(found.text).affirmed == {"control.hardware_failure"}


def test_a_write_error_of_kukas_fri_driver_is_a_hardware_failure(tmp_path: Path) -> None:
    # kuka_sunrise_fri_driver/src/hardware_interface.cpp:368@master, inside write()
    found = _explain(tmp_path, [GOAL, (1.0, "KukaFRIHardwareInterface", ERROR, "Could not send command to controller")])
    assert found.causes == ["control.hardware_failure"] and "write()" in found.text


def test_a_joint_interface_error_in_on_init_is_a_set_up_that_does_not_fit(tmp_path: Path) -> None:
    # robotiq_driver/src/hardware_interface.cpp:104@main, inside on_init
    found = _explain(tmp_path, [GOAL, (1.0, "RobotiqGripperHardwareInterface", FATAL,
                                       "Joint 'robotiq_85_left_knuckle_joint' has 2 command interfaces found. "
                                       "1 expected.")])
    assert found.causes == ["control.configuration_error"]
    assert "set up wrongly" in found.text and "on_init()" in found.text
    assert read_claims(found.text).affirmed == {"control.configuration_error"}


def test_a_parameter_not_set_in_on_init_never_reached_the_driver(tmp_path: Path) -> None:
    # franka_hardware/src/franka_hardware_interface.cpp:365@jazzy, inside on_init ("Parameter '%s' is not set.
    # Please update your URDF (aka franka_description).", kRobotIpName)
    found = _explain(tmp_path, [GOAL, (1.0, "franka_hardware", FATAL,
                                       "Parameter 'robot_ip' is not set. Please update your URDF (aka "
                                       "franka_description).")])
    assert found.causes == ["bringup.configuration_error"] and "never reached my driver" in found.text
    # and no words of another cause ("robot description was missing" is MoveIt's set-up in hexar/causes.yaml)
    assert read_claims(found.text).affirmed == {"bringup.configuration_error"}


def test_a_refused_switch_is_a_controller_that_could_not_be_activated(tmp_path: Path) -> None:
    # kortex_driver/src/hardware_interface.cpp:574@main, inside prepare_command_mode_switch
    found = _explain(tmp_path, [GOAL, (1.0, "KortexMultiInterfaceHardware", ERROR,
                                       "Can't start joint based controller while twist controller is running!")])
    assert found.causes == ["control.controller_activation_failed"]
    assert "could not be activated" in found.text and "prepare_command_mode_switch()" in found.text


def test_an_on_init_error_without_parameter_words_is_told_with_its_place_and_no_cause(tmp_path: Path) -> None:
    # franka_hardware/src/franka_hardware_interface.cpp:401@jazzy, inside on_init: a device out of reach or an
    # address that is wrong read the same
    found = _explain(tmp_path, [GOAL, (1.0, "franka_hardware", FATAL, "Could not connect to robot")])
    assert found.causes == ["control.unexplained_failure"]
    assert "on_init()" in found.text and "do not show a cause I know" in found.text
    assert read_claims(found.text).affirmed <= {"control.unexplained_failure"}


def test_a_kortex_exception_is_the_devices_once_the_controllers_run_and_the_starts_before(tmp_path: Path) -> None:
    running = _explain(tmp_path / "a", [GOAL, (1.0, "KortexMultiInterfaceHardware", ERROR, KORTEX)])
    assert running.causes == ["control.hardware_failure"] and "not why" in running.text
    at_start = _explain(tmp_path / "b", [(0.0, "KortexMultiInterfaceHardware", ERROR, KORTEX)])
    assert at_start.causes == ["control.unexplained_failure"] and "on_init()" in at_start.text
    assert "hardware interface failed" not in at_start.text


def test_a_rule_decides_before_a_drivers_role(tmp_path: Path) -> None:
    found = _explain(tmp_path, [GOAL, (1.0, "KortexMultiInterfaceHardware", ERROR, KORTEX),
                                (1.5, "controller_manager", ERROR,
                                 "Loader for controller 'joint_state_broadcaster' not found.")])
    assert found.causes == ["control.controller_load_failed"]


def test_a_goal_that_succeeded_after_a_drivers_error_claims_no_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [GOAL, (1.0, "URPositionHardwareInterface", ERROR, "Unable to read from hardware..."),
                                (2.0, "joint_trajectory_controller", INFO, "Goal reached, success!")])
    assert found.causes == ["control.nominal"]
