"""Detectors of the known navigation situations, over the filtered Nav2 logs and the robot's state.

Precedence keeps causes precise: a flag that stops the base (joystick lock, charger) explains a failure by
itself, so the progress failures it produces are not also reported as a blocked path; poor localisation
explains the trajectory failures and detours it produces (a mislocalised scan makes walls look misplaced), so
it hides blocked_path and moving_obstacles.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Literal

from hexar.events import contract as c
from hexar.events.log import View
from hexar.events.records import ERROR, WARN, BoolSample, LogLine, PoseSample, StatusRecord
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.catalogue import END_KINDS, GOAL_KINDS, REACHED, Entry, catalogue
from hexar.explainers.navigation.diagnose import START_IN_OBSTACLE, TRANSFORM, Tagged
from hexar.explainers.recorded import path_length

BLOCKED = "navigation.blocked_path"
JOYSTICK = "navigation.joystick"
CHARGING = "navigation.charging"
POOR_LOCALISATION = "navigation.poor_localisation"
MOVING_OBSTACLES = "navigation.moving_obstacles"
NOMINAL_SPEED = "navigation.nominal_speed"
NOMINAL = "navigation.nominal"
UNEXPLAINED = "navigation.unexplained_failure"

COV_LIMIT = 0.2
COV_MIN_RUN = 6  # "more than 5 consecutive poses"
JOY_TOGGLE = "Toggled joy_priority, current status is: True"
SPEED_KEY = "max_vel_x"
_SPEED_WORDS = re.compile(
    r"\b(speed|fast|faster|slow|slower|slowly|quick|quickly|velocity|long|took|time|hurry|m/s)\b|"
    # "why did you move like that?" asks about how the robot moved, which on a clean run is its speed profile
    r"\b(move|moving|moved|drive|driving|drove|go|going|went)\s+(like (that|this)|that way|this way|so)\b",
    re.I,
)
PROGRESS = ("Failed to make progress", "Controller patience exceeded")
# What shows something in the way of the controller (its trajectories rejected, a collision check stopping it):
# on a goal reached in the end, things that moved into the way and out again. Planner retries, costmap clears and
# recoveries alone show no obstacle: a slow run with only those is not told as people moving into my way.
_DISTURBANCE = ("No valid trajectories", "Trajectory Hits Obstacle", "detected collision ahead", "Robot to stop",
                "Robot to slowdown")
_RETRIES = ("Controller patience exceeded", "Received request to clear entirely", "Running spin", "Running backup",
            "Running wait", "Passing new path")

Outcome = Literal["reached", "failed", "unknown"]


def pose_item(p: PoseSample) -> str:
    return f"x={p.x:.2f} y={p.y:.2f} cov_xy={p.cov_xy:.3f} cov_yaw={p.cov_yaw:.3f}"


def flag_item(s: BoolSample) -> str:
    return f"data={s.value}"


def status_item(r: StatusRecord, key: str) -> str:
    return f"{r.name}: {key}={r.get(key)}"


def asks_about_speed(question: str) -> bool:
    return bool(_SPEED_WORDS.search(question))


@dataclass
class Finding:
    cause: str
    evidence: list[Evidence] = field(default_factory=list)
    facts: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)  # sentences the evidence supports (a node that never came up)


@dataclass
class Run:
    """What the window holds about navigation: filtered lines, poses, and how the goal ended."""

    lines: list[LogLine]
    poses: list[PoseSample]
    outcome: Outcome
    begin: LogLine | None
    end: LogLine | None
    notes: list[Tagged] = field(default_factory=list)  # lines the catalogue ties to a cause

    def first(self, needles: Iterable[str]) -> LogLine | None:
        return next(iter(self.matching(needles)), None)

    def matching(self, needles: Iterable[str]) -> list[LogLine]:
        keys = tuple(needles)
        return [ln for ln in self.lines if any(k in ln.msg for k in keys)]

    def distance(self) -> float:
        lo = self.begin.t if self.begin else -math.inf
        hi = self.end.t if self.end else math.inf
        ps = [p for p in self.poses if lo <= p.t <= hi]
        return path_length((p.x, p.y) for p in ps)

    def duration_s(self) -> float | None:
        if self.begin and self.end and self.end.t > self.begin.t:
            return (self.end.t - self.begin.t) / 1e9
        return None


def summarise(tagged: list[tuple[LogLine, Entry | None]], poses: list[PoseSample], skill_state: str | None,
              extra: list[tuple[LogLine, Entry]] | None = None) -> Run:
    """The run of the window: the goal's begin and end in any distro's wording (bt_navigator by role, or an
    unknown logger), and the catalogue's reading of each line (`extra`: weak evidence the filter drops)."""
    lines = [ln for ln, _ in tagged]
    cat = catalogue()

    def goal_entry(line: LogLine, entry: Entry | None) -> Entry | None:
        # Kilted's end line quotes the error, whose cause entry match() prefers: still the goal's end (a waypoint
        # follower's goals end one after the other, and the last end is the one that counts)
        if entry is None or entry.kind not in GOAL_KINDS:
            entry = cat.goal(line.msg)
        return entry if entry is not None and cat.role(line.name) in {"bt_navigator", None} else None

    goals = [(ln, g) for ln, e in tagged if (g := goal_entry(ln, e)) is not None]
    begins = [ln for ln, g in goals if g.kind == "begin"]
    ends = [(ln, g) for ln, g in goals if g.kind in END_KINDS]
    end = ends[-1][0] if ends else None
    outcome: Outcome = "unknown"
    if ends:
        kind = ends[-1][1].kind if ends[-1][1] is not None else None
        # a goal a client canceled, where no plan says its step failed, did not fail: what went wrong before it is
        # told as seen on the way (a home robot's plan that reports the step failed keeps its failure)
        outcome = "reached" if kind == "succeeded" else \
            "unknown" if kind == "canceled" and skill_state == "canceled" else "failed"
    elif skill_state == "succeeded":
        outcome = "reached"
    elif skill_state == "failed":
        outcome = "failed"
    elif (reached := _controller_reached(tagged)) is not None:
        outcome, end = "reached", reached
    begin = max((b for b in begins if end is None or b.t <= end.t), key=lambda b: b.t, default=None)
    notes = [Tagged(ln, e) for ln, e in [*tagged, *(extra or [])] if e is not None and e.cause is not None]
    return Run(lines, poses, outcome, begin, end, sorted(notes, key=lambda n: n.line.t))


def _controller_reached(tagged: list[tuple[LogLine, Entry | None]]) -> LogLine | None:
    """The controller's "Reached the goal!" when it is the last word of the window: with neither the navigator's
    end nor the task's status recorded, a path followed to the goal checker's satisfaction after earlier progress
    failures is a goal reached late, not one given up on. Any later error leaves the end unknown."""
    last = max((ln for ln, e in tagged if e is not None and e.id == REACHED), key=lambda ln: ln.t, default=None)
    if last is None or any(ln.t > last.t and ln.level >= ERROR for ln, _ in tagged):
        return None
    return last


def _latched(view: View, topic: str, window: tuple[int, int]) -> list[BoolSample]:
    """Samples that held during the window: the value latched at its start, then those inside it."""
    first = view.flag_at(topic, window[0])
    return ([first] if first is not None else []) + view.flags(topic)


def _flag(view: View, topic: str, window: tuple[int, int], cause: str, run: Run) -> Finding | None:
    held = [s for s in _latched(view, topic, window) if s.value]
    if not held or run.outcome == "reached" or (run.outcome == "unknown" and run.begin is None):
        return None  # a flag explains only a goal that did not complete, not a window where no goal ran
    found = Finding(cause, [Evidence(cause=cause, topic=topic, t=held[0].t, item=flag_item(held[0]))])
    if len(held) > 1:
        found.evidence.append(Evidence(cause=cause, topic=topic, t=held[-1].t, item=flag_item(held[-1])))
    for line in (run.first(PROGRESS), run.end if run.outcome == "failed" else None):
        if line is not None:
            found.evidence.append(Evidence.of_log(cause, line))
    return found


def joystick(view: View, window: tuple[int, int], run: Run, all_logs: list[LogLine]) -> Finding | None:
    found = _flag(view, c.JOY_PRIORITY, window, JOYSTICK, run)
    if found is not None:
        toggles = [ln for ln in all_logs if ln.t <= window[1] and ln.msg == JOY_TOGGLE]
        if toggles:
            found.evidence.insert(1, Evidence.of_log(JOYSTICK, toggles[-1]))
    return found


def charging(view: View, window: tuple[int, int], run: Run) -> Finding | None:
    return _flag(view, c.IS_CHARGING, window, CHARGING, run)


INITIAL_POSE = "amcl.set_initial_pose"


def _asks_initial_pose(line: LogLine) -> bool:
    entry = catalogue().match(line.msg)
    return entry is not None and entry.id == INITIAL_POSE


def pose_set_after(line: LogLine, lines: list[LogLine]) -> bool:
    """AMCL applied an initial pose after `line` asked for one ("Setting pose (%.6f): %.3f %.3f %.3f",
    amcl_node.cpp:589@humble) and did not ask again: its request was answered, it says nothing of the failure."""
    set_at = [ln.t for ln in lines if ln.t >= line.t and ln.msg.startswith("Setting pose (")]
    return bool(set_at) and not any(ln.t > set_at[-1] and _asks_initial_pose(ln) for ln in lines)


def poor_localisation(run: Run) -> Finding | None:
    best: list[PoseSample] = []
    current: list[PoseSample] = []
    for p in run.poses:
        if p.cov_xy > COV_LIMIT or p.cov_yaw > COV_LIMIT:
            current.append(p)
            if len(current) > len(best):
                best = list(current)
        else:
            current = []
    other = {id(n.line) for n in run.notes if n.entry.cause != POOR_LOCALISATION}
    said = [n.line for n in run.notes if n.entry.cause == POOR_LOCALISATION]
    cat = catalogue()
    warnings = [ln for ln in run.lines if cat.role(ln.name) == "amcl" and ln.level >= WARN and id(ln) not in other]
    warnings = sorted(set(warnings) | set(said), key=lambda ln: ln.t)
    if len(best) < COV_MIN_RUN and all(_asks_initial_pose(ln) for ln in warnings):
        # AMCL only waiting for an initial pose (a WARN every healthy bring-up prints until one is set) is a
        # symptom: none was given, or one was given and AMCL could not use it (scans or transforms out of time)
        return None
    found = Finding(POOR_LOCALISATION)
    if len(best) >= COV_MIN_RUN:
        worst = max(best, key=lambda p: max(p.cov_xy, p.cov_yaw))
        for p in dict.fromkeys([best[0], worst, best[-1]]):
            found.evidence.append(Evidence(cause=POOR_LOCALISATION, topic=c.AMCL_POSE, t=p.t,
                                           item=pose_item(p)))
        found.facts = {"poses": float(len(best)), "max_cov": max(worst.cov_xy, worst.cov_yaw),
                       "seconds": (best[-1].t - best[0].t) / 1e9}
    found.evidence += [Evidence.of_log(POOR_LOCALISATION, ln) for ln in warnings[:3]]
    if any(n.entry.id == INITIAL_POSE and not pose_set_after(n.line, run.lines) for n in run.notes):
        found.facts["no_initial_pose"] = 1.0  # AMCL never got a start pose: it was not localised at all
    return found


PLANNED = ("Passing new path to controller", "Received a goal, begin computing control effort")


def plan_failures(run: Run) -> list[LogLine]:
    """The planner's "no path" lines (catalogue kind plan_failed): a symptom with several causes."""
    cat = catalogue()
    return [ln for ln in run.lines if (e := cat.match(ln.msg)) is not None and e.kind == "plan_failed"]


# One planning attempt that fails logs two lines within milliseconds: the plugin's ("GridBased: failed to create
# plan ...") and the planner server's ("Planning algorithm GridBased failed to generate a valid path to ...").
ONE_ATTEMPT_S = 0.5


def bursts(lines: list[LogLine], gap_s: float) -> int:
    """How many bursts `lines` (oldest first) come in: a line more than `gap_s` after the one before starts one."""
    return sum(1 for i, ln in enumerate(lines) if i == 0 or ln.t - lines[i - 1].t > gap_s * 1e9)


def attempts(lines: list[LogLine]) -> int:
    """How many planning attempts `lines` (plan_failures, oldest first) come from."""
    return bursts(lines, ONE_ATTEMPT_S)


# tf2_ros's message-filter drop reasons that say a message was stamped before the transforms it needs (geometry2
# tf2_ros/message_filter.h): data and transforms from clocks that disagree.
_STAMPED_EARLY = ("earlier than all the data in the transform cache", "timestamp on the message is too old")
# Nav2's behaviour tree replans at 1 Hz: a controller failure this soon after the planner gave up meets the same
# start and goal the planner could not plan between.
SAME_ATTEMPT_S = 2.0
CLOCK_DOUBT = "clock_doubt"  # a finding's fact: obstacles the controller saw may come from mistimed data
REACH_DOUBT = "reach_doubt"  # a finding's fact: the goal was judged reached right after the robot's pose was lost


def after_planner_gave_up(run: Run, lines: list[LogLine]) -> list[LogLine]:
    """`lines` of the controller less those right after the planner found no path or reported my start on occupied
    cells: rejected trajectories there do not tell an obstacle on the way from a goal off the map or a start in an
    obstacle, so they are symptoms of what the planner met (its candidates), not a cause of their own. Transform
    errors that begin only after the planner gave up cannot have made it give up either."""
    gave_up = [ln.t for ln in plan_failures(run)]
    gave_up += [n.line.t for n in run.notes if n.entry.cause == START_IN_OBSTACLE]
    return [ln for ln in lines if not any(0 <= ln.t - t <= SAME_ATTEMPT_S * 1e9 for t in gave_up)]


def stamped_early(run: Run, before: int) -> LogLine | None:
    """The first message-filter drop of the window, before `before`, for data stamped earlier than its transforms."""
    return next((n.line for n in run.notes if n.line.t < before and any(w in n.line.msg for w in _STAMPED_EARLY)),
                None)


def blocked_path(run: Run, strength: str = "strong") -> Finding | None:
    """An obstacle on the way: the controller's obstacle critic before it gave up, or a planner that had planned
    to this goal from here and then found no path any more, even after clearing its maps (so neither the goal nor
    the start is the trouble: the way got blocked). A planner that never found a path is only a symptom, and so
    is the critic right after it. When the critic alone says so and data had been dropped for being stamped before
    its transforms, the obstacles may be misplaced readings: told as that doubt (a transform finding)."""
    if run.outcome == "reached":
        return None
    gave_up = [ln.t for ln in run.matching((*PROGRESS, "[follow_path] [ActionServer] Aborting handle"))]
    planner = [n.line for n in run.notes if n.entry.cause == BLOCKED and n.entry.strength == strength
               # DWB's obstacle critic is an obstacle on the way only when the controller then gave up; while
               # it keeps driving, rejected trajectories are the controller's own trouble (or a passer-by)
               and (n.entry.kind != "disturbance" or any(t >= n.line.t for t in gave_up))]
    planner = after_planner_gave_up(run, planner)
    if planner and strength == "strong" and (early := stamped_early(run, planner[0].t)) is not None:
        return _clock_doubt(run, early, planner)
    failed = plan_failures(run)
    planned = run.first(PLANNED)
    if strength == "strong" and failed and planned is not None and planned.t < failed[0].t:
        planner = sorted({*planner, *failed}, key=lambda ln: ln.t)
    if not planner:
        return None
    found = Finding(BLOCKED)
    progress = run.matching(PROGRESS)
    picks = progress[:1] + planner[:2] + run.matching(("Running ",))[:3]
    if run.outcome == "failed" and run.end is not None:
        picks.append(run.end)
    found.evidence = [Evidence.of_log(BLOCKED, ln) for ln in sorted(set(picks), key=lambda ln: ln.t)]
    recoveries = run.matching(("Running ",))
    found.facts = {"planner_failures": float(len(planner)), "recoveries": float(len(recoveries))}
    return found


def _clock_doubt(run: Run, early: LogLine, critic: list[LogLine]) -> Finding:
    found = Finding(TRANSFORM, [Evidence.of_log(TRANSFORM, early)])
    picks = critic[:1] + run.matching(PROGRESS)[:1] + ([run.end] if run.outcome == "failed" and run.end else [])
    found.evidence += [Evidence.of_log(TRANSFORM, ln) for ln in picks]
    found.facts = {CLOCK_DOUBT: 1.0}
    found.notes = [f"{early.speaker} had dropped sensor data stamped before my transforms (“{early.msg.strip()}”)"]
    return found


# A controller at 10-20 Hz warns on every cycle while one thing stands in its way: warnings up to a second apart
# are one obstacle event, not many.
ONE_EVENT_S = 1.0


def disturbances(run: Run) -> list[LogLine]:
    """The controller's obstacle warnings (trajectories hitting obstacles, a collision check stopping it), oldest
    first."""
    return sorted(run.matching(_DISTURBANCE), key=lambda ln: ln.t)


def moving_obstacles(run: Run) -> Finding | None:
    if run.outcome != "reached":
        return None
    warned = disturbances(run)
    if bursts(warned, ONE_EVENT_S) < 2:
        return None
    picks = sorted([*warned, *run.matching(_RETRIES)], key=lambda ln: ln.t)
    found = Finding(MOVING_OBSTACLES, [Evidence.of_log(MOVING_OBSTACLES, ln) for ln in picks[:8]])
    if run.end is not None:
        found.evidence.append(Evidence.of_log(MOVING_OBSTACLES, run.end))
    found.facts = {"disturbances": float(len(run.matching(_DISTURBANCE))),
                   "new_paths": float(len(run.matching(("Passing new path",))))}
    return found


def speed_limit(r: StatusRecord) -> float | None:
    """The positive, finite max_vel_x a /diagnostics record publishes, else None."""
    try:
        value = float(r.get(SPEED_KEY) or "nan")
    except ValueError:
        return None
    return value if math.isfinite(value) and value > 0 else None


# bt_navigator's begin line from Iron on (navigate_to_pose.cpp): "Begin navigating from current location (%.2f, %.2f)
# to (%.2f, %.2f)"; Humble's has no start.
_FROM_TO = re.compile(r"from current location \((-?[\d.]+), (-?[\d.]+)\) to \((-?[\d.]+), (-?[\d.]+)\)")


def speed(run: Run, statuses: list[StatusRecord], cause: str) -> Finding:
    """The normal run's figures: configured limit, distance and average speed."""
    found = Finding(cause)
    for line in (run.begin, run.end):
        if line is not None:
            found.evidence.append(Evidence.of_log(cause, line))
    limits = [r for r in statuses if speed_limit(r) is not None]  # an empty or "nan" limit is no limit to state
    if limits:
        r = limits[-1]
        item = status_item(r, SPEED_KEY)
        found.evidence.append(Evidence(cause=cause, topic=c.DIAGNOSTICS, t=r.t, item=item))
        found.facts["max_vel_x"] = speed_limit(r) or 0.0
    if not found.evidence and run.poses:
        # no navigator lines: the recorded poses are what shows the drive went as it did
        for p in dict.fromkeys([run.poses[0], run.poses[-1]]):
            found.evidence.append(Evidence(cause=cause, topic=c.AMCL_POSE, t=p.t, item=pose_item(p)))
    distance, duration = run.distance(), run.duration_s()
    if run.poses:
        found.facts["distance_m"] = distance
    elif run.begin is not None and (m := _FROM_TO.search(run.begin.msg)):
        # no poses recorded: the goal's begin line still says where I started and where I went
        x0, y0, x1, y1 = map(float, m.groups())
        found.facts["straight_m"] = math.dist((x0, y0), (x1, y1))
    if duration is not None:
        found.facts["duration_s"] = duration
        if run.poses:
            found.facts["average_speed"] = distance / duration
        elif "straight_m" in found.facts:
            found.facts["least_speed"] = found.facts["straight_m"] / duration
    return found
