"""One timeline whatever the robot's clock, on a real recording's messages as a transport hands them over: the
robot live (source times are its clock), `ros2 bag play` of an old recording at x10 (stamps of the recording day,
source times of today; with and without /clock), and simulated time (stamps and /clock from 100 s after the
simulation's start). Each gives the failure's cause `hexar ask` gives on the recording. Real DDS traffic for the
same clocks: tests/live/test_replay_explains.py::test_every_robot_clock."""

from __future__ import annotations

import copy
import time
from pathlib import Path
from typing import Any

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.events import read_recording
from hexar.events.humble import humble
from hexar.live.clock import CLOCK, NS, Timeline
from hexar.live.log import LiveLog
from hexar.live.node import FAILURE_QUESTION
from hexar.live.replay import bag_messages

TODAY = 1_800_000_000 * NS  # a source time years after the recording
RUN = "bagfile_11_1"  # ask human for help: nobody detected


def _restamp(msg: Any, shift: int) -> Any:
    msg = copy.deepcopy(msg)
    stamp = msg.stamp if hasattr(msg, "stamp") else getattr(getattr(msg, "header", None), "stamp", None)
    if stamp is not None and (stamp.sec or stamp.nanosec):
        t = stamp.sec * NS + stamp.nanosec + shift
        stamp.sec, stamp.nanosec = t // NS, t % NS
    return msg


def robot(run: Path, clock: str) -> tuple[Timeline, LiveLog, int]:
    """Feed the recording through a Timeline as `clock`'s robot would send it; the shift of its stamps."""
    played = bag_messages(run)
    messages, start = played.messages, played.start
    timeline, log = Timeline(), LiveLog()
    rate = 1.0 if clock == "live" else 10.0
    shift = 100 * NS - start if clock == "sim" else 0  # simulated time: the run starts 100 s into the simulation
    clock_type = humble().types["rosgraph_msgs/msg/Clock"]
    time_type = humble().types["builtin_interfaces/msg/Time"]
    for topic, _, t, msg in messages:
        source = t if clock == "live" else TODAY + int((t - start) / rate)
        if clock in {"bag-play --clock", "sim"}:
            now = t + shift
            timeline.records(CLOCK, clock_type(clock=time_type(sec=now // NS, nanosec=now % NS)), source)
        log.extend(timeline.records(topic, _restamp(msg, shift), source))
    log.extend(timeline.flush())
    return timeline, log, shift


@pytest.mark.parametrize("clock", ["live", "bag-play", "bag-play --clock", "sim"])
def test_every_clock_gives_the_recordings_answer(suite: Path, clock: str) -> None:
    run = suite / RUN
    rec = read_recording(run)
    (failed,) = [t for t in rec.tasks if t.outcome == "failed"]
    want = Session(RunSettings(recording=run, llm="none")).ask(FAILURE_QUESTION, task=failed.task_id)["causes"]
    timeline, log, shift = robot(run, clock)
    snap = log.snapshot()
    # every unstamped update lands where the recorder put it, on the robot's clock, within a few milliseconds
    # (the simulated recorder receives a stamped message 2 ms after its stamp)
    assert len(snap.task_updates) == len(rec.task_updates)
    for live, recorded in zip(snap.task_updates, rec.task_updates, strict=True):
        assert abs(live.t - (recorded.t + shift)) < 5_000_000, clock
    assert timeline.rate == pytest.approx(1.0 if clock == "live" else 10.0, rel=1e-3)
    session = Session(RunSettings(recording=Path("live"), llm="none"), log=snap)
    assert session.ask(FAILURE_QUESTION, task=failed.task_id)["causes"] == want == ["ask_human.nobody_detected"]


def test_a_robot_with_no_clock_of_its_own_keeps_source_times() -> None:
    """Before any reference an unstamped message waits; a robot that never sends one is dated by source time."""
    timeline = Timeline(hold_s=0.05)
    msg = humble().types["std_msgs/msg/Bool"](data=True)
    assert timeline.records("/joy_priority", msg, 5 * NS) == []  # held: no reference yet
    assert timeline.flush() == []
    time.sleep(0.1)
    (flag,) = timeline.flush()
    assert flag.t == 5 * NS and flag.value is True
