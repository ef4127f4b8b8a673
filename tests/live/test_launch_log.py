"""Launch's log followed while the robot runs (live/launch_log.py): a real launch.log that ros2/launch wrote here
(tests/events/launch_logs/crash: a Kilted rclpy node whose timer callback raised), grown on disk as launch grows it,
read into the live log beside /rosout, and asked about through `hexar serve` over DDS."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

from hexar.events.contract import LAUNCH_LOG
from hexar.events.records import ERROR, INFO, LogLine
from hexar.events.roslog import LOG_FILE_TYPE
from hexar.live.launch_log import LaunchLogFollower, log_root
from hexar.live.log import LiveLog
from tests.explainers.helpers import explain
from tests.live.dds_helpers import DEFAULT, Listener, fresh_domain

CRASH = Path(__file__).parents[1] / "events" / "launch_logs" / "crash" / "launch.log"
_STAMP = re.compile(r"\b(1795927\d{3})\.(\d+)")


def _now_lines() -> list[str]:
    """The crash's launch.log, its stamps (launch's and the node's) moved to end a second ago."""
    text = CRASH.read_text(encoding="utf-8")
    last = max(float(f"{a}.{b}") for a, b in _STAMP.findall(text))
    shift = time.time() - 1.0 - last
    moved = _STAMP.sub(lambda m: f"{float(m[0]) + shift:.{len(m[2])}f}", text)
    return moved.splitlines(keepends=True)


def _launch(root: Path, name: str, lines: list[str], latest: bool = True) -> Path:
    folder = root / name
    folder.mkdir(parents=True)
    (folder / LAUNCH_LOG).write_text("".join(lines), encoding="utf-8")
    if latest:
        link = root / "latest"
        if link.is_symlink():
            link.unlink()
        link.symlink_to(folder, target_is_directory=True)
    return folder / LAUNCH_LOG


def test_log_root_is_where_launch_writes() -> None:
    assert log_root({"ROS_LOG_DIR": "/var/log/ros", "ROS_HOME": "/x"}) == Path("/var/log/ros")
    assert log_root({"ROS_HOME": "/srv/ros"}) == Path("/srv/ros/log")
    assert log_root({}) == Path("~/.ros/log").expanduser()


def test_the_newest_launch_is_read_as_it_grows_with_a_traceback_kept_whole(tmp_path: Path) -> None:
    lines = _now_lines()
    path = _launch(tmp_path, "2026-11-29-07-00-00-000000-robot-1", lines[:6])  # cut inside the traceback
    follower = LaunchLogFollower(tmp_path)
    assert follower.poll(now=0.0) == []  # held: launch may still be writing the traceback
    first = follower.poll(now=0.5)
    assert [ln.msg for ln in first[:3]] == ["All log files can be found below /home/robot/ws/log/crash",
                                            "Default logging verbosity is set to INFO",
                                            "process started with pid [21717]"]
    assert {ln.origin for ln in first} == {LAUNCH_LOG}
    with path.open("a", encoding="utf-8") as f:
        f.write("".join(lines[6:]) + "1795999999.0 [scan_filter-3] a line launch is still writ")
    follower.poll(now=1.0)
    rest = follower.poll(now=1.5)
    died = [ln for ln in rest if ln.msg.startswith("process has died")]
    assert died and died[0].level == ERROR and died[0].name == "scan_filter-3"
    assert not any("still writ" in ln.msg for ln in rest)  # a line without its end waits for it


def test_a_new_launch_is_followed_from_its_first_line_and_humbles_newest_folder_without_latest(
        tmp_path: Path) -> None:
    lines = _now_lines()
    _launch(tmp_path / "jazzy", "a", lines[:3])
    follower = LaunchLogFollower(tmp_path / "jazzy")
    follower.poll(now=0.0)
    assert len(follower.poll(now=0.5)) == 3
    _launch(tmp_path / "jazzy", "b", lines[:2])  # `latest` moved to the new launch
    follower.poll(now=1.0)
    again = follower.poll(now=1.5)
    assert len(again) == 2 and again[0].msg.startswith("All log files")
    old = _launch(tmp_path / "humble", "old", lines[:1], latest=False)
    _launch(tmp_path / "humble", "new", lines[:2], latest=False)
    past = time.time() - 3600
    os.utime(old, (past, past))
    humble = LaunchLogFollower(tmp_path / "humble")
    assert humble.current() == tmp_path / "humble" / "new" / LAUNCH_LOG
    newer = _launch(tmp_path / "humble", "newer", lines[:1], latest=False)  # a new folder: the root changed
    os.utime(tmp_path / "humble", (time.time() + 60, time.time() + 60))
    assert humble.current() == newer


def test_lines_of_a_launch_before_the_horizon_are_left_out(tmp_path: Path) -> None:
    _launch(tmp_path, "a", _now_lines())
    follower = LaunchLogFollower(tmp_path, oldest_ns=time.time_ns() + 10**12)
    follower.poll(now=0.0)
    assert follower.poll(now=0.5) == []


def test_the_live_log_keeps_launch_lines_beside_rosout_once_and_explains_the_death(tmp_path: Path) -> None:
    _launch(tmp_path, "a", _now_lines())
    follower = LaunchLogFollower(tmp_path)
    follower.poll(now=0.0)
    read = follower.poll(now=0.5)
    started = next(ln for ln in read if ln.msg == "filtering scans at 10 Hz")
    live = LiveLog()
    live.add(LogLine(started.t, INFO, "scan_filter", started.msg))  # the same line as /rosout carried it
    assert live.extend(read) == len(read) - 1
    snapshot = live.snapshot()
    assert snapshot.topics[LAUNCH_LOG].type == LOG_FILE_TYPE and snapshot.topics[LAUNCH_LOG].count == len(read) - 1
    task, found = explain(snapshot, "control", "Why didn't that work?")
    assert task.outcome == "failed" and found.causes == ["bringup.process_died"]
    assert "min() arg is an empty sequence" in found.text
    assert LAUNCH_LOG in {e.topic for e in found.evidence}


def test_serve_answers_from_the_launch_log_of_this_computer(tmp_path: Path) -> None:
    _launch(tmp_path, "2026-11-29-07-00-00-000000-robot-1", _now_lines())
    domain = fresh_domain()
    serve = subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", DEFAULT, "--domain", str(domain),
                              "--launch-log", str(tmp_path), "--proactive", "off", "--duration", "60"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    listener = Listener(domain)
    try:
        assert serve.stderr is not None
        assert f"listening over {DEFAULT}" in serve.stderr.readline()
        assert f"following launch's log under {tmp_path}" in serve.stderr.readline()
        time.sleep(1.5)  # two polls: the file is read, then handed on
        listener.ask("Why didn't that work?")
        answers = listener.wait_answers(1, "question", timeout=20)
    finally:
        listener.close()
        serve.send_signal(signal.SIGTERM)
        out, err = serve.communicate(timeout=30)
    assert answers and answers[0]["causes"] == ["bringup.process_died"], answers
    assert "min() arg is an empty sequence" in answers[0]["answer"]
    assert [json.loads(x)["trigger"] for x in out.splitlines()] == ["question"]
    assert serve.returncode == 0 and "Traceback" not in err
