"""Whole consoles of the real Nav2 with its docking server (blind set 26, spent), written as recordings with rosbags,
with and without a /task_info task: a DockRobot goal is a task of its own (the trip to its staging pose is part of
it), and a docking that failed after that trip went well is no trip without a problem: the docking server's own
lines say which step failed, and the warnings before its error say why."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording
from hexar.events import read_recording


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in blind_set(26) if e.id == f"kilted-nav2-{ident}")


def _ask(tmp_path: Path, ident: str, task: bool, question: str = "Why did you fail?") -> dict[str, object]:
    bag = write_recording(_excerpt(ident), tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask(question))


@pytest.mark.parametrize("ident, outcome", [("dock-nominal", "succeeded"), ("detector-off", "failed"),
                                            ("dock-not-in-database", "failed")])
def test_a_dock_robot_goal_is_one_task_that_holds_the_trip_to_its_staging_pose(
        tmp_path: Path, ident: str, outcome: str) -> None:
    # "Attempting to dock robot at home_dock." ... bt_navigator's own begin and "Goal succeeded" for the staging
    # pose ... "Robot is charging!" (or the server's abort): one task, not a navigation goal beside a docking
    log = read_recording(write_recording(_excerpt(ident), tmp_path / "bag", task=False))
    assert [t.outcome for t in log.tasks] == [outcome]
    [task] = log.tasks
    assert [r.skill for r in task.skills] == ["dock_robot"] and task.skills[0].params["dock"] in {"home_dock",
                                                                                                 "kitchen_dock"}


@pytest.mark.parametrize("ident, cause, words", [
    # "Dock ID requested is not in database!" right after "Attempting to dock robot at kitchen_dock."
    ("dock-not-in-database", "navigation.docking_failure", "kitchen_dock, is not in my list of docks"),
    # the trip succeeded; then "Lost detection or did not detect: timeout exceeded" and "Failed initial dock detection"
    ("detector-off", "navigation.docking_failure", "I never detected the dock"),
    # tf2's 'Invalid frame ID "camera_link" passed to canTransform argument source_frame - frame does not exist' and
    # "Failed to transform detected dock pose" before "Failed initial dock detection"
    ("detector-frame", "navigation.transform_error", "in the frame camera_link, which has no transform"),
    # 'Transform error: "odom_combined" passed to lookupTransform argument target_frame does not exist.'
    ("fixed-frame", "navigation.transform_error", '"odom_combined" passed to lookupTransform'),
    # four "Made contact with dock, waiting for charge to start", then "Timed out waiting for charge to start"
    ("battery-silent", "navigation.docking_failure", "I made contact with the dock 4 times"),
    # "Collision detected at pose: (1.17, 2.10, 0.00) in frame odom" before each "Failed to get control"
    ("box-before-dock", "navigation.collision_ahead", "detected a collision ahead on its approach, at (1.17, 2.10)"),
])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_docking_that_failed_after_its_trip_is_told_by_the_step_that_failed(
        tmp_path: Path, ident: str, cause: str, words: str, task: bool) -> None:
    answer = _ask(tmp_path, ident, task)
    text = str(answer["answer"])
    assert answer["causes"] == [cause] and words in text
    assert read_claims(text).causes == {cause}  # "the dock" of a failed docking is no claim that it was charging
    assert "without any problem" not in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_staging_pose_outside_the_map_is_the_docks_and_a_box_on_the_way_is_the_trips(
        tmp_path: Path, task: bool) -> None:
    # the dock's yaw reversed put its staging pose at (-0.20, 2.00): 'Goal Coordinates of(-0.200000, 2.000000) was
    # outside bounds', then "Navigation request to staging pose failed."
    staged = _ask(tmp_path / "yaw", "dock-yaw-reversed", task)
    assert staged["causes"] == ["navigation.docking_failure"]
    assert "the dock's staging pose at (-0.20, 2.00)" in str(staged["answer"])
    # the same server line after a box closed the doorway: the trip's own reason, not "my docking failed"
    blocked = _ask(tmp_path / "door", "far-doorway-blocked", task)
    assert blocked["causes"] == ["navigation.blocked_path"]
    assert "docking failed" not in str(blocked["answer"])


def test_a_docking_that_went_well_is_told_as_such(tmp_path: Path) -> None:
    for ident in ("dock-nominal", "dock-far-charging"):
        answer = _ask(tmp_path / ident, ident, False, "What happened?")
        assert answer["causes"] == ["navigation.nominal"], ident
