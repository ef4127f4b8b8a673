"""`hexar replay` starts playing once the topics it sends are heard, on real DDS traffic from both vendors."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.records import INFO
from hexar.live.dds import DdsEndpoint
from hexar.live.replay import replay
from hexar.live.topics import SUBSCRIBED, TopicQos
from tests.live.conftest import NO_RCLPY
from tests.live.dds_helpers import fresh_domain, make_replayer

T0 = 1_700_000_000_000_000_000
TY = TYPESTORE.types
TWISTS = 20
QOS = {t.topic: t.qos for t in SUBSCRIBED}


def _driving(out: Path) -> Path:
    """A Nav2 robot without /task_info: one log line, then 2 s of velocity commands (a volatile topic)."""
    b = BagBuilder()
    b.log(T0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    for i in range(TWISTS):
        b.raw(T0 + sec_ns(0.1 * (i + 1)), c.CMD_VEL, c.TWIST_TYPE, TY["geometry_msgs/msg/Twist"](
            linear=TY["geometry_msgs/msg/Vector3"](x=0.2, y=0.0, z=0.0),
            angular=TY["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.1)))
    return b.write(out)


def _take(reader: Any, into: list[float], stop: threading.Event) -> None:
    while not stop.is_set():
        into.extend(float(s.linear.x) for s in reader.take(64) if s.sample_info.valid_data)
        time.sleep(0.01)


@pytest.mark.parametrize("kind", ["dds", pytest.param("rclpy", marks=NO_RCLPY)])
def test_a_volatile_topic_whose_reader_matches_late_loses_nothing(tmp_path: Path, kind: str) -> None:
    """A node's /rosout and /task_info readers matched at once, its /cmd_vel reader 1.5 s later (discovery on a
    busy machine): every velocity command still arrives. Waiting for /rosout and /task_info alone sent them all
    to nobody."""
    run = _driving(tmp_path / "drive")
    domain = fresh_domain()
    node = DdsEndpoint(domain)
    early = [node.reader(c.ROSOUT, c.LOG_TYPE, QOS[c.ROSOUT]), node.reader(c.TASK_INFO, c.STRING_TYPE,
                                                                           QOS[c.TASK_INFO])]
    heard: list[float] = []
    stop = threading.Event()

    def join_late() -> None:
        time.sleep(1.5)
        reader = node.reader(c.CMD_VEL, c.TWIST_TYPE, TopicQos(depth=100))
        _take(reader, heard, stop)

    late = threading.Thread(target=join_late, daemon=True)
    late.start()
    robot = make_replayer(kind, domain)
    try:
        stats = replay(run, robot, rate=10.0, warmup_s=30.0)
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline and len(heard) < TWISTS:
            time.sleep(0.02)
    finally:
        stop.set()
        late.join(5.0)
        robot.close()
        node.close()
    assert early and stats.published == TWISTS + 1 and stats.unmatched_topics == ()
    assert heard == [0.2] * TWISTS


def test_topics_nobody_reads_are_named_and_the_replay_still_plays(tmp_path: Path) -> None:
    run = _driving(tmp_path / "drive")
    robot = make_replayer("dds", fresh_domain())
    started = time.monotonic()
    try:
        stats = replay(run, robot, rate=20.0, warmup_s=0.5)
    finally:
        robot.close()
    assert stats.published == TWISTS + 1
    assert stats.unmatched_topics == (c.CMD_VEL, c.ROSOUT)  # /task_info is not in the recording: not waited for
    assert 0.5 <= time.monotonic() - started < 10.0
