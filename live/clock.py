"""One timeline for the live log, whatever clock the robot runs on.

A recording dates an unstamped message (`/task_info`, the Bool flags, the action status) by the time the
recorder received it, on the robot's clock; the live transports have the DDS source timestamp instead, the
publisher's wall clock. The two agree on a robot that runs live. They do not when the robot's clock is not its
wall clock:
- `ros2 bag play` of an old recording republishes header and /rosout stamps of the recording day, while the
  source timestamps are today (and, at `--rate 10`, advance ten times slower than the stamps);
- simulated time (`use_sim_time`, /clock from Gazebo or from `ros2 bag play --clock`): stamps count from the
  simulation's start.
Dated by source time, a failing /task_info then lands days away from its log lines, and every failure reads
"no log lines and no localisation data for that time".

So unstamped messages are dated on the robot's clock, mapped from their source time through reference points
(source time, robot time): each /clock message is one (the robot's clock itself), and so is each /rosout line
(rcl stamps a line when it is logged, just before it is published) and each diagnostic array. Robot time lies
on the line fitted through the recent references; its slope is the rate (1 on a live robot, 10 at `--rate 10`).
A robot whose references agree with the source times within `same_clock_s` runs live: its source times are used
as they are. Otherwise an unstamped record waits for the next reference (at most `hold_s`) and is kept between
the references written just before and after it: at x10 a few milliseconds of publishing jitter would
otherwise move it by tens of milliseconds of robot time, past the skill event it came with. A plan published
before the first log line waits too, so it is not dated on the wrong day.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from typing import Any

from hexar.events import contract as c
from hexar.events.records import Record, stamp_ns
from hexar.live.convert import to_records

NS = 1_000_000_000
MIN_SPAN = NS // 20  # references this far apart in source time fit a rate (source stamps are exact to µs)
CLOCK = "/clock"  # rosgraph_msgs/msg/Clock: the simulation's or `ros2 bag play --clock`'s time
CLOCK_TYPE = "rosgraph_msgs/msg/Clock"
# The topics whose records carry their own stamp whenever the publisher set one.
DIAGNOSTICS = frozenset(topic for topic, typ in c.TYPE_OF.items() if typ == c.DIAG_TYPE)
STAMPED = frozenset({c.ROSOUT, c.AMCL_POSE, c.ODOM, c.GOAL_POSE}) | DIAGNOSTICS
# The stamped topics whose stamp is taken when the message is published: /rosout lines and diagnostic arrays
# (a pose is stamped with its sensor's time, which lags by up to a scan period and is no reference).
REFERENCES = frozenset({c.ROSOUT}) | DIAGNOSTICS


class Timeline:
    """Source times -> robot times. Not thread-safe: each transport calls it from its one receive thread."""

    def __init__(self, same_clock_s: float = 10.0, hold_s: float = 1.0, window: int = 64,
                 on_dated: Callable[[str, Any, int], None] | None = None) -> None:
        # on_dated(topic, msg, robot time): each message once dated, held ones included (the rolling recorder)
        self.on_dated = on_dated
        self.same_clock_ns = int(same_clock_s * NS)
        self.hold_ns = int(hold_s * NS)
        self._clock: deque[tuple[int, int]] = deque(maxlen=window)  # (source, robot) from /clock
        self._logs: deque[tuple[int, int]] = deque(maxlen=window)  # (source, robot) from REFERENCES
        self._pending: list[tuple[str, Any, int, int]] = []  # (topic, msg, source, monotonic ns received)
        self.offset_ns = 0  # robot time - source time at the latest reference: for the node's messages
        self.rate = 1.0

    # -- references -----------------------------------------------------------------------------------------

    def clock(self, robot: int, source: int) -> None:
        self._append(self._clock, source, robot)

    def stamped(self, robot: int, source: int) -> None:
        if robot > 0 and source > 0:
            self._append(self._logs, source, robot)

    def _append(self, refs: deque[tuple[int, int]], source: int, robot: int) -> None:
        """Add a reference. One far (`same_clock_s`) from where the fitted clock puts it, or going back in
        robot time, starts a new clock (the robot restarted, a bag play began or looped): the old references
        are dropped."""
        if refs:
            fitted = len(refs) >= 2 and refs[-1][0] - refs[0][0] >= MIN_SPAN
            off = abs(robot - self._map(refs, source)) > self.same_clock_ns if fitted else False
            if off or robot < refs[-1][1] - self.same_clock_ns:
                refs.clear()
        refs.append((source, robot))

    def _refs(self) -> deque[tuple[int, int]]:
        # /clock, once heard, is the robot's clock; /rosout stamps are the fallback
        return self._clock if self._clock else self._logs

    def _live(self) -> bool:
        """The robot runs live: no /clock, and its references agree with their source times."""
        refs = self._logs
        return not self._clock and bool(refs) and all(abs(r - s) <= self.same_clock_ns for s, r in refs)

    @property
    def ready(self) -> bool:
        """Whether an unstamped message can be dated now: the robot runs live, or a rate is fitted."""
        refs = self._refs()
        return self._live() or (len(refs) >= 2 and refs[-1][0] - refs[0][0] >= MIN_SPAN)

    def date(self, source: int) -> int:
        """The robot time of a message written at `source` (DDS source timestamp, ns)."""
        refs = self._refs()
        if not refs or source <= 0:
            return source
        if self._live():
            self.offset_ns, self.rate = 0, 1.0
            return source  # the robot runs live: its source times are its clock
        return self._map(refs, source)

    def _bracketed(self, source: int) -> int:
        """`date(source)`, kept between the references written just before and just after it: a message goes
        out after what was stamped and published before it and before what is published after it, whatever
        the jitter that the fitted clock multiplies by the rate."""
        refs = self._refs()
        t = self.date(source)
        before = [r for s, r in refs if s <= source]
        after = [r for s, r in refs if s >= source]
        if before:
            t = max(t, max(before))
        if after:
            t = min(t, min(after))
        return t

    def _map(self, refs: deque[tuple[int, int]], source: int) -> int:
        """Robot time on the line fitted (least squares) through the references: the rate is its slope, and
        publishing jitter, which the rate multiplies (x10 in a bag play at --rate 10), averages out."""
        ref_source, ref_robot = refs[-1]
        self.offset_ns = ref_robot - ref_source
        if len(refs) < 2 or ref_source - refs[0][0] < MIN_SPAN:
            self.rate = 1.0
            return ref_robot + (source - ref_source)
        xs = [(s - ref_source) / NS for s, _ in refs]
        ys = [(r - ref_robot) / NS for _, r in refs]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        var = sum((x - mx) ** 2 for x in xs)
        rate = sum((x - mx) * (y - my) for x, y in zip(xs, ys, strict=True)) / var if var > 0 else 1.0
        self.rate = min(max(rate, 0.01), 1000.0)
        return ref_robot + int((my + self.rate * ((source - ref_source) / NS - mx)) * NS)

    # -- records --------------------------------------------------------------------------------------------

    def records(self, topic: str, msg: Any, source: int) -> list[Record]:
        """The records of one message, dated on the robot's clock; [] for /clock and for held messages.

        On a live robot an unstamped message is dated at once by its source time. Otherwise it waits until a
        reference written after it arrives (or `hold_s`), so that it can be dated between its neighbours."""
        if topic == CLOCK:
            self.clock(stamp_ns(msg.clock.sec, msg.clock.nanosec), source)
            return self.flush()
        if topic not in STAMPED:
            if self._live() and not self._pending:
                return self._dated(topic, msg, source)
            self._pending.append((topic, msg, source, time.monotonic_ns()))
            return self.flush()
        stamp = msg.stamp if topic == c.ROSOUT else getattr(getattr(msg, "header", None), "stamp", None)
        robot = stamp_ns(stamp.sec, stamp.nanosec) if stamp is not None else 0
        records = self._dated(topic, msg, robot or self.date(source))
        if topic in REFERENCES:
            self.stamped(robot, source)
        return self.flush() + records

    def flush(self) -> list[Record]:
        """The held records that can be dated now, in the order they came; the transports also call it when
        idle, so a held message waits at most `hold_s`."""
        out: list[Record] = []
        now = time.monotonic_ns()
        while self._pending:
            topic, msg, source, got = self._pending[0]
            refs = self._refs()
            if self._live():
                t = source
            elif self.ready and refs[-1][0] >= source:
                t = self._bracketed(source)
            elif now - got >= self.hold_ns:
                t = self._bracketed(source) if refs else source
            else:
                break
            self._pending.pop(0)
            out.extend(self._dated(topic, msg, t))
        return out

    def _dated(self, topic: str, msg: Any, t: int) -> list[Record]:
        if self.on_dated is not None:
            self.on_dated(topic, msg, t)
        return to_records(topic, msg, t)

def add_all(records: list[Record], add: Callable[[Record], bool], on_record: Callable[[Record], None]) -> bool:
    """Add records to the log, telling the node of each new one; True when any was new."""
    fresh = False
    for record in records:
        if add(record):
            fresh = True
            on_record(record)
    return fresh
