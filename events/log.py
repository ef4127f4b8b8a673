"""The event log V of one recording, indexed by topic and time, and per-explainer views V_e."""

from __future__ import annotations

from bisect import bisect_left, bisect_right
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TypeVar

from hexar.events import contract as c
from hexar.events.errors import NoTaskError
from hexar.events.records import (
    ERROR,
    BoolSample,
    GoalPose,
    GoalStatus,
    Grid,
    LogLine,
    OdomSample,
    ParameterSample,
    PoseSample,
    StatusRecord,
    TaskUpdate,
    TwistSample,
    clock,
)
from hexar.events.tasks import Task, build_tasks

# where tasks come from besides /task_info (`EventLog.tasks`), as the no-task error and `hexar inspect` say it
NO_TASK_SOURCES = ("no Nav2 navigation goal, no MoveIt or arm controller goal, and no start of the robot's drivers "
                   "or controllers in its logs")


def last_error(logs: Sequence[LogLine], limit: int = 160) -> str:
    """'; the last error it logged came from move_group at 10:33:12.345 UTC: "..."' for the no-task error, or ""
    when no line is an ERROR or FATAL: with no task to explain, the one error the recording holds is still what
    a developer replaying it needs to see (a quote, never a cause)."""
    errors = [ln for ln in logs if ln.level >= ERROR]
    if not errors:
        return ""
    line = max(errors, key=lambda ln: ln.t)
    text = " ".join(line.msg.split())
    if len(text) > limit:
        text = text[:limit - 1].rstrip() + "…"
    return f'; the last error it logged came from {line.speaker} at {clock(line.t)} UTC: "{text}"'


@dataclass(frozen=True, slots=True)
class TopicInfo:
    topic: str
    type: str
    count: int


R = TypeVar("R")


def _slice_by_t(items: Sequence[R], times: list[int], start: int | None, end: int | None) -> list[R]:
    lo = 0 if start is None else bisect_left(times, start)
    hi = len(items) if end is None else bisect_right(times, end)
    return list(items[lo:hi])


@dataclass
class EventLog:
    """Everything HEXAR decoded from one recording."""

    path: Path
    storage: str
    start: int
    end: int
    topics: dict[str, TopicInfo]
    warnings: list[str] = field(default_factory=list)
    logs: list[LogLine] = field(default_factory=list)
    task_updates: list[TaskUpdate] = field(default_factory=list)
    poses: list[PoseSample] = field(default_factory=list)
    flags: dict[str, list[BoolSample]] = field(default_factory=dict)
    statuses: dict[str, list[StatusRecord]] = field(default_factory=dict)
    twists: list[TwistSample] = field(default_factory=list)
    odometry: list[OdomSample] = field(default_factory=list)
    goals: list[GoalPose] = field(default_factory=list)
    goal_statuses: list[GoalStatus] = field(default_factory=list)
    grids: list[Grid] = field(default_factory=list)
    parameters: list[ParameterSample] = field(default_factory=list)
    _times: dict[str, list[int]] = field(default_factory=dict, repr=False)

    def finish(self) -> None:
        """Sort by message time: bags are ordered by receive time, which may differ from stamps."""
        self.logs.sort(key=lambda r: r.t)
        self.poses.sort(key=lambda r: r.t)
        for values in self.flags.values():
            values.sort(key=lambda r: r.t)
        for records in self.statuses.values():
            records.sort(key=lambda r: r.t)
        for motion in (self.twists, self.odometry, self.goals, self.goal_statuses):
            motion.sort(key=lambda r: r.t)
        self.grids.sort(key=lambda r: r.t)
        self.parameters.sort(key=lambda r: r.t)
        self.__dict__.pop("tasks", None)
        self._times.clear()

    def times(self, key: str, records: Sequence[LogLine | PoseSample | BoolSample | StatusRecord | TwistSample
                                                | OdomSample]) -> list[int]:
        """The sorted stamps of one record list, computed once: every explainer view bisects them."""
        if key not in self._times:
            self._times[key] = [r.t for r in records]
        return self._times[key]

    @cached_property
    def tasks(self) -> list[Task]:
        """The /task_info tasks; without any, one task per Nav2 navigation goal and per MoveIt or arm controller
        goal (derived, marked as such)."""
        if self.task_updates:
            return build_tasks(self.task_updates)
        # only recordings without /task_info need these
        from hexar.events.arm_goals import derive_arm_tasks, merge_tasks
        from hexar.events.nav_goals import derive_tasks

        nav = derive_tasks(self.logs, [s for s in self.goal_statuses if s.topic == c.NAV_STATUS], self.goals)
        return merge_tasks(nav, derive_arm_tasks(self.logs, self.goal_statuses), self.logs)

    def task(self, ref: str | None = None) -> Task:
        """A task by id, by its 1-based order, or by `first`/`latest`; default: the latest user task.

        A recovery task (empty instruction) is the robot's own follow-up; the person asks about the request
        that failed, so the default skips it.
        """
        tasks = self.tasks
        if not tasks:
            raise NoTaskError(f"no task to explain: {self.path} has no {c.TASK_INFO} messages, {NO_TASK_SOURCES}"
                              f"{last_error(self.logs)}")
        if ref is None or ref in {"latest", "last"}:
            user = [t for t in tasks if not t.is_recovery]
            return max(user or tasks, key=lambda t: t.last_update)
        if ref == "first":
            return tasks[0]
        if ref.isdigit() and 1 <= int(ref) <= len(tasks):
            return tasks[int(ref) - 1]
        matches = [t for t in tasks if t.task_id == ref or t.task_id.startswith(ref)]
        if len(matches) == 1:
            return matches[0]
        known = ", ".join(t.task_id for t in tasks)
        raise NoTaskError(f"no task {ref!r} in {self.path.name} (tasks: {known})")

    def settings(self, until: int) -> dict[tuple[str, str], ParameterSample]:
        """Each (node, parameter)'s last announcement on /parameter_events up to `until` (a parameter first
        announced later: its first value), an undeclared one left out: what each node was set to then."""
        last: dict[tuple[str, str], ParameterSample] = {}
        for p in self.parameters:
            if p.t <= until or (p.node, p.name) not in last:
                last[(p.node, p.name)] = p
        return {k: p for k, p in last.items() if p.change != "deleted"}

    def view(self, topics: frozenset[str] | set[str], window: tuple[int, int] | None = None) -> View:
        """The events of `topics` inside `window` (inclusive), for one explainer."""
        return View(self, frozenset(topics), window)


@dataclass(frozen=True)
class View:
    """V_e: an explainer's subset of the events, restricted to a time window."""

    log: EventLog
    topics: frozenset[str]
    window: tuple[int, int] | None

    def _bounds(self, pad_before: int = 0) -> tuple[int | None, int | None]:
        if self.window is None:
            return None, None
        return self.window[0] - pad_before, self.window[1]

    def _check(self, topic: str) -> None:
        if topic not in self.topics:
            raise KeyError(f"{topic} is not among this explainer's topics")

    def logs(self) -> list[LogLine]:
        self._check(c.ROSOUT)
        start, end = self._bounds()
        return _slice_by_t(self.log.logs, self.log.times("logs", self.log.logs), start, end)

    def poses(self) -> list[PoseSample]:
        self._check(c.AMCL_POSE)
        start, end = self._bounds()
        return _slice_by_t(self.log.poses, self.log.times("poses", self.log.poses), start, end)

    def flag_at(self, topic: str, t: int) -> BoolSample | None:
        """The latest value of a latched flag at time t (it may have been set long before the window)."""
        self._check(topic)
        samples = self.log.flags.get(topic, [])
        i = bisect_right(self.log.times(f"flag:{topic}", samples), t)
        return samples[i - 1] if i else None

    def flags(self, topic: str) -> list[BoolSample]:
        self._check(topic)
        samples = self.log.flags.get(topic, [])
        start, end = self._bounds()
        return _slice_by_t(samples, self.log.times(f"flag:{topic}", samples), start, end)

    def statuses(self, topic: str) -> list[StatusRecord]:
        self._check(topic)
        records = self.log.statuses.get(topic, [])
        start, end = self._bounds()
        return _slice_by_t(records, self.log.times(f"status:{topic}", records), start, end)

    def twists(self) -> list[TwistSample]:
        self._check(c.CMD_VEL)
        start, end = self._bounds()
        return _slice_by_t(self.log.twists, self.log.times("twists", self.log.twists), start, end)

    def odometry(self) -> list[OdomSample]:
        self._check(c.ODOM)
        start, end = self._bounds()
        return _slice_by_t(self.log.odometry, self.log.times("odometry", self.log.odometry), start, end)

    def grid_at(self, topic: str, t: int) -> Grid | None:
        """The grid of `topic` current at time t: the latest before it, else (a map latched before the recording
        began reaches it only then) the first; it may predate the window, as a map usually does."""
        self._check(topic)
        grids = [g for g in self.log.grids if g.topic == topic]
        before = [g for g in grids if g.t <= t]
        return before[-1] if before else (grids[0] if grids else None)
