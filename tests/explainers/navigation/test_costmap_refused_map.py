"""A costmap that refused its map: rclcpp's incompatible-QoS warning logged under the costmap's own node, for the map
topic, and no word of its static layer after it that a map came (spent blind17: ros-navigation/navigation2#4146,
Galactic, a map bridged from ROS 1 and published volatile against the static layer's transient-local subscription)."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import INFO, WARN
from hexar.explainers.navigation import diagnose as g
from tests.events.helpers import task_msg
from tests.explainers.helpers import T0, Line, explain, write_lines

QOS = ("New publisher discovered on topic '/map', offering incompatible QoS. No messages will be sent to it. Last "
       "incompatible policy: DURABILITY_QOS_POLICY")
REFUSED: list[Line] = [(0.5, "global_costmap.global_costmap", WARN, QOS)]


def _failed_trip(lines: list[Line]) -> BagBuilder:
    b = BagBuilder()
    for s, status in ((0.0, "Running"), (30.0, "failed")):
        b.task_info(T0 + sec_ns(s), task_msg("Q2w8Er5tYu1iOp3a", "go to the kitchen",
                                             [("navigate_to_zone", {"location": "kitchen"}, status, "")]))
    return b


def _ask(tmp_path: Path, lines: list[Line]) -> tuple[str, list[str], str | None]:
    _, found = explain(write_lines(tmp_path, lines, _failed_trip(lines)), "navigation", "Why didn't you get there?")
    return found.text, found.causes, found.fix


def test_a_costmap_that_refused_the_maps_publisher_is_a_configuration_problem(tmp_path: Path) -> None:
    text, causes, fix = _ask(tmp_path, REFUSED)
    assert causes == [g.CONFIGURATION]
    assert read_claims(text).affirmed == {g.CONFIGURATION}
    assert text.startswith("My global costmap never got my map: its subscription to /map did not match")
    assert "the durability of their QoS" in text and f"“[global_costmap.global_costmap] {QOS}”" in text
    assert fix is not None and "map_subscribe_transient_local: false" in fix


@pytest.mark.parametrize("said", ["StaticLayer: Received a 384 X 384 map at 0.050000 m/pix",  # DEBUG
                                  "StaticLayer: Resizing costmap to 384 X 384 at 0.050000 m/pix"])  # INFO
def test_a_map_that_came_later_is_no_such_finding(tmp_path: Path, said: str) -> None:
    # another publisher of the map (a map_server beside the bridge) may still serve the costmap
    text, causes, _ = _ask(tmp_path, [*REFUSED, (1.0, "global_costmap.global_costmap", INFO, said)])
    assert g.CONFIGURATION not in causes and "never got my map" not in text


def test_another_nodes_mismatch_is_not_the_costmaps(tmp_path: Path) -> None:
    # rclcpp logs the warning under the subscribing node: here rviz's, which the costmap's map does not depend on
    text, causes, _ = _ask(tmp_path, [(0.5, "rviz2", WARN, QOS)])
    assert g.CONFIGURATION not in causes and "never got my map" not in text
