"""A rolling rosbag2 recording of what the live node received, so a live answer can be replayed and checked
later with `hexar ask`. One bag per `chunk_s` of this machine's time; only the newest `keep` bags stay on disk.

Chunks follow our own clock, not the messages' stamps: a stamp is whatever the publisher wrote, and stamps
alternating +/-1000 s once rotated the bag on every message, so the kept bags held one junk message each and
everything recorded before was deleted. Bag names carry a counter that never repeats in a session and skip a
name already taken, so a clash cannot switch recording off.
"""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path
from typing import Any

from hexar.live.errors import BadOptionError

MAX_STAMP = 2**63 - 1


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
        self._started = 0  # time.monotonic_ns() when the current bag was opened
        self._count = 0
        self.failed = False

    def write(self, topic: str, ros_type: str, raw: bytes, t: int) -> None:
        """`raw`: the message's CDR (with its 4-byte encapsulation header), as rosbag2 stores it."""
        if self.failed:
            return
        if not 0 <= t <= MAX_STAMP:  # a stamp rosbag2 cannot store is recorded at its arrival
            t = time.time_ns()
        try:
            if self._writer is None or time.monotonic_ns() - self._started >= self.chunk_ns:
                self._rotate()
            conn = self._conns.get(topic)
            if conn is None:
                from hexar.events.humble import humble

                conn = self._conns[topic] = self._writer.add_connection(topic, ros_type, typestore=humble())
            self._writer.write(conn, t, raw)
        except Exception as err:  # a full disk must not stop the node from answering
            self.failed = True
            print(f"hexar serve: recording stopped: {type(err).__name__}: {err}", file=sys.stderr)

    def _next_path(self) -> Path:
        stamp = time.strftime("%Y%m%d_%H%M%S", time.gmtime())
        while True:
            self._count += 1
            path = self.folder / f"live_{stamp}_{self._count:04d}"
            if not path.exists():
                return path

    def _rotate(self) -> None:
        from rosbags.rosbag2 import Writer

        self.close()
        path = self._next_path()
        self._writer = Writer(path, version=9)
        self._writer.open()
        self._conns, self._started = {}, time.monotonic_ns()
        self.bags.append(path)
        while len(self.bags) > self.keep:
            shutil.rmtree(self.bags.pop(0), ignore_errors=True)

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
            self._writer = None
