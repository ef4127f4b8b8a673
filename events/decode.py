"""One message of a recording into HEXAR's records: hand decoders for the standard layouts, rosbags otherwise.

The live node reads the same fields of rclpy and DDS messages with these rules (live/convert.py), so that a live
answer and `hexar ask` on the same data read the same records.
"""

from __future__ import annotations

import math
import zlib
from typing import Any

from rosbags.interfaces import Connection
from rosbags.typesys.store import Typestore

from hexar.events import contract as c
from hexar.events.cdr import (
    Status,
    decode_bool,
    decode_diagnostics,
    decode_log,
    decode_odom,
    decode_pose_cov,
    decode_string,
    decode_twist,
)
from hexar.events.log import EventLog
from hexar.events.records import (
    BoolSample,
    GoalPose,
    GoalStatus,
    Grid,
    LogLine,
    OdomSample,
    ParameterSample,
    ParameterValue,
    PoseSample,
    StatusRecord,
    TwistSample,
    stamp_ns,
)
from hexar.events.task_info import parse_task_info


def yaw(qz: float, qw: float) -> float:
    return 2.0 * math.atan2(qz, qw)


def diag_fields(msg: Any) -> tuple[int, int, tuple[Status, ...]]:
    """What `decode_diagnostics` reads, from rosbags' message object."""
    return (msg.header.stamp.sec, msg.header.stamp.nanosec,
            tuple((int(s.level), str(s.name), str(s.message), str(s.hardware_id),
                   tuple((str(kv.key), str(kv.value)) for kv in s.values)) for s in msg.status))


def statuses(t: int, topic: str, msg: Any) -> list[StatusRecord]:
    """The records of a DiagnosticArray message object (rosbags' or a live one)."""
    return status_records(t, topic, diag_fields(msg))


def status_records(t: int, topic: str, diag: tuple[int, int, tuple[Status, ...]]) -> list[StatusRecord]:
    sec, nanosec, items = diag
    stamp = stamp_ns(sec, nanosec) or t
    return [StatusRecord(t=stamp, topic=topic, level=level, name=name, message=message, hardware_id=hardware_id,
                         values=values)
            for level, name, message, hardware_id, values in items]


def _motion(log: EventLog, ts: Typestore, topic: str, msgtype: str, t: int, raw: bytes, ros2: bool,
            standard: bool) -> None:
    """The ordinary Nav2 topics: velocity commands, odometry, goals and the navigation action's status."""
    if msgtype in (c.TWIST_TYPE, c.TWIST_STAMPED_TYPE):
        stamped = msgtype == c.TWIST_STAMPED_TYPE
        fast = decode_twist(raw, stamped) if standard else None
        if fast is not None:
            stamp, v = fast
        else:
            m = deser(ts, raw, msgtype, ros2)
            tw = m.twist if stamped else m
            stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) if stamped else 0
            v = (tw.linear.x, tw.linear.y, 0.0, 0.0, 0.0, tw.angular.z)
        log.twists.append(TwistSample(stamp or t, topic, float(v[0]), float(v[1]), float(v[5])))
    elif msgtype == c.ODOM_TYPE:
        odom = decode_odom(raw) if standard else None
        if odom is None:
            m = deser(ts, raw, msgtype, ros2)
            odom = (stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec), float(m.pose.pose.position.x),
                    float(m.pose.pose.position.y), float(m.twist.twist.linear.x), float(m.twist.twist.angular.z))
        log.odometry.append(OdomSample(odom[0] or t, *odom[1:]))
    elif msgtype == c.POSE_STAMPED_TYPE:
        m = deser(ts, raw, msgtype, ros2)
        stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t
        log.goals.append(GoalPose(stamp, float(m.pose.position.x), float(m.pose.position.y), str(m.header.frame_id)))
    elif msgtype == c.GOAL_STATUS_TYPE:
        m = deser(ts, raw, msgtype, ros2)
        for s in m.status_list:
            gid = bytes(bytearray(s.goal_info.goal_id.uuid)).hex()
            accepted = stamp_ns(s.goal_info.stamp.sec, s.goal_info.stamp.nanosec)
            log.goal_statuses.append(GoalStatus(t, gid, accepted, int(s.status), topic))


def grid_of(m: Any, topic: str, t: int) -> Grid | str:
    """An OccupancyGrid (a rosbags, rclpy or DDS message: the fields have the same names) as a Grid, or why it is
    left out: a grid that does not hold what its header says cannot place a point, and is never guessed at."""
    import numpy as np

    info = m.info
    cells = np.asarray(m.data, dtype=np.int8).tobytes()
    if len(cells) != int(info.width) * int(info.height) or not float(info.resolution) > 0:
        return (f"{topic}: left out a grid of {info.width} x {info.height} cells at resolution {info.resolution} "
                f"that holds {len(cells)} values")
    o = info.origin
    return Grid(stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t, topic, str(m.header.frame_id),
                float(info.resolution), int(info.width), int(info.height), float(o.position.x),
                float(o.position.y), yaw(float(o.orientation.z), float(o.orientation.w)), zlib.compress(cells, 1))


def same_grid(a: Grid | None, b: Grid) -> bool:
    """Whether `b` repeats `a` (the same cells where they were): an unchanged costmap republished."""
    return a is not None and (a.packed, a.width, a.origin_x, a.origin_y, a.frame) == (
        b.packed, b.width, b.origin_x, b.origin_y, b.frame)


def _grid(log: EventLog, m: Any, topic: str, t: int, warnings: list[str]) -> None:
    grid = grid_of(m, topic, t)
    if isinstance(grid, str):
        warnings.append(grid)
    elif not same_grid(next((g for g in reversed(log.grids) if g.topic == topic), None), grid):
        log.grids.append(grid)  # an unchanged grid adds nothing: the one before stands for it


def decode(log: EventLog, conn: Connection, t: int, raw: bytes, ts: Typestore, ros2: bool, standard: bool,
            warnings: list[str]) -> None:
    """Append the record(s) of one message to `log`."""
    msgtype = conn.msgtype
    if msgtype == c.LOG_TYPE:
        fast = decode_log(raw) if standard else None
        if fast is not None:
            stamp, level, name, text = fast
            log.logs.append(LogLine(stamp or t, level, name, text))
        else:
            m = deser(ts, raw, msgtype, ros2)
            stamp = stamp_ns(m.stamp.sec, m.stamp.nanosec)
            log.logs.append(LogLine(stamp or t, int(m.level), _text(m.name), _text(m.msg)))
    elif msgtype == c.ROS1_LOG_TYPE:
        m = deser(ts, raw, msgtype, ros2)
        stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t
        level = c.ROS1_LEVELS.get(int(m.level), int(m.level))
        log.logs.append(LogLine(stamp, level, str(m.name), str(m.msg)))
    elif msgtype == c.STRING_TYPE:
        data = decode_string(raw) if standard else None
        if data is None:
            data = str(deser(ts, raw, msgtype, ros2).data)
        if conn.topic == c.TASK_INFO:
            update = parse_task_info(t, data)
            if update is None:
                warnings.append(f"{conn.topic}: ignored a message that is not task JSON")
            else:
                log.task_updates.append(update)
    elif msgtype == c.BOOL_TYPE:
        flag = decode_bool(raw) if standard else None
        if flag is None:
            flag = bool(deser(ts, raw, msgtype, ros2).data)
        log.flags.setdefault(conn.topic, []).append(BoolSample(t, conn.topic, flag))
    elif msgtype == c.POSE_COV_TYPE:
        fast_pose = decode_pose_cov(raw) if standard else None
        if fast_pose is not None:
            stamp, v = fast_pose
            log.poses.append(PoseSample(stamp or t, v[0], v[1], yaw(v[5], v[6]), v[7], v[7 + 7], v[7 + 35]))
        else:
            m = deser(ts, raw, msgtype, ros2)
            p, cov = m.pose.pose, m.pose.covariance
            log.poses.append(
                PoseSample(
                    stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t,
                    float(p.position.x), float(p.position.y),
                    yaw(float(p.orientation.z), float(p.orientation.w)),
                    float(cov[0]), float(cov[7]), float(cov[35]),
                )
            )
    elif msgtype == c.GRID_TYPE:
        _grid(log, deser(ts, raw, msgtype, ros2), conn.topic, t, warnings)
    elif msgtype == c.PARAMETER_EVENT_TYPE:
        log.parameters.extend(parameter_samples(deser(ts, raw, msgtype, ros2), t))
    elif msgtype == c.DIAG_TYPE:
        diag = decode_diagnostics(raw) if standard else None
        if diag is None:
            diag = diag_fields(deser(ts, raw, msgtype, ros2))
        log.statuses.setdefault(conn.topic, []).extend(status_records(t, conn.topic, diag))
    else:
        _motion(log, ts, conn.topic, msgtype, t, raw, ros2, standard)


# rcl_interfaces/msg/ParameterValue's fields, by the value of its type field
_VALUE_FIELDS = {1: "bool_value", 2: "integer_value", 3: "double_value", 4: "string_value", 5: "byte_array_value",
                 6: "bool_array_value", 7: "integer_array_value", 8: "double_array_value", 9: "string_array_value"}


def parameter_value(value: Any) -> ParameterValue:
    """A ParameterValue's one set field (rosbags, rclpy and DDS messages alike), None when not set. A byte array is
    kept as one hex string (rclpy gives its bytes as one-byte `bytes`, rosbags as numbers)."""
    kind = int(value.type)
    name = _VALUE_FIELDS.get(kind)
    if name is None:
        return None
    field = getattr(value, name)
    if kind == 1:
        return bool(field)
    if kind == 2:
        return int(field)
    if kind == 3:
        return float(field)
    if kind == 4:
        return str(field)
    items = list(field.tolist() if hasattr(field, "tolist") else field)
    if kind == 5:
        return (bytes(b[0] if isinstance(b, bytes) else int(b) for b in items).hex(),)
    return tuple(items)


def parameter_samples(m: Any, t: int) -> list[ParameterSample]:
    """One ParameterEvent's parameters: declared, set and undeclared, stamped by the event (else `t`)."""
    stamp = stamp_ns(m.stamp.sec, m.stamp.nanosec) or t
    node = _text(m.node)
    return ([ParameterSample(stamp, node, _text(p.name), parameter_value(p.value), "new") for p in m.new_parameters]
            + [ParameterSample(stamp, node, _text(p.name), parameter_value(p.value), "changed")
               for p in m.changed_parameters]
            + [ParameterSample(stamp, node, _text(p.name), None, "deleted") for p in m.deleted_parameters])


def _text(value: object) -> str:
    """A string field; anything else means the definition gives the field another type."""
    if not isinstance(value, str):
        raise TypeError(f"a text field holds {type(value).__name__}")
    return value


def deser(ts: Typestore, raw: bytes, msgtype: str, ros2: bool) -> Any:
    return ts.deserialize_cdr(raw, msgtype) if ros2 else ts.deserialize_ros1(raw, msgtype)
