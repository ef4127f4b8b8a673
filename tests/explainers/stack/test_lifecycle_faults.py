"""Managed nodes driven by a manager of the robot's own, read from the lines the real ROS 2 Kilted stack printed here
with one fault each (rclpy 9.1.2's LifecycleNode, rcl_lifecycle, Fast DDS; scripts/lifecycle_faults.py, the spent
held-out set 29), written as recordings with rosbags: no task and no goal, so the robot's start is derived from them."""

from __future__ import annotations

from pathlib import Path

from tests.explainers.helpers import claimed, console_lines, derived_start, printed, write_lines


def _lines(ident: str) -> list[tuple[float, str, int, str]]:
    return console_lines(printed("real-modules-heldout29", ident))


def test_a_transition_the_nodes_state_does_not_have_is_a_failed_lifecycle_transition(tmp_path: Path) -> None:
    # rcl_lifecycle's "No transition matching active found for current state inactive": a state asked for as if it
    # were a transition
    found = derived_start(tmp_path, _lines("kilted-lifecycle-transition-label-misspelt"))
    assert found.causes == ["bringup.lifecycle_transition_failed"]
    assert claimed(found) == {"bringup.lifecycle_transition_failed"}
    assert "asked for the transition 'active', which its current state (inactive) does not have" in found.text
    assert "ros2 lifecycle list" in (found.fix or "")


def test_a_robots_own_lifecycle_manager_is_no_navigation(tmp_path: Path) -> None:
    # its node is named lifecycle_manager, as Nav2's is, but it manages a base driver in its own words
    log = write_lines(tmp_path, _lines("kilted-lifecycle-configure-serial-port-missing"))
    assert [t.skills[0].skill for t in log.tasks] == ["bring_up_controllers"]
    nav2 = write_lines(tmp_path / "nav2", [(0.0, "lifecycle_manager_navigation", 20, "Configuring controller_server"),
                                           (0.5, "lifecycle_manager_navigation", 40,
                                            "Failed to change state for node: controller_server")])
    assert [t.skills[0].skill for t in nav2.tasks] == ["navigate_to_pose"]  # Nav2's own manager, in Nav2's words
