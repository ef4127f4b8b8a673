"""ROS 2 launch's log file beside a recording: the lines that never reach /rosout (stable API).

    launch_logs(folder) -> list[Path]
    read_launch_log(path, until=None) -> list[LogLine]
    launch_log_lines(text) -> list[LogLine]
    merge_launch_logs(log) -> None

`ros2 launch` writes `launch.log` into its own folder under ~/.ros/log (launch/logging/__init__.py@jazzy). It holds
launch's own lines, "{created:.7f} [LEVEL] [logger]: msg" ("process started with pid", "process has died [pid, exit
code, cmd]", "Caught exception in launch"), and, for processes whose output is 'log' (a launch_ros Node's default),
'both' or 'full', every line they print as "{created:.7f} [process-N] line": stderr too, which /rosout never carries,
such as a Python node's traceback (rclpy's RCLError when rcl refused its arguments), rcl's errors before a node
exists, the dynamic loader's and libstdc++'s last words, and Fast DDS's and Cyclone DDS's own errors.

A recording's folder may hold that log: `launch.log` in the folder or in a subfolder up to two levels down (a copy of
the launch's log folder, e.g. `log/2026-11-29-04-40-12-…/launch.log`). Its lines are read with the console reader
(events/console.py), stamped with the node's own time where printed and launch's time otherwise, and added to the
recording's log lines with origin LAUNCH_LOG. Lines after the recording's end are left out: they cannot explain it.
A line that also reached /rosout (the same text at the same stamp) is read once, from /rosout.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from hexar.events.contract import LAUNCH_LOG
from hexar.events.errors import CorruptRecordingError
from hexar.events.log import EventLog, TopicInfo
from hexar.events.records import LogLine

if TYPE_CHECKING:
    from hexar.events.console import ConsoleLine

LOG_FILE_TYPE = "text: ROS 2 launch's log file (lines read)"
MAX_BYTES = 64 * 1024 * 1024  # a launch that ran for weeks with chatty nodes: read its first 64 MiB only


def launch_logs(folder: Path) -> list[Path]:
    """The launch.log files in `folder` and its subfolders up to two levels down, in name order."""
    if not folder.is_dir():
        return []
    found = [folder / LAUNCH_LOG, *folder.glob(f"*/{LAUNCH_LOG}"), *folder.glob(f"*/*/{LAUNCH_LOG}")]
    return sorted(p for p in found if p.is_file())


def _line(r: ConsoleLine) -> LogLine:
    assert r.stamp_ns is not None
    # a process's own output without a logger (stderr) is told by launch's name for the process
    return LogLine(r.stamp_ns, r.level, r.name or r.process, r.msg, LAUNCH_LOG)


def read_launch_log(path: Path, until: int | None = None) -> list[LogLine]:
    """The lines of one launch.log, oldest first, without those stamped after `until` (ns)."""
    try:
        with path.open("rb") as f:
            raw = f.read(MAX_BYTES)
    except OSError as err:
        raise CorruptRecordingError(f"cannot read {path}: {err.strerror or err}") from err
    lines = launch_log_lines(raw.decode("utf-8", errors="replace"))
    return [ln for ln in lines if until is None or ln.t <= until]


def launch_log_lines(text: str) -> list[LogLine]:
    """The lines of launch.log text (whole lines), oldest first, with origin LAUNCH_LOG; live/launch_log.py reads a
    launch's file as it grows with this too."""
    # imported here: every recording is read through this module, few have a launch.log beside them
    from hexar.events.console import parse_console, stamped

    return sorted((_line(r) for r in stamped(parse_console(text))), key=lambda ln: ln.t)


def merge_launch_logs(log: EventLog) -> None:
    """Add the lines of the launch logs in `log`'s recording folder to its log lines (see the module's docstring)."""
    files = launch_logs(log.path)
    if not files:
        return
    seen = {(ln.t, ln.msg) for ln in log.logs}
    added = 0
    for path in files:
        for line in read_launch_log(path, until=log.end):
            if (line.t, line.msg) not in seen:
                seen.add((line.t, line.msg))
                log.logs.append(line)
                added += 1
    if added:
        # the recording now begins with the launch's first line: times in answers count from there
        log.start = min(log.start, min(ln.t for ln in log.logs))
        # shown beside the recorded topics (`hexar inspect`, the web page's contract), as what it is
        log.topics[LAUNCH_LOG] = TopicInfo(LAUNCH_LOG, LOG_FILE_TYPE, added)
        log.finish()
