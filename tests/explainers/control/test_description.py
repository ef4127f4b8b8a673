"""A controller manager waiting for its robot description (explainers/control/description.py), on real rosbag2
recordings with a failed task on /task_info. The lines are ros2_control's own (controller_manager.cpp@jazzy:
"Subscribing to '%s' topic for robot description." :759, "Waiting for data on 'robot_description' topic to finish
initialization" :770, "Received robot description from topic." :777)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Explanation
from tests.explainers.helpers import T0, explain, write_lines

CM = "controller_manager"
SUBSCRIBED = (0.0, CM, INFO, "Subscribing to '/robot_description' topic for robot description.")
WAITING = [(s, CM, WARN, "Waiting for data on 'robot_description' topic to finish initialization") for s in (1, 2)]


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]]) -> Explanation:
    def task(status: str) -> dict[str, Any]:
        return {"instruction": "move the arm", "task_id": "0000000000000031", "task_status": "valid",
                "task_error_msg": "", "skill_sequence": [{"skill": "follow_joint_trajectory", "params": {},
                                                          "status": status, "error_msg": ""}]}

    b = BagBuilder()
    b.task_info(T0 - sec_ns(1), task("waiting"))
    b.task_info(T0 - sec_ns(0.5), task("Running"))
    b.task_info(T0 + sec_ns(3), task("failed"))
    return explain(write_lines(tmp_path, lines, b), "control", "Why didn't that work?")[1]


def _claims(found: Explanation) -> set[str]:
    return {c for c in read_claims(found.text).affirmed if not c.startswith("claim.")}


def test_a_manager_that_subscribed_and_only_waited_never_got_its_description(tmp_path: Path) -> None:
    found = _explain(tmp_path, [SUBSCRIBED, *WAITING])
    assert found.causes == ["bringup.configuration_error"]
    assert _claims(found) == {"bringup.configuration_error"}
    assert "never reached my controller manager" in found.text
    assert found.evidence[0].item.endswith("Waiting for data on 'robot_description' topic to finish initialization")


def test_the_warning_alone_is_told_with_both_readings_and_no_cause(tmp_path: Path) -> None:
    # a pasted excerpt: the subscription may have come before it, and a hardware error after a description arrived
    found = _explain(tmp_path, WAITING)
    assert found.causes == ["control.unexplained_failure"]
    assert _claims(found) == set()
    assert "Either no description arrived" in found.text and "hardware that did not load" in found.text


def test_a_description_that_arrived_leaves_the_hardware_error_to_decide(tmp_path: Path) -> None:
    # the resource manager could not load the hardware the description named; the manager then waits again
    found = _explain(tmp_path, [
        SUBSCRIBED, (0.5, CM, INFO, "Received robot description from topic."),
        (0.6, "resource_manager", ERROR,
         "Failed to load hardware 'openarm' from plugin 'fake_components/GenericSystem'"), *WAITING])
    assert "bringup.configuration_error" not in found.causes
    assert "never reached my controller manager" not in found.text
    assert "Either no description arrived" not in found.text
