"""A rolling rosbag2 recording of what the live node received, so a live answer can be replayed and checked
later with `hexar ask`. One bag per `chunk_s` of robot time; only the newest `keep` bags stay on disk."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path
from typing import Any

from hexar.live.errors import BadOptionError


class RollingRecorder:
    def __init__(self, folder: Path, chunk_s: float = 300.0, keep: int = 12) -> None:
        if chunk_s <= 0 or keep < 1:
            raise BadOptionError("--record-chunk must be above 0 and --record-keep at least 1")
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise BadOptionError(f"cannot record into {folder}: {err.strerror or err}") from err
        self.folder, self.chunk_ns, self.keep = folder, int(chunk_s * 1e9), keep
        self.bags: list[Path] = []
        self._writer: Any = None
        self._conns: dict[str, Any] = {}
        self._start = 0
        self.failed = False

    def write(self, topic: str, ros_type: str, raw: bytes, t: int) -> None:
        """`raw`: the message's CDR (with its 4-byte encapsulation header), as rosbag2 stores it."""
        if self.failed:
            return
        try:
            # a new bag per chunk, and on a clock that went back by a chunk (messages a little out of order stay)
            if self._writer is None or t - self._start >= self.chunk_ns or t < self._start - self.chunk_ns:
                self._rotate(t)
            conn = self._conns.get(topic)
            if conn is None:
                from hexar.events.reader import _humble

                conn = self._conns[topic] = self._writer.add_connection(topic, ros_type, typestore=_humble())
            self._writer.write(conn, t, raw)
        except Exception as err:  # a full disk must not stop the node from answering
            self.failed = True
            print(f"hexar serve: recording stopped: {type(err).__name__}: {err}", file=sys.stderr)

    def _rotate(self, t: int) -> None:
        from rosbags.rosbag2 import Writer

        self.close()
        path = self.folder / f"live_{t // 1_000_000_000}_{len(self.bags):04d}"
        self._writer = Writer(path, version=9)
        self._writer.open()
        self._conns, self._start = {}, t
        self.bags.append(path)
        while len(self.bags) > self.keep:
            shutil.rmtree(self.bags.pop(0), ignore_errors=True)

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
            self._writer = None
