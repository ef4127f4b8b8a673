"""Findings from what held the robot back: the collision monitor's stops on a goal reached late, velocity commands
that the base never followed (commands_not_reaching_base, claimed only from /cmd_vel and /odom), and a speed filter
in force when the controller made no progress (a candidate, never claimed)."""

from __future__ import annotations

import re

from hexar.events import contract as c
from hexar.events.log import View
from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import detectors as d
from hexar.explainers.navigation import diagnose as g

# nav2_collision_monitor/src/collision_monitor_node.cpp:628-642@jazzy: the actions that slow the robot rather than
# stop it ("Robot to slowdown for … percents due to … polygon", "Robot to limit speed due to …", "Robot to approach
# for … seconds away from collision": its speed scaled to stay that long from a collision)
SLOWED = re.compile(r"^Robot to (slowdown|limit speed|approach)\b")

def by_collision_monitor(run: d.Run) -> d.Finding | None:
    """A goal reached late because the collision monitor stopped the robot: its stop lines, and how long it
    held the robot (until it let it continue). Slowing down (an approach, slowdown or limit polygon) that the
    monitor then released is no stop: the robot kept moving and got there."""
    stops = [n.line for n in run.notes if n.entry.id == "cmon.stop"]
    if not stops:
        return None
    resumed = next((ln for ln in run.lines if ln.t > stops[0].t and "Robot to continue normal operation" in ln.msg),
                   None)
    if resumed is not None and all(SLOWED.match(ln.msg) for ln in stops):
        return None
    found = d.Finding(g.COLLISION_AHEAD, g.evidence(g.COLLISION_AHEAD, stops))
    if resumed is not None:
        found.evidence.append(Evidence.of_log(g.COLLISION_AHEAD, resumed))
        found.facts["held_s"] = (resumed.t - stops[0].t) / 1e9
    if run.end is not None:
        found.evidence.append(Evidence.of_log(g.COLLISION_AHEAD, run.end))
    return found


def slowed(run: d.Run, found: d.Finding) -> d.Finding:
    """A normal run's figures (d.speed) with the time the collision monitor slowed the robot on the way, from each
    slowing line to the monitor's next other action ("Robot to continue normal operation", a stop) or the goal's end:
    what a question about the time it took is owed, though a slowdown the monitor released is no failure
    (by_collision_monitor)."""
    held_ns, first, since = 0, None, None
    for ln in run.lines:
        if SLOWED.match(ln.msg):
            first = first or ln
            since = ln.t if since is None else since  # a change of slowing action before "continue": one slowdown
        elif since is not None and (ln.msg.startswith("Robot to ") or ln is run.end):
            held_ns, since = held_ns + ln.t - since, None
    if since is not None and run.end is not None and run.end.t > since:
        held_ns += run.end.t - since
    if first is not None:
        found.evidence.insert(1, Evidence.of_log(found.cause, first))
        found.facts["slowed_s"] = held_ns / 1e9
        found.notes.append(f"'{first.msg.strip()}'")
    return found


def stall(view: View, run: d.Run) -> d.Finding | None:
    """Commands on /cmd_vel that /odom never followed: the only evidence for commands_not_reaching_base."""
    if c.CMD_VEL not in view.log.topics or c.ODOM not in view.log.topics:
        return None
    stall = g.stalled(view.twists(), view.odometry())
    if stall is None:
        return None
    item = f"vx={stall.first.vx:.2f} vy={stall.first.vy:.2f} wz={stall.first.wz:.2f}"
    odom = f"x={stall.odom.x:.2f} y={stall.odom.y:.2f} vx={stall.odom.vx:.3f} wz={stall.odom.wz:.3f}"
    found = d.Finding(g.NOT_REACHING_BASE, [
        Evidence(cause=g.NOT_REACHING_BASE, topic=c.CMD_VEL, t=stall.first.t, item=item),
        Evidence(cause=g.NOT_REACHING_BASE, topic=c.ODOM, t=stall.odom.t, item=odom)])
    found.facts = {"seconds": stall.commanded_s, "max_cmd": stall.max_cmd, "max_odom": stall.max_odom}
    return found


SPEED_MASK = "costmap.speed_mask"  # the catalogue's entry for the speed filter's "Received filter mask from …"


def speed_filtered(found: d.Finding, before: list[LogLine]) -> d.Finding:
    """A controller that made no progress while a speed filter's zones were in force (its mask arrived before the
    goal ended, in `before`): the filter is named among what the logs leave open (wording.SYMPTOMS), as
    chain.with_last_error names it when the mask's line lies in the goal's own window."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.navigation.wording import SYMPTOMS

    said = SYMPTOMS[SPEED_MASK]
    if found.cause != g.NO_PROGRESS or said in found.notes:
        return found
    cat = catalogue()
    if any((e := cat.match(ln.msg)) is not None and e.id == SPEED_MASK for ln in before):
        found.notes.append(said)
    return found
