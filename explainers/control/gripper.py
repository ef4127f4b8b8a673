"""A gripper's GripperCommand goal (events/arm_goals.py derives it from the gripper action controller's "Received &
accepted new action goal") whose end the log does not show.

The gripper action controllers (ros2_controllers gripper_controllers, parallel_gripper_controller) log a goal's
start and its cancel at INFO, and its success ("Successfully moved to goal.") and a stall at DEBUG only
(parallel_gripper_action_controller_impl.hpp@kilted): a console at INFO never shows whether the gripper reached its
position. The answer says so, with what the log does show: the joint limiter's clamping of the command on the way
(explainers/control/limits.py) and the launch stopped after it.
"""

from __future__ import annotations

from hexar.events.records import LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.control.limits import slowed, slowed_said
from hexar.explainers.module_wording import verbatim
from hexar.explainers.shutdown import CTRL_C

CAUSE = "control.nominal"


def open_goal(explainer: str, task: Task, logs: list[LogLine], end: int) -> Explanation | None:
    """A gripper goal still running at the window's `end`, told as what the log shows and cannot show."""
    run = next((r for r in reversed(task.skills) if r.skill == "command_gripper" and r.state == "running"), None)
    start = run.time_of("running") if run is not None else None
    if start is None or start > end:
        return None
    began = next((ln for ln in logs if start <= ln.t <= end and "accepted new action goal" in ln.msg), None)
    if began is None:
        return None
    text = (f"My gripper's controller ({began.name or 'its node'}) received a goal at {hms(began.t)} "
            f"({verbatim(began)}), and my log does not show what became of it: the gripper action controller logs a "
            "goal's success or stall at DEBUG level only, so a log at INFO cannot tell whether the gripper reached its "
            "position.")
    evidence = [Evidence.of_log(CAUSE, began)]
    # the spawner's "Configured and activated <controller>" (controller_manager/spawner.py): it came up first
    up = next((ln for ln in reversed(logs) if ln.t <= began.t and ln.msg.startswith("Configured and activated")
               and began.name and began.name in ln.msg), None)
    if up is not None:
        text += f" {began.name} had come up before it ({verbatim(up)} at {hms(up.t)})."
    clamped = slowed([ln for ln in logs if ln.t <= end])
    if clamped is not None and clamped.clamped.t >= began.t:
        text += f" On the way, {slowed_said(clamped)}"
        evidence.append(Evidence.of_log(CAUSE, clamped.clamped))
    stop = next((ln for ln in logs if ln.t >= began.t and CTRL_C.match(ln.msg)), None)
    if stop is not None:
        text += (f" Then my launch was stopped by a ctrl-c at {hms(stop.t)}, "
                 f"{(stop.t - began.t) / 1e9:.1f} s after the goal began.")
    return Explanation(explainer=explainer, text=text, causes=[CAUSE], evidence=evidence, confidence=0.5,
                       details=["No line of the gripper controller says the goal succeeded, stalled or was canceled."])
