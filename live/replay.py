"""`hexar replay`: publish a recording onto the live topics like `ros2 bag play`, so any simulated or real
recording can stand in for a robot.

Each message is written with the DDS source timestamp of its bag time, so a listening node dates unstamped
messages (`/task_info`) as the recorder did; stamped messages keep their own stamps. At `--rate 10` the
recording plays ten times faster; the robot's clock as the node sees it runs ten times faster too.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

from hexar.events import contract as c
from hexar.events.errors import CorruptRecordingError
from hexar.live.errors import BadOptionError
from hexar.live.topics import PUBLISHED_BY_ROBOT, SUBSCRIBED, TopicQos

QOS_OF: dict[str, TopicQos] = {t.topic: PUBLISHED_BY_ROBOT.get(t.topic, TopicQos(depth=100)) for t in SUBSCRIBED}


class BagMessages(NamedTuple):
    """A recording's contract messages as `replay` sends them."""

    messages: Iterator[tuple[str, str, int, Any]]  # (topic, type, bag time, rosbags message) in bag order
    skipped: list[str]  # the recording's topics that are not sent
    start: int  # the recording's start time
    topics: frozenset[str]  # the topics that are sent


@dataclass
class ReplayStats:
    published: int = 0
    skipped_topics: tuple[str, ...] = ()
    unmatched_topics: tuple[str, ...] = ()  # sent while no reader had matched them (within the warm-up)
    seconds: float = 0.0


def _open(path: Path) -> tuple[Any, Path]:
    from rosbags.highlevel import AnyReader

    from hexar.events.humble import humble
    from hexar.events.reader import damage, resolve_path

    src = resolve_path(path)
    reader = AnyReader([src], default_typestore=humble())
    try:
        reader.open()
    except Exception as err:  # rosbags raises many unrelated classes for damaged files
        raise CorruptRecordingError(f"cannot read {src}: {type(err).__name__}: {damage(err)}") from err
    return reader, src


def _begin(reader: Any, src: Path, start_s: float) -> int:
    length_s = (reader.end_time - reader.start_time) / 1e9
    if start_s > length_s:  # also inf; a start past the end would overflow the storage's integer
        reader.close()
        raise BadOptionError(f"--start {start_s:g} s is past the end of {src.name}, which lasts {length_s:.1f} s")
    return int(reader.start_time) + int(start_s * 1e9)


def check_start(path: Path, start_s: float) -> None:
    """Fail on a damaged recording or a start past its end before any DDS participant exists."""
    reader, src = _open(path)
    _begin(reader, src, start_s)
    reader.close()


def bag_messages(path: Path, start_s: float = 0.0) -> BagMessages:
    """The contract topics' messages of `path` from `start_s` on, and which topics are sent and skipped."""
    reader, src = _open(path)
    # a Nav2 topic name that this robot uses for another type is skipped, as the reader skips it
    wanted = [conn for conn in reader.connections
              if conn.topic in QOS_OF and conn.msgtype in c.ACCEPTED_TYPES.get(c.topic_key(conn.topic), frozenset())]
    skipped = sorted({conn.topic for conn in reader.connections} - {conn.topic for conn in wanted})
    begin = _begin(reader, src, start_s)

    def gen() -> Iterator[tuple[str, str, int, Any]]:
        try:
            for conn, t, raw in reader.messages(connections=wanted, start=begin):
                yield conn.topic, conn.msgtype, t, reader.deserialize(raw, conn.msgtype)
        finally:
            reader.close()

    return BagMessages(gen(), skipped, reader.start_time, frozenset(conn.topic for conn in wanted))


def to_dds(msgtype: str, m: Any) -> Any:
    """A rosbags message as the DDS dataclass of its ROS 2 type (ROS 1 logs mapped to rcl_interfaces/Log)."""
    from hexar.live import msgs

    if msgtype == c.LOG_TYPE:
        return msgs.Log(stamp=msgs.Time(m.stamp.sec, m.stamp.nanosec), level=int(m.level), name=m.name, msg=m.msg,
                        file=m.file, function=m.function, line=int(m.line))
    if msgtype == c.ROS1_LOG_TYPE:
        return msgs.Log(stamp=msgs.Time(m.header.stamp.sec, m.header.stamp.nanosec),
                        level=c.ROS1_LEVELS.get(int(m.level), int(m.level)), name=m.name, msg=m.msg,
                        file=m.file, function=m.function, line=int(m.line))
    if msgtype == c.STRING_TYPE:
        return msgs.String(data=m.data)
    if msgtype == c.BOOL_TYPE:
        return msgs.Bool(data=bool(m.data))
    if msgtype == c.TWIST_TYPE:
        return _twist(m)
    if msgtype == c.GOAL_STATUS_TYPE:
        return msgs.GoalStatusArray(status_list=[
            msgs.GoalStatus(goal_info=msgs.GoalInfo(
                goal_id=msgs.UUID(uuid=[int(b) for b in s.goal_info.goal_id.uuid]),
                stamp=msgs.Time(s.goal_info.stamp.sec, s.goal_info.stamp.nanosec)), status=int(s.status))
            for s in m.status_list])
    if msgtype == c.PARAMETER_EVENT_TYPE:
        return msgs.ParameterEvent(stamp=msgs.Time(m.stamp.sec, m.stamp.nanosec), node=m.node, **{
            kind: [_parameter(p) for p in getattr(m, kind)]
            for kind in ("new_parameters", "changed_parameters", "deleted_parameters")})
    header = msgs.Header(stamp=msgs.Time(m.header.stamp.sec, m.header.stamp.nanosec), frame_id=m.header.frame_id)
    if msgtype == c.POSE_COV_TYPE:
        p = m.pose.pose
        pose = msgs.Pose(position=msgs.Point(p.position.x, p.position.y, p.position.z),
                         orientation=msgs.Quaternion(p.orientation.x, p.orientation.y, p.orientation.z,
                                                     p.orientation.w))
        return msgs.PoseWithCovarianceStamped(header=header, pose=msgs.PoseWithCovariance(
            pose=pose, covariance=[float(v) for v in m.pose.covariance]))
    if msgtype == c.DIAG_TYPE:
        return msgs.DiagnosticArray(header=header, status=[
            msgs.DiagnosticStatus(level=int(s.level) & 0xFF, name=s.name, message=s.message,
                                  hardware_id=s.hardware_id,
                                  values=[msgs.KeyValue(kv.key, kv.value) for kv in s.values])
            for s in m.status])
    if msgtype == c.POSE_STAMPED_TYPE:
        return msgs.PoseStamped(header=header, pose=_pose(m.pose))
    if msgtype == c.ODOM_TYPE:
        return msgs.Odometry(header=header, child_frame_id=m.child_frame_id, pose=msgs.PoseWithCovariance(
            pose=_pose(m.pose.pose), covariance=[float(v) for v in m.pose.covariance]),
            twist=msgs.TwistWithCovariance(twist=_twist(m.twist.twist),
                                           covariance=[float(v) for v in m.twist.covariance]))
    if msgtype == c.TWIST_STAMPED_TYPE:
        return _twist(m.twist)  # the live topic carries Humble's Twist; the header's stamp is not sent
    if msgtype == c.GRID_TYPE:
        i = m.info
        return msgs.OccupancyGrid(header=header, info=msgs.MapMetaData(
            map_load_time=msgs.Time(i.map_load_time.sec, i.map_load_time.nanosec), resolution=float(i.resolution),
            width=int(i.width), height=int(i.height), origin=_pose(i.origin)), data=[int(v) for v in m.data])
    raise BadOptionError(f"cannot replay type {msgtype}")


def _parameter(p: Any) -> Any:
    from hexar.live import msgs

    v = p.value
    return msgs.Parameter(name=p.name, value=msgs.ParameterValue(
        type=int(v.type), bool_value=bool(v.bool_value), integer_value=int(v.integer_value),
        double_value=float(v.double_value), string_value=v.string_value,
        byte_array_value=[int(b) for b in v.byte_array_value], bool_array_value=[bool(b) for b in v.bool_array_value],
        integer_array_value=[int(i) for i in v.integer_array_value],
        double_array_value=[float(d) for d in v.double_array_value], string_array_value=list(v.string_array_value)))


def _pose(p: Any) -> Any:
    from hexar.live import msgs

    return msgs.Pose(position=msgs.Point(p.position.x, p.position.y, p.position.z),
                     orientation=msgs.Quaternion(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w))


def _twist(tw: Any) -> Any:
    from hexar.live import msgs

    return msgs.Twist(linear=msgs.Vector3(tw.linear.x, tw.linear.y, tw.linear.z),
                      angular=msgs.Vector3(tw.angular.x, tw.angular.y, tw.angular.z))


class DdsReplayer:
    """Writers for the robot's topics on one DDS domain, offering the robot's QoS."""

    wants_dds = True

    def __init__(self, domain_id: int = 0) -> None:
        from hexar.live.dds import DdsEndpoint

        self.endpoint = DdsEndpoint(domain_id)

    def write(self, topic: str, msgtype: str, msg: Any, t: int) -> None:
        # a ROS 1 log goes out as rcl_interfaces/Log, a TwistStamped as Twist; a controller's status topic is FJT_STATUS
        ros_type = c.TYPE_OF[c.topic_key(topic)]
        self.endpoint.writer(topic, ros_type, QOS_OF[topic]).write(msg, timestamp=t)

    def matched(self, topic: str) -> int:
        # the status count, not the list: cyclonedds' get_matched_subscriptions asks for the count and then fills
        # a list of that size, and raises IndexError when a reader matches between its two calls
        return int(self.endpoint.writers[topic].get_publication_matched_status().current_count)

    def clock(self, t: int) -> None:
        from hexar.live import msgs
        from hexar.live.clock import CLOCK, CLOCK_TYPE
        from hexar.live.topics import CLOCK_QOS

        self.endpoint.writer(CLOCK, CLOCK_TYPE, CLOCK_QOS).write(msgs.Clock(clock=msgs.time_of(t)), timestamp=t)

    def prepare(self) -> None:
        """Create every writer up front, so readers have matched them before the first message."""
        for topic, qos in QOS_OF.items():
            self.endpoint.writer(topic, c.TYPE_OF[c.topic_key(topic)], qos)

    def close(self, linger_s: float = 2.0) -> None:
        """Wait (at most `linger_s` in all) until matched reliable readers acknowledged what was written: a
        process that exits right after its last write would otherwise take the unacknowledged tail with it (a
        sample lost on a busy loopback is resent only after the reader's NACK)."""
        deadline = time.monotonic() + linger_s
        for writer in self.endpoint.writers.values():
            left = deadline - time.monotonic()
            if left <= 0:
                break
            try:
                writer.wait_for_acks(int(left * 1e9))
            except Exception:  # a writer the binding has already torn down has nothing left to deliver
                continue
        self.endpoint.close()


def wait_for_readers(writer: Any, topics: Iterable[str], timeout_s: float,
                     settle_s: float = 0.5) -> tuple[str, ...]:
    """Wait (at most `timeout_s`) until each of `topics` has a matched reader, then `settle_s` more: discovery
    across DDS vendors takes a second or more, and what a volatile topic carries before its reader matched is
    lost; the writer's side matches first, and a Fast DDS reader drops samples from a writer it has not matched
    itself yet. The topics still without a reader at the end, in order (a replay to nobody still plays)."""
    deadline = time.monotonic() + timeout_s
    topics = sorted(topics)
    while True:
        missing = tuple(topic for topic in topics if not writer.matched(topic))
        if not missing or time.monotonic() >= deadline:
            break
        time.sleep(0.02)
    if len(missing) < len(topics):
        # also when one topic timed out: the others may have matched just now, on the writer's side only
        time.sleep(settle_s)
    return missing


def replay(path: Path, writer: Any, rate: float = 1.0, start_s: float = 0.0, warmup_s: float = 3.0,
           on_message: Callable[[str, int, float], None] | None = None,
           should_stop: Callable[[], bool] | None = None, clock_hz: float = 0.0) -> ReplayStats:
    """Publish `path` through `writer` (DdsReplayer or the rclpy one) at `rate` x real time.

    `on_message(topic, bag_time, wall_time)` sees each message right after it was written. With `clock_hz`,
    the recording's time also goes out on /clock, at most `clock_hz` times per second of recording time and
    before each message (as `ros2 bag play --clock` publishes it). Playing starts once every topic the recording
    sends has a matched reader, or after `warmup_s`: a HEXAR node reads them all, and a Nav2 goal's first status
    or its velocity commands sent before the node's reader matched would be lost for good.
    """
    if not rate > 0:
        raise BadOptionError(f"--rate must be above 0, not {rate}")
    messages, skipped, _, topics = bag_messages(path, start_s)
    writer.prepare()
    stats = ReplayStats(skipped_topics=tuple(skipped), unmatched_topics=wait_for_readers(writer, topics, warmup_s))
    started = time.monotonic()
    first: int | None = None
    clock_every = int(1e9 / clock_hz) if clock_hz > 0 else 0
    last_clock = -clock_every
    for topic, msgtype, t, m in messages:
        if should_stop is not None and should_stop():
            break
        first = t if first is None else first
        due = started + (t - first) / 1e9 / rate
        delay = due - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        if clock_every and t - last_clock >= clock_every:
            writer.clock(t)
            last_clock = t
        writer.write(topic, msgtype, to_dds(msgtype, m) if writer.wants_dds else m, t)
        stats.published += 1
        if on_message is not None:
            on_message(topic, t, time.monotonic())
    stats.seconds = time.monotonic() - started
    return stats
