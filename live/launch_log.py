"""Launch's log file on this computer, followed while the robot runs (stable API).

    log_root(environ=None) -> Path
    follower(given, horizon_s) -> LaunchLogFollower | None
    LaunchLogFollower(root, hold_s=2.0, oldest_ns=0).poll(now=None) -> list[LogLine]

A process that dies is told by launch alone ("process has died [pid N, exit code -11, cmd '…']"), and a node's
stderr (a Python traceback, rcl's errors before a node exists, the dynamic loader's last words) never reaches /rosout:
both are in `launch.log` (events/roslog.py reads it beside a recording). `ros2 launch` writes that file into a folder
of its own under $ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log (launch/logging/__init__.py:41-61@jazzy), and from
Jazzy on points `latest` in that folder at it (`_renew_latest_log_dir`). The follower reads `latest/launch.log`, or,
without a `latest` (Humble), the launch.log most recently written, looked for again when the folder changed or every
RESCAN_S (a robot keeps hundreds of launch folders: not at every poll); a new launch is followed from its first line.

Lines are handed on when the file has been quiet for one poll, or `hold_s` after they came: launch writes a
traceback line by line, and the console reader keeps it as one record only when it has all of it. Each line keeps
origin `launch.log`; its time is the node's own printed stamp, else launch's, both the computer's clock, as the stamps
of /rosout are. So HEXAR must run on the computer that runs the launch to read it; elsewhere there is nothing to read.
"""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from pathlib import Path

from hexar.events.contract import LAUNCH_LOG
from hexar.events.records import LogLine
from hexar.events.roslog import launch_log_lines

CHUNK = 4 * 1024 * 1024  # read at most this much per poll: a launch started long ago is caught up in steps
RESCAN_S = 5.0  # a new launch folder's launch.log may come after the folder: looked for again this often
NS = 1_000_000_000


def log_root(environ: Mapping[str, str] | None = None) -> Path:
    """The folder launch writes its log folders into, as launch computes it."""
    env = os.environ if environ is None else environ
    if env.get("ROS_LOG_DIR"):
        return Path(env["ROS_LOG_DIR"]).expanduser()
    home = Path(env["ROS_HOME"]).expanduser() if env.get("ROS_HOME") else Path("~/.ros").expanduser()
    return home / "log"


def follower(given: Path | None, horizon_s: float) -> LaunchLogFollower | None:
    """The follower of launch's log under `given`, else under log_root() when that folder exists (None when it does
    not); a launch of yesterday is not what the robot did now, so lines older than `horizon_s` are left out."""
    root = given or log_root()
    if given is None and not root.is_dir():
        return None
    return LaunchLogFollower(root, oldest_ns=time.time_ns() - int(horizon_s * NS))


class LaunchLogFollower:
    """Reads what the current launch appends to its launch.log, one poll at a time."""

    def __init__(self, root: Path, hold_s: float = 2.0, oldest_ns: int = 0) -> None:
        self.root = root
        self.hold_s = hold_s
        self.oldest_ns = oldest_ns  # lines stamped before this are left out
        self.path: Path | None = None
        self._offset = 0
        self._pending: list[str] = []
        self._since = 0.0
        self._listed: tuple[int, float] | None = None  # the root's mtime and the monotonic time of the last look
        self._newest: Path | None = None

    def current(self) -> Path | None:
        """The launch.log of the newest launch under the root; None when there is none."""
        latest = self.root / "latest" / LAUNCH_LOG
        if latest.is_file():
            return latest.resolve()
        try:
            changed = self.root.stat().st_mtime_ns
        except OSError:
            return None
        now = time.monotonic()
        if self._listed is None or self._listed[0] != changed or now - self._listed[1] >= RESCAN_S:
            self._listed = (changed, now)
            try:
                found = [(p.stat().st_mtime, p) for p in self.root.glob(f"*/{LAUNCH_LOG}")]
            except OSError:
                return None
            self._newest = max(found)[1] if found else None
        return self._newest

    def poll(self, now: float | None = None) -> list[LogLine]:
        """The lines that are complete and whole since the last poll (see the module's docstring)."""
        now = time.monotonic() if now is None else now
        path = self.current()
        if path != self.path:  # a new launch (or the first): from its first line
            self.path, self._offset, self._pending, self._since = path, 0, [], 0.0
        text = self._read() if path is not None else ""
        if text:
            self._pending.append(text)
            self._since = self._since or now
        if not self._pending or (text and now - self._since < self.hold_s):
            return []
        lines = launch_log_lines("".join(self._pending))
        self._pending, self._since = [], 0.0
        return [ln for ln in lines if ln.t >= self.oldest_ns]

    def _read(self) -> str:
        assert self.path is not None
        try:
            if self.path.stat().st_size < self._offset:
                self._offset = 0  # the file was cut or written anew
            with self.path.open("rb") as f:
                f.seek(self._offset)
                data = f.read(CHUNK)
        except OSError:
            return ""  # gone between the look and the read: the next poll finds the new one
        whole = data[:data.rfind(b"\n") + 1]  # a line launch is still writing waits for its end
        self._offset += len(whole)
        return whole.decode("utf-8", errors="replace")
