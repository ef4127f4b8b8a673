"""The fast way of reading (events.bag's storages, QoS texts parsed once; rows straight from storage) gives the same
events as rosbags' own reader on real recordings written with rosbags, offered QoS and all, in sqlite3 and MCAP;
a QoS text rosbags cannot parse fails the same way, every time."""

from __future__ import annotations

import sqlite3
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from rosbags.highlevel import AnyReader
from rosbags.interfaces import Qos, QosDurability, QosHistory, QosLiveliness, QosReliability, QosTime
from rosbags.rosbag2 import StoragePlugin, Writer

from hexar.evals.cases import scenarios
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.evals.scenarios.suite import record
from hexar.events import bag
from hexar.events import contract as c
from hexar.events.errors import CorruptRecordingError
from hexar.events.humble import humble
from hexar.events.log import EventLog
from hexar.events.reader import _read_skipping, read_recording

T = TYPESTORE.types


def _qos(reliability: QosReliability, durability: QosDurability, depth: int) -> Qos:
    never = QosTime(0x7FFFFFFF, 0xFFFFFFFF)  # rosbag2's "infinite" deadline and lifespan
    return Qos(QosHistory.KEEP_LAST, depth, reliability, durability, never, never, QosLiveliness.AUTOMATIC, never,
               False)


# what Nav2 and rosout publishers offer: latched task and map-like topics, reliable logs, best-effort sensors
LATCHED = [_qos(QosReliability.RELIABLE, QosDurability.TRANSIENT_LOCAL, 1)]
RELIABLE = [_qos(QosReliability.RELIABLE, QosDurability.VOLATILE, 1000)]
SENSOR = [_qos(QosReliability.BEST_EFFORT, QosDurability.VOLATILE, 5),
          _qos(QosReliability.RELIABLE, QosDurability.VOLATILE, 10)]  # two publishers on one topic


def _offered(topic: str) -> list[Qos]:
    if topic in (c.TASK_INFO, c.JOY_PRIORITY):
        return LATCHED
    return SENSOR if topic in (c.ODOM, "/amcl_pose") else RELIABLE


def _with_motion(b: BagBuilder) -> None:
    """Velocity commands and odometry over the run, which the simulated scenarios leave out."""
    t0, t1 = min(m[0] for m in b.messages), max(m[0] for m in b.messages)
    for i in range(40):
        t = t0 + (t1 - t0) * i // 40
        stamp = T["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)
        header = T["std_msgs/msg/Header"](stamp=stamp, frame_id="odom")
        twist = T["geometry_msgs/msg/Twist"](linear=T["geometry_msgs/msg/Vector3"](x=0.3, y=0.0, z=0.0),
                                             angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.1 * i))
        point = T["geometry_msgs/msg/Point"](x=0.01 * i, y=0.02 * i, z=0.0)
        pose = T["geometry_msgs/msg/Pose"](position=point, orientation=T["geometry_msgs/msg/Quaternion"](
            x=0.0, y=0.0, z=0.0, w=1.0))
        odom = T["nav_msgs/msg/Odometry"](
            header=header, child_frame_id="base_footprint",
            pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.zeros(36)),
            twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=np.zeros(36)))
        b.raw(t, c.CMD_VEL, c.TWIST_TYPE, twist)
        b.raw(t + 1000, c.ODOM, c.ODOM_TYPE, odom)


def _write(scenario: int, out: Path, storage: str) -> Path:
    """A simulated run of one scenario, with motion, written by rosbags' Writer with each topic's offered QoS."""
    b = record(scenarios()[scenario], 1, 0)
    _with_motion(b)
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    with Writer(out, version=9, storage_plugin=plugin) as writer:
        conns: dict[tuple[str, str], Any] = {}
        for t, topic, msgtype, msg in sorted(b.messages, key=lambda m: m[0]):
            if (topic, msgtype) not in conns:
                conns[topic, msgtype] = writer.add_connection(topic, msgtype, typestore=TYPESTORE,
                                                              offered_qos_profiles=_offered(topic))
            writer.write(conns[topic, msgtype], t, TYPESTORE.serialize_cdr(msg, msgtype))
    return out


def _rosbags_way(path: Path) -> EventLog:
    """rosbags' AnyReader opened afresh, every message through its own time-ordered reader."""
    with AnyReader([path], default_typestore=humble()) as reader:
        return _read_skipping(reader, path, c.ALL_TOPICS, fast=False)[0]


def _storage_connections(cls: type[AnyReader], path: Path) -> list[Any]:
    with cls([path], default_typestore=humble()) as reader:
        return [[conn._replace(owner=None) for conn in storage.connections]
                for r in reader.readers for storage in r.storage.storages]


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_the_fast_way_reads_the_events_rosbags_reads(tmp_path: Path, storage: str) -> None:
    paths = [_write(n, tmp_path / f"run{n}", storage) for n in (0, 5, 11)]
    before = bag._qos_of_text.cache_info().hits + bag._mcap_qos_of.cache_info().hits
    for path in paths:
        fast, plain = read_recording(path), _rosbags_way(path)
        assert fast.tasks and fast.logs and fast.odometry and fast.poses  # a run with something to compare
        assert fast == plain
        assert _storage_connections(bag.Reader, path) == _storage_connections(AnyReader, path)
    # the QoS rosbags' storage parsed is what was offered, and the same texts were parsed once for every run
    stored = _storage_connections(bag.Reader, paths[0])[0]
    assert {conn.topic: conn.ext.offered_qos_profiles for conn in stored}[c.TASK_INFO] == LATCHED
    assert bag._qos_of_text.cache_info().hits + bag._mcap_qos_of.cache_info().hits > before


def test_a_qos_text_rosbags_cannot_parse_fails_as_rosbags_fails(tmp_path: Path) -> None:
    path = _write(0, tmp_path / "run", "sqlite3")
    db = sqlite3.connect(next(path.glob("*.db3")))
    db.execute("UPDATE topics SET offered_qos_profiles = ? WHERE name = ?", ("- history: [1", c.TASK_INFO))
    db.commit()
    db.close()
    errors = []
    for cls in (AnyReader, bag.Reader, bag.Reader):  # twice: a failed parse is not kept as an answer
        with pytest.raises(Exception) as err:  # the point: the same class and text from each
            _storage_connections(cls, path)
        errors.append((type(err.value), str(err.value)))
    assert errors[0] == errors[1] == errors[2]
    assert "offered_qos_profiles" in errors[0][1]
    with pytest.raises(CorruptRecordingError, match=r"cannot read .*offered_qos_profiles"):
        read_recording(path)
