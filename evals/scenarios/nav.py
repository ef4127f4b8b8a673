"""Simulated Nav2 (ROS 2 Humble) navigation runs of a TIAGo, written into a BagBuilder.

Every `/rosout` text of a Nav2 node is a verbatim Nav2 Humble format string (shared/reference/
nav2_log_messages.md) with realistic numbers; the skill logger's lines are ours and never name a cause.
The robot's background state (flags, idle poses, diagnostics, noise) is in `robot_state`.
Timings follow TIAGo's Nav2 parameters: the behaviour tree replans at 1 Hz (each replan makes the controller
log `Passing new path to controller.`), the progress checker allows 10 s to move 0.5 m, the default BT retries
the navigation 6 times with the recoveries [clear costmaps, spin 1.57, wait 5 s, back up 0.30 m at 0.05 m/s]
in round-robin order (a failed recovery hands over to the next in the same tick), and each timed behaviour
gives up after its 10 s time allowance.

Charging: no public PAL source says what TIAGo does with velocity commands while docked, nor logs it. We model
that the base stays still (as under a twist_mux lock); Nav2 then fails exactly like a robot that cannot move,
and the back-up recovery stops with `Collision Ahead` because the dock is right behind the robot.
"""

from __future__ import annotations

import itertools
import math
import random
from dataclasses import dataclass, field
from typing import Any, Literal

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.evals.scenarios.nav_names import BEH, BT, CTRL, GCM, LCM, PLAN
from hexar.evals.scenarios.robot_state import _pose_tuple, simulate_robot_state
from hexar.events import contract as c
from hexar.events.records import ERROR, INFO, WARN

__all__ = ["NavSituation", "simulate_navigation", "simulate_robot_state"]

NavSituation = Literal["nominal", "blocked", "joystick", "charging", "poor_localisation", "moving_obstacles"]

BT_RETRIES = 6
MOVEMENT_ALLOWANCE_S = 10.0
AMCL_UPDATE_MIN_D = 0.25


@dataclass
class _Run:
    """One NavigateToPose goal as it unfolds; `t` is seconds since the goal was sent."""

    b: BagBuilder
    rng: random.Random
    start: int
    x: float
    y: float
    yaw: float
    goal: tuple[float, float]
    t: float = 0.0
    poses: list[int] = field(default_factory=list)
    next_replan: float = 1.0
    following: bool = True

    def at(self, dt: float = 0.0) -> int:
        return self.start + sec_ns(self.t + dt)

    def log(self, name: str, level: int, msg: str, dt: float = 0.0) -> None:
        self.b.log(self.at(dt), name, level, msg)

    def step(self, seconds: float) -> None:
        self.t += seconds

    def pose(self, cov: tuple[float, float, float] | None = None) -> None:
        cx, cy, cyaw = cov or (self.rng.uniform(0.01, 0.05), self.rng.uniform(0.01, 0.05),
                               self.rng.uniform(0.005, 0.03))
        self.b.pose(self.at(), self.x, self.y, self.yaw, cx, cy, cyaw)
        self.poses.append(self.at())

    def replans(self) -> None:
        """The 1 Hz replanning ticks that fell due up to now (a preempting new path each time)."""
        while self.next_replan < self.t:
            if not self.following:
                self.next_replan += 1.0
                continue
            tick = self.start + sec_ns(self.next_replan)
            self.b.log(tick, CTRL, INFO, "Passing new path to controller.")
            if self.rng.random() < 0.04:
                self.b.log(self.start + sec_ns(self.next_replan + 0.01), PLAN, WARN,
                           "Planner loop missed its desired rate of 20.0000 Hz. Current loop rate is "
                           f"{self.rng.uniform(11.0, 19.5):.4f} Hz")
            if self.rng.random() < 0.05:
                self.b.log(self.start + sec_ns(self.next_replan + 0.4), CTRL, WARN,
                           "Control loop missed its desired rate of 20.0000Hz")
            self.next_replan += 1.0

    def drive(self, to: tuple[float, float], speed: float, *, jitter: float = 0.0,
              cov: tuple[float, float] | None = None, min_samples: int = 1) -> None:
        """Follow the path towards `to`; AMCL publishes every 0.25 m. `cov` = range of x/y variance."""
        dx, dy = to[0] - self.x, to[1] - self.y
        dist = math.hypot(dx, dy)
        if dist < 1e-6:
            return
        self.following = True
        self.yaw = math.atan2(dy, dx)
        x0, y0, n = self.x, self.y, max(min_samples, round(dist / AMCL_UPDATE_MIN_D))
        for i in range(1, n + 1):
            self.step(dist / n / speed * self.rng.uniform(0.9, 1.1))
            self.x = x0 + dx * i / n + (self.rng.uniform(-jitter, jitter) if i < n else 0.0)
            self.y = y0 + dy * i / n + (self.rng.uniform(-jitter, jitter) if i < n else 0.0)
            if cov is None:
                self.pose()
            else:
                self.pose((self.rng.uniform(*cov), self.rng.uniform(*cov), self.rng.uniform(0.02, 0.12)))
            self.replans()

    def drive_along(self, poly: list[tuple[float, float]], s0: float, s1: float, speed: float,
                    **kw: Any) -> None:
        """Drive the polyline from arc length s0 to s1, through its corners."""
        for s in [*(d for d in _corners(poly) if s0 < d < s1), s1]:
            self.drive(_along(poly, s), speed, **kw)

    def stand(self, seconds: float) -> None:
        """Time passes with the base still: AMCL samples every ~2 s, replanning goes on."""
        end = self.t + seconds
        while self.t + 2.0 < end:
            self.step(self.rng.uniform(1.8, 2.2))
            self.pose()
            self.replans()
        self.t = end
        self.replans()


Point = tuple[float, float]


def _path(rng: random.Random, origin: Point, goal: Point) -> list[Point]:
    """A planned path bends around furniture: one intermediate corner off the straight line."""
    dx, dy = goal[0] - origin[0], goal[1] - origin[1]
    dist = math.hypot(dx, dy) or 1.0
    off = rng.uniform(0.2, 0.6) * rng.choice((-1.0, 1.0))
    f = rng.uniform(0.4, 0.6)
    return [origin, (origin[0] + dx * f - dy / dist * off, origin[1] + dy * f + dx / dist * off), goal]


def _corners(poly: list[tuple[float, float]]) -> list[float]:
    """Arc length at each vertex."""
    out = [0.0]
    for (x0, y0), (x1, y1) in itertools.pairwise(poly):
        out.append(out[-1] + math.hypot(x1 - x0, y1 - y0))
    return out


def _along(poly: list[tuple[float, float]], s: float) -> tuple[float, float]:
    marks = _corners(poly)
    for i in range(1, len(poly)):
        if s <= marks[i] or i == len(poly) - 1:
            seg = (marks[i] - marks[i - 1]) or 1.0
            f = min(1.0, max(0.0, (s - marks[i - 1]) / seg))
            (x0, y0), (x1, y1) = poly[i - 1], poly[i]
            return x0 + (x1 - x0) * f, y0 + (y1 - y0) * f
    return poly[-1]


def _follow_path_failure(run: _Run, reason: str) -> None:
    run.following = False
    run.log(CTRL, ERROR, reason)
    run.log(CTRL, WARN, "[follow_path] [ActionServer] Aborting handle.", 0.001)


def _follow_path_goal(run: _Run) -> None:
    run.step(run.rng.uniform(0.1, 0.3))
    run.log(CTRL, INFO, "Received a goal, begin computing control effort.")
    run.following = True
    run.next_replan = run.t + 1.0


def _clear(run: _Run, which: str) -> None:
    logger = GCM if which == "global" else LCM
    run.step(run.rng.uniform(0.02, 0.08))
    run.log(logger, INFO, f"Received request to clear entirely the {which}_costmap")


def _planner_failure(run: _Run) -> None:
    run.step(run.rng.uniform(0.05, 0.3))
    run.log(PLAN, WARN, "GridBased: failed to create plan with tolerance 0.50.")
    run.log(PLAN, WARN, f"Planning algorithm GridBased failed to generate a valid path to "
            f"({run.goal[0]:.2f}, {run.goal[1]:.2f})", 0.001)
    run.log(PLAN, WARN, "[compute_path_to_pose] [ActionServer] Aborting handle.", 0.002)


def _recovery(run: _Run, index: int, *, can_move: bool, dock_behind: bool = False) -> None:
    """Recovery `index` of the round robin [clear, spin, wait, backup]; a failed one hands over."""
    kind = ("clear", "spin", "wait", "backup")[index % 4]
    if kind == "clear":
        _clear(run, "local")
        _clear(run, "global")
    elif kind == "wait":
        run.step(0.05)
        run.log(BEH, INFO, "Running wait")
        run.stand(5.0)
        run.log(BEH, INFO, "wait completed successfully")
    elif kind == "spin":
        run.step(0.05)
        run.log(BEH, INFO, "Running spin")
        run.log(BEH, INFO, "Turning 1.57 for spin behavior.", 0.001)
        if can_move:
            for _ in range(4):
                run.step(run.rng.uniform(0.45, 0.6))
                run.yaw = (run.yaw + 1.57 / 4 + math.pi) % (2 * math.pi) - math.pi
                run.pose()
            run.log(BEH, INFO, "spin completed successfully")
        else:
            run.stand(10.0)
            run.log(BEH, WARN, "Exceeded time allowance before reaching the Spin goal - Exiting Spin")
            run.log(BEH, WARN, "spin failed", 0.001)
            _recovery(run, index + 1, can_move=can_move, dock_behind=dock_behind)
    else:
        run.step(0.05)
        run.log(BEH, INFO, "Running backup")
        if dock_behind:
            run.step(run.rng.uniform(0.1, 0.3))
            run.log(BEH, WARN, "Collision Ahead - Exiting DriveOnHeading")
        elif can_move:
            run.x -= 0.30 * math.cos(run.yaw)
            run.y -= 0.30 * math.sin(run.yaw)
            run.step(6.0)
            run.pose()
            run.log(BEH, INFO, "backup completed successfully")
            return
        else:
            run.stand(10.0)
            run.log(BEH, WARN, "Exceeded time allowance before reaching the DriveOnHeading goal - Exiting "
                    "DriveOnHeading")
        run.log(BEH, WARN, "backup failed", 0.001)
        _recovery(run, index + 1, can_move=can_move, dock_behind=dock_behind)


def _goal_failed(run: _Run) -> None:
    run.step(run.rng.uniform(0.02, 0.1))
    run.log(BT, ERROR, "Goal failed")
    run.log(BT, WARN, "[navigate_to_pose] [ActionServer] Aborting handle.", 0.001)


def _blocked(run: _Run, path: list[tuple[float, float]]) -> None:
    """Drive until the obstacle, stall in front of it, then planning keeps failing through every recovery."""
    run.drive_along(path, 0.0, _corners(path)[-1] * run.rng.uniform(0.3, 0.6), run.rng.uniform(0.4, 0.5))
    run.stand(MOVEMENT_ALLOWANCE_S)
    _follow_path_failure(run, "Failed to make progress")
    _clear(run, "local")
    for round_ in range(BT_RETRIES + 1):
        _planner_failure(run)
        _clear(run, "global")
        _planner_failure(run)
        if round_ < BT_RETRIES:
            _recovery(run, round_, can_move=True)
    _goal_failed(run)


def _stuck(run: _Run, *, dock_behind: bool) -> None:
    """The base ignores Nav2's velocity commands: every follow-path attempt and every recovery times out."""
    for round_ in range(BT_RETRIES + 1):
        for attempt in range(2):
            if round_ or attempt:
                _follow_path_goal(run)
            run.stand(MOVEMENT_ALLOWANCE_S)
            _follow_path_failure(run, "Failed to make progress")
            if attempt == 0:
                _clear(run, "local")
        if round_ < BT_RETRIES:
            _recovery(run, round_, can_move=False, dock_behind=dock_behind)
    _goal_failed(run)


def _reached(run: _Run) -> None:
    run.step(run.rng.uniform(0.05, 0.2))
    run.log(CTRL, INFO, "Reached the goal!")
    run.log(BT, INFO, "Goal succeeded", run.rng.uniform(0.02, 0.08))
    run.step(0.1)


def _moving_obstacles(run: _Run, path: list[tuple[float, float]]) -> None:
    """People cross the path: the controller briefly finds no trajectory, once long enough for a recovery."""
    speed = run.rng.uniform(0.35, 0.45)
    total = _corners(path)[-1]
    crossings = run.rng.randint(3, 5)
    long_one = run.rng.randrange(crossings)
    marks = sorted(run.rng.uniform(0.1, 0.9) * total for _ in range(crossings))
    s = 0.0
    for i, mark in enumerate(marks):
        run.drive_along(path, s, mark, speed)
        s = mark
        for _ in range(run.rng.randint(2, 6)):  # 20 Hz control loop, still within failure_tolerance
            run.step(0.05)
            run.log(CTRL, WARN, "No valid trajectories out of 360! ")
        if i != long_one:
            run.stand(run.rng.uniform(1.0, 2.5))
            continue
        run.step(0.3)
        _follow_path_failure(run, "Controller patience exceeded")
        _clear(run, "local")
        _follow_path_goal(run)
        run.stand(run.rng.uniform(0.5, 1.0))
        run.log(CTRL, WARN, "No valid trajectories out of 360! ")
        run.step(0.3)
        _follow_path_failure(run, "Controller patience exceeded")
        _recovery(run, 0, can_move=True)
        _follow_path_goal(run)
    run.drive_along(path, s, total, speed)
    _reached(run)


def _poor_localisation(run: _Run, path: list[tuple[float, float]]) -> None:
    """AMCL's estimate spreads in a featureless stretch: the pose jumps, progress is slow, yet it arrives."""
    total = _corners(path)[-1]
    split = total * run.rng.uniform(0.3, 0.5)
    run.drive_along(path, 0.0, split, run.rng.uniform(0.3, 0.4), cov=(0.02, 0.08))
    run.drive_along(path, split, total, run.rng.uniform(0.15, 0.22), jitter=0.25, cov=(0.25, 0.6),
                    min_samples=8)
    run.step(run.rng.uniform(0.5, 1.5))
    run.log(CTRL, WARN, "No valid trajectories out of 360! ")
    run.stand(run.rng.uniform(2.0, 4.0))
    _reached(run)


def simulate_navigation(
    b: BagBuilder,
    rng: random.Random,
    start: int,
    origin: tuple[float, float],
    goal: tuple[float, float],
    situation: NavSituation = "nominal",
    *,
    skill_logger: str = "skill_navigate_to_zone",
    goal_label: str = "kitchen",
) -> SkillResult:
    """One NavigateToPose goal from `origin` to `goal`, sent by the skill at `start`, run as `situation`.

    Failed runs end with Nav2's `Goal failed` after the BT's recoveries; `joystick`/`charging` take ~3 min.
    """
    yaw0 = math.atan2(goal[1] - origin[1], goal[0] - origin[0])
    run = _Run(b, rng, start, origin[0], origin[1], yaw0, goal)
    place = goal_label.replace("_", " ")
    run.log(skill_logger, INFO, f"Navigating to {place} at ({goal[0]:.2f}, {goal[1]:.2f})")
    run.step(rng.uniform(0.02, 0.1))
    run.log(BT, INFO, f"Begin navigating from current location ({origin[0]:.2f}, {origin[1]:.2f}) "
            f"to ({goal[0]:.2f}, {goal[1]:.2f})")
    run.step(rng.uniform(0.1, 0.3))
    run.log(CTRL, INFO, "Received a goal, begin computing control effort.")
    path = _path(rng, origin, goal)
    if situation == "nominal":
        run.drive_along(path, 0.0, _corners(path)[-1], rng.uniform(0.4, 0.55))
        _reached(run)
    elif situation == "blocked":
        _blocked(run, path)
    elif situation in ("joystick", "charging"):
        _stuck(run, dock_behind=situation == "charging")
    elif situation == "moving_obstacles":
        _moving_obstacles(run, path)
    elif situation == "poor_localisation":
        _poor_localisation(run, path)
    else:
        raise ValueError(f"unknown navigation situation {situation!r}")
    succeeded = situation in ("nominal", "moving_obstacles", "poor_localisation")
    run.step(rng.uniform(0.03, 0.1))
    error = ""
    if succeeded:
        run.log(skill_logger, INFO, f"Arrived at {place}")
    else:
        error = f"Navigation to {place} failed"
        run.log(skill_logger, ERROR, error)
    run.step(0.02)
    _settle_poses(b, run, origin)
    return SkillResult(end=run.at(), succeeded=succeeded, error_msg=error)


def _settle_poses(b: BagBuilder, run: _Run, origin: tuple[float, float]) -> None:
    """Idle samples written earlier must not contradict the run: drop those inside it, move later ones."""
    own = set(run.poses)
    keep: list[tuple[int, str, str, Any]] = []
    moved: list[tuple[int, float, float, float, float, float, float]] = []
    for m in b.messages:
        if m[1] != c.AMCL_POSE:
            keep.append(m)
            continue
        p = _pose_tuple(m[3])
        if p[0] in own or p[0] < run.start:
            keep.append(m)
        elif p[0] > run.at() and math.hypot(p[1] - origin[0], p[2] - origin[1]) < 1e-6:
            moved.append(p)
        elif p[0] > run.at():
            keep.append(m)
    b.messages[:] = keep
    for stamp, _, _, _, cx, cy, cyaw in moved:
        b.pose(stamp, run.x, run.y, run.yaw, cx, cy, cyaw)
