"""What the figure and the page show of one task: skill spans, the robot's path, its trips and where it stopped."""

from __future__ import annotations

from bisect import bisect_right
from dataclasses import dataclass
from typing import Any

from hexar.events.log import EventLog
from hexar.events.records import PoseSample
from hexar.events.tasks import SkillRun, Task

# A skill counts as a trip when its module is navigation or the robot moved this far while it ran: the
# approach of ask_human_for_help drives the base too.
MOVED_M = 0.2
NAVIGATION = "navigation"
SIGMAS = 2.0  # covariance ellipses enclose about 86 % of a 2-D Gaussian's mass
POOR_COV = 0.2  # the contract's poor-localisation threshold (README, "Topic contract")


@dataclass(frozen=True)
class Span:
    """One skill on the timeline."""

    index: int
    skill: str
    label: str
    status: str
    start: int
    end: int
    error_msg: str

    def as_dict(self) -> dict[str, Any]:
        return {"index": self.index, "skill": self.skill, "label": self.label, "status": self.status,
                "start_ns": self.start, "end_ns": self.end, "error_msg": self.error_msg}


@dataclass(frozen=True)
class Trip:
    """A skill that moved the robot: where it began and where it ended."""

    index: int
    skill: str
    status: str
    begin: PoseSample
    end: PoseSample


@dataclass(frozen=True)
class Track:
    """The task's path from /amcl_pose and the points worth marking on it."""

    poses: list[PoseSample]
    trips: list[Trip]
    stop: PoseSample | None
    stop_label: str


def spans(task: Task) -> list[Span]:
    """Each skill from its start to its last status change; a skill that never started has no length."""
    out = []
    for run in task.skills:
        start, end = task.skill_window(run) if run.history else (task.created, task.created)
        if run.state == "waiting":
            start = end = run.last_change if run.history else task.created
        out.append(Span(run.index, run.skill, run.label(), run.state, start, max(start, end), run.error_msg))
    return out


def navigation_skills() -> set[str]:
    from hexar.explainers.registry import read_config

    modules: dict[str, list[str]] = read_config(None).get("modules", {})
    return {skill for skill, names in modules.items() if NAVIGATION in names}


def pose_at(log: EventLog, t: int) -> PoseSample | None:
    """The latest pose at time t (AMCL publishes on change, so the last one still holds)."""
    i = bisect_right(log.times("poses", log.poses), t)
    return log.poses[i - 1] if i else (log.poses[0] if log.poses else None)


def task_poses(log: EventLog, task: Task) -> list[PoseSample]:
    """The poses of the task, starting with the one that held when it was created."""
    times = log.times("poses", log.poses)
    lo, hi = bisect_right(times, task.created), bisect_right(times, task.last_update)
    return log.poses[max(lo - 1, 0):hi]


def _trip(log: EventLog, task: Task, run: SkillRun, nav: set[str]) -> Trip | None:
    if not run.history or run.state == "waiting":
        return None
    start, end = task.skill_window(run)
    a, b = pose_at(log, start), pose_at(log, end)
    if a is None or b is None:
        return None
    moved = ((a.x - b.x) ** 2 + (a.y - b.y) ** 2) ** 0.5
    if run.skill not in nav and moved < MOVED_M:
        return None
    return Trip(run.index, run.skill, run.state, a, b)


def track(log: EventLog, task: Task) -> Track:
    poses = task_poses(log, task)
    nav = navigation_skills()
    trips = [trip for run in task.skills if (trip := _trip(log, task, run, nav)) is not None]
    failed = task.failed_skill
    if not poses:
        return Track([], trips, None, "")
    if failed is not None:
        t = failed.time_of("failed") or failed.last_change
        stop = pose_at(log, t)
        return Track(poses, trips, stop, f"stopped here: {failed.skill} failed")
    return Track(poses, trips, poses[-1], f"ended here: task {task.outcome}")
