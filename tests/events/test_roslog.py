"""ROS 2 launch's log file beside a recording, read with the recording: real launch.log files that ros2/launch
(jazzy) wrote here while it started real rclpy programs with bring-up faults (scripts/launch_logs.py), and
recordings written with rosbags around their times."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.records import ERROR, INFO, LogLine
from hexar.events.roslog import launch_logs, read_launch_log

LOGS = Path(__file__).parent / "launch_logs"
# launch's own time for the first line of the params_file run, and odom_relay's first line with its own stamp
FIRST = 1795927629259869300
RELAYED = 1795927629810320651


def _recording(tmp_path: Path, run: str, start: int, end: int, rosout: list[LogLine], where: str = "log") -> Path:
    b = BagBuilder()
    b.log(start, "recorder", INFO, "recording started")
    for line in rosout:
        b.log(line.t, line.name, line.level, line.msg)
    b.log(end, "recorder", INFO, "recording stopped")
    rec = b.write(tmp_path / "rec")
    target = rec / where / f"2026-11-29-04-40-29-259869-robot-{run}" if where else rec
    target.mkdir(parents=True, exist_ok=True)
    shutil.copy(LOGS / run / "launch.log", target / "launch.log")
    return rec


def test_a_python_traceback_is_one_error_line_of_its_process() -> None:
    lines = read_launch_log(LOGS / "params_file" / "launch.log")
    errors = [ln for ln in lines if ln.level >= ERROR]
    assert [ln.name for ln in errors] == ["scan_filter-2", "scan_filter-2"]
    raised, died = errors
    assert raised.msg.startswith("rclpy.exceptions.InvalidParameterTypeException: Trying to set parameter "
                                 "'scan_rate' to 'fast' of type 'STRING', expecting type 'INTEGER'")
    assert 'File "/home/robot/ws/scan_filter.py", line 7, in <module>' in raised.msg  # the frames stay with it
    assert died.msg.startswith("process has died [pid 21679, exit code 1, cmd '")
    assert all(ln.origin == c.LAUNCH_LOG for ln in lines)
    # a node's own line keeps its logger and its own stamp, not launch's
    relayed = next(ln for ln in lines if ln.msg == "relayed odometry message 0")
    assert (relayed.name, relayed.t) == ("odom_relay", RELAYED)


def test_a_traceback_raised_in_a_callback_names_the_exception_first() -> None:
    raised = next(ln for ln in read_launch_log(LOGS / "crash" / "launch.log") if ln.level >= ERROR)
    assert raised.msg.splitlines()[0] == "ValueError: min() arg is an empty sequence"
    assert 'File "/home/robot/ws/scan_filter.py", line 12, in tick' in raised.msg


def test_screen_output_leaves_launch_its_own_lines_only() -> None:
    lines = read_launch_log(LOGS / "screen" / "launch.log")
    assert [ln.name for ln in lines] == ["launch", "launch", "scan_filter-4", "scan_filter-4"]
    assert lines[-1].level == ERROR and "exit code 1" in lines[-1].msg


@pytest.mark.parametrize("where", ["", "log"])
def test_a_recording_reads_the_launch_log_in_its_folder(tmp_path: Path, where: str) -> None:
    on_rosout = LogLine(RELAYED, INFO, "odom_relay", "relayed odometry message 0")
    rec = _recording(tmp_path, "params_file", FIRST + 10**8, 1795927629900000000, [on_rosout], where)
    assert launch_logs(rec)
    log = read_recording(rec)
    # the line that reached /rosout is read once, from /rosout; lines after the recording's end are left out
    assert [ln.origin for ln in log.logs if ln.msg == on_rosout.msg] == [c.ROSOUT]
    assert not any(ln.msg == "relayed odometry message 1" for ln in log.logs)
    died = next(ln for ln in log.logs if ln.msg.startswith("process has died"))
    assert (died.name, died.origin) == ("scan_filter-2", c.LAUNCH_LOG)
    assert log.start == FIRST  # the recording now begins with the launch's first line
    assert log.topics[c.LAUNCH_LOG].count == sum(1 for ln in log.logs if ln.origin == c.LAUNCH_LOG)
    assert [ln.t for ln in log.logs] == sorted(ln.t for ln in log.logs)


def test_without_a_launch_log_nothing_is_added(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(FIRST, "recorder", INFO, "recording started")
    rec = b.write(tmp_path / "rec")
    (rec / "log").mkdir()
    (rec / "log" / "robot.log").write_text("1795927629.2598693 [ERROR] [launch]: not launch.log\n")
    log = read_recording(rec)
    assert [ln.origin for ln in log.logs] == [c.ROSOUT]


def test_ask_explains_a_death_only_launch_log_shows_and_cites_it(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.cli import main

    # the robot's /rosout held only the scan filter's start line: its traceback and death went to launch.log
    started = LogLine(1795927630609408233, INFO, "scan_filter", "filtering scans at 10 Hz")
    rec = _recording(tmp_path, "crash", 1795927630300000000, 1795927631000000000, [started])
    assert main(["ask", str(rec), "Why didn't that work?", "--llm", "none", "--json", "--verbose"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert "died of an uncaught Python exception (ValueError)" in row["answer"]
    assert "“[scan_filter-3] min() arg is an empty sequence”, raised in tick" in row["answer"]
    cited = [e for e in row["evidence"] if e["topic"] == c.LAUNCH_LOG]
    assert cited and cited[0]["item"].startswith("[scan_filter-3] ERROR ValueError: min() arg is an empty sequence")


def test_without_its_launch_log_the_same_recording_shows_no_failure(tmp_path: Path,
                                                                   capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.cli import main

    started = LogLine(1795927630609408233, INFO, "scan_filter", "filtering scans at 10 Hz")
    rec = _recording(tmp_path, "crash", 1795927630300000000, 1795927631000000000, [started])
    shutil.rmtree(rec / "log")
    assert main(["ask", str(rec), "Why didn't that work?", "--llm", "none"]) == 2
    assert "no task to explain" in capsys.readouterr().err


def test_a_launch_log_of_garbage_bytes_is_read_without_inventing_a_failure(tmp_path: Path,
                                                                           capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.cli import main

    rec = _recording(tmp_path, "screen", FIRST, FIRST + 10**9, [])
    (next(rec.glob("log/*")) / "launch.log").write_bytes(bytes(range(256)) * 40)
    log = read_recording(rec)
    assert not [t for t in log.tasks if t.outcome == "failed"]
    assert main(["ask", str(rec), "Why didn't that work?", "--llm", "none"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: no task to explain") and len(err.strip().splitlines()) == 1
