"""What the recorded maps say about a planner that found no path: where the goal and the robot lay on the global
costmap (and on map_server's map), and whether any free way joined them.

A planner's "no valid path" is a symptom with several causes (wording.PLAN_CANDIDATES); the global costmap the
planner plans on tells them apart, when the recording holds it (`/global_costmap/costmap`, nav_msgs/OccupancyGrid
as nav2_costmap_2d's Costmap2DPublisher translates costs: 100 lethal, 99 inscribed, 1-98 cost, 0 free, -1 unknown;
`/map` from map_server: 100 occupied, 0 free, -1 unknown):
- the goal outside the grid, or on a lethal or inscribed cell: goal_unreachable (the goal itself cannot be reached);
- the robot's own position on such a cell: start_in_obstacle (on a wall of the map itself, the position estimate
  is the likelier fault, and the answer says so);
- both ends free, but no free way between them: blocked_path, unless map_server's map has no way either, when the
  goal lies in an area the map closes off (goal_unreachable);
- both ends free and joined: no cause is claimed; the answer says the costmap showed a way, which rules out an
  obstacle and leaves the planner's own limits.
Unknown cells count as passable, as Nav2's planners treat them by default (allow_unknown: true). Without a grid,
or with a goal in another frame than the grid's, nothing is read from maps and the answer is what the lines say.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from hexar.events import contract as c
from hexar.events.log import View
from hexar.events.records import Grid, LogLine, clock
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.detectors import UNEXPLAINED, Finding, Run

LETHAL = 100
INSCRIBED = 99  # within the robot's inscribed radius of an obstacle: the robot's centre there means a collision
FACT = "grid"  # a finding's fact: its sentence comes from the recorded grids (finding.notes[0])
FREE_WAY = "grid_free_way"  # a hedged finding's fact: both ends free and joined on the costmap
# Cells a connectivity check may hold: larger grids are not searched (the ends are still read).
MAX_SEARCH_CELLS = 16_000_000

_FROM = re.compile(r"from current location \((?P<x>-?[\d.]+), (?P<y>-?[\d.]+)\)")
_TO = re.compile(r"(?:\bto|from .* to) \((?P<x>-?[\d.]+), (?P<y>-?[\d.]+)\)")


@dataclass(frozen=True)
class Point:
    x: float
    y: float
    said: str  # where it came from, for the evidence

    def text(self) -> str:
        return f"({self.x:.2f}, {self.y:.2f})"


def _coords(pattern: re.Pattern[str], msg: str) -> tuple[float, float] | None:
    found = pattern.search(msg)
    if found is None:
        return None
    try:
        return float(found["x"]), float(found["y"])
    except ValueError:
        return None


def goal_of(view: View, run: Run, until: int, frame: str) -> Point | None:
    """The goal: bt_navigator's begin line, the planner's own "path to (x, y)", else the last `/goal_pose` when it
    is given in the grid's `frame` (a goal in another frame is not placed without the transform between them)."""
    for line in (run.begin, *run.lines):
        if line is not None and line.t <= until and (at := _coords(_TO, line.msg)) is not None:
            return Point(*at, said=line.render())
    sent = [p for p in view.log.goals if p.t <= until]
    if sent and sent[-1].frame.lstrip("/") in {frame.lstrip("/"), ""}:
        return Point(sent[-1].x, sent[-1].y, said=f"{c.GOAL_POSE} at {clock(sent[-1].t)}")
    return None


# The begin line's start is where the robot stood for the first plan only; a replan later starts where it got to.
FIRST_PLAN_S = 2.0


def start_of(run: Run, until: int) -> Point | None:
    """Where the robot was when planning failed at `until`: the last `/amcl_pose` before it, else bt_navigator's
    begin line when the failure was the goal's first plan."""
    poses = [p for p in run.poses if p.t <= until]
    if poses:
        return Point(poses[-1].x, poses[-1].y, said=f"{c.AMCL_POSE} at {clock(poses[-1].t)}")
    begin = run.begin
    if begin is not None and until - begin.t <= FIRST_PLAN_S * 1e9 and (at := _coords(_FROM, begin.msg)):
        return Point(*at, said=begin.render())
    return None


def _blocked(value: int | None) -> bool:
    return value is not None and value >= INSCRIBED


def _joined(grid: Grid, unpacked: bytes, a: Point, b: Point, lethal: int) -> bool | None:
    """Whether a way of passable cells (below `lethal`, unknown included) joins a and b; None when not searched."""
    if grid.width * grid.height > MAX_SEARCH_CELLS:
        return None
    import numpy as np
    from scipy import ndimage

    ia, ib = grid.index(a.x, a.y), grid.index(b.x, b.y)
    if ia is None or ib is None:
        return None
    cells = np.frombuffer(unpacked, dtype=np.int8).reshape(grid.height, grid.width)
    passable = cells < lethal
    passable[ia[1], ia[0]] = passable[ib[1], ib[0]] = True  # the ends were read apart; only the way is asked
    labels, _ = ndimage.label(passable, structure=np.ones((3, 3), dtype=bool))
    return bool(labels[ia[1], ia[0]] == labels[ib[1], ib[0]])


def _where(grid: Grid) -> str:
    x0, x1, y0, y1 = grid.corners()
    return f"x {x0:.1f} to {x1:.1f} m, y {y0:.1f} to {y1:.1f} m"


def _cell_words(value: int) -> str:
    return ("a cell it marks as an obstacle (lethal)" if value >= LETHAL else
            "the inflated border of an obstacle, closer to it than my robot's radius")


def _evidence(cause: str, grid: Grid, what: str) -> Evidence:
    return Evidence(cause=cause, topic=grid.topic, t=grid.t,
                    item=f"{grid.topic} ({grid.width} x {grid.height} cells of {grid.resolution:.3f} m, frame "
                         f"{grid.frame or 'unnamed'}, {_where(grid)}): {what}")


def found(cause: str, sentence: str, grid: Grid, what: str, failed: LogLine) -> Finding:
    """A finding read from `grid` (FACT): the sentence the answer gives, the line that failed and the grid's cell."""
    return Finding(cause, [Evidence.of_log(cause, failed), _evidence(cause, grid, what)], {FACT: 1.0}, [sentence])


def read_grids(view: View, run: Run, failed: LogLine) -> Finding | None:
    """A finding from the grids current when the planner failed (`failed`, its first line), or None when the
    recording holds none or they cannot place the goal. A finding with FREE_WAY claims nothing."""
    if not ({c.GLOBAL_COSTMAP, c.MAP} & set(view.log.topics)):
        return None
    costmap, static = view.grid_at(c.GLOBAL_COSTMAP, failed.t), view.grid_at(c.MAP, failed.t)
    grid = costmap or static
    if grid is None:
        return None
    goal, start = goal_of(view, run, failed.t, grid.frame), start_of(run, failed.t)
    if goal is None:
        return None
    name = "my global costmap" if grid is costmap else "my map"
    # each grid unpacked once for all its look-ups (a costmap of millions of cells takes tens of milliseconds)
    cells = grid.cells()
    map_cells = static.cells() if static is not None and static is not grid else None
    start_value = grid.value(start.x, start.y, cells) if start is not None else None
    if start is not None and _blocked(start_value):
        assert start_value is not None
        on_wall = static is not None and map_cells is not None and static.value(start.x, start.y, map_cells) == LETHAL
        why = (" That cell is a wall of my map itself, where I cannot have stood: my position estimate was "
               "probably wrong." if on_wall else " My map shows no wall there, so it was an obstacle my sensors "
               "marked around me (or a keepout zone), or my position estimate was wrong."
               if map_cells is not None else "")
        where = ("was on an obstacle" if start_value >= LETHAL else
                 "was inside an obstacle's inflated border, closer to it than my robot's radius,")
        return found(g.START_IN_OBSTACLE,
                      f"my own start position {where} in {name} (at {start.text()}), so my planner could not start "
                      f"a plan from there.{why}",
                      grid, f"my position {start.text()} on a cell of value {start_value}", failed)
    goal_value = grid.value(goal.x, goal.y, cells)
    if goal_value is None:
        return found(g.GOAL_UNREACHABLE,
                      f"my goal lies outside {name} (the goal is at {goal.text()}; it covers {_where(grid)}), so no "
                      "plan can reach it.", grid, f"the goal {goal.text()} outside the grid", failed)
    if _blocked(goal_value):
        wall = static is not None and map_cells is not None and static.value(goal.x, goal.y, map_cells) == LETHAL
        where = ("lies on an obstacle" if goal_value >= LETHAL else
                 "lies in an obstacle's inflated border, closer to it than my robot's radius,")
        also = " (a wall or obstacle of my map itself)" if wall else ""
        return found(g.GOAL_UNREACHABLE, f"my goal {where} in {name}{also}, so no plan can end there.",
                      grid, f"the goal {goal.text()} on a cell of value {goal_value}", failed)
    if start is None or start_value is None:
        return None
    joined = _joined(grid, cells, start, goal, INSCRIBED)
    if joined is False:
        static_joined = _joined(static, map_cells, start, goal, LETHAL) if static is not None and map_cells else None
        if static_joined is False:
            return found(g.GOAL_UNREACHABLE,
                          f"my goal cannot be reached from where I stood: even my map has no free way from "
                          f"{start.text()} to {goal.text()}, as the goal lies in an area the map closes off.",
                          grid, f"no free cells join {start.text()} and {goal.text()}", failed)
        return found(g.BLOCKED,
                      f"both where I stood, {start.text()}, and my goal {goal.text()} were free in {name}, but no "
                      "free way joined them: the way was blocked by obstacles marked on it, or by their inflated "
                      "borders where a passage is narrower than my robot.",
                      grid, f"no free cells join {start.text()} and {goal.text()}", failed)
    if joined:
        return Finding(UNEXPLAINED, [_evidence(UNEXPLAINED, grid, f"free cells join {start.text()} and {goal.text()}")],
                       {FREE_WAY: 1.0}, [f"{name} showed where I stood, {start.text()}, and my goal "
                                         f"{goal.text()} on free cells with a free way between them, so my planner's "
                                         "own limits (how long or how far it may search, my footprint or "
                                         "turning radius) may have stopped it"])
    return None


_FREE_LEADS = ("my global costmap showed where I stood", "my map showed where I stood")


def free_way(f: Finding) -> str:
    """The FREE_WAY sentence of a hedged finding ("" when none)."""
    return next((n for n in f.notes if n.startswith(_FREE_LEADS)), "") if FREE_WAY in f.facts else ""


def template(f: Finding, place: str) -> tuple[str, str | None, list[str]] | None:
    """The answer of a finding read from the grids (FACT), or None for any other finding."""
    if FACT not in f.facts or not f.notes:
        return None
    fixes = {
        g.START_IN_OBSTACLE: "Check where the robot is on the map (its pose estimate against the map), and clear "
                             "the costmap around it; if it really stands in an obstacle's inflation, drive it out.",
        g.GOAL_UNREACHABLE: "Pick a goal on free space of the map, reachable from where the robot stands.",
        g.BLOCKED: "Look at what the costmap marks on the way (a real obstacle, or stale marks to clear), and at "
                   "the inflation radius against the narrowest passage.",
    }
    grid = next((e.item for e in f.evidence if e.topic not in c.LOG_SOURCES), "")
    return (f"I couldn't reach {place} because {f.notes[0]}", fixes.get(f.cause),
            [f"The recorded grid: {grid}"] if grid else [])
