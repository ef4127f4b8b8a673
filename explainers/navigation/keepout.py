"""Keepout zones (nav2_costmap_2d's KeepoutFilter) and a start the robot could not leave.

A keepout zone is no obstacle: the filter copies a mask's zones into the costmap as occupied cells once its mask
arrives ("KeepoutFilter: Received filter mask from … topic.", "KeepoutFilter: New filter mask arrived from … topic.
Updating old filter mask.": keepout_filter.cpp@kilted), and says when the robot itself stands in one ("KeepoutFilter:
Pose is in keepout zone, reducing cost override to navigate out.", jazzy on, with override_lethal_cost; the catalogue
reads that line as start_in_obstacle). So a planner that had a path and then found none right after the filter's
first mask arrived was not stopped by something that came into its way: a zone of the mask covers the goal or
closes the way to it, which the lines alone do not tell apart. The mask itself, where the recording holds it
(`/keepout_filter_mask`, as nav2_bringup's keepout_zone_launch.py has map_server serve it: 100 in a zone), does: a
goal (or the robot) on a zone's cell is told as that, a goal outside every zone leaves the way the zones close.

Without a line that says where the robot stood, a spin in place that hits something right after the planner could
not start a plan from where the robot stood (Nav2's recovery spins first: "Collision Ahead - Exiting Spin",
nav2_behaviors spin.cpp) says that the robot's own cells are occupied: for a round robot a spin covers no cell it does
not already cover. The start is then told as on occupied cells, what put it there left open.
"""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.log import View
from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import grids
from hexar.explainers.navigation.detectors import PLANNED, UNEXPLAINED, Finding, Run, plan_failures
from hexar.explainers.navigation.diagnose import GOAL_UNREACHABLE, START_IN_OBSTACLE

# the filter's first mask; "New filter mask arrived … Updating old filter mask" is a zone server publishing again,
# which the original HEXAR system's recordings hold at every start (evals/scenarios/robot_state.py)
MASK = re.compile(r"KeepoutFilter: Received filter mask from")
IN_ZONE = "KeepoutFilter: Pose is in keepout zone"
SPIN_BLOCKED = "Collision Ahead - Exiting Spin"
MASK_LAG_NS = 5_000_000_000
MASK_FACT = "keepout_mask"  # a finding's fact: the mask arrived between the plan and the planner's failures
SPIN_FACT = "spin_blocked"  # a start_in_obstacle finding read from a spin that could not turn where it stood


def mask_closed_way(view: View, run: Run, before: list[LogLine]) -> Finding | None:
    """A planner that had a path, then found none after the keepout filter's first mask arrived, or arrived so
    shortly before the plan that the costmap may not have held its zones yet (in `before`, the lines up to the
    goal's end: the filter's own lines are no navigation evidence of their own): told as the zones, neither cause
    claimed (the goal inside one, or one across the way), unless the recorded mask shows which (`in_zone`)."""
    failed = plan_failures(run)
    planned = run.first(PLANNED)
    if run.outcome == "reached" or not failed or planned is None or planned.t >= failed[0].t:
        return None
    # a mask is in the costmap from its next update (1 Hz for nav2_bringup's global costmap): one received just
    # before the plan may not have been in the costmap it was planned on
    mask = next((ln for ln in before if MASK.search(ln.msg)
                 and planned.t - MASK_LAG_NS <= ln.t <= failed[0].t), None)
    if mask is None:
        return None
    zoned = in_zone(view, run, failed[0])
    if zoned is not None:
        zoned.evidence.insert(0, Evidence.of_log(zoned.cause, mask))
        return zoned
    picks = [mask, failed[0], *([run.end] if run.outcome == "failed" and run.end is not None else [])]
    found = Finding(UNEXPLAINED, [Evidence.of_log(UNEXPLAINED, ln) for ln in picks])
    found.facts[MASK_FACT] = float(len(failed))
    return found


ZONE = 100  # a zone's cells in a keepout mask served by map_server (trinary: occupied)


def in_zone(view: View, run: Run, failed: LogLine) -> Finding | None:
    """The recorded keepout mask current when planning failed: the goal on a zone's cell (goal_unreachable), else
    the robot's own position on one (start_in_obstacle); None without a mask, or with both outside every zone."""
    if c.KEEPOUT_MASK not in view.log.topics or (mask := view.grid_at(c.KEEPOUT_MASK, failed.t)) is None:
        return None
    cells = mask.cells()
    goal, start = grids.goal_of(view, run, failed.t, mask.frame), grids.start_of(run, failed.t)
    if goal is not None and (mask.value(goal.x, goal.y, cells) or 0) >= ZONE:
        return grids.found(GOAL_UNREACHABLE, f"my goal {goal.text()} lies inside a keepout zone of my keepout "
                           "filter's mask, where I may never go, so no plan can end there.",
                           mask, f"the goal {goal.text()} on a zone's cell", failed)
    if start is not None and (mask.value(start.x, start.y, cells) or 0) >= ZONE:
        return grids.found(START_IN_OBSTACLE, f"my own start position {start.text()} lay inside a keepout zone of "
                           "my keepout filter's mask, so my planner could not start a plan from there.",
                           mask, f"my position {start.text()} on a zone's cell", failed)
    return None


def spin_blocked_start(run: Run) -> Finding | None:
    """The planner never planned from where the robot stood, and the spin in place that followed hit something."""
    failed = plan_failures(run)
    planned = run.first(PLANNED)
    if not failed or (planned is not None and planned.t < failed[0].t):
        return None
    spin = next((ln for ln in run.lines if ln.msg.startswith(SPIN_BLOCKED) and ln.t > failed[0].t), None)
    if spin is None:
        return None
    picks: list[LogLine] = [failed[0], spin, *([run.end] if run.outcome == "failed" and run.end is not None else [])]
    found = Finding(START_IN_OBSTACLE, [Evidence.of_log(START_IN_OBSTACLE, ln) for ln in picks])
    found.facts[SPIN_FACT] = 1.0
    return found
