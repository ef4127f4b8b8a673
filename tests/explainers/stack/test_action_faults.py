"""Goals of rclpy actions, read from the lines the real ROS 2 Kilted stack printed here with one fault each (rclpy
9.1.2, rcl_action, Fast DDS, test_msgs' Fibonacci; scripts/action_faults.py, the spent held-out set 27), and a
launch_ros lifecycle bring-up (scripts/launch_faults.py, set 26), written as recordings with rosbags."""

from __future__ import annotations

from pathlib import Path

from hexar.explainers.base import Explanation
from hexar.explainers.stack.actions import action_finding
from tests.explainers.helpers import claimed, console_lines, derived_start, one_step_task, printed, write_lines


def _action(ident: str) -> list[tuple[float, str, int, str]]:
    return console_lines(printed("real-modules-heldout27", ident))


def _arm(tmp_path: Path, ident: str) -> Explanation:
    return one_step_task(tmp_path, _action(ident), "manipulation", "move_arm")


def test_a_goal_the_controller_did_not_take_is_the_execution_failing_with_its_reason(tmp_path: Path) -> None:
    found = _arm(tmp_path, "kilted-action-goal-rejected-client-goes-on")
    assert found.causes == ["manipulation.execution_failed"] and claimed(found) == {"manipulation.execution_failed"}
    assert "did not take the goal, saying '[arm_controller] Trajectory has 150 points" in found.text


def test_a_goal_the_servers_code_never_ended_is_the_execution_failing(tmp_path: Path) -> None:
    found = _arm(tmp_path, "kilted-action-execute-no-terminal-state")
    assert found.causes == ["manipulation.execution_failed"] and claimed(found) == {"manipulation.execution_failed"}
    assert "ended the goal without a result" in found.text and "goal_handle.succeed()" in (found.fix or "")


def test_a_goal_the_server_did_not_keep_without_an_error_of_its_own_stays_open(tmp_path: Path) -> None:
    # rejected silently or its result dropped after result_timeout: the lines do not tell which
    lines = _action("kilted-action-result-expired")
    told = action_finding(write_lines(tmp_path / "lines", lines).logs)
    assert told is not None and told.kind == "unknown_goal" and told.reason is None
    found = one_step_task(tmp_path / "arm", lines, "manipulation", "move_arm")
    assert found.causes == ["manipulation.unexplained_failure"] and not claimed(found)


def test_two_action_servers_of_one_name_are_a_configuration_error(tmp_path: Path) -> None:
    lines = _action("kilted-action-two-servers-one-name")
    for found in (one_step_task(tmp_path / "task", lines, "control", "follow_joint_trajectory"),
                  derived_start(tmp_path / "start", lines)):
        assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
        assert "two action servers answer to the same action name (/arm_controller/follow_joint_trajectory)" \
            in found.text


def test_an_action_clients_goal_lines_are_no_navigation(tmp_path: Path) -> None:
    # "Goal was canceled" is bt_navigator's words too; with no Nav2 node in the recording it is the program's own
    log = write_lines(tmp_path, _action("kilted-action-goal-canceled-on-purpose"))
    assert not log.tasks


def test_a_lifecycle_transition_whose_node_said_why_is_told(tmp_path: Path) -> None:
    lines = console_lines(printed("real-modules-heldout26", "kilted-lifecycle-configure-returns-failure"))
    found = derived_start(tmp_path, lines)
    assert found.causes == ["bringup.lifecycle_transition_failed"]
    assert claimed(found) == {"bringup.lifecycle_transition_failed"}
    assert "launch asked /lidar_driver to configure" in found.text



def test_an_old_error_of_the_server_is_no_reason_for_a_goal_it_did_not_keep(tmp_path: Path) -> None:
    # the same run with the controller's error a minute before the goal: it is about something else
    lines = [(s - 60.0 if msg.startswith("Trajectory has") else s, name, level, msg)
             for s, name, level, msg in _action("kilted-action-goal-rejected-client-goes-on")]
    told = action_finding(sorted(write_lines(tmp_path, lines).logs, key=lambda ln: ln.t))
    assert told is not None and told.kind == "unknown_goal" and told.reason is None
