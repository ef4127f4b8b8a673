"""The rows of selected topics read straight from rosbag2 storage, faster than rosbags' time-ordered merge."""

from __future__ import annotations

import itertools
import sqlite3
from collections.abc import Iterator
from pathlib import Path

from rosbags.interfaces import Connection

from hexar.events.bag import metadata
from hexar.events.mcap_index import check_mcap, mcap_messages


def sqlite_messages(src: Path, selected: list[Connection]) -> Iterator[tuple[Connection, int, bytes]] | None:
    """Rows of the selected topics straight from uncompressed sqlite3 storage, in file order.

    rosbags walks the timestamp index and visits every row in time order, so a big unsubscribed topic (camera
    images interleaved with the logs) slows it down; a filter on topic_id alone reads only the rows we need.
    Records are sorted by their own stamps afterwards anyway.
    """
    files = sorted(src.glob("*.db3")) if src.is_dir() else []
    meta = src / "metadata.yaml"
    if not files or not meta.is_file():
        return None
    info = metadata(meta).get("rosbag2_bagfile_information", {})
    if info.get("compression_format") or info.get("compression_mode"):
        return None
    wanted = {(conn.topic, conn.msgtype): conn for conn in selected}

    def rows() -> Iterator[tuple[Connection, int, bytes]]:
        for file in files:
            db = sqlite3.connect(f"file:{file}?mode=ro", uri=True)
            try:
                ids = {tid: wanted[(name, typ)] for tid, name, typ in db.execute("SELECT id, name, type FROM topics")
                       if (name, typ) in wanted}
                if not ids:
                    continue
                marks = ",".join("?" * len(ids))
                query = f"SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN ({marks})"
                for tid, t, data in db.execute(query, list(ids)):
                    yield ids[tid], t, data
            finally:
                db.close()

    return rows()


def mcap_rows(src: Path, selected: list[Connection]) -> Iterator[tuple[Connection, int, bytes]] | None:
    """Rows of the selected topics from indexed MCAP files without rosbags' per-chunk heap merge."""
    files = sorted(src.glob("*.mcap")) if src.is_dir() else []
    if not files:
        return None
    wanted = {(conn.topic, conn.msgtype): conn for conn in selected}
    parts = [mcap_messages(f, wanted) for f in files]
    if any(p is None for p in parts):
        for f in files:
            check_mcap(f)  # rosbags reads on without checking CRCs or truncation
        return None
    return itertools.chain.from_iterable(p for p in parts if p is not None)
