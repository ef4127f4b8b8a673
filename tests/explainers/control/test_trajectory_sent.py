"""Whole consoles of the real ros2_control sent a FollowJointTrajectory goal as a script builds it (held-out set 36,
spent), written as recordings with rosbags, with and without a /task_info task: the trajectory controller's check that
rejected the goal says what in the trajectory did not fit, and without a task that line ends the goal derived from
the log, failed."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.real_modules import QUESTIONS, Excerpt, load_excerpts, write_recording
from hexar.events import read_recording
from tests.explainers.helpers import explain


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in load_excerpts("real-modules-heldout36") if e.id == f"kilted-control-{ident}")


@pytest.mark.parametrize("ident, words", [
    # "Time between points 0 and 1 is not strictly increasing, it is 2.000000 and 1.000000 respectively"
    ("traj-time-not-increasing", "the times of its points did not increase"),
    # "Mismatch between joint_names size (2) and positions (1) at point #0."
    ("traj-one-position", "a point gave more or fewer values than the joints the trajectory names"),
    ("traj-empty", "it had no points"),  # "Empty trajectory received."
    # "Velocity of last trajectory point of joint shoulder_joint is not zero: 0.500000000000000"
    ("traj-last-moving", "its last point still moved"),
    # "Received trajectory with non-zero start time (1796046767.384635) that ends in the past (1796046769.384635)"
    ("traj-stamp-past", "its stamp put the whole of it in the past"),
])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_trajectory_the_controller_rejected_is_told_by_the_check_it_failed(
        tmp_path: Path, ident: str, words: str, task: bool) -> None:
    log = read_recording(write_recording(_excerpt(ident), tmp_path / "run", task=task))
    if not task:
        assert [(t.skills[0].skill, t.outcome) for t in log.tasks] == [("follow_joint_trajectory", "failed")]
    _, found = explain(log, "control", QUESTIONS["failed"])
    assert found.causes == ["control.configuration_error"] and words in found.text
    assert read_claims(found.text).causes == {"control.configuration_error"}


def test_a_trajectory_faster_than_the_joints_stays_a_tolerance_and_no_limit_beyond(tmp_path: Path) -> None:
    # 3 rad in 0.2 s against a 2 rad/s velocity limit: the limiter clamps the velocity (no position beyond the joints'
    # limits) and the controller aborts "due to goal_time_tolerance exceeding by 1.009889 seconds"
    log = read_recording(write_recording(_excerpt("traj-too-fast"), tmp_path / "run", task=True))
    _, found = explain(log, "control", QUESTIONS["failed"])
    assert found.causes == ["control.tolerance_violated"] and "beyond its position limits" not in found.text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_goal_for_fewer_joints_is_the_senders_not_the_controllers_set_up(tmp_path: Path, task: bool) -> None:
    # held-out set 33: "Joints on incoming trajectory don't match the controller joints." (validate_trajectory_msg)
    excerpt = next(e for e in load_excerpts("real-modules-heldout33") if e.id == "kilted-control-goal-partial-joints")
    log = read_recording(write_recording(excerpt, tmp_path / "run", task=task))
    if not task:
        assert [(t.skills[0].skill, t.outcome) for t in log.tasks] == [("follow_joint_trajectory", "failed")]
    _, found = explain(log, "control", QUESTIONS["failed"])
    assert found.causes == ["control.configuration_error"]
    assert "the trajectory they were sent did not fit the controller, which rejected the goal before it started: it " \
           "named other joints, or fewer, than the controller's joints" in found.text
    assert "robot description" not in found.text and "set up wrongly" not in found.text
    assert read_claims(found.text).causes == {"control.configuration_error"}
