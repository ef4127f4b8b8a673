"""The live event log: records from a running robot, bounded, de-duplicated, and snapshotted as an EventLog.

Explainers and the agent read an `EventLog` (events/log.py); a snapshot is one, built from the records kept
here, so they run unchanged on live data. Times follow the recording conventions: stamped messages use their
own stamp; unstamped ones (`/task_info`, the Bool flags) use the time the publisher wrote them (DDS source
timestamp), which is the robot's clock, like a bag's receive time on the robot.
"""

from __future__ import annotations

import threading
import time
from bisect import bisect_left, insort
from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import replace
from pathlib import Path
from typing import TypeVar

from hexar.events import contract as c
from hexar.events.decode import same_grid
from hexar.events.log import EventLog, TopicInfo
from hexar.events.records import (
    BoolSample,
    GoalPose,
    GoalStatus,
    Grid,
    LogLine,
    OdomSample,
    ParameterSample,
    PoseSample,
    Record,
    StatusRecord,
    TaskUpdate,
    TwistSample,
)
from hexar.events.roslog import LOG_FILE_TYPE
from hexar.live.contact import Contact
from hexar.live.lateness import Lateness
from hexar.live.limits import Limits

NS = 1_000_000_000
S = TypeVar("S", LogLine, PoseSample, BoolSample, StatusRecord, TwistSample, OdomSample, GoalPose, GoalStatus, Grid,
              ParameterSample)


def _truncate(text: str, limit: int) -> str:
    if len(text) <= limit:
        return text
    return f"{text[:limit]} [... {len(text) - limit} more characters not kept]"


class LiveLog:
    """Thread-safe: transports add from their threads, the node snapshots from its own."""

    def __init__(self, limits: Limits | None = None, name: str = "live",
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.limits = limits or Limits()
        self.name = name
        self._clock = clock  # this machine's seconds, for how late records come
        self._lock = threading.Lock()
        self.changed = threading.Condition(self._lock)
        self._logs: list[LogLine] = []
        self._poses: list[PoseSample] = []
        self._flags: dict[str, list[BoolSample]] = {}
        self._statuses: dict[str, list[StatusRecord]] = {}
        # the Nav2 topics: /odom and /cmd_vel come at 20-50 Hz, bounded by the same horizon and max_records
        self._twists: list[TwistSample] = []
        self._odom: list[OdomSample] = []
        self._goals: list[GoalPose] = []
        self._goal_statuses: list[GoalStatus] = []
        self._grids: dict[str, list[Grid]] = {}
        # a node's parameters are announced once, at its start: kept whatever their age, the newest max_records
        self._parameters: list[ParameterSample] = []
        self._tasks: dict[str, list[TaskUpdate]] = {}  # insertion order = order first seen
        self._runs: dict[str, tuple[str, int]] = {}  # task id as published -> (its current run's id, run number)
        self._counts: dict[str, int] = {}
        self._seen: set[int] = set()
        self._seen_order: deque[int] = deque()
        self._behind = 0
        self._since_prune = 0
        self.newest = 0
        self._lateness = Lateness(self.limits.late_kept, self.limits.join_s)
        self.warnings: deque[str] = deque(maxlen=50)
        self.received = 0
        self.duplicates = 0
        self.truncated = 0
        self.clock_jumps = 0
        self.contact = Contact(lambda: self.newest)  # whom the transport hears, and the holes a lost link left

    # -- adding ---------------------------------------------------------------------------------------------

    def add(self, record: Record) -> bool:
        """Keep one record; False when it is a duplicate of one already kept."""
        with self._lock:
            added = self._add(record)
            if added:
                self.changed.notify_all()
            return added

    def extend(self, records: Iterable[Record]) -> int:
        with self._lock:
            n = sum(1 for r in records if self._add(r))
            if n:
                self.changed.notify_all()
            return n

    def _key(self, r: Record) -> int:
        if isinstance(r, LogLine):
            return hash(("log", r.t, r.level, r.name, r.msg))
        if isinstance(r, TaskUpdate):
            return hash(("task", r.task_id, r.raw))  # the same JSON twice adds nothing to a task's history
        if isinstance(r, PoseSample):
            return hash(("pose", r.t, r.x, r.y, r.yaw))
        if isinstance(r, BoolSample):
            return hash(("flag", r.topic, r.t, r.value))
        if isinstance(r, Grid):
            return hash(("grid", r.topic, r.t, r.width, r.height, r.packed))
        if isinstance(r, (TwistSample, OdomSample, GoalPose, GoalStatus, ParameterSample)):
            return hash((type(r).__name__, *(getattr(r, f) for f in r.__slots__)))
        return hash(("status", r.topic, r.t, r.name, r.message, r.values))

    def _add(self, r: Record) -> bool:
        self.received += 1
        if isinstance(r, TaskUpdate):
            r = self._run_of(r)
        key = self._key(r)
        if key in self._seen:
            self.duplicates += 1
            return False
        self._seen.add(key)
        self._seen_order.append(key)
        if len(self._seen_order) > self.limits.dedup_keys:
            self._seen.discard(self._seen_order.popleft())
        if isinstance(r, Grid):
            self._add_grid(r)
            return True
        if isinstance(r, ParameterSample):  # no clock to watch: a node's start-up values are old by nature
            self._insert(self._parameters, r, c.PARAMETER_EVENTS)
            del self._parameters[:-self.limits.max_records]
            return True
        if not isinstance(r, BoolSample):  # a latched flag may legitimately be hours old
            self._watch_clock(r.t, fresh=isinstance(r, (LogLine, TaskUpdate)))
            self._watch_lateness(r.t)
        if isinstance(r, LogLine):
            if len(r.msg) > self.limits.max_chars:
                self.truncated += 1
                r = replace(r, msg=_truncate(r.msg, self.limits.max_chars))
            # counted under where it came from: /rosout, or launch's log file followed beside it (live/launch_log.py)
            self._insert(self._logs, r, r.origin)
        elif isinstance(r, TaskUpdate):
            updates = self._tasks.pop(r.task_id, [])
            updates.append(r)
            self._tasks[r.task_id] = updates  # re-inserted: the most recently updated task is last
            self._count(c.TASK_INFO)
        elif isinstance(r, PoseSample):
            self._insert(self._poses, r, c.AMCL_POSE)
        elif isinstance(r, BoolSample):
            self._insert(self._flags.setdefault(r.topic, []), r, r.topic)
        elif isinstance(r, TwistSample):
            self._insert(self._twists, r, r.topic)
        elif isinstance(r, OdomSample):
            self._insert(self._odom, r, c.ODOM)
        elif isinstance(r, GoalPose):
            self._insert(self._goals, r, c.GOAL_POSE)
        elif isinstance(r, GoalStatus):
            self._insert(self._goal_statuses, r, r.topic)
        else:
            self._insert(self._statuses.setdefault(r.topic, []), r, r.topic)
        if r.t > self.newest:
            self.newest = r.t
        self._since_prune += 1
        # pruning copies lists, so it runs every few hundred records (and on each task update), not per line
        if self._since_prune >= 512 or isinstance(r, TaskUpdate):
            self._prune()
            self._since_prune = 0
        return True

    def _add_grid(self, r: Grid) -> None:
        """A grid, unless it repeats the last of its topic; the oldest beyond `max_grids` is dropped."""
        self._count(r.topic)
        grids = self._grids.setdefault(r.topic, [])
        if same_grid(grids[-1] if grids else None, r):
            return
        insort(grids, r, key=_stamp)
        del grids[:-self.limits.max_grids]

    def _run_of(self, r: TaskUpdate) -> TaskUpdate:
        """A robot that restarts numbers its tasks again from the start: an update that starts a task anew after
        the task of that id finished (failed, succeeded, canceled or invalid), later on the robot's clock, is a
        new task, kept as `<id>#2`, `<id>#3`... instead of merging two runs into one. A re-sent copy (same
        time) stays a duplicate."""
        run_id, n = self._runs.get(r.task_id, (r.task_id, 1))
        updates = self._tasks.get(run_id)
        if updates and _finished(updates[-1]) and _starts(r) and r.t > updates[-1].t:
            n += 1
            run_id = f"{r.task_id}#{n}"
            self.warnings.append(f"task {r.task_id} started again after it ended: kept as a new task {run_id}")
        if n > 1 or r.task_id in self._runs:
            self._runs[r.task_id] = (run_id, n)
        return r if run_id == r.task_id else replace(r, task_id=run_id)

    def _count(self, topic: str) -> None:
        self._counts[topic] = self._counts.get(topic, 0) + 1

    def _insert(self, items: list[S], r: S, topic: str) -> None:
        self._count(topic)
        if not items or items[-1].t <= r.t:
            items.append(r)
        else:  # out of order: lists stay sorted by stamp (after equal ones), so snapshots need no full sort
            insort(items, r, key=_stamp)

    # -- bounds ---------------------------------------------------------------------------------------------

    def _watch_clock(self, t: int, fresh: bool) -> None:
        """A robot whose clock goes back (reboot without NTP, a restarted simulation) would otherwise sort its
        new events before the old ones and make an old task look like the latest; on a confirmed jump the
        events from the abandoned future are dropped."""
        if not fresh or self.newest == 0:
            return
        if t >= self.newest - int(self.limits.jump_back_s * NS):
            self._behind = 0
            return
        if self._resent(t):
            return
        self._behind += 1
        if self._behind < self.limits.jump_confirm:
            return
        cut = t + int(self.limits.jump_back_s * NS)
        self.clock_jumps += 1
        self.warnings.append(f"the robot's clock jumped back by {(self.newest - t) / NS:.0f} s: "
                             "dropped the events stamped after the jump")
        self._logs = [r for r in self._logs if r.t <= cut]
        self._poses = [r for r in self._poses if r.t <= cut]
        self._statuses = {k: [r for r in v if r.t <= cut] for k, v in self._statuses.items()}
        self._twists = [r for r in self._twists if r.t <= cut]
        self._odom = [r for r in self._odom if r.t <= cut]
        self._goals = [r for r in self._goals if r.t <= cut]
        self._goal_statuses = [r for r in self._goal_statuses if r.t <= cut]
        self._tasks = {k: v for k, v in self._tasks.items() if v[-1].t <= cut}
        self.newest = max([t, *(r.t for r in self._logs[-1:]), *(r.t for r in self._poses[-1:])])
        self._behind = 0
        self._lateness.forget_front()

    def _resent(self, t: int, within_s: float | None = None) -> bool:
        """Whether a record stamped `t` may be a resend: a participant DDS had dropped was heard again within
        `within_s` (`resend_s`) of our seconds, and `t` is no older than its last record before the hole, less
        `jump_back_s` (what a failing link lost, or a loaded machine had not read yet, came a moment before)."""
        since_t = self.contact.back_since(self.limits.resend_s if within_s is None else within_s)
        return since_t is not None and t >= since_t - int(self.limits.jump_back_s * NS)

    def _watch_lateness(self, t: int) -> None:
        behind = self.newest - t
        late = behind > 0 and (behind <= int(self.limits.jump_back_s * NS) or self._resent(t))
        self._lateness.note(t, behind, self._clock(), late)

    def _prune(self) -> None:
        lim = self.limits
        oldest = self.newest - int(lim.horizon_s * NS)
        while len(self._tasks) > lim.keep_tasks + 1:  # the current task and the last keep_tasks
            del self._tasks[next(iter(self._tasks))]
        if self._tasks:
            # never drop the evidence of a task that is still kept
            oldest = min(oldest, min(u[0].t for u in self._tasks.values()))
        self._logs = _trim(self._logs, oldest, lim.max_records)
        self._poses = _trim(self._poses, oldest, lim.max_records)
        for key, samples in self._flags.items():
            # the latest value before the horizon still says what holds now (a latched joystick flag)
            self._flags[key] = _trim(samples, oldest, lim.max_records, keep_one=True)
        for key, records in self._statuses.items():
            self._statuses[key] = _trim(records, oldest, lim.max_records)
        self._twists = _trim(self._twists, oldest, lim.max_records)
        self._odom = _trim(self._odom, oldest, lim.max_records)
        self._goals = _trim(self._goals, oldest, lim.max_records)
        self._goal_statuses = _trim(self._goal_statuses, oldest, lim.max_records)

    # -- reading --------------------------------------------------------------------------------------------

    def wait_until(self, t: int, timeout_s: float) -> bool:
        """Block until an event stamped at or after `t` arrived (the robot's clock passed t), or timeout."""
        with self._lock:
            return self.changed.wait_for(lambda: self.newest >= t, timeout=timeout_s)

    def resending(self, t: int, within_s: float) -> bool:
        """Whether what the robot sent up to `t` may still come, resent: a participant DDS had dropped was heard
        again within the last `within_s` of our seconds, and `t` is no older than its hole (less `jump_back_s`)."""
        with self._lock:
            return self._resent(t, within_s)

    def wait_resends(self, quiet_s: float, timeout_s: float) -> None:
        """Block until no late record has come for `quiet_s` of our seconds, at most `timeout_s`."""
        with self._lock:
            start = self._clock()
            while True:
                last = max(start, self._lateness.last_arrival())
                left = min(start + timeout_s, last + quiet_s) - self._clock()
                if left <= 0:
                    return
                self.changed.wait(timeout=left)

    def late_since(self, since: float, stamped_by: int) -> int:
        """How many records stamped at or before `stamped_by` arrived late after `since` (on the log's clock,
        time.monotonic() unless given)."""
        with self._lock:
            return self._lateness.count_since(since, stamped_by)

    def lateness_s(self, window_s: float = 60.0, over_s: float = 0.0, q: float = 0.9, least: int = 1) -> float:
        """The `q` quantile of how late records came in the last `window_s` seconds: how many of this machine's
        seconds after the robot's clock had passed their stamp, counting only those later than `over_s` and none of
        a late joiner's history; 0 when fewer than `least` were."""
        since = self._clock() - window_s
        with self._lock:
            late = self._lateness.late_s(since, over_s)
        return late[min(len(late) - 1, int(q * len(late)))] if len(late) >= max(1, least) else 0.0

    def snapshot(self) -> EventLog:
        """An EventLog of what is kept now; later additions do not change it."""
        with self._lock:
            updates = [u for ups in self._tasks.values() for u in ups]
            logs, poses = list(self._logs), list(self._poses)
            flags = {k: list(v) for k, v in self._flags.items()}
            statuses = {k: list(v) for k, v in self._statuses.items()}
            twists, odom, goals = list(self._twists), list(self._odom), list(self._goals)
            goal_statuses = list(self._goal_statuses)
            grids = [g for kept in self._grids.values() for g in kept]
            parameters = list(self._parameters)
            counts = dict(self._counts)
            warnings = list(self.warnings)
        stamps = [*(r.t for r in logs[:1] + logs[-1:]), *(r.t for r in poses[:1] + poses[-1:]),
                  *(u.t for u in updates),
                  *(r.t for seq in (twists, odom, goals, goal_statuses) for r in seq[:1] + seq[-1:])]
        topics = {t: TopicInfo(t, LOG_FILE_TYPE if t == c.LAUNCH_LOG else c.TYPE_OF.get(t, ""), n)
                  for t, n in sorted(counts.items())}
        log = EventLog(path=Path(self.name), storage="live", start=min(stamps, default=0),
                       end=max(stamps, default=0), topics=topics, warnings=warnings, logs=logs,
                       task_updates=updates, poses=poses, flags=flags, statuses=statuses, twists=twists,
                       odometry=odom, goals=goals, goal_statuses=goal_statuses, grids=grids,
                       parameters=parameters)
        log.finish()
        return log

    def stats(self) -> dict[str, int]:
        with self._lock:
            return {"received": self.received, "duplicates": self.duplicates, "truncated": self.truncated,
                    "clock_jumps": self.clock_jumps, "logs": len(self._logs), "poses": len(self._poses),
                    "tasks": len(self._tasks), "statuses": sum(len(v) for v in self._statuses.values()),
                    "twists": len(self._twists), "odometry": len(self._odom), "goals": len(self._goals),
                    "goal_statuses": len(self._goal_statuses), "grids": sum(len(v) for v in self._grids.values())}


def _finished(u: TaskUpdate) -> bool:
    states = [step.state for step in u.skills]
    return not u.valid or "failed" in states or "canceled" in states or (bool(states) and all(
        s == "succeeded" for s in states))


def _starts(u: TaskUpdate) -> bool:
    """An update that could be a task's first: an invalid plan, or one with no skill done, failed or canceled."""
    return not u.valid or not any(step.state in {"succeeded", "failed", "canceled"} for step in u.skills)


def _trim(items: list[S], oldest: int, max_records: int, keep_one: bool = False) -> list[S]:
    """Drop what is older than `oldest` and what exceeds `max_records` (oldest first). Lists are sorted."""
    if len(items) > max_records:
        items = items[len(items) - max_records:]
    if not items or items[0].t >= oldest:
        return items
    lo = bisect_left(items, oldest, key=_stamp)
    if keep_one:
        lo = max(lo - 1, 0)
    return items[lo:] if lo else items


def _stamp(r: Record) -> int:
    return r.t
