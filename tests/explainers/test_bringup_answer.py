"""The answer about a start derived from the logs (no /task_info, no goal): a start that completed is told as one
with nothing failed, its warnings as ones that only look like failures; a start that did not complete is never told
as a success or a failure; a failed one quotes its first error."""

from __future__ import annotations

from pathlib import Path

from hexar.claims import ALL_FINE, TASK_FAILED, read_claims
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Explanation
from tests.explainers.helpers import explain, write_lines

# ros2_control's own lines: hardware_interface/src/resource_manager.cpp:88,120@humble,
# controller_manager/controller_manager/spawner.py:273@humble, controller_manager/src/controller_manager.cpp:3401@jazzy
LOADING = (0.0, "resource_manager", INFO, "Loading hardware 'RRBot'")
DONE = [(0.2, "resource_manager", INFO, "Successful initialization of hardware 'RRBot'"),
        (1.0, "spawner_joint_state_broadcaster", INFO, "Configured and activated joint_state_broadcaster")]
NO_CLOCK = (0.1, "controller_manager", WARN, "No clock received, using time argument instead! Check your node's "
            "clock configuration (use_sim_time parameter) and if a valid clock source is available")


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


def test_a_start_the_recording_does_not_see_complete_claims_neither_success_nor_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [LOADING, NO_CLOCK], "Why didn't that work?")
    claims = read_claims(found.text).affirmed
    assert found.causes == [] and not claims & {ALL_FINE, TASK_FAILED, "control.nominal"}
    assert "do not show what came of the start" in found.text and "No clock received" in found.text


def test_a_failed_start_quotes_its_first_error_and_never_says_it_went_fine(tmp_path: Path) -> None:
    driver = "ydlidar_ros2_driver_node"  # ydlidar_ros2_driver's own lines (a console of ydlidar_ros2#4)
    found = _explain(tmp_path, [(0.0, driver, INFO, "[YDLIDAR INFO] Current ROS Driver Version: 1.0.1"),
                                (2.6, driver, ERROR, "Unknown error")], "Why didn't that work?")
    assert found.text.startswith("Starting my drivers and controllers failed")
    assert "Unknown error" in found.text and ALL_FINE not in read_claims(found.text).affirmed
