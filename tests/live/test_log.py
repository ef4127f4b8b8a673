"""The live event log on real recordings: the same records as the recording reader, in any arrival order,
with duplicates, bounded, and sane across a clock jump."""

from __future__ import annotations

import random
import threading
import time
from pathlib import Path

from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.records import BoolSample, LogLine, ParameterSample, SkillStep, TaskUpdate
from hexar.live.contact import Contact
from hexar.live.convert import to_records
from hexar.live.limits import Limits
from hexar.live.log import NS, LiveLog
from hexar.live.replay import bag_messages


def records_of(run: Path) -> list[object]:
    """What a transport hands the log: each bag message as records, dated like the DDS transport does."""
    messages = bag_messages(run).messages
    return [r for topic, _, t, m in messages for r in to_records(topic, m, t)]


def test_shuffled_duplicated_arrival_gives_the_recordings_log(suite: Path) -> None:
    run = suite / "bagfile_13_1"
    records = records_of(run)
    rng = random.Random(1)
    # up to 5 s late: reordered across topics and within one, and every third message twice
    arrived = sorted(records + records[::3], key=lambda r: r.t + rng.uniform(0, 5) * NS)  # type: ignore[attr-defined]
    assert arrived != records
    live = LiveLog()
    live.extend(arrived)  # type: ignore[arg-type]
    snap, rec = live.snapshot(), read_recording(run)
    assert snap.logs == rec.logs
    assert snap.poses == rec.poses
    assert snap.statuses == rec.statuses
    assert [t.task_id for t in snap.tasks] == [t.task_id for t in rec.tasks]
    assert [t.outcome for t in snap.tasks] == [t.outcome for t in rec.tasks]
    assert live.duplicates == len(records[::3])
    assert live.clock_jumps == 0


def _line(t_s: float, msg: str = "x") -> LogLine:
    return LogLine(int(t_s * NS), 20, "amcl", msg)


def _task(t_s: float, task_id: str) -> TaskUpdate:
    return TaskUpdate(int(t_s * NS), task_id, "go", "valid", "", (), f'{{"task_id": "{task_id}", "t": {t_s}}}')


def test_keeps_the_current_and_last_n_tasks_and_a_horizon() -> None:
    live = LiveLog(Limits(keep_tasks=2, horizon_s=60.0))
    for i in range(10):
        live.add(_task(i * 100.0, f"task{i}"))
        for k in range(100):
            live.add(_line(i * 100.0 + k * 0.5, f"line {i} {k}"))
    snap = live.snapshot()
    assert [t.task_id for t in snap.tasks] == ["task7", "task8", "task9"]
    # the evidence of every kept task stays, older lines go
    assert snap.logs[0].t >= 700 * NS
    assert snap.task("task7").created == 700 * NS


def test_a_nodes_start_up_parameters_outlive_the_horizon_and_count_once() -> None:
    live = LiveLog(Limits(keep_tasks=2, horizon_s=60.0, max_records=50))
    declared = [ParameterSample(NS, "/amcl", f"p{k}", float(k), "new") for k in range(60)]
    live.extend(declared + declared[:10])  # a late joiner's second copy adds nothing
    for i in range(10):
        live.add(_task(i * 100.0, f"task{i}"))
        live.add(_line(i * 100.0 + 1, f"line {i}"))
    snap = live.snapshot()
    assert snap.logs[0].t >= 700 * NS
    assert [p.name for p in snap.parameters] == [f"p{k}" for k in range(10, 60)]  # the newest max_records
    assert live.duplicates == 10


def test_record_cap_and_long_lines_are_cut() -> None:
    live = LiveLog(Limits(max_records=1000, max_chars=100))
    for k in range(5000):
        live.add(_line(k * 0.001, f"line {k}"))
    live.add(_line(6.0, "y" * 10_000_000))
    snap = live.snapshot()
    assert len(snap.logs) <= 1000 + 512
    assert snap.logs[-1].msg.startswith("y" * 100) and len(snap.logs[-1].msg) < 200
    assert live.truncated == 1


def test_clock_jump_back_drops_the_abandoned_future() -> None:
    live = LiveLog(Limits(jump_back_s=30.0, jump_confirm=3))
    live.add(_task(1000.0, "before"))
    for k in range(20):
        live.add(_line(1000.0 + k))
    # the robot restarts with its clock 900 s behind and starts a new task
    live.add(_task(100.0, "after"))
    for k in range(5):
        live.add(_line(100.0 + k))
    snap = live.snapshot()
    assert [t.task_id for t in snap.tasks] == ["after"]
    assert snap.task().task_id == "after"
    assert all(line.t < 200 * NS for line in snap.logs)
    assert live.clock_jumps == 1


ROBOT = b"\x01" * 12


class _Clock:
    """This machine's seconds, moved on by the test (monotonic for the log, wall for its contact)."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def _log(clock: _Clock | None = None) -> LiveLog:
    live = LiveLog(clock=clock) if clock is not None else LiveLog()
    live.contact = Contact(lambda: live.newest, wall=clock or time.time, report=lambda line: None)
    live.contact.seen({ROBOT: "amcl"})
    return live


def _hear(live: LiveLog, record: LogLine | TaskUpdate) -> None:
    """What a transport does with each record the robot sends: says who wrote it, then keeps it."""
    live.contact.heard(ROBOT, c.ROSOUT)
    live.add(record)


def _drop(live: LiveLog, clock: _Clock | None, seconds: float) -> None:
    """The robot's DDS participant is dropped (its lease ran out) and is back `seconds` later."""
    live.contact.seen({})
    if clock is not None:
        clock.now += seconds
    live.contact.seen({ROBOT: "amcl"})


def _dropout(clock: _Clock, live: LiveLog, hole_s: float = 35.0) -> tuple[list[LogLine], list[LogLine]]:
    """A robot logging twice a second whose link drops for `hole_s` of its clock: what came, and what DDS
    resends once the link is back (behind the lines sent after it)."""
    came = [_line(1000.0 + k * 0.5, f"before {k}") for k in range(20)]
    hole = [_line(1010.0 + k * 0.5, f"in the hole {k}") for k in range(int(hole_s * 2))]
    after = [_line(1010.0 + hole_s + k * 0.5, f"after {k}") for k in range(4)]
    for line in came:
        _hear(live, line)
        clock.now += 0.5
    _drop(live, clock, 7.0)
    for line in after + hole:  # the robot's new lines first, its resends behind them
        _hear(live, line)
        clock.now += 0.001
    return came + hole + after, hole


def test_what_a_dropout_resends_is_late_not_a_clock_jump() -> None:
    clock = _Clock()
    live = _log(clock)
    lines, hole = _dropout(clock, live)
    assert live.clock_jumps == 0 and not live.warnings
    assert live.snapshot().logs == sorted(lines, key=lambda ln: ln.t)
    # every resend counts as late, so a second look at an explanation given before it came reads it
    assert live.late_since(100.0, hole[-1].t) == len(hole)


def test_a_clock_that_jumps_back_after_a_dropout_is_still_a_jump() -> None:
    clock = _Clock()
    live = _log(clock)
    _dropout(clock, live)
    live.add(_task(100.0, "after a restart"))  # the robot restarted with its clock 900 s behind
    for k in range(5):
        live.add(_line(100.0 + k))
    assert live.clock_jumps == 1
    assert [t.task_id for t in live.snapshot().tasks] == ["after a restart"]


def test_old_records_are_a_jump_once_resends_are_over() -> None:
    clock = _Clock()
    live = _log(clock)
    _dropout(clock, live, hole_s=80.0)
    clock.now += Limits().resend_s + 1.0
    for k in range(5):  # stamped inside the 80 s hole, long after DDS would have resent anything
        live.add(_line(1012.0 + k, f"back to {k}"))
    assert live.clock_jumps == 1


def test_a_robot_that_went_quiet_resends_nothing_so_old_records_are_a_jump() -> None:
    clock = _Clock()
    live = _log(clock)
    for k in range(20):
        _hear(live, _line(1000.0 + k * 0.5, f"before {k}"))
        clock.now += 0.5
    clock.now += 40.0  # no lease ran out: the node never dropped the robot, which sends on
    for k in range(4):
        _hear(live, _line(1050.0 + k * 0.5, f"after {k}"))
    for k in range(5):
        _hear(live, _line(1012.0 + k, f"back to {k}"))
    assert live.clock_jumps == 1


def _resend(live: LiveLog, lines: list[LogLine], every_s: float) -> threading.Thread:
    def send() -> None:
        for line in lines:
            time.sleep(every_s)
            _hear(live, line)

    thread = threading.Thread(target=send)
    thread.start()
    return thread


def test_a_failure_as_the_link_comes_back_waits_for_the_resends_until_they_stop() -> None:
    live = _log()
    for k in range(10):
        _hear(live, _line(1000.0 + k * 0.5))
    assert not live.resending(int(1040.0 * NS), within_s=5.0)
    _drop(live, None, 0.0)
    _hear(live, _task(1040.0, "failed"))  # the link is back 35 s later on the robot's clock
    assert live.resending(int(1040.0 * NS), within_s=5.0) and not live.resending(int(960.0 * NS), within_s=5.0)
    start = time.monotonic()
    thread = _resend(live, [_line(1005.0 + k * 0.5, f"resent {k}") for k in range(20)], 0.02)
    live.wait_resends(quiet_s=0.5, timeout_s=10.0)
    waited, got = time.monotonic() - start, live.late_since(start, int(1040.0 * NS))
    thread.join()
    assert got == 20 and 0.9 <= waited < 5.0  # every resend in, then half a second without one
    # resends that go on are waited for no longer than the timeout
    start = time.monotonic()
    thread = _resend(live, [_line(1015.0 + k * 0.01, f"more {k}") for k in range(100)], 0.02)
    live.wait_resends(quiet_s=0.5, timeout_s=0.6)
    waited = time.monotonic() - start
    thread.join()
    assert 0.6 <= waited < 1.5
    assert not live.resending(int(1040.0 * NS), within_s=0.1)  # long after the link came back


def test_a_latched_old_flag_is_no_clock_jump() -> None:
    live = LiveLog()
    live.add(_line(5000.0))
    live.add(BoolSample(10 * NS, c.JOY_PRIORITY, True))  # latched hours ago, delivered to a late joiner
    for k in range(5):
        live.add(_line(5001.0 + k))
    snap = live.snapshot()
    assert live.clock_jumps == 0
    assert snap.view({c.JOY_PRIORITY}).flag_at(c.JOY_PRIORITY, 5003 * NS) == BoolSample(10 * NS, c.JOY_PRIORITY, True)


def _finished_task(t_s: float, task_id: str, state: str) -> TaskUpdate:
    raw = f'{{"task_id": "{task_id}", "skill_sequence": [{{"skill": "say", "status": "{state}"}}]}}'
    return TaskUpdate(int(t_s * NS), task_id, "say hi", "valid", "", (SkillStep("say", {}, state),), raw)


def test_a_task_id_repeated_after_a_restart_is_a_new_task() -> None:
    live = LiveLog()
    for t_s, state in ((10.0, "pending"), (11.0, "running"), (12.0, "failed")):
        live.add(_finished_task(t_s, "1", state))
    live.add(_finished_task(12.0, "1", "failed"))  # a copy sent again: a duplicate, not a task
    # the robot restarted and numbers its tasks from 1 again: the same JSON, later
    for t_s, state in ((100.0, "pending"), (101.0, "running"), (102.0, "succeeded")):
        live.add(_finished_task(t_s, "1", state))
    snap = live.snapshot()
    assert [(t.task_id, t.outcome) for t in snap.tasks] == [("1", "failed"), ("1#2", "succeeded")]
    assert live.duplicates == 1
    assert any("started again" in w for w in snap.warnings)


class _Clock:
    """This machine's seconds, moved on by the test."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def test_lateness_counts_records_that_arrive_behind_the_robots_clock() -> None:
    clock = _Clock()
    live = LiveLog(Limits(join_s=0.0), clock=clock)
    before = clock.now
    for t_s in (10.0, 10.1, 12.0):  # the robot's clock moves as ours does
        clock.now = before + t_s - 10.0
        live.add(_line(t_s))
    assert live.late_since(before, int(20 * NS)) == 0 and live.lateness_s() == 0.0  # in order: nothing late
    clock.now += 1.0
    live.add(_line(11.0, "resent"))  # the clock passed 11.0 at 12.0: a resent message, 1 s late
    live.add(_line(11.5, "resent too"))
    assert live.late_since(before, int(11.2 * NS)) == 1  # only those stamped by then
    assert live.late_since(clock.now, int(20 * NS)) == 0  # and only those arrived since
    assert live.lateness_s() == 1.0 and live.lateness_s(q=0.0) == 1.0
    assert live.lateness_s(over_s=0.8) == 1.0 and live.lateness_s(over_s=2.0) == 0.0
    assert live.lateness_s(least=3) == 0.0  # two late records are not yet a late network


def test_lateness_is_in_our_seconds_however_fast_the_robots_clock_runs() -> None:
    clock = _Clock()
    live = LiveLog(Limits(join_s=0.0), clock=clock)
    start = clock.now
    for i in range(60):  # a recording played ten times faster: 10 robot seconds in one of ours
        clock.now = start + i / 60
        live.add(_line(10.0 + i / 6))
    clock.now += 0.05
    for t_s in (19.0, 19.1, 19.2):  # 0.6-0.8 s behind on the robot's clock, but 0.12-0.13 s of ours
        live.add(_line(t_s, f"jittered {t_s}"))
    assert 0.11 <= live.lateness_s() <= 0.14
    assert live.lateness_s(over_s=0.2, least=3) == 0.0  # jitter, not a late network


def test_a_late_joiners_history_is_no_lateness() -> None:
    live = LiveLog()  # join_s 5: what comes in the first seconds may be transient-local history, in any order
    live.extend([_line(12.0), _line(10.0), _line(11.0), _line(10.5), _line(10.2)])
    assert live.lateness_s() == 0.0  # no network lateness to wait for
    assert live.late_since(0.0, int(20 * NS)) == 4  # but a second look at an explanation still reads them
