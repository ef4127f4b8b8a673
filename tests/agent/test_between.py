"""The time between two moments a developer names by their lines, and what the log holds in between, on real
consoles written as recordings."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_how_long_after_a_fatal_line_a_process_exited(tmp_path: Path) -> None:
    run = real_module_run("kilted-control-controller-type-missing", tmp_path / "run")
    (after,) = converse(run, "How long after the FATAL from spawner_arm_controller did spawner-4 actually exit?")
    text = str(after["answer"])
    assert text.startswith("5.6 s passed from spawner_arm_controller's \"Failed loading controller arm_controller\" at "
                           "04:51:32 to spawner-4's \"process has died [pid 24175, exit code 1,")
    assert text.endswith("My log holds no line in between, so it does not say what took that time.")


def test_a_gap_between_two_quoted_lines(tmp_path: Path) -> None:
    run = real_nav2_run("kybot-share-mission-goal-succeeded", tmp_path / "run")
    (gap,) = converse(run, "Why is there a 15 second gap between 'Mission started' and 'Navigating...'?")
    assert str(gap["answer"]).startswith("15.7 s passed from mission_executor's \"Mission started: 1 waypoints\" at "
                                         "11:22:24 to mission_executor's \"[1/1] Navigating...\" at 11:22:39.")


def test_what_happened_between_two_lines_names_what_was_logged(tmp_path: Path) -> None:
    run = real_nav2_run("tb4-530-time-desync-controller-patience", tmp_path / "run")
    (during,) = converse(run, "What happened during the two minutes between the amcl message drop and the controller "
                              "error?")
    text = str(during["answer"])
    assert text.startswith("1 min 56 s passed from amcl's \"Message Filter dropping message:")
    assert "to controller_server's \"Controller patience exceeded\" at 09:40:11. In between, my log holds 2 " \
           "lines" in text


@pytest.mark.parametrize(("question", "kind"), [
    ("How long after the FATAL from spawner_arm_controller did spawner-4 actually exit?", "between"),
    ("Why is there a 15 second gap between 'Mission started' and 'Navigating...'?", "between"),
    # the task's own times stay the measures' questions
    ("how long after launch did bt_navigator start on the goal?", "when"),
    ("How long did it take?", "long"),
])
def test_a_time_between_two_named_moments_is_its_own_question(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_which_of_two_named_lines_came_first(tmp_path: Path) -> None:
    run = real_nav2_run("slam-wheeled-robot-amcl-initialpose-race-bringup-abort", tmp_path / "run")
    (first,) = converse(run, "Which came first, the global_costmap TF timeout or the AMCL warning?")
    text = str(first["answer"])
    assert text.startswith("First came global_costmap.global_costmap's \"Timed out waiting for transform from "
                           "base_link to map to become available")
    assert text.endswith("amcl's \"AMCL cannot publish a pose or update the transform.\" at 22:13:20 came 300 ms "
                         "later.")


def test_a_span_from_launch_until_a_controller_was_activated(tmp_path: Path) -> None:
    """"From X until Y" is the span between them, not the task's own time; "both controllers" ends at the last."""
    run = real_module_run("kilted-control-base-nominal", tmp_path / "run")
    (until,) = converse(run, "How long did it take from launch until diff_drive_controller was activated?")
    assert str(until["answer"]).startswith("2.0 s passed from launch's \"All log files can be found below ")
    assert "to controller_manager's \"Activating controllers: [ diff_drive_controller ]\" at 07:05:52." in \
        str(until["answer"])
    both = real_module_run("janvanhulzen-mobile-base-hardware-bringup-fifo-warn-nominal", tmp_path / "both")
    (active,) = converse(both, "how long from loading MobileBase to both controllers being active?")
    assert str(active["answer"]).startswith("3.5 s passed from controller_manager's \"Loading hardware 'MobileBase'\" "
                                            "at 17:20:42 to spawner_diff_drive_controller's \"Configured and "
                                            "activated diff_drive_controller\" at 17:20:45.")
