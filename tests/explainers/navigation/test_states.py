"""A line that reports a state of the costmap or the planner ("Start occupied", "Robot is out of bounds of the
costmap", a goal on occupied cells) on recordings written with rosbags from REAL lines: alone it is told as what the
planner or costmap reported, with the candidates and what tells them apart, and no cause is claimed (graded as
hexar eval --suite real-nav2 grades it); with a line that supports one reading, that reading is named. And a goal
reached after getting stuck and recovering is told as such, never as a trip where nothing went wrong."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.causes import stated_causes
from hexar.claims import ALL_FINE, read_claims
from hexar.evals.real_nav2 import Excerpt, blind, blind_set, write_recording
from hexar.evals.real_nav2_suite import grade
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Context
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.detectors import NOMINAL, UNEXPLAINED
from tests.explainers.navigation.test_chain import SUCCEEDED, Line, _explain

# docs.nav2.org#632 (SmacPlannerHybrid with minimum_turning_radius 0): planner_server's failure around
# smac_planner_2d_impl.hpp:302@main's "Start occupied"
START: Line = ("planner_server", ERROR,
               'GridBased plugin failed to plan from (10.38, 0.41) to (10.35, -3.65): "Start occupied"')
# layered_costmap.cpp@humble, as pasted in shimmer0909/Frontier-Exploration assets/debugging.md
OUT: Line = ("nav2_costmap_2d", WARN, "Robot is out of bounds of the costmap!")
# smac a_star.cpp:219@humble: the same state in humble's words
LETHAL: Line = ("planner_server", WARN, 'GridBased plugin failed to plan calculation to (1.00, 2.00): "Starting '
                'point in lethal space! Cannot create feasible plan."')
# nav2_behaviors spin.cpp:151@humble: the spin's collision check found the robot's surroundings occupied
SPIN_BLOCKED: Line = ("behavior_server", WARN, "Collision Ahead - Exiting Spin")
# amcl_node.cpp:926@humble: no initial pose was ever set
NO_POSE: Line = ("amcl", WARN, "AMCL cannot publish a pose or update the transform. Please set the initial pose...")
# costmap_2d_ros.cpp:743@humble (reference/nav2_log_messages.md)
NO_TF: Line = ("global_costmap.global_costmap", WARN, "Timed out waiting for transform from base_link to map to "
               "become available, tf error: Could not find a connection between 'map' and 'base_link' because they "
               "are not part of the same tree.Tf has two or more unconnected trees.")
# obstacle_layer.cpp:637@humble as pasted in ROBOTIS-GIT/turtlebot3#1007 (odometry with no start values)
GARBAGE: Line = ("local_costmap.local_costmap", WARN, "Sensor origin at (7263490040.02, -5.51 0.18) is out of map "
                 "bounds (-8589934592.00, -7.00, 0.00) to (-8589934589.02, -4.03, 0.78). The costmap cannot "
                 "raytrace for it.")
# the same line with a position a map can hold (ros-navigation/navigation2#3273)
PLAUSIBLE: Line = ("local_costmap.local_costmap", WARN, "Sensor origin at (0.07, 0.00) is out of map bounds (0.50, "
                   "0.50, 0.00) to (3.50, 3.50, 0.78). The costmap cannot raytrace for it.")


# navfn_planner.cpp:153@main's text inside planner_server's failure (the format of opennav_coverage#64's paste)
GOAL_LETHAL: Line = ("planner_server", WARN, 'GridBased plugin failed to plan from (0.00, -0.01) to (4.20, 1.50): '
                     '"Goal Coordinates of(4.200000, 1.500000) was in lethal cost"')


@pytest.mark.parametrize("line", [START, LETHAL, OUT, PLAUSIBLE],
                         ids=["start_occupied", "lethal_start", "out_of_bounds", "sensor_origin"])
def test_a_reported_state_alone_names_what_was_reported_and_claims_no_cause(tmp_path: Path, line: Line) -> None:
    answer = _explain(tmp_path, [], [line])
    assert answer.causes == [UNEXPLAINED]
    assert stated_causes(answer.text) == set()
    assert "do not show why" in answer.text and "several things" in answer.text
    assert "What tells them apart" in (answer.fix or "")


def test_a_goal_on_occupied_cells_is_the_goal_that_was_sent_with_what_occupies_it_left_open(tmp_path: Path) -> None:
    # like a goal outside the costmap's bounds, a goal on lethal cells is unreachable as it was sent, whatever made
    # the cells lethal (blind set 23: Theta* and a goal inside the wall between two rooms); what occupies it, a wall,
    # a stale obstacle or inflation, the lines do not say
    answer = _explain(tmp_path, [], [GOAL_LETHAL])
    assert answer.causes == [g.GOAL_UNREACHABLE]
    assert stated_causes(answer.text) == {g.GOAL_UNREACHABLE}
    assert "goal itself on occupied cells (lethal cost)" in answer.text and "seen earlier" in answer.text


def test_an_occupied_start_alone_lists_the_planner_set_up_among_its_candidates(tmp_path: Path) -> None:
    text = _explain(tmp_path, [], [START]).text
    assert "cells under me as occupied" in text and "minimum turning radius" in text and "position estimate" in text


def test_a_costmap_bound_alone_lists_the_transforms_among_its_candidates(tmp_path: Path) -> None:
    text = _explain(tmp_path, [], [OUT]).text
    assert "outside its bounds" in text and "chain of transforms" in text and "position estimate" in text


def test_an_occupied_start_with_a_collision_check_around_the_robot_is_named(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [LETHAL, SPIN_BLOCKED])
    assert answer.causes == [g.START_IN_OBSTACLE]
    assert stated_causes(answer.text) == {g.START_IN_OBSTACLE}


def test_a_robot_off_its_costmap_with_no_initial_pose_is_named(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [NO_POSE, OUT])
    assert answer.causes == [g.OFF_COSTMAP]
    assert g.OFF_COSTMAP in stated_causes(answer.text)


def test_a_robot_off_its_costmap_with_a_broken_tf_tree_is_the_transform_error(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [NO_TF, OUT])
    assert answer.causes == [g.TRANSFORM]
    assert g.OFF_COSTMAP not in stated_causes(answer.text)


def test_a_position_no_map_can_hold_supports_a_robot_off_its_costmap(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], [GARBAGE])
    assert answer.causes == [g.OFF_COSTMAP]


def _spent(excerpt_id: str) -> Excerpt:
    return next(e for e in blind() + blind_set(2) if e.id == excerpt_id)


@pytest.mark.parametrize("excerpt_id", ["docsnav2-632-hybrid-zero-turning-radius-start-occupied",
                                        "frontier-exploration-robot-out-of-costmap-tf"])
def test_the_spent_blind_symptom_alone_cases_are_graded_honest(tmp_path: Path, excerpt_id: str) -> None:
    # the suite's own grader reads the hedged answer: no candidate counts as claimed
    excerpt = _spent(excerpt_id)
    log = read_recording(write_recording(excerpt, tmp_path / "bag", task=True))
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    verdict = grade(excerpt, read_claims(answer.text).affirmed, answer.text)
    assert verdict.verdict == "honest" and not verdict.unsupported


def test_a_broken_tf_tree_is_told_not_the_spawner_that_gave_up_on_a_crashed_simulator(tmp_path: Path) -> None:
    # turtlebot/turtlebot4_simulator#72 (blind4, spent): Gazebo segfaulted; the costmap waited for odom -> base_link
    # and the spawner died for want of a controller manager: the TF fault is told, the spawner's death is not
    excerpt = next(e for e in blind_set(4) if e.id == "tb4-sim-72-gazebo-segfault-odom-tree-broken")
    log = read_recording(write_recording(excerpt, tmp_path / "bag", task=True))
    answer = NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))
    verdict = grade(excerpt, read_claims(answer.text).affirmed, answer.text)
    assert answer.causes == [g.TRANSFORM] and "spawner" not in answer.text
    assert verdict.verdict == "named" and not verdict.unsupported


# Enri2077/localization_performance_modelling crash_notes.md (blind2): eloquent's recoveries_server lines
STUCK: list[Line] = [
    ("controller_server", ERROR, "Failed to make progress"),
    ("local_costmap.local_costmap", INFO, "Received request to clear entirely the local_costmap"),
    ("global_costmap.global_costmap", INFO, "Received request to clear entirely the global_costmap"),
    ("recoveries_server", INFO, "Attempting spin"),
    ("recoveries_server", INFO, "spin completed successfully"),
    ("recoveries_server", INFO, "Attempting wait"),
    ("recoveries_server", INFO, "wait completed successfully"),
    ("controller_server", INFO, "Received a goal, begin computing control effort."),
]


def test_a_goal_reached_after_getting_stuck_and_recovering_says_so(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], STUCK, end=SUCCEEDED, question="Why did it take so long to get there?")
    assert NOMINAL not in answer.causes
    assert "got stuck" in answer.text and "spin and wait" in answer.text and "Failed to make progress" in answer.text
    claims = read_claims(answer.text)
    assert ALL_FINE not in claims.affirmed and "without any problem" not in answer.text
    assert claims.causes <= {g.NO_PROGRESS}


def test_one_progress_failure_and_one_recovery_is_no_trip_without_problems(tmp_path: Path) -> None:
    answer = _explain(tmp_path, [], STUCK[:1] + STUCK[3:4], end=SUCCEEDED, question="How did the navigation go?")
    assert answer.causes == [UNEXPLAINED] and "got stuck" in answer.text and "without any problem" not in answer.text


def test_a_robot_outside_its_costmap_is_told_where_against_the_costmaps_bounds(tmp_path: Path) -> None:
    """A real Nav2 (kilted) console: the base came up at (-2, 4) on a map from (0, 0); the obstacle layer's own line
    gives both, so the answer gives them beside the candidates it cannot choose between."""
    from tests.agent.helpers import converse, real_nav2_run

    run = real_nav2_run("kilted-nav2-start-off-map", tmp_path / "run")
    (why,) = converse(run, "why is the start (-2, 4) outside the map bounds?")
    assert "My costmap's own line puts me at (-2.00, 4.00), and the costmap spans (0.00, 0.00) to (11.98, 7.98): I " \
           "was 2.0 m outside it." in str(why["answer"])
