"""Whole consoles of the real Nav2 with keepout zones (blind set 25, spent), written as recordings with rosbags, with
and without a /task_info task: the keepout filter's "Pose is in keepout zone" is the robot's start on occupied cells;
a spin that could not turn where the planner could not start is that start too, where no line says where the robot
stood; a planner that had a path and found none once the keepout mask was in its costmap is told as the zones, never
as something that came into the way; and a spin's collision check after the planner had planned is no such start."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording


def _excerpt(ident: str, n: int = 25) -> Excerpt:
    return next(e for e in blind_set(n) if e.id == ident)


def _ask(tmp_path: Path, ident: str, task: bool, n: int = 25) -> dict[str, object]:
    bag = write_recording(_excerpt(ident, n), tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_the_keepout_filters_pose_in_zone_is_a_start_on_occupied_cells(tmp_path: Path, task: bool) -> None:
    # "KeepoutFilter: Pose is in keepout zone, reducing cost override to navigate out." (override_lethal_cost on),
    # then RPP's "detected collision ahead!" and "Controller patience exceeded": the zone, not a collision check
    answer = _ask(tmp_path, "kilted-nav2-keepout-start", task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.start_in_obstacle"]
    assert "navigation.collision_ahead" not in read_claims(text).affirmed and "keepout zone" in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_spin_that_could_not_turn_where_the_planner_could_not_start_is_a_start_on_occupied_cells(
        tmp_path: Path, task: bool) -> None:
    # override off: only "failed to plan from (2.00, 4.00)" (NavFn on Kilted names no occupied start), then
    # "Collision Ahead - Exiting Spin" and the backup's "Collision Ahead - Exiting DriveOnHeading"
    answer = _ask(tmp_path, "kilted-nav2-keepout-start-no-override", task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.start_in_obstacle"]
    assert read_claims(text).affirmed - {"claim.task_failed"} == {"navigation.start_in_obstacle"}
    assert "My logs do not show what put me there" in text


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_path_lost_once_the_keepout_mask_was_in_the_costmap_is_the_zones_not_an_obstacle(
        tmp_path: Path, task: bool) -> None:
    # the first plan came 0.9 s after "KeepoutFilter: Received filter mask", before the global costmap's next
    # update; every plan after failed: the goal lay inside a zone
    answer = _ask(tmp_path, "kilted-nav2-keepout-goal", task)
    text = str(answer["answer"])
    assert "navigation.blocked_path" not in read_claims(text).affirmed and "keepout zone" in text
    assert "do not show which" in text


def test_a_spin_stopped_after_a_plan_was_followed_is_no_start_on_occupied_cells(tmp_path: Path) -> None:
    # set 23's 1 m local costmap: the robot drove on a plan, then its spin recovery hit something; no planner
    # failure came before it, so the spin says nothing of where the robot started
    answer = _ask(tmp_path, "kilted-nav2-local-costmap-tiny", True, 23)
    assert answer["causes"] != ["navigation.start_in_obstacle"]
