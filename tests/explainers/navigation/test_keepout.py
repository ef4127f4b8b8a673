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


def _masked(tmp_path: Path, ident: str, zones: list[tuple[float, float, float, float]]) -> Path:
    """The console as a recording with the keepout mask map_server served (set 25's two-room map: 12 m x 8 m at
    0.05 m, 100 in each zone), recorded when the stack started, as a latched map reaches a recording."""
    import numpy as np

    from hexar.evals.scenarios.bag import BagBuilder
    from hexar.events import contract as c
    from hexar.events.console import parse_console, stamped
    from tests.explainers.navigation.maps import grid_msg

    cells = np.zeros((160, 240), dtype=np.int8)
    for x0, y0, x1, y1 in zones:
        cells[round(y0 / 0.05):round(y1 / 0.05), round(x0 / 0.05):round(x1 / 0.05)] = 100
    records = stamped(parse_console(_excerpt(ident).lines))
    b = BagBuilder()
    for r in records:
        assert r.stamp_ns is not None
        b.log(r.stamp_ns, r.name or r.process, r.level, r.msg)
    first = min(r.stamp_ns or 0 for r in records)
    b.raw(first, c.KEEPOUT_MASK, c.GRID_TYPE, grid_msg(first, cells, 0.05, (0.0, 0.0)))
    return b.write(tmp_path / "bag")


def test_a_recorded_keepout_mask_tells_a_goal_inside_a_zone(tmp_path: Path) -> None:
    # set 25's last pose (9, 4) inside the 2 m zone x 8 to 10, y 3 to 5: the mask says which of the two it was
    bag = _masked(tmp_path, "kilted-nav2-keepout-goal", [(8.0, 3.0, 10.0, 5.0)])
    answer = dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.goal_unreachable"]
    assert "(9.00, 4.00) lies inside a keepout zone" in text and "do not show which" not in text
    assert any(e["topic"] == "/keepout_filter_mask" for e in answer["evidence"])  # type: ignore[attr-defined]


def test_a_recorded_keepout_mask_with_the_goal_outside_its_zones_claims_nothing_more(tmp_path: Path) -> None:
    # the same console with a mask whose only zone lies in a far corner: the mask does not put the goal in a zone,
    # so the answer stays the one the lines give
    bag = _masked(tmp_path, "kilted-nav2-keepout-goal", [(10.5, 6.5, 11.8, 7.8)])
    answer = dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))
    assert "do not show which" in str(answer["answer"]) and answer["causes"] != ["navigation.goal_unreachable"]
