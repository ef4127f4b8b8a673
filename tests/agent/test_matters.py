""""Is that warning anything to worry about?", "is this error related to it?": the answer says first whether the
line named is what the finding rests on, from what the recording shows, then the finding and the line."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.agent.matters import asks_matters
from hexar.evals.scenarios.arm import simulate_arm_suite
from tests.agent.helpers import converse, real_module_run, real_nav2_run


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s == "nominal")
    return out


def test_a_warning_before_a_task_that_went_through_stopped_nothing(arm: Path) -> None:
    (said,) = converse(arm / "armfile_nominal_1", "Is the local_costmap 'Map update loop missed its desired rate of "
                                                  "5.0000Hz' warning at 16:01:27 anything to worry about?")
    text = str(said["answer"])
    assert text.startswith("Not for this task: it went through after the line you name (local_costmap.local_costmap, "
                           "16:01:27), so that line stopped nothing.")
    assert '"Costmap2DROS: Map update loop missed its desired rate of 5.0000Hz' in text


def test_a_line_the_failure_rests_on_is_said_to_matter(tmp_path: Path) -> None:
    run = real_module_run("kilted-lifecycle-transition-label-misspelt", tmp_path / "run")
    (said,) = converse(run, "Is the 'No transition matching active found for current state inactive' warning the "
                            "reason it failed?")
    assert str(said["answer"]).startswith("Yes: the line you name (rcl_lifecycle, 13:47:26, the first of 2 alike) is "
                                          "among the lines my finding below rests on.")


def test_a_line_the_failure_does_not_rest_on_is_not_told_as_its_cause(tmp_path: Path) -> None:
    run = real_nav2_run("rs500-c61-fastdds-shm-velocity-smoother-inactive", tmp_path / "run")
    (said,) = converse(run, "Is the Fast DDS SHM \"open_and_lock_file failed\" error related to the robot not moving?")
    text = str(said["answer"])
    assert text.startswith("My finding below does not rest on the line you name")
    assert "so the log does not show that line as the cause" in text


def test_a_set_up_command_that_failed_before_ctrl_c_stopped_nothing(tmp_path: Path) -> None:
    """launch ran `rm` for a stale lock file, which was not there (exit code 1); the driver came up after it, then
    Ctrl-C stopped everything: no failure of the start, and the command's exit said as what it was."""
    run = real_module_run("kilted-bringup-stale-lock-cleanup-exits-1", tmp_path / "run")
    matters, stopped = converse(run, "Does rm-2 dying with exit code 1 actually matter if the lock file just wasn't "
                                     "there?", "Was the launch stopped because of the rm failure or did someone hit "
                                               "ctrl-c?")
    assert str(matters["answer"]).startswith("Not as a failure: the task was stopped from outside, not by the line you "
                                             "name (rm, 12:58:41)")
    text = str(stopped["answer"])
    assert text.startswith("Starting my drivers and controllers went fine: my controllers were starting "
                           "without any problem when it was stopped from outside "
                           "(“[launch] user interrupted with ctrl-c (SIGINT)”")
    assert "a command launch ran for the set-up (rm /var/lock/lidar.lock), not one of my nodes, ended with an " \
           "error, and my nodes went on after it, so it stopped nothing." in text


@pytest.mark.parametrize(("question", "asked"), [
    ("Should I worry about the 'no odometry on /odom for 1.0 s' warnings from odom_monitor?", True),
    ("Are the 'No position interface found... Skipping sync!' warnings for the four wheels actually harmful?", True),
    ("Is the repeated 'Velocity command timed out. Braking.' from diff_drive_controller a problem?", True),
    ("Does the 'No valid trajectories out of 360!' warning have anything to do with the failed pick?", True),
    ("Is the battery a problem?", False),  # names no line
    ("why did you fail?", False),
])
def test_whether_a_line_matters_is_asked_in_many_ways(question: str, asked: bool) -> None:
    assert asks_matters(question) is asked
    if asked:
        assert content_kind(question) is None  # the finding answers it, led by the verdict


def test_a_finding_that_names_no_cause_rules_no_line_out(tmp_path: Path) -> None:
    """A hardware interface's segfault the logs do not explain: asked whether a frame of its stack trace is the
    cause, the answer does not say the finding rests on other lines (it names no cause to rest on)."""
    run = real_module_run("rokae-ros2-hardware-interface-callback-in-write-segfault", tmp_path / "run")
    (asked,) = converse(run, "Is RokaeHardwareInterface::callback being called from write() the cause of the crash?")
    assert "does not rest on" not in str(asked["answer"])
    assert str(asked["answer"]).startswith("I can't tell from my logs whether the line you name (")
    assert ") is: my finding below names no cause for sure." in str(asked["answer"])
    assert "Starting my drivers and controllers failed, but my control logs do not show a cause I know." in \
        str(asked["answer"])
