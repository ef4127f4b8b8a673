"""Whole consoles of the real ros2_control (its kilted branch, built here) that scripts/control_faults.py and
scripts/base_faults.py ran with one fault each (held-out sets 30 to 33, spent), written as recordings with rosbags,
with and without a /task_info task: ros2_control 5.x's fmt-built activation line and a parameter rclcpp could not
type are read with their causes; the controller manager killed by SIGKILL is told as the death it was; spawners that
asked for another controller manager are told with both names; a spawner given a parameters file that is not there
(set 31) is that file, not a death; spawners that gave up before the description came (set 33) are told with its
delay; a mobile base's commands stamped by another clock (set 32) are use_sim_time not set alike, a controller that
did not accept its parameters at init is set up wrongly, and asked why it failed, a start that went fine is not told
as nothing wrong; the stack stopped with Ctrl-C is no warning of the motion, and a node's output its pipe held back
past launch's Ctrl-C line is still read."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.real_modules import QUESTIONS, load_excerpts, write_recording
from hexar.events import read_recording
from tests.explainers.helpers import ask_run, explain


def _ask(tmp_path: Path, ident: str, task: bool, suite: str = "real-modules-heldout30"
         ) -> tuple[list[str], str, str]:
    found = ask_run(tmp_path, suite, ident, task)
    return found.causes, found.text, " ".join(e.item for e in found.evidence)


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_trajectory_followed_before_ctrl_c_quotes_no_shutdown_line(tmp_path: Path, task: bool) -> None:
    causes, text, _ = _ask(tmp_path, "control-nominal", task)
    assert causes == ["control.nominal"] and "ctrl-c" not in text.lower() and "did not stop it" not in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_kilteds_unable_to_activate_line_is_an_activation_failure(tmp_path: Path, task: bool) -> None:
    # "Unable to activate controller 'arm_controller' since the command interface 'wrist_joint/position' is not
    # available." (fmt::format in controller_manager.cpp@kilted, logged through "%s")
    causes, text, evidence = _ask(tmp_path, "jtc-unknown-joint", task)
    assert causes == ["control.controller_activation_failed"]
    # a trajectory goal derived from the log opens its window after the spawner's activation: the controller
    # manager's reason is read from before it, and the refused goal ends there, not with the recording
    assert "since the command interface 'wrist_joint/position' is not available" in evidence
    assert "recording ends" not in text


def test_a_parameter_rclcpp_could_not_type_is_a_configuration_error(tmp_path: Path) -> None:
    # joints: [] -> "Caught exception of type : ...InvalidParameterValueExceptionE while initializing controller
    # 'arm_controller': No parameter value set" (rclcpp parameter_map.cpp)
    causes, _, evidence = _ask(tmp_path, "jtc-no-joints", True)
    assert causes == ["control.configuration_error"] and "No parameter value set" in evidence


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_the_controller_manager_killed_mid_trajectory_is_the_death(tmp_path: Path, task: bool) -> None:
    causes, text, _ = _ask(tmp_path, "manager-killed", task)
    assert causes == ["bringup.process_died"]
    assert "ros2_control_node was killed" in text and "SIGKILL" in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_spawners_that_asked_for_another_controller_manager_are_told_with_both_names(
        tmp_path: Path, task: bool) -> None:
    causes, text, evidence = _ask(tmp_path, "spawner-wrong-manager", task)
    assert causes == ["bringup.configuration_error"]
    assert "/arm/controller_manager" in text and "ran as /controller_manager" in text
    assert "bringup.configuration_error" in read_claims(text).affirmed
    assert "Could not contact service /arm/controller_manager/list_controllers" in evidence


def test_a_tolerance_abort_the_pipe_printed_after_launchs_ctrl_c_line_is_still_read(tmp_path: Path) -> None:
    # the hardware ignored commands and flooded its console with warnings, so ros2_control_node's pipe flushed the
    # tolerance abort (stamped 3 s after the goal) after launch's unstamped "user interrupted with ctrl-c (SIGINT)"
    excerpt = next(e for e in load_excerpts("real-modules-heldout30")
                   if e.id == "kilted-control-hardware-ignores-commands")
    assert excerpt.lines.index("user interrupted with ctrl-c") < excerpt.lines.index("Aborted due to goal_time")
    causes, _, _ = _ask(tmp_path, "hardware-ignores-commands", False)
    assert causes == ["control.tolerance_violated"]


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_spawner_given_a_parameters_file_that_is_not_there_is_that_file_not_a_death(
        tmp_path: Path, task: bool) -> None:
    # spawner --param-file config/arm_controllers.yaml: "FileNotFoundError: [Errno 2] No such file or directory:
    # 'config/arm_controllers.yaml'" from the spawner's own code, and launch's "process has died [... exit code 1"
    causes, text, evidence = _ask(tmp_path, "spawner-param-file-missing", task, "real-modules-heldout31")
    assert causes == ["bringup.configuration_error"]
    assert read_claims(text).affirmed == {"bringup.configuration_error"}
    assert "'config/arm_controllers.yaml'" in text and "No such file or directory" in evidence


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_base_commands_stamped_by_another_clock_are_use_sim_time_not_the_same_everywhere(
        tmp_path: Path, task: bool) -> None:
    # set 32: a teleop on use_sim_time while an old recording's /clock played; diff_drive_controller: "Ignoring the
    # received message (timestamp 1717236004.70...) because it is older than the current time by 78786503.02...
    # seconds, which exceeds the allowed timeout (0.5000)"; and nothing else was wrong
    causes, text, evidence = _ask(tmp_path, "base-sim-time-teleop", task, "real-modules-heldout32")
    assert causes == ["bringup.configuration_error"]
    assert read_claims(text).affirmed == {"bringup.configuration_error"}
    assert "use_sim_time" in text and "older than the current time by 78786503" in evidence


def test_base_commands_a_moment_late_are_no_clock_of_another_kind(tmp_path: Path) -> None:
    # the same console with each command 0.6 s old, as a message late on a network or a clock a little off would
    # be: nothing tells which, so no bringup cause is claimed from it
    excerpt = next(e for e in load_excerpts("real-modules-heldout32") if e.id == "kilted-control-base-sim-time-teleop")
    lines = re.sub(r"older than the current time by 787865\d\d\.\d+ seconds",
                   "older than the current time by 0.6000000000 seconds", excerpt.lines)
    assert lines != excerpt.lines
    log = read_recording(write_recording(dataclasses.replace(excerpt, lines=lines), tmp_path / "run", task=True))
    _, found = explain(log, "control", QUESTIONS["failed"])
    assert "bringup.configuration_error" not in found.causes
    assert "bringup.configuration_error" not in read_claims(found.text).affirmed


def test_a_controller_that_did_not_accept_its_parameters_as_it_started_is_set_up_wrongly(tmp_path: Path) -> None:
    # set 32: no wheel_radius, so diff_drive_controller's on_init printed to stderr "Exception thrown during init
    # stage with message: parameter 'wheel_radius' could not be set: Parameter {wheel_radius} doesn't comply with
    # floating point range."; after it only "Calling shutdown transition ... due to init failure."
    causes, text, evidence = _ask(tmp_path, "base-radius-missing", True, "real-modules-heldout32")
    assert causes == ["control.configuration_error"]
    assert read_claims(text).affirmed == {"control.configuration_error"}
    assert "wheel_radius" in evidence


def test_asked_why_it_failed_a_start_that_went_fine_is_not_told_as_nothing_wrong(tmp_path: Path) -> None:
    # set 32: the teleop sent geometry_msgs/Twist where diff_drive_controller listens for TwistStamped, so no command
    # ever arrived, and nothing logs it; with no task the logs give only the start, which completed
    causes, text, _ = _ask(tmp_path, "base-unstamped", False, "real-modules-heldout32")
    assert causes == ["control.unexplained_failure"]
    claims = read_claims(text).affirmed
    assert "control.nominal" not in claims and "claim.all_fine" not in claims
    assert "Successful 'activate' of hardware 'BaseSystem'" in text and "My logs do not show what" in text
    # asked how it went, the same start is told as the start that went fine
    excerpt = next(e for e in load_excerpts("real-modules-heldout32") if e.id == "kilted-control-base-unstamped")
    log = read_recording(write_recording(excerpt, tmp_path / "how", task=False))
    _, found = explain(log, "control", QUESTIONS["succeeded"])
    assert found.causes == ["control.nominal"]


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_spawners_that_gave_up_before_the_description_came_are_told_with_the_delay(
        tmp_path: Path, task: bool) -> None:
    # set 33: spawners with --controller-manager-timeout 2, the description published 8 s late: "Could not contact
    # service /controller_manager/list_controllers" while the manager logged "Waiting for data on 'robot_description'
    # topic", and "Received robot description from topic." after the last spawner died (outside a derived window)
    causes, text, evidence = _ask(tmp_path, "spawner-timeout-short", task, "real-modules-heldout33")
    assert causes == ["bringup.configuration_error"]
    assert read_claims(text).affirmed == {"bringup.configuration_error"}
    assert "after my spawners gave up" in text and "Received robot description from topic" in evidence


def test_spawners_that_reached_their_manager_are_not_told_as_giving_up_early(tmp_path: Path) -> None:
    # set 33's fault-free run: the description came first, the spawners loaded their controllers
    causes, _, _ = _ask(tmp_path, "goal-nominal", True, "real-modules-heldout33")
    assert causes == ["control.nominal"]


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_goal_refused_by_a_controller_left_inactive_is_the_controller_never_activated(
        tmp_path: Path, task: bool) -> None:
    # held-out set 31: arm_controller configured, never in an "Activating controllers: [...]" line, then its
    # "Can't accept new action goals. Controller is not running." for the goal that came a second later
    causes, text, _ = _ask(tmp_path, "spawned-inactive", task, "real-modules-heldout31")
    assert causes == ["control.controller_activation_failed"]
    assert text.startswith("My controller arm_controller was never activated: my controller manager configured it, "
                           "then activated my other controllers but not it")
    assert "took too long" not in text
