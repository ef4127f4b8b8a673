""""How many times was X logged (before Y)?": counted from the log, on real consoles written as recordings."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


def test_a_line_counted_up_to_a_quoted_line(tmp_path: Path) -> None:
    run = real_nav2_run("deepracer-thesis-guide-expected-goal-succeeded", tmp_path / "run")
    (many,) = converse(run, "How many times was a new path passed to the controller before 'Reached the goal!'?")
    assert str(many["answer"]).startswith("3 times before controller_server's \"Reached the goal!\" at 22:13:20: "
                                          "controller_server logged \"Passing new path to controller.\"")


def test_a_warning_counted_up_to_ctrl_c(tmp_path: Path) -> None:
    """"brake" finds diff_drive_controller's "Braking." (the word's own ending aside), "the ctrl-c" launch's line."""
    run = real_module_run("kilted-control-base-velocity-feedback", tmp_path / "run")
    (many,) = converse(run, "how many times did it brake before the ctrl-c?")
    assert many["answer"] == ("4 times before launch's \"user interrupted with ctrl-c (SIGINT)\" at 07:06:17: "
                              "diff_drive_controller logged \"Velocity command timed out. Braking.\" from 07:06:11 to "
                              "07:06:17.")


@pytest.mark.parametrize(("question", "kind"), [
    ("how many times did it brake before the ctrl-c?", "count"),
    ("how many times did you try?", "tried"),  # the tries stay the tries' question
    ("how many times did it warn?", "logs"),
])
def test_how_often_is_its_own_question(question: str, kind: str) -> None:
    assert content_kind(question) == kind
