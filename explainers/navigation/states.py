"""Lines that report a state of the costmap or the planner which several causes produce: a start on occupied cells
("Start occupied"), a robot outside its costmap ("Robot is out of bounds of the costmap"), a goal on occupied cells.

Such a line says where the planner or the costmap saw the robot or its goal, not why: "Start occupied" follows an
obstacle or keepout zone under the robot, a wrong position estimate, or a planner set-up that rejects every start
(SmacPlannerHybrid with minimum_turning_radius 0, ros-navigation/docs.nav2.org#632); "Robot is out of bounds of the
costmap" follows a position estimate off the map, a broken TF chain or a wrong robot_base_frame, or a costmap too
small for the place. It is told as the cause only when another line of the window supports that reading (an
obstacle or collision line for an occupied start; a localisation line, or a position no map can hold, for a robot
off its costmap); alone, the
answer names what was reported, the candidates and what tells them apart, and claims none of them. A line of
another cause (TF, configuration, localisation) is claimed before these anyway (diagnose.ORDER).

Kept apart on purpose: a goal outside the costmap's bounds ("Goal Coordinates ... was outside bounds") or on
lethal cells ("Goal Coordinates of(...) was in lethal cost", Smac's "Goal is occupied") names the goal that was
sent, which is what goal_unreachable means whatever made it so (what occupies the goal is left open in the answer:
wording.GOAL_OCCUPIED); Theta*'s "Either of the start or goal pose are an obstacle" does not say which, so it
stays a state. The controller's "No valid
trajectories" is what controller_failure means. The planner's own "no valid path" lines are symptoms already
(catalogue kind plan_failed, wording.PLAN_CANDIDATES).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from hexar.events.records import LogLine
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.catalogue import Entry, catalogue
from hexar.explainers.navigation.diagnose import Tagged
from hexar.explainers.navigation.nomap import map_never_came


@dataclass(frozen=True)
class State:
    """What the line reports, the candidates that produce it and what tells them apart, in words that claim none
    of them (hexar/claims.py reads the candidates as possibilities, not causes: tests/explainers/navigation)."""

    key: str
    cause: str  # the cause id the catalogue ties the line to: claimed only with support
    support: frozenset[str]  # causes whose lines (not states themselves) support that reading
    reported: str
    candidates: str
    checks: str


START = State(
    "start_occupied", g.START_IN_OBSTACLE, frozenset({g.COLLISION_AHEAD, g.BLOCKED}),
    "my planner could not start a plan from where I stood, as it reported the cells under me as occupied",
    "something may really stand there (an obstacle, or a keepout zone), my position estimate may be wrong, or the "
    "planner's own set-up may reject every start (its footprint, or a motion model such as a minimum turning radius "
    "of 0)",
    "What tells them apart: what the global costmap shows around the robot, AMCL's pose and warnings, and the "
    "planner plugin's parameters (footprint, minimum_turning_radius, motion model).")
OUTSIDE = State(
    "outside_costmap", g.OFF_COSTMAP, frozenset({g.POOR_LOCALISATION}),
    "my costmap reported that my position lay outside its bounds",
    "my position estimate may be wrong (no initial pose given, or odometry that jumped), the chain of transforms "
    "from the map to my base may be broken or name the wrong base frame, or the costmap may be too small or placed "
    "wrong for where I am",
    "What tells them apart: AMCL's warnings and the pose it publishes, the frames from map to the robot's base "
    "(ros2 run tf2_tools view_frames, and robot_base_frame in the costmap parameters), and the costmap's size and "
    "origin against the robot's position.")
GOAL = State(
    "goal_occupied", g.GOAL_UNREACHABLE, frozenset(),
    "my planner reported the cells under my goal as occupied",
    "the goal may really have been chosen in an obstacle or a wall, an obstacle seen earlier may still be marked "
    "there, or the inflation around obstacles may cover it",
    "What tells them apart: the goal's position on the map, the global costmap around it (cleared or not), and the "
    "inflation radius.")
STATES = (START, OUTSIDE, GOAL)
FACT = "state:"  # a hedged finding's fact key: FACT + State.key
BY_KEY = {s.key: s for s in STATES}

# Catalogue ids (nav2_catalogue.json) of the lines that report such a state, by state.
_IDS = {
    "planner.start_lethal": START, "smac.start_lethal": START,
    "navfn.start_off_costmap": OUTSIDE, "navfn.start_outside": OUTSIDE, "cm.robot_out_of_bounds": OUTSIDE,
    "cm.sensor_out_of_bounds": OUTSIDE, "dwb.critic_offgrid": OUTSIDE, "nav2.not_localized": OUTSIDE,
    "theta.start_or_goal_obstacle": GOAL,
}
_OCCUPIED_WORDS = ("occupied", "lethal", "obstacle")
# smac.start_lethal also holds "Start pose is out of costmap" (a start outside it, not on occupied cells).
_OUTSIDE_WORDS = ("out of costmap", "outside", "OUTSIDE", "off the global costmap", "out of bounds")


# A position this far from the map's origin is no place a robot can be: the pose itself is garbage (odometry with
# no start values, ROBOTIS-GIT/turtlebot3#1007: "Sensor origin at (7263490040.02, -5.51)"), which tells "my position
# estimate is wrong" apart from a broken TF chain or a costmap too small, whose coordinates are plausible.
BEYOND_ANY_MAP_M = 1e5
_POSITION = re.compile(r"(?:Sensor origin at|Start Coordinates of) ?\((?P<x>-?[\d.]+), (?P<y>-?[\d.]+)")


def _beyond_any_map(msg: str) -> bool:
    m = _POSITION.search(msg)
    try:
        return m is not None and max(abs(float(m["x"])), abs(float(m["y"]))) > BEYOND_ANY_MAP_M
    except ValueError:
        return False


# obstacle_layer.cpp's "Sensor origin at (%.2f, %.2f) is out of map bounds (%.2f, %.2f) to (%.2f, %.2f). The costmap
# cannot raytrace for it.": where the robot was and where the costmap lies, in one line
_NUM = r"(-?\d+(?:\.\d+)?)"
OUTSIDE_BY = "My costmap's own line puts me at"
_BOUNDS = re.compile(rf"Sensor origin at \({_NUM}, {_NUM}\) is out of map bounds \({_NUM}, {_NUM}\) to "
                     rf"\({_NUM}, {_NUM}\)")


def outside_by(lines: list[LogLine]) -> str:
    """"My costmap's own line puts me at (-2.00, 4.00), and it spans (0.00, 0.00) to (11.98, 7.98): 2.0 m outside
    it.", from the first such line; empty without one (or with a position no map can hold)."""
    m = next((m for ln in lines if (m := _BOUNDS.search(ln.msg)) is not None), None)
    if m is None:
        return ""
    x, y, x0, y0, x1, y1 = (float(v) for v in m.groups())
    if max(abs(x), abs(y)) > BEYOND_ANY_MAP_M:
        return ""
    off = math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1))
    return (f"{OUTSIDE_BY} ({x:.2f}, {y:.2f}), and the costmap spans ({x0:.2f}, {y0:.2f}) to "
            f"({x1:.2f}, {y1:.2f}): I was {off:.1f} m outside it.")


def state_of(entry: Entry, msg: str) -> State | None:
    """The state a catalogued line reports, or None when the line names a cause by itself. A line read through the
    mined stack catalogue (chain.stack_notes, id "stack:...") is looked up by its text in the Nav2 catalogue."""
    if entry.id.startswith("stack:"):
        own = catalogue().match(msg)
        entry = own if own is not None else entry
    state = _IDS.get(entry.id)
    if state is GOAL and not any(w in msg for w in _OCCUPIED_WORDS):
        return None
    if state is START and any(w in msg for w in _OUTSIDE_WORDS):
        return OUTSIDE
    return state


def sentence(state: State, place: str, verb: str) -> str:
    """The hedged answer: what was reported, the candidates, and that the logs do not say which."""
    return (f"My navigation to {place} {verb}: {state.reported}, and my logs do not show why. It can be one of "
            f"several things: {state.candidates}.")


def claimable(notes: list[Tagged], cause: str, lines: list[LogLine], seen: list[LogLine] | None = None
              ) -> list[LogLine]:
    """`lines` (those supporting `cause`) as far as they may be claimed: when every one of them only reports a
    state, the lines of another kind that support that state's reading join them, and without any they are not
    enough (an empty list). A robot outside its costmap is backed, too, by the static layer's word that no map ever
    came (in `seen`, the lines up to the goal's end): such a costmap keeps its default size."""
    entries = {id(n.line): n.entry for n in notes}
    said = [s for ln in lines if (e := entries.get(id(ln))) is not None and (s := state_of(e, ln.msg))]
    if len(said) < len(lines) or not said:
        return lines
    support = said[0].support
    backing = [n.line for n in notes if n.entry.cause in support and state_of(n.entry, n.line.msg) is None]
    if said[0] is OUTSIDE:
        backing += [ln for ln in lines if _beyond_any_map(ln.msg)]
        backing += map_never_came(seen or [])
    return sorted({*lines, *backing}, key=lambda ln: ln.t) if backing else []


def reported(notes: list[Tagged]) -> list[tuple[LogLine, State]]:
    """The window's state lines, oldest first."""
    return [(n.line, s) for n in notes if (s := state_of(n.entry, n.line.msg)) is not None]


def of_finding(facts: dict[str, float]) -> State | None:
    """The state a hedged finding reports (its fact FACT + key), if any."""
    return next((BY_KEY[k.removeprefix(FACT)] for k in facts if k.startswith(FACT)), None)
