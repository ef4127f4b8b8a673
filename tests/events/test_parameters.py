"""/parameter_events: every node's parameters as it declared them, and every later change, read from real rosbag2
recordings (one made by someone else, others written with rosbags in both storage formats)."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events import read_recording

T0 = 1_741_600_000 * 1_000_000_000


def test_a_real_recording_gives_each_nodes_declared_parameters(real_bags: Path) -> None:
    log = read_recording(real_bags / "gps_vehicle_run")
    held = {(p.node, p.name): p for p in log.parameters}
    assert len(log.parameters) == 13
    assert held[("/motion_spec_provider", "look_ahead_dist")].value == 3.0
    assert held[("/stanley_controller", "L_wheelbase_m")].said == "0.33"
    assert held[("/route_pose_provider", "want_loop")].value is False
    assert held[("/route_pose_provider", "pose_filename")].said.startswith("'/home/")
    assert {p.change for p in log.parameters} == {"new"}
    assert sum(p.name == "use_sim_time" and p.value is False for p in log.parameters) == 5
    assert [p.t for p in log.parameters] == sorted(p.t for p in log.parameters)


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_every_value_kind_and_every_change_is_read(tmp_path: Path, storage: str) -> None:
    b = BagBuilder()
    b.parameters(T0, "/controller_server", new={
        "use_sim_time": True, "odom_topic_count": 3, "failure_tolerance": 0.3, "odom_topic": "odom",
        "goal_checker_plugins": ["general_goal_checker"], "FollowPath.footprint": [0.1, -0.1],
        "ids": [4, 5]})
    b.parameters(T0 + sec_ns(5), "/controller_server", changed={"failure_tolerance": 0.5})
    b.parameters(T0 + sec_ns(6), "/controller_server", deleted=["ids"])
    b.log(T0 + sec_ns(7), "controller_server", 20, "Received a goal, begin computing control effort.")
    log = read_recording(b.write(tmp_path / "run", storage))  # type: ignore[arg-type]
    said = [(p.name, p.said, p.change) for p in log.parameters]
    assert said == [
        ("use_sim_time", "true", "new"), ("odom_topic_count", "3", "new"), ("failure_tolerance", "0.3", "new"),
        ("odom_topic", "'odom'", "new"), ("goal_checker_plugins", "['general_goal_checker']", "new"),
        ("FollowPath.footprint", "[0.1, -0.1]", "new"), ("ids", "[4, 5]", "new"),
        ("failure_tolerance", "0.5", "changed"), ("ids", "not set", "deleted")]
    assert log.topics[c.PARAMETER_EVENTS].count == 3
    assert not log.warnings


def test_another_type_on_the_parameter_topic_is_skipped_not_refused(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import TYPESTORE

    b = BagBuilder()
    b.raw(T0, c.PARAMETER_EVENTS, c.STRING_TYPE, TYPESTORE.types[c.STRING_TYPE](data="use_sim_time: true"))
    b.log(T0 + sec_ns(1), "amcl", 20, "Configuring")
    log = read_recording(b.write(tmp_path / "run"))
    assert log.parameters == []
    assert any(w.startswith(f"skipped {c.PARAMETER_EVENTS}: type std_msgs/msg/String") for w in log.warnings)
