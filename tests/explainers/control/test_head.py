"""Whole consoles of the real ros2_control pointing a pan-tilt head with forward_command_controller (held-out set 35,
spent), written as recordings with rosbags, with and without a /task_info task: a command of the wrong size does not
fit the controller; a command beyond a joint's position limits is told with the limits the controller manager
logged, while the joint limiter's clamp of an ordinary step is not; and a controller manager on simulated time with
no clock is told as such, not as an activation that took too long."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.real_modules import Excerpt, load_excerpts, write_recording
from hexar.events import read_recording
from hexar.events.records import LogLine
from hexar.explainers.control.clock import stalled
from hexar.explainers.control.limits import beyond_limits
from tests.explainers.helpers import ask_run


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in load_excerpts("real-modules-heldout35") if e.id == f"kilted-control-{ident}")


def _logs(tmp_path: Path, ident: str) -> list[LogLine]:
    return list(read_recording(write_recording(_excerpt(ident), tmp_path / ident, task=False)).logs)


def _ask(tmp_path: Path, ident: str, task: bool) -> tuple[list[str], str]:
    found = ask_run(tmp_path, "real-modules-heldout35", ident, task)
    return found.causes, found.text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_command_of_the_wrong_size_does_not_fit_the_controller(tmp_path: Path, task: bool) -> None:
    # head_controller's "command size (3) does not match number of interfaces (2)", once a second
    causes, text = _ask(tmp_path, "head-command-size", task)
    assert causes == ["control.configuration_error"] and "did not fit it" in text


def test_a_command_beyond_a_joints_limits_is_told_with_them(tmp_path: Path) -> None:
    # "Using JointLimiter for joint 'head_tilt_joint' ... has position limits: true [-0.2, 0.2]", then every second
    # "Command of at least one joint is out of limits ... command: [... position: -0.300000], limited: [... -0.200000]"
    causes, text = _ask(tmp_path, "head-tilt-limit", True)
    assert causes == ["control.configuration_error"]
    assert "head_tilt_joint was commanded to -0.3 rad, beyond its position limits [-0.2, 0.2]" in text
    assert read_claims(text).causes == {"control.configuration_error"}


def test_the_limiters_clamp_of_an_ordinary_step_is_no_command_beyond_limits(tmp_path: Path) -> None:
    # the pan's step to 0.6 clamped to 0.03 by its velocity limit (3 rad/s at 100 Hz) within [-1.2, 1.2]
    nominal = _logs(tmp_path, "head-nominal")
    assert any("out of limits" in ln.msg for ln in nominal) and beyond_limits(nominal) is None
    assert beyond_limits(_logs(tmp_path, "head-tilt-limit")) is not None


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_controller_manager_on_sim_time_with_no_clock_is_told_so(tmp_path: Path, task: bool) -> None:
    # "Using ROS clock for triggering controller manager cycles.", then "Switch controller timed out after 5 seconds!"
    # for each spawner; the steady clock's runs print "Steady (Monotonic)" and switch at once
    causes, text = _ask(tmp_path, "head-manager-sim-time", task)
    assert causes == ["bringup.configuration_error"] and "never received a clock" in text
    assert read_claims(text).causes == {"bringup.configuration_error"}
    assert stalled(_logs(tmp_path, "head-nominal")) is None
