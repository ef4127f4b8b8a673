""""Did you hit anything?", "what was in the way?", "was the door closed?": what the recording cannot hold is said
first (no contact sensor, no camera), then the finding it does support; never that finding as if it answered."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals import real_nav2
from tests.agent.helpers import converse


@pytest.mark.parametrize(("question", "kind"), [
    ("did you hit anything?", "contact"), ("did you bump into someone?", "contact"),
    ("did you crash into the wall?", "contact"), ("what was in the way?", "blocked"),
    ("what blocked your path?", "blocked"), ("was the door closed?", "blocked"),
    ("why did you hit the wall?", None), ("what is an obstacle?", None),
])
def test_unseen_questions_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_what_the_recording_cannot_hold_is_said_before_the_finding(suite: Path) -> None:
    hit, what, door = converse(suite / "bagfile_5_1", "did you hit anything?", "what was in the way?",
                               "was the door closed?")
    finding = "I couldn't reach the kitchen because something blocked my path and I found no other way around it."
    assert hit["answer"] == f"I can't tell: my recording holds no bumper or contact sensor. {finding}"
    assert str(what["answer"]).startswith("I can't tell what it was: my recording holds no camera image")
    assert str(door["answer"]).startswith("I can't tell whether a door was closed")
    assert all(str(a["answer"]).endswith(finding) for a in (what, door))
    assert hit["causes"] == ["navigation.blocked_path"]  # "why?" goes on to the blocked path's evidence
    (clear,) = converse(suite / "bagfile_10_1", "what was in the way?")
    assert clear["answer"] == ('My recording shows nothing in my way. Your request "Bring me a coffee from the '
                               'kitchen" went without a problem.')


def test_a_collision_check_that_stopped_me_is_the_nearest_to_a_touch(tmp_path: Path) -> None:
    case = next(e for e in real_nav2.corpus() if e.id == "nav2-6255-collision-monitor-approach-no-progress")
    run = real_nav2.write_recording(case, tmp_path / "run", task=False)
    (hit,) = converse(run, "did you hit anything?")
    assert str(hit["answer"]).startswith("I can't tell: my recording holds no bumper or contact sensor. What it holds "
                                         "is that a collision check stopped me first.")
    assert "navigation.collision_ahead" in hit["causes"]  # type: ignore[operator]
