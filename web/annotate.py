"""`hexar annotate RUN --out FILE.mcap`: the recording, copied with its schemas, plus HEXAR's explanations.

Added topics:
- `/hexar/explanations` (std_msgs/msg/String): per task, the JSON object `hexar ask --json` gives for the
  generic question, stamped when the task failed (or last changed).
- `/hexar/log` (rcl_interfaces/msg/Log): the answer as a log line at the same time, and each cited evidence
  item at its own time, so both show on the Log panel and timeline of Foxglove or any ROS-aware MCAP viewer.

The log is rcl_interfaces/msg/Log rather than a JSON-schema foxglove.Log because rosbags' MCAP reader only
accepts ros2msg/ros2idl/omgidl schemas: a JSON-schema channel would make the file unreadable to rosbags.
"""

from __future__ import annotations

import heapq
import json
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexar.web.errors import AnnotateError

EXPLANATIONS = "/hexar/explanations"
HEXAR_LOG = "/hexar/log"
STRING = "std_msgs/msg/String"
LOG = "rcl_interfaces/msg/Log"
INFO, WARN, ERROR = 20, 30, 40


@dataclass(frozen=True, order=True)
class Extra:
    t: int
    topic: str
    data: bytes


def _log_cdr(typestore: Any, t: int, level: int, name: str, msg: str) -> bytes:
    types = typestore.types
    stamp = types["builtin_interfaces/msg/Time"](sec=t // 1_000_000_000, nanosec=t % 1_000_000_000)
    m = types[LOG](stamp=stamp, level=level, name=name, msg=msg, file="", function="", line=0)
    return bytes(typestore.serialize_cdr(m, LOG))


def extras(typestore: Any, log: Any, results: list[dict[str, Any]]) -> list[Extra]:
    """The added messages, one explanation per task plus its log lines."""
    out: list[Extra] = []
    for result in results:
        task = log.task(result["task_id"])
        t = task.window()[1]
        body = json.dumps(result)
        out.append(Extra(t, EXPLANATIONS, bytes(typestore.serialize_cdr(typestore.types[STRING](data=body), STRING))))
        level = ERROR if task.outcome in {"failed", "invalid"} else INFO
        text = result["answer"] or result["error"]
        causes = ", ".join(result["causes"])
        out.append(Extra(t, HEXAR_LOG, _log_cdr(typestore, t, level, "hexar",
                                                f"task {task.order} {task.outcome}: {text}"
                                                + (f" [{causes}]" if causes else ""))))
        for ev in result["evidence"]:
            out.append(Extra(int(ev["t"]), HEXAR_LOG, _log_cdr(typestore, int(ev["t"]), WARN, "hexar.evidence",
                                                               f"{ev['cause']}: {ev['topic']} {ev['item']}")))
    return sorted(out)


def _originals(path: Path) -> tuple[Any, Iterator[tuple[int, int, bytes]]]:
    from rosbags.highlevel import AnyReader
    from rosbags.highlevel.anyreader import AnyReaderError
    from rosbags.rosbag2 import Reader
    from rosbags.rosbag2.errors import ReaderError

    try:
        # a rosbag2 folder, or one MCAP or sqlite3 file that is a recording of its own (AnyReader reads a file)
        reader: Any = Reader(path) if path.is_dir() else AnyReader([path])
        reader.open()
    except (ReaderError, AnyReaderError, OSError) as err:
        raise AnnotateError(f"cannot read {path}: {err}") from err

    def stream() -> Iterator[tuple[int, int, bytes]]:
        try:
            for conn, t, raw in reader.messages():
                yield t, conn.id, bytes(raw)
        finally:
            reader.close()

    return reader, stream()


def annotate(run: Path, out: Path, llm: str = "none") -> int:
    """Write `out`; return the number of explanations added."""
    from mcap.writer import CompressionType, Writer
    from rosbags.typesys import Stores, get_typestore

    from hexar.events.reader import resolve_path
    from hexar.web.explain import explain_tasks

    source = resolve_path(run)
    if source.suffix == ".bag":
        raise AnnotateError(f"cannot annotate {run}: only rosbag2 recordings (sqlite3 or mcap) are copied, "
                            "not ROS 1 bags")
    log, results = explain_tasks(run, llm)
    if not results:
        log.task()  # no task: the same one-line error as every command
    typestore = get_typestore(Stores.ROS2_HUMBLE)
    added = extras(typestore, log, results)
    reader, originals = _originals(source)
    try:
        fh = out.open("wb")
    except OSError as err:
        reader.close()
        raise AnnotateError(f"cannot write {out}: {err.strerror or err}") from err
    with fh:
        writer = Writer(fh, compression=CompressionType.ZSTD)
        writer.start(profile="ros2", library="hexar annotate")
        schemas: dict[str, int] = {}
        channels: dict[Any, int] = {}

        def schema(msgtype: str, msgdef: str) -> int:
            if msgtype not in schemas:
                text = msgdef or typestore.generate_msgdef(msgtype, ros_version=2)[0]
                schemas[msgtype] = writer.register_schema(msgtype, "ros2msg", text.encode())
            return schemas[msgtype]

        # a copy annotated before: its explanations are replaced by today's, not kept beside them on a second channel
        stale = {conn.id for conn in reader.connections if conn.topic in {EXPLANATIONS, HEXAR_LOG}}
        for conn in reader.connections:
            if conn.id not in stale:
                channels[conn.id] = writer.register_channel(conn.topic, "cdr", schema(conn.msgtype,
                                                                                     conn.msgdef.data))
        for topic, msgtype in ((EXPLANATIONS, STRING), (HEXAR_LOG, LOG)):
            channels[topic] = writer.register_channel(topic, "cdr", schema(msgtype, ""))
        merged = heapq.merge(originals, ((e.t, e.topic, e.data) for e in added), key=lambda m: m[0])
        for t, key, data in merged:
            if key in stale:
                continue
            writer.add_message(channels[key], log_time=t, data=data, publish_time=t)
        writer.finish()  # type: ignore[no-untyped-call]
    return sum(1 for e in added if e.topic == EXPLANATIONS)
