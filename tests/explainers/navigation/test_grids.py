"""A planner that found no path, told from the recorded maps: recordings written with rosbags that hold Nav2's real
lines (shared/reference/nav2_log_messages.md) and nav2_bringup's real tb3_sandbox map as /map and as an inflated
/global_costmap/costmap (maps.py). The map tells apart what the lines alone cannot (wording.PLAN_CANDIDATES)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Context, Explanation
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.detectors import UNEXPLAINED
from hexar.explainers.navigation.wording import PLAN_CANDIDATES
from tests.explainers.navigation.maps import Cells, cell_of, costmap, grid_msg, record_grids, sandbox

T0 = 1_700_000_000_000_000_000
STATIC, RES, ORIGIN = sandbox()
COST = costmap(STATIC, RES)
START = (-2.0, -0.5)  # the TurtleBot3 world's usual initial pose, free on the map
FREE_GOAL = (0.5, 0.5)


def centre(row: int, col: int) -> tuple[float, float]:
    return ORIGIN[0] + (col + 0.5) * RES, ORIGIN[1] + (row + 0.5) * RES


def nearest(cells: Cells, value: int, x: float, y: float) -> tuple[float, float]:
    """The centre of the cell holding `value` nearest to (x, y): taken from the map, not typed in."""
    rows, cols = np.nonzero(cells == value)
    r0, c0 = cell_of(x, y, RES, ORIGIN)
    i = int(np.argmin((rows - r0) ** 2 + (cols - c0) ** 2))
    return centre(int(rows[i]), int(cols[i]))


def ring(cells: Cells, x: float, y: float, radius: float) -> Cells:
    """`cells` with a closed ring of occupied cells around (x, y): boxes that a robot's sensors saw, or a wall."""
    out = cells.copy()
    rows, cols = np.indices(cells.shape)
    r0, c0 = cell_of(x, y, RES, ORIGIN)
    dist = np.hypot(rows - r0, cols - c0) * RES
    out[(dist >= radius) & (dist <= radius + 2 * RES)] = 100
    return out


def failed_goal(tmp: Path, start: tuple[float, float], goal: tuple[float, float], static: Cells | None = STATIC,
                cost: Cells | None = COST, amcl: bool = True) -> Explanation:
    """A NavigateToPose goal that failed because the planner found no path (no /task_info: a derived task)."""
    b = BagBuilder()
    record_grids(b, T0, static, cost, RES, ORIGIN)
    if amcl:
        b.pose(T0 + sec_ns(0.5), *start, 0.0, 0.02, 0.02, 0.01)
    t = T0 + sec_ns(1.0)
    b.log(t, "bt_navigator", INFO, f"Begin navigating from current location ({start[0]:.2f}, {start[1]:.2f}) to "
                                   f"({goal[0]:.2f}, {goal[1]:.2f})")
    b.log(t + sec_ns(0.1), "planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50.")
    b.log(t + sec_ns(0.1), "planner_server", WARN,
          f"Planning algorithm GridBased failed to generate a valid path to ({goal[0]:.2f}, {goal[1]:.2f})")
    b.log(t + sec_ns(0.1), "planner_server", WARN, "[compute_path_to_pose] [ActionServer] Aborting handle.")
    b.log(t + sec_ns(2.0), "bt_navigator", ERROR, "Goal failed")
    log = read_recording(b.write(tmp / "run"))
    return NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))


def test_the_recorded_maps_are_read_as_map_server_and_the_costmap_publish_them(tmp_path: Path) -> None:
    b = BagBuilder()
    record_grids(b, T0, STATIC, COST, RES, ORIGIN)
    b.log(T0 + sec_ns(1), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 0.00)")
    log = read_recording(b.write(tmp_path / "run"))
    by_topic = {grid.topic: grid for grid in log.grids}
    assert set(by_topic) == {c.MAP, c.GLOBAL_COSTMAP}
    wall = nearest(STATIC, 100, 0.3, 0.0)
    assert by_topic[c.MAP].value(*wall) == 100 and by_topic[c.MAP].value(*START) == 0
    assert by_topic[c.GLOBAL_COSTMAP].value(*wall) == 100 and by_topic[c.GLOBAL_COSTMAP].value(30.0, 30.0) is None
    assert by_topic[c.MAP].corners() == pytest.approx((-10.0, -10.0 + 384 * RES, -10.0, -10.0 + 384 * RES))


def test_a_goal_on_a_wall_of_the_map_is_unreachable(tmp_path: Path) -> None:
    goal = nearest(STATIC, 100, 1.3, 1.0)  # on a pillar's edge
    ans = failed_goal(tmp_path, START, goal)
    assert ans.causes == [g.GOAL_UNREACHABLE] and read_claims(ans.text).causes == {g.GOAL_UNREACHABLE}
    assert "lies on an obstacle" in ans.text and "a wall or obstacle of my map itself" in ans.text
    assert any(e.topic == c.GLOBAL_COSTMAP and "value 100" in e.item for e in ans.evidence)


def test_a_goal_beside_a_pillar_is_inside_its_inflation(tmp_path: Path) -> None:
    goal = nearest(COST, 99, 1.3, 1.0)
    ans = failed_goal(tmp_path, START, goal)
    assert ans.causes == [g.GOAL_UNREACHABLE] and "inflated border" in ans.text


def test_a_goal_off_the_map_is_outside_it(tmp_path: Path) -> None:
    ans = failed_goal(tmp_path, START, (30.0, 30.0))
    assert ans.causes == [g.GOAL_UNREACHABLE] and read_claims(ans.text).causes == {g.GOAL_UNREACHABLE}
    assert "outside my global costmap" in ans.text and "x -10.0 to 9.2 m" in ans.text


def test_a_position_estimate_inside_a_wall_is_a_start_in_an_obstacle(tmp_path: Path) -> None:
    start = nearest(STATIC, 100, -1.3, -1.0)
    ans = failed_goal(tmp_path, start, FREE_GOAL)
    assert ans.causes == [g.START_IN_OBSTACLE] and read_claims(ans.text).causes == {g.START_IN_OBSTACLE}
    assert "a wall of my map itself" in ans.text and "position estimate was probably wrong" in ans.text


def test_obstacles_only_the_costmap_holds_block_the_way(tmp_path: Path) -> None:
    # boxes around the goal that the sensors saw: on the costmap, not on map_server's map
    boxed = ring(STATIC, *FREE_GOAL, radius=0.45)
    ans = failed_goal(tmp_path, START, FREE_GOAL, cost=costmap(boxed, RES))
    assert ans.causes == [g.BLOCKED] and read_claims(ans.text).causes == {g.BLOCKED}
    assert "no free way joined them" in ans.text


def test_a_goal_the_map_itself_closes_off_is_unreachable(tmp_path: Path) -> None:
    walled = ring(STATIC, *FREE_GOAL, radius=0.45)
    ans = failed_goal(tmp_path, START, FREE_GOAL, static=walled, cost=costmap(walled, RES))
    assert ans.causes == [g.GOAL_UNREACHABLE] and read_claims(ans.text).causes == {g.GOAL_UNREACHABLE}
    assert "closes off" in ans.text


def test_a_free_way_is_told_and_no_obstacle_is_claimed(tmp_path: Path) -> None:
    ans = failed_goal(tmp_path, START, FREE_GOAL)
    assert ans.causes == [UNEXPLAINED] and read_claims(ans.text).causes <= {UNEXPLAINED}
    assert "free way between them" in ans.text and "planner's own limits" in ans.text
    assert PLAN_CANDIDATES not in ans.text


def test_without_a_recorded_grid_the_candidates_are_named_as_before(tmp_path: Path) -> None:
    ans = failed_goal(tmp_path, START, nearest(STATIC, 100, 1.3, 1.0), static=None, cost=None)
    assert ans.causes == [UNEXPLAINED] and PLAN_CANDIDATES in ans.text


def test_map_server_map_alone_is_read_when_no_costmap_was_recorded(tmp_path: Path) -> None:
    ans = failed_goal(tmp_path, START, nearest(STATIC, 100, 1.3, 1.0), cost=None)
    assert ans.causes == [g.GOAL_UNREACHABLE] and "in my map" in ans.text


def test_a_replan_far_from_the_start_without_a_pose_is_not_placed(tmp_path: Path) -> None:
    # no /amcl_pose: the begin line gives where the robot stood only for the first plan, which this is; a start
    # inside a wall is still found from it
    start = nearest(STATIC, 100, -1.3, -1.0)
    ans = failed_goal(tmp_path, start, FREE_GOAL, amcl=False)
    assert ans.causes == [g.START_IN_OBSTACLE]


def test_a_goal_pose_in_another_frame_is_not_placed_on_the_map(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import TYPESTORE

    T = TYPESTORE.types
    b = BagBuilder()
    record_grids(b, T0, STATIC, COST, RES, ORIGIN)
    goal = T["geometry_msgs/msg/PoseStamped"](
        header=T["std_msgs/msg/Header"](stamp=T["builtin_interfaces/msg/Time"](sec=1_700_000_001, nanosec=0),
                                        frame_id="odom"),
        pose=T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=30.0, y=30.0, z=0.0),
                                         orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)))
    b.raw(T0 + sec_ns(1.0), c.GOAL_POSE, c.POSE_STAMPED_TYPE, goal)
    b.pose(T0 + sec_ns(0.5), *START, 0.0, 0.02, 0.02, 0.01)
    b.log(T0 + sec_ns(1.1), "planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50.")
    b.log(T0 + sec_ns(3.0), "bt_navigator", ERROR, "Goal failed")
    log = read_recording(b.write(tmp_path / "run"))
    ans = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    assert g.GOAL_UNREACHABLE not in ans.causes and "outside my global costmap" not in ans.text


def test_a_grid_that_does_not_hold_its_cells_is_left_out_with_a_warning(tmp_path: Path) -> None:
    b = BagBuilder()
    bad = grid_msg(T0, STATIC, RES, ORIGIN)
    bad.data = bad.data[:-7]
    b.raw(T0, c.GLOBAL_COSTMAP, c.GRID_TYPE, bad)
    b.log(T0 + sec_ns(1), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 0.00)")
    log = read_recording(b.write(tmp_path / "run"))
    assert log.grids == [] and any("left out a grid of 384 x 384 cells" in w for w in log.warnings)


def test_an_unchanged_costmap_is_kept_once(tmp_path: Path) -> None:
    b = BagBuilder()
    for i in range(5):
        record_grids(b, T0 + sec_ns(i), None, COST, RES, ORIGIN)
    record_grids(b, T0 + sec_ns(5), None, ring(COST, *FREE_GOAL, radius=0.45), RES, ORIGIN)
    b.log(T0 + sec_ns(6), "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 0.00)")
    log = read_recording(b.write(tmp_path / "run"))
    assert [grid.t for grid in log.grids] == [T0, T0 + sec_ns(5)]
