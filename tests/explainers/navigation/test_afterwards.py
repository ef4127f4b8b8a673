"""A goal reached is not a task done. The real Nav2's console of a fault-free goal (blind set 20, spent), written as a
recording with rosbags, and the same console with a server HEXAR has no reading of failing after the goal: the
following server's own ERROR (opennav_following following_server.cpp@main, "Failed object detection") and nav2_util's
SimpleActionServer abort line in each distro's form (simple_action_server.hpp). Such a run is never told as "without
any problem"; nor is one whose /task_info says the navigation step failed."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording
from hexar.events.records import LogLine
from hexar.explainers.navigation.afterwards import _action

HUMBLE_ABORT = "[follow_object] [ActionServer] Aborting handle."
JAZZY_ABORT = "[follow_object] [ActionServer] Aborting handle. error_code:999, error_msg:'Failed object detection'."


def _nominal() -> Excerpt:
    return next(e for e in blind_set(20) if e.id == "kilted-nav2-nominal")


def _followed_by(abort: str) -> Excerpt:
    """The fault-free console with a following server that failed 2 s after bt_navigator's "Goal succeeded" (and
    before the Ctrl-C that ends the console)."""
    nominal = _nominal()
    lines = nominal.lines.splitlines()
    at = next(i for i, ln in enumerate(lines) if "Goal succeeded" in ln) + 1
    added = ["[opennav_following-8] [ERROR] [1796002261.402000000] [following_server]: Failed object detection",
             f"[opennav_following-8] [WARN] [1796002261.402100000] [following_server]: {abort}"]
    return replace(nominal, lines="\n".join(lines[:at] + added + lines[at:]) + "\n", outcome="failed",
                   cause="navigation.unexplained_failure")


def _ask(tmp_path: Path, excerpt: Excerpt, task: bool, question: str = "Why did you fail?") -> dict[str, object]:
    bag = write_recording(excerpt, tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask(question))


@pytest.mark.parametrize("abort, said", [(HUMBLE_ABORT, "The last error it logged before that was 'Failed object "
                                                        "detection'"),
                                         (JAZZY_ABORT, "aborted it with 'Failed object detection' (error code 999)")])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_server_with_no_reading_that_failed_after_the_goal_is_told_in_its_own_words(
        tmp_path: Path, abort: str, said: str, task: bool) -> None:
    answer = _ask(tmp_path, _followed_by(abort), task)
    text = str(answer["answer"])
    assert "my follow object goal failed: following_server aborted it" in text and said in text
    assert "without any problem" not in text and "can't tell why beyond its own words" in text
    assert read_claims(text).causes == set()
    assert answer["causes"] == ["navigation.unexplained_failure"]


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_the_fault_free_goal_alone_is_still_a_goal_reached_without_a_problem(tmp_path: Path, task: bool) -> None:
    answer = _ask(tmp_path, _nominal(), task, "How did it go?")
    assert "without any problem" in str(answer["answer"]) and answer["causes"] == ["navigation.nominal"]


def test_a_step_the_task_reports_failed_is_not_told_as_a_goal_reached_without_a_problem(tmp_path: Path) -> None:
    # the same console, with /task_info saying the navigation step failed ("The navigation goal was aborted"): the
    # logs and the task record disagree, and the answer says both
    answer = _ask(tmp_path, replace(_nominal(), outcome="failed"), task=True)
    text = str(answer["answer"])
    assert "My logs show that I reached my goal, but my task reports that step failed ('The navigation goal was " \
           "aborted'), and my logs do not show why." in text
    assert "without any problem" not in text and read_claims(text).causes == set()


def _line(msg: str) -> LogLine:
    return LogLine(t=0, level=30, name="following_server", msg=msg)


@pytest.mark.parametrize("msg, action", [
    (HUMBLE_ABORT, "follow_object"), (JAZZY_ABORT, "follow_object"),
    ("[compute_and_track_route] [ActionServer] Aborting handle. error_code:0.", "compute_and_track_route"),
    # servers told by their own readings: the navigator, the docking server, a behaviour
    ("[navigate_to_pose] [ActionServer] Aborting handle.", None),
    ("[dock_robot] [ActionServer] Aborting handle. error_code:904, error_msg:'Failed initial dock detection'.", None),
    ("[spin] [ActionServer] Aborting handle.", None),
    ("[follow_object] [ActionServer] Client requested to cancel the goal. Cancelling.", None),
])
def test_the_abort_line_is_read_in_every_distros_form_for_servers_with_no_reading(msg: str, action: str | None) -> None:
    assert _action(_line(msg)) == action


def test_an_abort_after_the_navigator_began_another_goal_is_that_goals_to_tell() -> None:
    from hexar.explainers.navigation.afterwards import aborted
    from hexar.explainers.navigation.detectors import Run

    reached = LogLine(t=10, level=20, name="bt_navigator", msg="Goal succeeded")
    error = LogLine(t=30, level=40, name="following_server", msg="Failed object detection")
    abort = LogLine(t=31, level=30, name="following_server", msg=HUMBLE_ABORT)
    run = Run(lines=[reached], poses=[], outcome="reached", begin=None, end=reached)
    told = aborted(run, [reached, error, abort], "my goal")
    assert told is not None and "my follow object goal failed" in told.notes[0]
    began = LogLine(t=20, level=20, name="bt_navigator",
                    msg="Begin navigating from current location (10.00, 4.00) to (2.00, 4.00)")
    assert aborted(run, [reached, began, error, abort], "my goal") is None
