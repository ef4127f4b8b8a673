"""The behaviour server's actions (nav2_behaviors; Foxy and Galactic's recoveries server): a spin, a backup, a drive
on a heading, a wait or an assisted teleop that a program asked for (nav2_simple_commander's spin(), backup(), ...),
not a navigation goal's recovery.

timed_behavior.hpp@kilted begins each goal with "Running %s" (:205; "Attempting %s" in recovery.hpp@foxy, galactic)
and ends it with "%s completed successfully" (:257), "%s failed:%s" (:267; "%s failed" up to Jazzy), "Initial checks
failed for %s - %s" (:221; without the reason up to Jazzy), "Canceling %s" (:246), or "Received a preemption request
for %s, however feature is currently not implemented. Aborting and stopping." (:235). Why a goal failed:
- "Collision Ahead - Exiting %s" (spin.cpp:155, drive_on_heading.hpp:173): the collision check stopped the motion.
  When the collision checker first failed itself ("Costmap is not available", costmap_subscriber.cpp:63; "Current
  footprint not available.", costmap_topic_collision_checker.cpp:110; "Failed to check pose score!", :74) it had no
  costmap or footprint to check against, and took the pose for a collision: its topics, not an obstacle;
- "Exceeded time allowance before reaching the %s goal - Exiting %s" (spin.cpp:106, drive_on_heading.hpp:108): the
  goal's time allowance ran out. Too short an allowance for the motion at the speed allowed, and a base that did not
  move, print the same line; the console does not tell them apart;
- "Current robot pose is not available." / "Initial robot pose is not available.": no transform from the local frame
  to the robot's base frame;
- any other: quoted.
"""

from __future__ import annotations

import re
from functools import partial

from hexar.events.nav_servers import spans
from hexar.events.records import LogLine
from hexar.explainers.navigation import worded
from hexar.explainers.navigation.catalogue import GOAL_KINDS, catalogue
from hexar.explainers.navigation.detectors import NOMINAL, UNEXPLAINED, Finding
from hexar.explainers.navigation.diagnose import COLLISION_AHEAD, CONFIGURATION, NOT_REACHING_BASE, TRANSFORM
from hexar.explainers.navigation.docking import BEGIN as DOCKING

BEGIN = re.compile(r"^(?:Running|Attempting) (?P<name>\w+)$")
DONE = re.compile(r"^(?P<name>\w+) completed successfully$")
FAILED = re.compile(r"^(?P<name>\w+) failed(?::(?P<msg>.*))?$", re.S)
INITIAL = re.compile(r"^Initial checks failed for (?P<name>\w+)(?: - (?P<msg>.*))?$", re.S)
CANCELED = re.compile(r"^Canceling (?P<name>\w+)$")
PREEMPTED = re.compile(r"^Received a preemption request for (?P<name>\w+),")
_ENDS = (DONE, FAILED, INITIAL, CANCELED, PREEMPTED)
_TURNING = re.compile(r"^Turning (?P<angle>-?\d+(?:\.\d+)?) for spin behavior")
_CHECKER = re.compile(r"^(Costmap is not available|Current footprint not available|Failed to check pose score)")
_COLLISION = re.compile(r"^Collision Ahead - Exiting (?P<what>\w+)")
_TIMEOUT = re.compile(r"^Exceeded time allowance before reaching the (?P<what>\w+) goal")
_POSE = re.compile(r"^(Initial|Current) robot pose is not available")
_finding = partial(worded.finding, speaker="The behaviour server")
_WORDS = {"spin": "my spin", "backup": "my backup", "back_up": "my backup", "drive_on_heading": "my drive ahead",
          "wait": "my wait", "assisted_teleop": "my assisted teleop"}


def words(name: str) -> str:
    """`drive_on_heading` -> "my drive ahead", as the robot says it."""
    return _WORDS.get(name.lower(), f"my {name.replace('_', ' ')} behaviour")


def end_of(line: LogLine) -> tuple[str, str, str] | None:
    """(name, state, error) of a line that ends a behaviour's goal, else None."""
    msg = line.msg.strip()
    for pattern, state in zip(_ENDS, ("succeeded", "failed", "failed", "canceled", "failed"), strict=True):
        if (m := pattern.match(msg)) is not None:
            error = "" if state == "succeeded" else (m.groupdict().get("msg") or msg).strip()
            return m["name"], state, error
    return None


def begins(line: LogLine) -> bool:
    """`line` begins a behaviour's goal."""
    return BEGIN.match(line.msg.strip()) is not None


def name_of(begin: LogLine) -> str:
    """The behaviour a begin line names ("Running spin": spin)."""
    return begin.msg.strip().split()[-1]


def ends(begin: LogLine, line: LogLine) -> tuple[str, str] | None:
    """(state, error) when `line` ends the goal of the behaviour `begin` began."""
    ended = end_of(line)
    return ended[1:] if ended is not None and ended[0] == name_of(begin) else None


def last_run(raw: list[LogLine]) -> tuple[LogLine, LogLine | None] | None:
    """The last behaviour goal of `raw`: its begin line and the line that ended it (None while it ran on)."""
    found = spans(raw, "behavior_server", begins, ends)
    return (found[-1].begin, found[-1].end) if found else None


# lines that show a navigation goal at work (a controller following a path, a planner's action, a navigator's goal):
# a behaviour beside them is that goal's recovery, even where the goal's own begin and end are not in the recording
_WORK = re.compile(r"^(Received a goal, begin|Passing new path to controller|Failed to make progress|Reached the goal|"
                   r"\[(follow_path|compute_path_to_pose|compute_path_through_poses|navigate_to_pose|"
                   r"navigate_through_poses|follow_waypoints)\] )")


def navigating(line: LogLine) -> bool:
    """`line` shows a navigation goal or a docking at work."""
    msg = line.msg.strip()
    if _WORK.match(msg) or DOCKING.match(msg):
        return True
    cat = catalogue()
    entry = cat.goal(line.msg)
    return entry is not None and entry.kind in GOAL_KINDS and cat.role(line.name) in {"bt_navigator", None}


def standalone(raw: list[LogLine]) -> bool:
    """A behaviour goal that no navigation goal or docking ran: `raw` holds a behaviour's begin and no line of a
    navigation goal or a docking at work."""
    return any(BEGIN.match(ln.msg.strip()) for ln in raw) and not any(navigating(ln) for ln in raw)


def explained(behavior: tuple[LogLine, LogLine | None] | None, raw: list[LogLine],
              stall: Finding | None = None) -> Finding | None:
    """What the behaviour goal `behavior` (as `last_run` reads it) did, from the behaviour server's lines; None when
    it ran on past the recording. `stall`: recorded /cmd_vel that /odom never followed in its window (held.stall),
    which tells a time allowance that ran out on a base that never moved."""
    if behavior is None:
        return None
    begin, end = behavior
    ended = end_of(end) if end is not None else None
    if end is None or ended is None:
        return None
    name, state, error = ended
    what = words(name)
    during = [ln for ln in raw if begin.t <= ln.t <= end.t]
    seconds = (end.t - begin.t) / 1e9
    turn = next((m for ln in during if (m := _TURNING.match(ln.msg))), None)
    size = f" of {abs(float(turn['angle'])):.2f} rad" if turn else ""
    if state == "succeeded":
        return _finding(NOMINAL, [begin, end], f"I finished {what}{size} without any problem, in "
                        f"{seconds:.1f} s.", None)
    if state == "canceled":
        return _finding(UNEXPLAINED, [begin, end], f"{what.capitalize()} was canceled after "
                        f"{seconds:.1f} s, by whoever asked for it; my logs do not show why.", None)
    checker = next((ln for ln in during if _CHECKER.match(ln.msg)), None)
    collision = next((ln for ln in during if _COLLISION.match(ln.msg)), None)
    if collision is not None and checker is not None:
        return _finding(CONFIGURATION, [checker, collision], f"{what.capitalize()} stopped at once, and nothing was "
                        f"in my way that my logs show: my collision checker could not check at all "
                        f"('{checker.msg.strip()}'), so it took every pose for a collision. My behaviour server was "
                        "misconfigured: it gets no costmap or footprint.",
                        "Check the behaviour server's local_costmap_topic and local_footprint_topic against what the "
                        "local costmap publishes (local_costmap/costmap_raw, local_costmap/published_footprint).")
    if collision is not None:
        when = "at once" if seconds < 0.5 else f"after {seconds:.1f} s"
        return _finding(COLLISION_AHEAD, [collision, end], f"{what.capitalize()}{size} stopped {when}: my collision "
                        "checker detected a collision ahead in the way of the motion, so I did not "
                        "move on. My logs do not say what it saw: something beside me, or cost marked there.",
                        "Look at what stands around the robot: a turn in place needs the whole footprint's sweep "
                        "clear, and a backup the space behind it.")
    timeout = next((ln for ln in during if _TIMEOUT.match(ln.msg)), None)
    if timeout is not None and stall is not None:
        return _finding(NOT_REACHING_BASE, [timeout, end], f"{what.capitalize()}{size} ran out of the time allowed "
                        f"for it ({seconds:.1f} s) because I never moved: I commanded my base for "
                        f"{stall.facts['seconds']:.1f} s and my odometry stayed still, so my velocity commands did not "
                        "reach my base.",
                        "Check that the behaviour server's cmd_vel reaches the base: the topic the base's driver "
                        "listens on, its message type (Twist or TwistStamped) and what stands between them.",
                        more=stall.evidence)
    if timeout is not None:
        need = (f" A turn{size} in {seconds:.1f} s needs {abs(float(turn['angle'])) / seconds:.2f} rad/s on average; "
                "if my max_rotational_vel is lower, the allowance was too short." if turn and seconds > 0 else "")
        return _finding(UNEXPLAINED, [timeout, end], f"{what.capitalize()}{size} ran out of the time allowed for it "
                        f"({seconds:.1f} s) before it was done, and my logs do not show why: the allowance was too "
                        "short for the motion at the velocities I am allowed, or my base did not move as "
                        f"commanded.{need}",
                        "Compare the goal's time_allowance with the distance (or angle) at the behaviour server's "
                        "speed limits, and check in the odometry that the base moved.")
    pose = next((ln for ln in during if _POSE.match(ln.msg)), None)
    if pose is not None:
        return _finding(TRANSFORM, [pose, end], f"{what.capitalize()} could not start: I could not look up my own "
                        "pose, because the transform from my local frame to my base frame was missing (a transform "
                        "(TF) error).",
                        "Check the behaviour server's robot_base_frame and local_frame against the robot's TF tree "
                        "(base_link or base_footprint).")
    return _finding(UNEXPLAINED, [end], f"{what.capitalize()} failed: my behaviour server said "
                    f"'{error}'; my logs do not show why.", "Check the behaviour server's log around that line.")
