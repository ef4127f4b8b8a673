"""A map that could not be saved: nav2_map_server's map_saver got no map in time, read from its real lines (spent
blind16: Adlink-ROS/neuronbot2#15 and rt-net/raspimouse_ros2_examples#38 on Foxy, ros-navigation/navigation2#3048 on
Galactic with gmapping's volatile map)."""

from __future__ import annotations

from pathlib import Path

from hexar.claims import read_claims
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.navigation import diagnose as g
from tests.explainers.helpers import Line, explain, write_lines

FOXY: list[Line] = [
    (0.0, "map_saver", WARN, "Free threshold unspecified. Setting it to default value: 0.250000"),
    (0.0, "map_saver", WARN, "Occupied threshold unspecified. Setting it to default value: 0.650000"),
    (2.0, "map_saver", ERROR, "Failed to save the map: timeout"),
    (2.0, "map_saver", INFO, "Destroying"),
]
GALACTIC: list[Line] = [
    (0.0, "map_saver", INFO, "Saving map from 'map' topic to 'WHEELTEC' file"),
    (0.0, "map_saver", WARN, "Free threshold unspecified. Setting it to default value: 0.250000"),
    (0.01, "map_saver", WARN, "New publisher discovered on topic '/map', offering incompatible QoS. No messages will "
     "be sent to it. Last incompatible policy: DURABILITY_QOS_POLICY"),
    (2.01, "map_saver", ERROR, "Failed to spin map subscription"),
    (2.01, "map_saver", INFO, "Destroying"),
]


def test_a_map_saver_that_got_no_map_in_time_is_its_wait_against_the_maps_publication(tmp_path: Path) -> None:
    _, found = explain(write_lines(tmp_path, FOXY), "navigation", "What went wrong?")
    assert found.causes == [g.CONFIGURATION]
    assert read_claims(found.text).affirmed == {g.CONFIGURATION}
    assert found.text.startswith("I couldn't save my map") and "2000 ms by default on Foxy" in found.text
    assert "“[map_saver] Failed to save the map: timeout”" in found.text and "nothing published a map" in found.text
    assert found.fix is not None and "save_map_timeout:=10000" in found.fix
    assert [e.item for e in found.evidence][-1].endswith("Failed to save the map: timeout")


def test_a_durability_mismatch_before_it_is_the_reason(tmp_path: Path) -> None:
    _, found = explain(write_lines(tmp_path, GALACTIC), "navigation", "Why did it fail?")
    assert found.causes == [g.CONFIGURATION]
    assert "the durability of their QoS" in found.text and "Failed to spin map subscription" in found.text
    assert found.fix is not None and "map_subscribe_transient_local:=false" in found.fix
    assert len(found.evidence) == 2


def test_map_savers_lines_do_not_explain_a_navigation_goal(tmp_path: Path) -> None:
    nav: list[Line] = [
        (3.0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (4.20, 2.10)"),
        (9.0, "controller_server", ERROR, "Failed to make progress"),
        (9.5, "bt_navigator", ERROR, "Goal failed"),
    ]
    _, found = explain(write_lines(tmp_path, FOXY + nav), "navigation", "Why didn't you get there?")
    assert "save my map" not in found.text and g.CONFIGURATION not in found.causes
