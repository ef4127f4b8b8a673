"""Keepout zones (nav2_costmap_2d's KeepoutFilter) and a start the robot could not leave.

A keepout zone is no obstacle: the filter copies a mask's zones into the costmap as occupied cells once its mask
arrives ("KeepoutFilter: Received filter mask from … topic.", "KeepoutFilter: New filter mask arrived from … topic.
Updating old filter mask.": keepout_filter.cpp@kilted), and says when the robot itself stands in one ("KeepoutFilter:
Pose is in keepout zone, reducing cost override to navigate out.", jazzy on, with override_lethal_cost; the catalogue
reads that line as start_in_obstacle). So a planner that had a path and then found none right after the filter's
first mask arrived was not stopped by something that came into its way: a zone of the mask covers the goal or
closes the way to it, which the lines alone do not tell apart.

Without a line that says where the robot stood, a spin in place that hits something right after the planner could
not start a plan from where the robot stood (Nav2's recovery spins first: "Collision Ahead - Exiting Spin",
nav2_behaviors spin.cpp) says that the robot's own cells are occupied: for a round robot a spin covers no cell it does
not already cover. The start is then told as on occupied cells, what put it there left open.
"""

from __future__ import annotations

import re

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.detectors import PLANNED, UNEXPLAINED, Finding, Run, plan_failures
from hexar.explainers.navigation.diagnose import START_IN_OBSTACLE

# the filter's first mask; "New filter mask arrived … Updating old filter mask" is a zone server publishing again,
# which the original HEXAR system's recordings hold at every start (evals/scenarios/robot_state.py)
MASK = re.compile(r"KeepoutFilter: Received filter mask from")
IN_ZONE = "KeepoutFilter: Pose is in keepout zone"
SPIN_BLOCKED = "Collision Ahead - Exiting Spin"
MASK_LAG_NS = 5_000_000_000
MASK_FACT = "keepout_mask"  # a finding's fact: the mask arrived between the plan and the planner's failures
SPIN_FACT = "spin_blocked"  # a start_in_obstacle finding read from a spin that could not turn where it stood


def mask_closed_way(run: Run, before: list[LogLine]) -> Finding | None:
    """A planner that had a path, then found none after the keepout filter's first mask arrived, or arrived so
    shortly before the plan that the costmap may not have held its zones yet (in `before`, the lines up to the
    goal's end: the filter's own lines are no navigation evidence of their own): told as the zones, neither cause
    claimed (the goal inside one, or one across the way)."""
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
    picks = [mask, failed[0], *([run.end] if run.outcome == "failed" and run.end is not None else [])]
    found = Finding(UNEXPLAINED, [Evidence.of_log(UNEXPLAINED, ln) for ln in picks])
    found.facts[MASK_FACT] = float(len(failed))
    return found


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
