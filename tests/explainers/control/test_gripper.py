"""Whole consoles of the real ros2_control closing a parallel gripper (held-out set 34, spent), written as recordings
with rosbags, with and without a /task_info task: a goal with a position per finger does not fit the controller; a
controller configured and never activated while the others were is told as never activated; and ros2_control's
joint limiter clamping a command, which it logs as an ERROR on healthy grippers, is no failure."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.real_modules import QUESTIONS, Excerpt, load_excerpts, write_recording
from hexar.events import read_recording
from hexar.explainers.control.spawners import never_activated
from tests.explainers.helpers import ask_run, explain


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in load_excerpts("real-modules-heldout34") if e.id == f"kilted-control-{ident}")


def _ask(tmp_path: Path, ident: str, task: bool) -> tuple[list[str], str]:
    found = ask_run(tmp_path, "real-modules-heldout34", ident, task)
    return found.causes, found.text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_goal_with_a_position_per_finger_does_not_fit_the_controller(tmp_path: Path, task: bool) -> None:
    # "Received action goal with wrong number of position values, expects 1, got 2"
    causes, text = _ask(tmp_path, "gripper-two-positions", task)
    assert causes == ["control.configuration_error"] and "a position per finger" in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_controller_configured_and_never_activated_is_told_so(tmp_path: Path, task: bool) -> None:
    # "Configuring controller: 'gripper_controller'", and the only "Activating controllers: [ ... ]" named
    # joint_state_broadcaster: its spawner was given --inactive
    causes, text = _ask(tmp_path, "gripper-inactive", task)
    assert causes == ["control.controller_activation_failed"]
    assert "gripper_controller was never activated" in text
    assert read_claims(text).causes == {"control.controller_activation_failed"}


def test_every_controller_activated_leaves_none_never_activated(tmp_path: Path) -> None:
    for ident in ("gripper-nominal", "gripper-stall-allowed"):
        log = read_recording(write_recording(_excerpt(ident), tmp_path / ident, task=False))
        assert never_activated(log.logs) is None, ident


def test_the_joint_limiters_clamped_command_is_no_failure(tmp_path: Path) -> None:
    # "Command of at least one joint is out of limits (throttled log). ..." (ERROR) as the fingers closed on an
    # object, and the grasp succeeded: without a task the start is not told as failed at that line
    log = read_recording(write_recording(_excerpt("gripper-stall-allowed"), tmp_path / "run", task=False))
    assert [t.outcome for t in log.tasks] != ["failed"]
    _, found = explain(log, "control", QUESTIONS["succeeded"])
    assert "out of limits" not in found.text and found.causes == ["control.nominal"]
