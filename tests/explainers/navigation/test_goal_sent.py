"""Whole consoles of the real Nav2 sent one NavigateToPose goal as a script sends it (blind set 29, spent), written as
recordings with rosbags, with and without a /task_info task: a goal bt_navigator could not put in its global frame is
told by why (a frame nothing publishes, no frame, a stamp older than its transforms), and a goal turned away before
the stack was up is told as such, while a stack that a missing transform kept from coming up stays that transform."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import blind_set, write_recording


def _ask(tmp_path: Path, blind: int, ident: str, task: bool) -> dict[str, object]:
    excerpt = next(e for e in blind_set(blind) if e.id == f"kilted-nav2-{ident}")
    bag = write_recording(excerpt, tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("Why didn't you get there?"))


@pytest.mark.parametrize("ident, words", [
    # transformPoseInTargetFrame's '"odom_combined" passed to lookupTransform argument source_frame does not exist.'
    # before "Failed to transform a goal pose provided with frame_id 'odom_combined' to the global frame 'map'."
    ("goal-frame-unknown", "it was given in the frame 'odom_combined', which nothing publishes"),
    # "Failed to transform from  to map", frame_id ''
    ("goal-frame-empty", "it had no frame at all (an empty frame_id)"),
    # "Lookup would require extrapolation into the past.  Requested time 1796045705.035247 but the earliest data is
    # at time 1796045732.347945"
    ("goal-stamp-old", "with a stamp 27 s older than the oldest transform I keep"),
])
@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_goal_that_could_not_be_put_in_the_global_frame_is_told_by_why(
        tmp_path: Path, ident: str, words: str, task: bool) -> None:
    answer = _ask(tmp_path, 29, ident, task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.transform_error"] and words in text
    assert read_claims(text).causes == {"navigation.transform_error"}


def test_a_goal_turned_away_before_the_stack_was_up_is_told_so(tmp_path: Path) -> None:
    # "Action server is inactive. Rejecting the goal." between "Configuring bt_navigator" and "Managed nodes are
    # active", and no goal began after it
    answer = _ask(tmp_path, 29, "goal-before-active", True)
    assert answer["causes"] == ["navigation.configuration_error"]
    assert "my stack was not brought up yet when the goal came" in str(answer["answer"])


@pytest.mark.parametrize("blind, ident", [(20, "no-map-tf"), (27, "ekf-input-missing")])
def test_a_stack_that_a_missing_transform_kept_from_coming_up_is_that_transform(
        tmp_path: Path, blind: int, ident: str) -> None:
    # the same rejection, in a stack that never came up: its costmaps waited for a transform nothing published
    answer = _ask(tmp_path, blind, ident, True)
    assert answer["causes"] == ["navigation.transform_error"]
    assert "not brought up yet" not in str(answer["answer"])
