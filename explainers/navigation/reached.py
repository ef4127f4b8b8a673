"""Goals reached with something on the way: a goal reached late after the controller got stuck or the planner failed
and recoveries ran (`slow_retries`), and one the controller judged reached just after it could not place the robot on
its plan (`reached_without_pose`). Neither is told as a trip where nothing went wrong.
"""

from __future__ import annotations

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.catalogue import REACHED, TRANSFORM_PLAN, catalogue
from hexar.explainers.navigation.detectors import (
    REACH_DOUBT,
    UNEXPLAINED,
    Finding,
    Run,
    attempts,
    disturbances,
    plan_failures,
)
from hexar.explainers.navigation.diagnose import TRANSFORM


def slow_retries(run: Run) -> Finding | None:
    """A goal reached after the controller stopped making progress, stopped for one obstacle event, or the planner
    failed, and recoveries ran, with nothing that shows what was in the way: said as a goal reached late after
    getting stuck, never as a trip where nothing went wrong (nor as people moving about, which one event is not)."""
    plans = plan_failures(run)
    stuck = run.matching(("Failed to make progress",))
    cat = catalogue()
    behaviours = [ln for ln in run.lines if (e := cat.match(ln.msg)) is not None and e.kind == "recovery"]
    clears = [ln for ln in run.lines if (e := cat.match(ln.msg)) is not None and e.kind == "clear"]
    # one obstacle event (moving_obstacles needs two): the controller's own line says it stopped for something
    warned = disturbances(run)
    gave_up = [ln for ln in run.matching(("Controller patience exceeded",))
               if ln.msg.startswith("Controller patience exceeded")] if warned else []  # not the server's echo
    if not plans and not stuck and not gave_up and len(behaviours) + len(clears) < 2:
        return None
    picks = warned[:1] + gave_up[:1] + stuck[:1] + plans[:2] + behaviours[:2] + clears[:1]
    found = Finding(UNEXPLAINED, [Evidence.of_log(UNEXPLAINED, ln) for ln in sorted(picks, key=lambda x: x.t)])
    if run.end is not None:
        found.evidence.append(Evidence.of_log(UNEXPLAINED, run.end))
    found.facts = {"plan_failures": float(attempts(plans)), "progress_failures": float(len(stuck)),
                   "recoveries": float(len(behaviours) + len(clears)), "reached": 1.0,
                   "controller_gave_up": float(len(gave_up))}
    if warned:
        found.facts["collision_warned"] = 1.0
        found.notes.append(f"'{warned[0].msg.strip()}'")
    found.notes.append(_recovered(behaviours, bool(clears)))
    return found


def reached_without_pose(run: Run) -> Finding | None:
    """A goal the controller judged reached on the line after it could not place the robot on its plan ("Unable to
    transform robot pose into global plan's frame", then "Reached the goal!"): the goal checker used a pose the
    controller had just failed to get, so the reach is not told as a clean one."""
    if run.outcome != "reached":
        return None
    cat = catalogue()
    ids = [e.id if (e := cat.match(ln.msg)) is not None else "" for ln in run.lines]
    if REACHED not in ids:
        return None
    at = len(ids) - 1 - ids[::-1].index(REACHED)
    if at == 0 or ids[at - 1] != TRANSFORM_PLAN:
        return None
    lost, reached = run.lines[at - 1], run.lines[at]
    found = Finding(TRANSFORM, [Evidence.of_log(TRANSFORM, lost), Evidence.of_log(TRANSFORM, reached)])
    found.facts = {REACH_DOUBT: 1.0}
    found.notes.append(f"'{lost.msg.strip()}'")
    return found


def _recovered(behaviours: list[LogLine], cleared: bool) -> str:
    """'I cleared my costmaps and ran my spin and wait recoveries' (the behaviours by the names Nav2 logged)."""
    names = list(dict.fromkeys(ln.msg.split()[-1].lower() for ln in behaviours))
    ran = f"ran my {' and '.join(names)} recover{'ies' if len(names) > 1 else 'y'}" if names else ""
    done = " and ".join(p for p in ("cleared my costmaps" if cleared else "", ran) if p)
    return f"I {done}" if done else "I retried"
