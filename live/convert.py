"""ROS messages (DDS dataclasses or rclpy messages: the fields have the same names) into HEXAR's records."""

from __future__ import annotations

from typing import Any

from hexar.events import contract as c
from hexar.events.decode import grid_of, parameter_samples, statuses, yaw
from hexar.events.records import (
    BoolSample,
    GoalPose,
    GoalStatus,
    Grid,
    LogLine,
    OdomSample,
    PoseSample,
    Record,
    TwistSample,
    stamp_ns,
)
from hexar.events.task_info import parse_task_info


def _stamp(header: Any) -> int:
    return stamp_ns(header.stamp.sec, header.stamp.nanosec)


def _motion(topic: str, msg: Any, t: int) -> list[Record]:
    """The Nav2 topics, field for field as the reader's `_motion` (events/decode.py) reads them."""
    if topic == c.CMD_VEL:
        stamped = hasattr(msg, "header")  # TwistStamped (Jazzy's cmd_vel) carries its twist under `twist`
        tw = msg.twist if stamped else msg
        return [TwistSample((_stamp(msg.header) if stamped else 0) or t, topic, float(tw.linear.x),
                            float(tw.linear.y), float(tw.angular.z))]
    if topic == c.ODOM:
        return [OdomSample(_stamp(msg.header) or t, float(msg.pose.pose.position.x), float(msg.pose.pose.position.y),
                           float(msg.twist.twist.linear.x), float(msg.twist.twist.angular.z))]
    if topic == c.GOAL_POSE:
        return [GoalPose(_stamp(msg.header) or t, float(msg.pose.position.x), float(msg.pose.position.y),
                         str(msg.header.frame_id))]
    if topic == c.NAV_STATUS or c.topic_key(topic) in c.ARM_STATUS_TOPICS:
        # the array is dated by its write time, like the reader dates it by the bag's receive time
        return [GoalStatus(t, bytes(bytearray(s.goal_info.goal_id.uuid)).hex(),
                           stamp_ns(s.goal_info.stamp.sec, s.goal_info.stamp.nanosec), int(s.status), topic)
                for s in msg.status_list]
    return []


def to_records(topic: str, msg: Any, t: int) -> list[Record]:
    """The records of one message on `topic`; `t` is the publisher's write time (for unstamped types).

    The decoding rules are the recording reader's (events/decode.py), reused, so that a live answer and
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
                           yaw(float(p.orientation.z), float(p.orientation.w)),
                           float(cov[0]), float(cov[7]), float(cov[35]))]
    if c.TYPE_OF.get(topic) == c.BOOL_TYPE:
        return [BoolSample(t, topic, bool(msg.data))]
    if c.TYPE_OF.get(topic) == c.DIAG_TYPE:
        return list(statuses(t, topic, msg))
    if topic == c.PARAMETER_EVENTS:
        # HEXAR's own rclpy nodes announce their parameters too: they are not the robot's
        own = str(msg.node).rsplit("/", 1)[-1].startswith("hexar")
        return [] if own else list[Record](parameter_samples(msg, t))
    if c.TYPE_OF.get(topic) == c.GRID_TYPE:
        grid = grid_of(msg, topic, t)
        return [grid] if isinstance(grid, Grid) else []
    return _motion(topic, msg, t)
