"""ROS messages (DDS dataclasses or rclpy messages: the fields have the same names) into HEXAR's records."""

from __future__ import annotations

from typing import Any

from hexar.events import contract as c
from hexar.events.reader import _statuses, _yaw, parse_task_info
from hexar.events.records import BoolSample, LogLine, PoseSample, StatusRecord, TaskUpdate, stamp_ns

Record = LogLine | TaskUpdate | PoseSample | BoolSample | StatusRecord


def to_records(topic: str, msg: Any, t: int) -> list[Record]:
    """The records of one message on `topic`; `t` is the publisher's write time (for unstamped types).

    The decoding rules are the recording reader's (events/reader.py), reused, so that a live answer and
    `hexar ask` on the same data read the same records.
    """
    if topic == c.ROSOUT:
        stamp = stamp_ns(msg.stamp.sec, msg.stamp.nanosec)
        return [LogLine(stamp or t, int(msg.level), str(msg.name), str(msg.msg))]
    if topic == c.TASK_INFO:
        update = parse_task_info(t, str(msg.data))
        return [update] if update is not None else []
    if topic == c.AMCL_POSE:
        p, cov = msg.pose.pose, msg.pose.covariance
        return [PoseSample(stamp_ns(msg.header.stamp.sec, msg.header.stamp.nanosec) or t,
                           float(p.position.x), float(p.position.y),
                           _yaw(float(p.orientation.z), float(p.orientation.w)),
                           float(cov[0]), float(cov[7]), float(cov[35]))]
    if c.TYPE_OF.get(topic) == c.BOOL_TYPE:
        return [BoolSample(t, topic, bool(msg.data))]
    if c.TYPE_OF.get(topic) == c.DIAG_TYPE:
        return list(_statuses(t, topic, msg))
    return []
