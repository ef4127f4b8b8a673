"""A moment or a span asked about by the log's clock ("what happened at 11:15:36?", "nothing was logged between
11:14:46 and 11:15:33, what was it doing?"): the lines the recording holds then, or that none was logged and what
came either side; a time the recording does not reach is said to be outside it. Real Nav2 excerpts written with
rosbags."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_nav2_run

CASE = "nav2-6255-collision-monitor-approach-no-progress"


@pytest.mark.parametrize(("question", "kind"), [
    ("what happened at 11:15:36?", "at_time"), ("what was the robot doing between 11:14:46 and 11:15:33?", "at_time"),
    ("nothing logged between 11:14:46 and 11:15:33. why?", "at_time"), ("anything at 10:33?", "at_time"),
    ("when did it fail?", "when"), ("what happened?", None),
])
def test_a_time_of_day_names_the_moment_asked_about(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_silent_span_is_said_with_the_lines_either_side(tmp_path: Path) -> None:
    run = real_nav2_run(CASE, tmp_path / "run")
    (silent,) = converse(run, "nothing logged between 11:14:46 and 11:15:33. what was the robot doing for those 47 s?")
    assert silent["answer"] == (
        'My log holds no line between 11:14:46 and 11:15:33. The last one before came at 11:14:46, controller_server '
        '"Passing new path to controller."; the next at 11:15:33, controller_server "Passing new path to '
        'controller.".')


def test_a_moment_gives_its_lines_warnings_first(tmp_path: Path) -> None:
    run = real_nav2_run(CASE, tmp_path / "run")
    (moment, outside) = converse(run, "what happened at 11:15:36?", "and at 23:59?")
    # a line of the second before is among them: said to be near the moment, not at it
    assert str(moment["answer"]).startswith("My log holds 4 lines within 1 s of 11:15:36 (2 more at info level): at "
                                            '11:15:36, controller_server (ERROR) "Failed to make progress"')
    assert any("Failed to make progress" in e["item"] for e in moment["evidence"])  # type: ignore[union-attr]
    assert str(outside["answer"]).endswith("My recording does not cover 23:59:00 UTC: it runs from 11:14:45 to "
                                           "11:15:36.")
