"""A global costmap that never received its map (Xyntexx/ROS2-Hector-SLAM-NAV2-Demo's nav2_log.txt, Jazzy; spent
blind14): the static layer's "no map received", the robot outside the costmap's default bounds, and the planner's
"Costmap timed out waiting for update", which that missing map explains, not stale transforms."""

from __future__ import annotations

from pathlib import Path

from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.navigation import diagnose as g
from tests.events.helpers import task_msg
from tests.explainers.helpers import T0, Line, explain, write_lines

QOS = ("New publisher discovered on topic '/map', offering incompatible QoS. No messages will be sent to it. Last "
       "incompatible policy: DURABILITY_QOS_POLICY")
TIMEOUT = 'GridBased plugin failed to plan from (0.00, 0.00) to (1.82, 1.14): "Costmap timed out waiting for update"'
HECTOR: list[Line] = [
    (0.0, "global_costmap.global_costmap", WARN, QOS),
    (1.6, "nav2_costmap_2d", WARN, "Robot is out of bounds of the costmap!"),
    (1.6, "global_costmap.global_costmap", WARN, "Sensor origin at (-0.03, 0.00) is out of map bounds (0.00, 0.00) "
     "to (4.98, 4.98). The costmap cannot raytrace for it."),
    (10.6, "global_costmap.global_costmap", WARN, "Can't update static costmap layer, no map received"),
    (93.7, "bt_navigator", INFO, "Begin navigating from current location (3.02, 0.74) to (1.82, 1.14)"),
    (94.7, "planner_server", WARN, TIMEOUT),
    (94.7, "planner_server", WARN, "[compute_path_to_pose] [ActionServer] Aborting handle."),
    (95.8, "planner_server", WARN, TIMEOUT),
    (100.6, "global_costmap.global_costmap", WARN, "Can't update static costmap layer, no map received"),
    (108.5, "bt_navigator", ERROR, "Goal failed"),
]


def _with_task(tmp_path: Path, lines: list[Line]) -> BagBuilder:
    b = BagBuilder()
    for s, status in ((-1.0, "waiting"), (-0.5, "Running"), (110.0, "failed")):
        b.task_info(T0 + sec_ns(s), task_msg("Zq3J9kLm0pQr7sT1", "go to the kitchen",
                                             [("navigate_to_zone", {"location": "kitchen"}, status, "")]))
    return b


def test_a_costmap_that_never_got_its_map_is_the_robot_off_it(tmp_path: Path) -> None:
    _, found = explain(write_lines(tmp_path, HECTOR, _with_task(tmp_path, HECTOR)), "navigation",
                       "Why didn't you get there?")
    assert found.causes == [g.OFF_COSTMAP]
    assert read_claims(found.text).affirmed - {"claim.task_failed"} == {g.OFF_COSTMAP}
    assert "never received its map" in found.text and "the durability of their QoS" in found.text


def test_without_the_static_layers_word_the_timeout_is_still_a_stale_costmap(tmp_path: Path) -> None:
    lines = [ln for ln in HECTOR if "no map received" not in ln[3] and ln[3] != QOS]
    _, found = explain(write_lines(tmp_path, lines, _with_task(tmp_path, lines)), "navigation",
                       "Why didn't you get there?")
    assert found.causes == [g.TRANSFORM] and "never received its map" not in found.text


def test_a_map_that_came_after_the_warning_is_no_missing_map(tmp_path: Path) -> None:
    # the static layer stops warning once a map comes and says so (static_layer.cpp:203@humble, INFO)
    came: Line = (50.0, "global_costmap.global_costmap", INFO,
                  "StaticLayer: Resizing costmap to 384 X 384 at 0.050000 m/pix")
    lines = sorted([ln for ln in HECTOR if ln[0] != 100.6] + [came], key=lambda ln: ln[0])
    _, found = explain(write_lines(tmp_path, lines, _with_task(tmp_path, lines)), "navigation",
                       "Why didn't you get there?")
    assert "never received its map" not in found.text
    assert g.OFF_COSTMAP not in read_claims(found.text).affirmed


def test_another_costmaps_map_does_not_answer_for_this_one(tmp_path: Path) -> None:
    came: Line = (50.0, "local_costmap.local_costmap", INFO,
                  "StaticLayer: Resizing costmap to 384 X 384 at 0.050000 m/pix")
    lines = sorted([*HECTOR, came], key=lambda ln: ln[0])
    _, found = explain(write_lines(tmp_path, lines, _with_task(tmp_path, lines)), "navigation",
                       "Why didn't you get there?")
    assert found.causes == [g.OFF_COSTMAP] and "never received its map" in found.text
