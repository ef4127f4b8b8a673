"""Every topic HEXAR subscribes to crosses DDS vendors, in both directions: a robot on rclpy (Fast DDS) is heard
by the Cyclone transport and a robot on Cyclone by the rclpy transport, one message of each type, with their
fields intact (a `byte` level, 36 covariances, a 16-byte goal id); and HEXAR's answers on /hexar/answer reach
an rclpy subscriber from the Cyclone transport. Before, Cyclone refused Fast DDS's type objects for every type
with a sequence or an array (PoseWithCovarianceStamped, DiagnosticArray, Odometry, GoalStatusArray)."""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.records import INFO
from hexar.live.log import LiveLog
from hexar.live.replay import replay as replay_in_process
from hexar.live.topics import ANSWER, ANSWER_QOS, ARM_STATUS, SUBSCRIBED
from tests.explainers.navigation.maps import grid_msg
from tests.live.dds_helpers import fresh_domain, make_replayer, make_transport
from tests.live.test_nav2_topics import T0, TY, _odom, _pose, _status, _time, _twist

pytest.importorskip("rclpy")

# same stamps whatever the sender's clock
STAMPED = ("logs", "poses", "statuses", "odometry", "goals", "grids", "parameters")


def every_type(out: Path) -> Path:
    """A recording with one message on each subscribed topic."""
    b = BagBuilder()
    b.log(T0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    b.task_info(T0 + sec_ns(0.1), {"instruction": "go", "task_id": "t1", "task_status": "valid",
                                   "task_error_msg": "", "skill_sequence": [
                                       {"skill": "navigate_to_zone", "params": {"location": "kitchen"},
                                        "status": "running", "error_msg": ""}]})
    b.pose(T0 + sec_ns(0.2), 1.0, 2.0, 0.5, 0.25, 0.3, 0.1)
    b.flag(T0 + sec_ns(0.3), c.JOY_PRIORITY, True)
    b.flag(T0 + sec_ns(0.4), c.IS_CHARGING, False)
    for i, topic in enumerate((c.EPISODIC_MEMORY, c.DIAGNOSTICS, c.SAY_EVENTS, c.PIZZA_EVENTS)):
        b.status(T0 + sec_ns(0.5 + i * 0.1), topic, f"status {i}", "a message", [("key", f"value {i}")], level=2)
    b.raw(T0 + sec_ns(1.0), c.CMD_VEL, c.TWIST_TYPE, _twist(0.26, 0.1))
    b.raw(T0 + sec_ns(1.1), c.ODOM, c.ODOM_TYPE, _odom(T0 + sec_ns(1.1), 0.5, 0.2))
    b.raw(T0 + sec_ns(1.2), c.GOAL_POSE, c.POSE_STAMPED_TYPE, TY["geometry_msgs/msg/PoseStamped"](
        header=TY["std_msgs/msg/Header"](stamp=_time(T0 + sec_ns(1.2)), frame_id="map"), pose=_pose(1.0, 2.0)))
    b.raw(T0 + sec_ns(1.3), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(1.3), 2))
    for i, topic in enumerate(sorted(ARM_STATUS)):  # MoveIt's and the arm controllers' action status topics
        b.raw(T0 + sec_ns(1.4 + i * 0.1), topic, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(1.4 + i * 0.1), 2))
    # the maps: every cell value a costmap publishes (-1 unknown, 0 free, 1-98 cost, 99 inscribed, 100 lethal)
    cells = np.array([[-1, 0, 1], [50, 98, 99], [100, 100, 0], [0, -1, 7]], dtype=np.int8)
    for i, topic in enumerate((c.MAP, c.GLOBAL_COSTMAP, c.KEEPOUT_MASK)):
        t = T0 + sec_ns(2.5 + i * 0.1)
        b.raw(t, topic, c.GRID_TYPE, grid_msg(t, cells, 0.05, (-1.5, 2.25)))
    # a node's parameters: every kind of value a ParameterValue holds but bytes, and a change
    b.parameters(T0 + sec_ns(2.9), "/amcl", new={"use_sim_time": True, "max_particles": 2000, "alpha1": 0.2,
                                                 "base_frame_id": "base_footprint", "plugins": ["a", "b"],
                                                 "footprint": [0.1, -0.1], "ids": [4, 5]},
                 changed={"alpha1": 0.3}, deleted=["ids"])
    return b.write(out)


def unstamped(records: list[Any]) -> list[Any]:
    return [dataclasses.replace(r, t=0) for r in records]


@pytest.mark.parametrize(("robot", "node"), [("rclpy", "dds"), ("dds", "rclpy")])
def test_every_subscribed_type_crosses_dds_vendors(tmp_path: Path, robot: str, node: str) -> None:
    from hexar.events.reader import read_recording

    run = every_type(tmp_path / "robot")
    rec = read_recording(run)
    domain = fresh_domain()
    transport, log = make_transport(node, domain), LiveLog()
    transport.start(log, lambda r: None, lambda q: None)
    writer = make_replayer(robot, domain)
    try:
        replay_in_process(run, writer, rate=2.0)
        writer.close()
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline and len(log.snapshot().topics) < len(SUBSCRIBED):
            time.sleep(0.05)
        time.sleep(0.3)
    finally:
        transport.close()
    snap = log.snapshot()
    # the live log counts records: the one parameter event carries 9 (7 declared, 1 set, 1 undeclared)
    assert {t: info.count for t, info in snap.topics.items()} == {
        spec.topic: 9 if spec.topic == c.PARAMETER_EVENTS else 1 for spec in SUBSCRIBED}
    assert transport.errors == 0  # type: ignore[attr-defined]
    for name in STAMPED:
        assert getattr(snap, name) == getattr(rec, name), name
    assert [s.level for s in snap.statuses[c.DIAGNOSTICS]] == [2]  # an octet, not b'\x02'
    assert (snap.poses[0].cov_x, snap.poses[0].cov_yaw) == (0.25, 0.1)
    assert [p.said for p in snap.parameters][:4] == ["true", "2000", "0.2", "'base_footprint'"]
    assert [g.value(-1.5 + 0.125, 2.25 + 0.075) for g in snap.grids] == [99, 99, 99]  # a signed cell, in its place
    assert unstamped(snap.task_updates) == unstamped(rec.task_updates)
    assert {k: unstamped(v) for k, v in snap.flags.items()} == {k: unstamped(v) for k, v in rec.flags.items()}
    assert unstamped(snap.twists) == unstamped(rec.twists)
    assert unstamped(snap.goal_statuses) == unstamped(rec.goal_statuses)


def test_answers_from_cyclone_reach_an_rclpy_subscriber() -> None:
    from hexar.live.dds import DdsTransport
    from hexar.live.ros import RosNode, msg_class, qos_profile

    domain = fresh_domain()
    hexar = DdsTransport(domain)
    heard: list[str] = []
    display = RosNode("display", domain)
    display.node.create_subscription(msg_class(c.STRING_TYPE), ANSWER, lambda m: heard.append(m.data),
                                     qos_profile(ANSWER_QOS))
    display.spin(print)
    try:
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline and not hexar._answer.get_matched_subscriptions():
            time.sleep(0.05)
        hexar.publish(ANSWER, '{"answer": "I was plugged into my charger."}')
        while time.monotonic() < deadline and not heard:
            time.sleep(0.05)
    finally:
        display.close()
        hexar.close()
    assert heard == ['{"answer": "I was plugged into my charger."}']
