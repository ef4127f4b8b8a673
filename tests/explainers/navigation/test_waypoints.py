"""Whole consoles of the real Nav2 with its waypoint follower (blind set 24, spent), written as recordings with
rosbags, with and without a /task_info task: a follower's goals end one after the other, and the last end counts
(Kilted's end line quotes the error, which a cause's entry would otherwise claim); a waypoint reached whose task then
failed (PhotoAtWaypoint on a camera topic with no images) is no trip without a problem; a server started but left out
of the lifecycle manager's list is the node that never came up, when no goal reached the navigator."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording
from hexar.events import read_recording
from hexar.explainers.navigation.unmanaged import unmanaged


def _excerpt(ident: str, n: int = 24) -> Excerpt:
    return next(e for e in blind_set(n) if e.id == f"kilted-nav2-{ident}")


def _ask(tmp_path: Path, ident: str, task: bool) -> dict[str, object]:
    bag = write_recording(_excerpt(ident), tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))


def test_the_last_of_a_followers_goals_decides_the_window_it_shares_with_the_others(tmp_path: Path) -> None:
    # three NavigateToPose goals in one task: two "Goal succeeded", then "Goal failed error_code:204 error_msg:'...
    # Goal Coordinates of(16.000000, 4.000000) was outside bounds'" for the waypoint off the map
    answer = _ask(tmp_path, "waypoint-off-map", True)
    assert answer["causes"] == ["navigation.goal_unreachable"]
    assert "without any problem" not in str(answer["answer"])


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_waypoint_reached_whose_photo_task_failed_is_that_task_and_its_camera_topic(
        tmp_path: Path, task: bool) -> None:
    # "Couldn't take photo at waypoint 0! Caught exception: Unrecognized image encoding [] / Make sure that the image
    # topic named: /camera/color/image_raw is valid and active!", then "Task execution at waypoint 0 failed!"
    answer = _ask(tmp_path, "waypoint-photo-no-camera", task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.configuration_error"]
    assert read_claims(text).affirmed == {"navigation.configuration_error"}
    assert "/camera/color/image_raw" in text and "without any problem" not in text
    if not task:  # the goal derived from the log ends at the task's failure, not at the waypoint
        log = read_recording(write_recording(_excerpt("waypoint-photo-no-camera"), tmp_path / "d", task=False))
        assert [t.outcome for t in log.tasks] == ["failed", "failed", "failed"]


def test_waypoints_whose_tasks_went_well_are_goals_reached(tmp_path: Path) -> None:
    log = read_recording(write_recording(_excerpt("waypoints-nominal"), tmp_path / "bag", task=False))
    assert [t.outcome for t in log.tasks] == ["succeeded", "succeeded", "succeeded"]


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_server_left_out_of_the_lifecycle_managers_list_is_the_node_that_never_came_up(
        tmp_path: Path, task: bool) -> None:
    # waypoint_follower printed "waypoint_follower lifecycle node launched." and never "Configuring"; the manager
    # said "Managed nodes are active" without it; the client found no follow_waypoints server and sent nothing
    answer = _ask(tmp_path, "waypoint-follower-unmanaged", task)
    assert answer["causes"] == ["navigation.bringup_failure"]
    assert "waypoint_follower was started but never configured" in str(answer["answer"])


def test_a_stack_whose_every_node_was_configured_has_no_unmanaged_node(tmp_path: Path) -> None:
    # set 24's executor misspelt: waypoint_follower was configured (and then died) -- configured all the same
    for ident, n in (("waypoints-nominal", 24), ("nominal", 20), ("waypoint-executor-misspelt", 24)):
        log = read_recording(write_recording(_excerpt(ident, n), tmp_path / ident, task=False))
        assert unmanaged(log.logs) is None, ident
    log = read_recording(write_recording(_excerpt("waypoint-follower-unmanaged"), tmp_path / "un", task=False))
    assert unmanaged(log.logs) is not None
