"""Open a recording (rosbag2 sqlite3/mcap folder, or ROS 1 bag) and decode the HEXAR topics into records."""

from __future__ import annotations

import math
import sqlite3
import zlib
from collections.abc import Callable, Iterable
from functools import lru_cache
from pathlib import Path
from typing import Any

from rosbags.highlevel import AnyReader
from rosbags.interfaces import Connection
from rosbags.serde import SerdeError
from rosbags.typesys.store import Typestore

from hexar.events import contract as c
from hexar.events.bag import Reader
from hexar.events.cdr import (
    LayoutError,
    Status,
    decode_bool,
    decode_diagnostics,
    decode_log,
    decode_odom,
    decode_pose_cov,
    decode_string,
    decode_twist,
)
from hexar.events.errors import (
    CorruptRecordingError,
    EmptyRecordingError,
    NotARecordingError,
    RecordingNotFoundError,
    UnknownMessageTypeError,
)
from hexar.events.humble import has_standard, humble, humble_hash, is_humble
from hexar.events.log import EventLog, TopicInfo
from hexar.events.mcap_index import check_mcap
from hexar.events.records import (
    BoolSample,
    GoalPose,
    GoalStatus,
    Grid,
    LogLine,
    OdomSample,
    PoseSample,
    StatusRecord,
    TwistSample,
    stamp_ns,
)
from hexar.events.recover import holds_storage, is_cut_short, read_recovered, storage_files
from hexar.events.storage_rows import mcap_rows, sqlite_messages
from hexar.events.task_info import parse_task_info


class _Unreadable(Exception):
    """A connection whose messages do not fit the definition HEXAR would decode them with."""

    def __init__(self, conn: Connection, reason: str) -> None:
        super().__init__(reason)
        self.conn, self.reason = conn, reason


# what a message that does not fit the definition it is decoded with raises
_MISFIT = (LayoutError, SerdeError, AttributeError, TypeError, KeyError)


@lru_cache(maxsize=256)  # typestores are shared between recordings (events.bag), and hashing one is not cheap
def _same_layout(ts: Typestore, msgtype: str) -> bool:
    """Whether the recording's definition of `msgtype` is the standard (Humble) one the fast decoders assume."""
    if is_humble(ts):
        return True
    try:
        return ts.hash_rihs01(msgtype) == humble_hash(msgtype)
    except Exception:  # a type rosbags cannot hash is no standard layout
        return False


def _read_skipping(reader: AnyReader, src: Path, wanted: frozenset[str],
                   fast: bool = True) -> tuple[EventLog, bool]:
    """`_read`, again without each connection found unreadable, which is then named in the warnings."""
    skip: dict[int, str] = {}
    while True:
        try:
            return _read(reader, src, wanted, skip, fast)
        except _Unreadable as bad:
            if bad.conn.id in skip:
                raise CorruptRecordingError(f"cannot read {src}: {bad.reason}") from bad
            skip[bad.conn.id] = bad.reason


def resolve_path(path: Path) -> Path:
    """The path AnyReader wants: a rosbag2 folder or a `.bag` file."""
    if not path.exists():
        raise RecordingNotFoundError(f"recording not found: {path}")
    if path.is_file():
        if path.suffix == ".bag":
            _rosbag1_header(path)
            return path
        if path.suffix in {".db3", ".mcap"}:
            return path.parent  # its folder's metadata.yaml, or the metadata rebuilt from the storage files
        raise NotARecordingError(f"not a recording: {path} (expected a rosbag2 folder or a ROS 1 .bag file)")
    if not (path / "metadata.yaml").is_file() and not holds_storage(path):
        raise NotARecordingError(f"not a rosbag2 recording: {path} has no metadata.yaml and no .db3 or .mcap file")
    return path


# rosbag's format 2.0 (ROS 1) opens with this line (wiki.ros.org/Bags/Format/2.0)
ROSBAG_V2 = b"#ROSBAG V2.0\n"


def _rosbag1_header(path: Path) -> None:
    try:
        with path.open("rb") as f:
            head = f.read(len(ROSBAG_V2))
    except OSError as err:
        raise CorruptRecordingError(f"cannot read {path}: {err.strerror or err}") from err
    if head != ROSBAG_V2:
        raise CorruptRecordingError(f"cannot read {path}: not a ROS 1 bag (it does not begin with '#ROSBAG V2.0')")


def _yaw(qz: float, qw: float) -> float:
    return 2.0 * math.atan2(qz, qw)


def _diag_fields(msg: Any) -> tuple[int, int, tuple[Status, ...]]:
    """What `decode_diagnostics` reads, from rosbags' message object."""
    return (msg.header.stamp.sec, msg.header.stamp.nanosec,
            tuple((int(s.level), str(s.name), str(s.message), str(s.hardware_id),
                   tuple((str(kv.key), str(kv.value)) for kv in s.values)) for s in msg.status))


def _statuses(t: int, topic: str, msg: Any) -> list[StatusRecord]:
    """The records of a DiagnosticArray message object (rosbags' or a live one)."""
    return _status_records(t, topic, _diag_fields(msg))


def _status_records(t: int, topic: str, diag: tuple[int, int, tuple[Status, ...]]) -> list[StatusRecord]:
    sec, nanosec, statuses = diag
    stamp = stamp_ns(sec, nanosec) or t
    return [StatusRecord(t=stamp, topic=topic, level=level, name=name, message=message, hardware_id=hardware_id,
                         values=values)
            for level, name, message, hardware_id, values in statuses]


def read_recording(path: str | Path, topics: Iterable[str] | None = None) -> EventLog:
    """Read `topics` (default: every topic of the contract) of the recording at `path`.

    Connections on other topics are never deserialised; their counts come from the bag's index.
    """
    wanted = frozenset(topics) if topics is not None else c.ALL_TOPICS
    src = resolve_path(Path(path))
    cut = [f for f in src.glob("*.mcap") if is_cut_short(f)] if src.is_dir() else []
    if cut or holds_storage(src):
        log = _guarded(src, lambda: read_recovered(src, cut, lambda files: _read_files(files, src, wanted)))
    else:
        log = _guarded(src, lambda: _read_whole(src, wanted))
    if c.ROSOUT in wanted:
        from hexar.events.roslog import merge_launch_logs

        merge_launch_logs(log)
    return log


def damage(err: BaseException) -> str:
    """What a storage library said about a damaged file, its first line only: a YAML parser's message goes on
    with the offending text and a caret on lines of their own."""
    text = str(err).strip()
    return text.splitlines()[0] if text else type(err).__name__


def _guarded(src: Path, read: Callable[[], EventLog]) -> EventLog:
    """One error class per kind of damage, whatever the storage library raised."""
    try:
        return read()
    except (RecordingNotFoundError, NotARecordingError, UnknownMessageTypeError, EmptyRecordingError,
            CorruptRecordingError):
        raise
    except (sqlite3.DatabaseError, OSError, EOFError) as err:
        raise CorruptRecordingError(f"cannot read {src}: {damage(err)}") from err
    except Exception as err:  # rosbags raises many unrelated classes for damaged files
        raise CorruptRecordingError(f"cannot read {src}: {type(err).__name__}: {damage(err)}") from err


def _read_files(files: list[Path], src: Path, wanted: frozenset[str]) -> EventLog:
    """The recording at `src` read from other storage files (a recovered copy): rosbags only, no fast paths."""
    with AnyReader(files, default_typestore=humble()) as reader:
        return _read_skipping(reader, src, wanted, fast=False)[0]


def _read_whole(src: Path, wanted: frozenset[str]) -> EventLog:
    for file in sorted(src.glob("*.mcap")) if src.is_dir() else []:
        check_mcap(file, crc=False)
    with Reader([src]) as reader:
        log, complete = _read_skipping(reader, src, wanted)
    if not complete:
        # Some rosbag2 versions write different QoS into metadata.yaml than into the storage file, and
        # rosbags then matches no message to its connection; the storage files alone are consistent.
        files = storage_files(src)
        if files:
            with Reader(files) as reader:
                log, _ = _read_skipping(reader, src, wanted)
    return log


def _read(reader: AnyReader, src: Path, wanted: frozenset[str], skip: dict[int, str],
          fast: bool = True) -> tuple[EventLog, bool]:
    """The log, and whether every message the index promised for the selected topics was read. `fast` reads the
    storage files of `src` directly (a recovered recording's are not those rosbags reads).

    Connections in `skip` are left out and reported: their messages fit neither the standard definition nor
    one stored in the recording, and misreading them could invent a cause.
    """
    warnings: list[str] = []
    infos: dict[str, TopicInfo] = {}
    for conn in reader.connections:
        info = infos.setdefault(conn.topic, TopicInfo(conn.topic, conn.msgtype, 0))
        infos[conn.topic] = TopicInfo(conn.topic, conn.msgtype, info.count + (conn.msgcount or 0))
    if reader.message_count == 0:
        raise EmptyRecordingError(f"empty recording: {src} holds no messages")

    known = set(reader.typestore.fielddefs)
    selected = []
    typestores: dict[int, Typestore] = {}
    for conn in reader.connections:
        if conn.id in skip:
            warnings.append(f"{conn.topic} is unreadable and was not used: {skip[conn.id]}")
            continue
        key = c.topic_key(conn.topic)
        if key not in wanted:
            if conn.msgtype not in known and not has_standard(conn.msgtype):
                warnings.append(f"skipped {conn.topic}: unknown type {conn.msgtype}")
            continue
        expected = c.TYPE_OF.get(key)
        if expected is not None and conn.msgtype not in c.ACCEPTED_TYPES[key] and (
                key in c.NAV2_TOPICS or key in c.ARM_STATUS_TOPICS or key in c.GRID_TOPICS):
            # an ordinary topic name that this robot uses for another type: not ours to read, not an error
            warnings.append(f"skipped {conn.topic}: type {conn.msgtype}, HEXAR reads it as {expected}")
            continue
        if expected is not None and conn.msgtype not in c.ACCEPTED_TYPES[key]:
            raise UnknownMessageTypeError(
                f"{conn.topic} has type {conn.msgtype}, but HEXAR reads it as {expected}"
            )
        if conn.msgtype in known:
            typestores[conn.id] = reader.typestore
        elif has_standard(conn.msgtype):
            typestores[conn.id] = humble()
        else:
            raise UnknownMessageTypeError(f"{conn.topic} has unknown type {conn.msgtype} and the bag defines none")
        selected.append(conn)

    log = EventLog(
        path=src,
        storage=_storage(src),
        start=reader.start_time,
        end=reader.end_time,
        topics=dict(sorted(infos.items())),
        warnings=warnings,
    )
    if not selected:
        return log, True
    ros2 = reader.is2
    messages = (sqlite_messages(src, selected) or mcap_rows(src, selected)) if ros2 and fast else None
    if messages is None:
        messages = reader.messages(connections=selected)
    promised = sum(conn.msgcount or 0 for conn in selected)
    # The hand decoders assume the standard layout; a recording that stores another definition is decoded by
    # rosbags with that definition instead.
    standard = {conn.id: ros2 and _same_layout(typestores[conn.id], conn.msgtype) for conn in selected}
    seen = 0
    for conn, t, raw in messages:
        seen += 1
        try:
            _decode(log, conn, t, raw, typestores[conn.id], ros2, standard[conn.id], warnings)
        except _MISFIT as err:
            if standard[conn.id] or not ros2:
                raise _Unreadable(conn, f"its messages do not fit the standard {conn.msgtype} and the recording "
                                        f"stores no definition that fits them ({type(err).__name__}: {err})") from err
            # A stored definition that does not fit its own bytes (test bags carry such stand-ins): the standard
            # one may still fit them exactly, which the strict decoders check.
            try:
                _decode(log, conn, t, raw, humble(), ros2, True, warnings)
            except Exception as err2:
                raise _Unreadable(conn, f"its messages fit neither the definition of {conn.msgtype} stored in "
                                        f"the recording nor the standard one ({type(err).__name__}: {err})") from err2
            standard[conn.id], typestores[conn.id] = True, humble()
            warnings.append(f"{conn.topic}: the definition of {conn.msgtype} stored in the recording does not fit "
                            "its messages; they fit the standard definition exactly and were read with it")
    log.finish()
    return log, seen > 0 or promised == 0


def _motion(log: EventLog, ts: Typestore, topic: str, msgtype: str, t: int, raw: bytes, ros2: bool,
            standard: bool) -> None:
    """The ordinary Nav2 topics: velocity commands, odometry, goals and the navigation action's status."""
    if msgtype in (c.TWIST_TYPE, c.TWIST_STAMPED_TYPE):
        stamped = msgtype == c.TWIST_STAMPED_TYPE
        fast = decode_twist(raw, stamped) if standard else None
        if fast is not None:
            stamp, v = fast
        else:
            m = _deser(ts, raw, msgtype, ros2)
            tw = m.twist if stamped else m
            stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) if stamped else 0
            v = (tw.linear.x, tw.linear.y, 0.0, 0.0, 0.0, tw.angular.z)
        log.twists.append(TwistSample(stamp or t, topic, float(v[0]), float(v[1]), float(v[5])))
    elif msgtype == c.ODOM_TYPE:
        odom = decode_odom(raw) if standard else None
        if odom is None:
            m = _deser(ts, raw, msgtype, ros2)
            odom = (stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec), float(m.pose.pose.position.x),
                    float(m.pose.pose.position.y), float(m.twist.twist.linear.x), float(m.twist.twist.angular.z))
        log.odometry.append(OdomSample(odom[0] or t, *odom[1:]))
    elif msgtype == c.POSE_STAMPED_TYPE:
        m = _deser(ts, raw, msgtype, ros2)
        stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t
        log.goals.append(GoalPose(stamp, float(m.pose.position.x), float(m.pose.position.y), str(m.header.frame_id)))
    elif msgtype == c.GOAL_STATUS_TYPE:
        m = _deser(ts, raw, msgtype, ros2)
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
                float(o.position.y), _yaw(float(o.orientation.z), float(o.orientation.w)), zlib.compress(cells, 1))


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


def _decode(log: EventLog, conn: Connection, t: int, raw: bytes, ts: Typestore, ros2: bool, standard: bool,
            warnings: list[str]) -> None:
    """Append the record(s) of one message to `log`."""
    msgtype = conn.msgtype
    if msgtype == c.LOG_TYPE:
        fast = decode_log(raw) if standard else None
        if fast is not None:
            stamp, level, name, text = fast
            log.logs.append(LogLine(stamp or t, level, name, text))
        else:
            m = _deser(ts, raw, msgtype, ros2)
            stamp = stamp_ns(m.stamp.sec, m.stamp.nanosec)
            log.logs.append(LogLine(stamp or t, int(m.level), _text(m.name), _text(m.msg)))
    elif msgtype == c.ROS1_LOG_TYPE:
        m = _deser(ts, raw, msgtype, ros2)
        stamp = stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t
        level = c.ROS1_LEVELS.get(int(m.level), int(m.level))
        log.logs.append(LogLine(stamp, level, str(m.name), str(m.msg)))
    elif msgtype == c.STRING_TYPE:
        data = decode_string(raw) if standard else None
        if data is None:
            data = str(_deser(ts, raw, msgtype, ros2).data)
        if conn.topic == c.TASK_INFO:
            update = parse_task_info(t, data)
            if update is None:
                warnings.append(f"{conn.topic}: ignored a message that is not task JSON")
            else:
                log.task_updates.append(update)
    elif msgtype == c.BOOL_TYPE:
        flag = decode_bool(raw) if standard else None
        if flag is None:
            flag = bool(_deser(ts, raw, msgtype, ros2).data)
        log.flags.setdefault(conn.topic, []).append(BoolSample(t, conn.topic, flag))
    elif msgtype == c.POSE_COV_TYPE:
        fast_pose = decode_pose_cov(raw) if standard else None
        if fast_pose is not None:
            stamp, v = fast_pose
            log.poses.append(PoseSample(stamp or t, v[0], v[1], _yaw(v[5], v[6]), v[7], v[7 + 7], v[7 + 35]))
        else:
            m = _deser(ts, raw, msgtype, ros2)
            p, cov = m.pose.pose, m.pose.covariance
            log.poses.append(
                PoseSample(
                    stamp_ns(m.header.stamp.sec, m.header.stamp.nanosec) or t,
                    float(p.position.x), float(p.position.y),
                    _yaw(float(p.orientation.z), float(p.orientation.w)),
                    float(cov[0]), float(cov[7]), float(cov[35]),
                )
            )
    elif msgtype == c.GRID_TYPE:
        _grid(log, _deser(ts, raw, msgtype, ros2), conn.topic, t, warnings)
    elif msgtype == c.DIAG_TYPE:
        diag = decode_diagnostics(raw) if standard else None
        if diag is None:
            diag = _diag_fields(_deser(ts, raw, msgtype, ros2))
        log.statuses.setdefault(conn.topic, []).extend(_status_records(t, conn.topic, diag))
    else:
        _motion(log, ts, conn.topic, msgtype, t, raw, ros2, standard)


def _text(value: object) -> str:
    """A string field; anything else means the definition gives the field another type."""
    if not isinstance(value, str):
        raise TypeError(f"a text field holds {type(value).__name__}")
    return value


def _deser(ts: Typestore, raw: bytes, msgtype: str, ros2: bool) -> Any:
    return ts.deserialize_cdr(raw, msgtype) if ros2 else ts.deserialize_ros1(raw, msgtype)


def _storage(src: Path) -> str:
    if src.suffix == ".bag":
        return "rosbag1"
    if any(src.glob("*.mcap")):
        return "mcap"
    if any(src.glob("*.db3")):
        return "sqlite3"
    return "unknown"


def read_tasks(path: str | Path) -> EventLog:
    """Only what the recording's tasks need: `/task_info`, else the Nav2 log and goal topics that tasks are
    derived from (a recording without `/task_info`), so listing many recordings stays cheap."""
    log = read_recording(path, topics={c.TASK_INFO})
    return log if log.tasks else read_recording(path, topics=c.GOAL_TOPICS)
