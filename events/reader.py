"""Open a recording (rosbag2 sqlite3/mcap folder, or ROS 1 bag) and decode the HEXAR topics into records
(events/decode.py), naming each kind of damage with one error class."""

from __future__ import annotations

import sqlite3
from collections.abc import Callable, Iterable
from functools import lru_cache
from pathlib import Path

from rosbags.highlevel import AnyReader
from rosbags.interfaces import Connection
from rosbags.serde import SerdeError
from rosbags.typesys.store import Typestore

from hexar.events import contract as c
from hexar.events.bag import Reader
from hexar.events.cdr import LayoutError
from hexar.events.decode import decode
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
from hexar.events.recover import STORAGE, holds_storage, is_cut_short, loose_storage, read_recovered, storage_files
from hexar.events.storage_rows import mcap_rows, sqlite_messages


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
        if path.suffix in STORAGE:
            # one file of its folder's recording (its metadata.yaml, or the splits of one bag cut short), else a
            # recording of its own: never read with files beside it that another run wrote
            folder = path.parent
            split = holds_storage(folder) and len(storage_files(folder)) > 1
            return folder if (folder / "metadata.yaml").is_file() or split else path
        if path.name == "metadata.yaml":
            return resolve_path(path.parent)  # the file `ros2 bag info` prints: its folder is the recording
        raise NotARecordingError(f"not a recording: {path} (expected a rosbag2 folder or a ROS 1 .bag file)")
    loose = loose_storage(path)
    if loose:
        names = ", ".join(f.name for f in loose[:3]) + (", ..." if len(loose) > 3 else "")
        raise NotARecordingError(f"not one recording: {path} has no metadata.yaml and holds {len(loose)} storage "
                                 f"files of separate recordings ({names}): give one of them")
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


def read_recording(path: str | Path, topics: Iterable[str] | None = None) -> EventLog:
    """Read `topics` (default: every topic of the contract) of the recording at `path`.

    Connections on other topics are never deserialised; their counts come from the bag's index.
    """
    wanted = frozenset(topics) if topics is not None else c.ALL_TOPICS
    src = resolve_path(Path(path))
    cut = [f for f in src.glob("*.mcap") if is_cut_short(f)] if src.is_dir() else []
    if src.suffix in STORAGE and src.is_file():  # a storage file that is a recording of its own
        alone = [src] if src.suffix == ".mcap" and is_cut_short(src) else []
        log = _guarded(src, lambda: read_recovered(src, alone, lambda files: _read_files(files, src, wanted)))
    elif cut or holds_storage(src):
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
                key in c.OPTIONAL_TOPICS or key in c.ARM_STATUS_TOPICS):
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
            decode(log, conn, t, raw, typestores[conn.id], ros2, standard[conn.id], warnings)
        except _MISFIT as err:
            if standard[conn.id] or not ros2:
                raise _Unreadable(conn, f"its messages do not fit the standard {conn.msgtype} and the recording "
                                        f"stores no definition that fits them ({type(err).__name__}: {err})") from err
            # A stored definition that does not fit its own bytes (test bags carry such stand-ins): the standard
            # one may still fit them exactly, which the strict decoders check.
            try:
                decode(log, conn, t, raw, humble(), ros2, True, warnings)
            except Exception as err2:
                raise _Unreadable(conn, f"its messages fit neither the definition of {conn.msgtype} stored in "
                                        f"the recording nor the standard one ({type(err).__name__}: {err})") from err2
            standard[conn.id], typestores[conn.id] = True, humble()
            warnings.append(f"{conn.topic}: the definition of {conn.msgtype} stored in the recording does not fit "
                            "its messages; they fit the standard definition exactly and were read with it")
    log.finish()
    return log, seen > 0 or promised == 0


def _storage(src: Path) -> str:
    if src.suffix == ".bag":
        return "rosbag1"
    if src.suffix in STORAGE:
        return {".mcap": "mcap", ".db3": "sqlite3"}[src.suffix]
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
