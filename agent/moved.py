""""Did the robot move at all before the goal failed?", "did the arm move at all?", "did the trajectory ever get sent
to the controller?": whether a motion was handed to a controller, from my positions where the recording holds them,
else from the lines that hand a path or a trajectory to one (their real texts below). Without either, the answer
says what the log does not show; it claims neither a motion nor its absence that the recording cannot tell.
"""

from __future__ import annotations

import re

from hexar.agent.content import task_name
from hexar.agent.logs import line_evidence, quote
from hexar.agent.measures import far, worked_until
from hexar.events.log import EventLog
from hexar.events.nav_servers import BEHAVIOR_SKILL
from hexar.events.records import LogLine
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation
from hexar.explainers.recorded import positions

MOVED = re.compile(
    r"(^|[,;:] )(and |so |but )?did (you|it|i|the robot|the (arm|base|robot|gripper))( even| ever)? (move|drive|"
    r"budge|go "
    r"anywhere|start moving)\b|"
    r"^(and |so |but )?did (the |my |your |any )?(trajectory|motion|path|plan) (ever |even )?(get )?(sent|executed|"
    r"passed|handed|reach)")
# the lines that hand a motion to a controller: Nav2's controller_server.cpp:361 and :541@humble
# (shared/reference/nav2_log_messages.md), joint_trajectory_controller's goal_received_callback, and MoveIt's
# execute_trajectory capability and trajectory_execution_manager (the mined catalogues)
HANDED = re.compile(r"^(Received a goal, begin computing control effort|Passing new path to controller|Received new "
                    r"action goal|Accepted new action goal|Execution request received|Starting trajectory execution)")


def moved_kind(q: str) -> str | None:
    return "moved" if MOVED.search(q) else None


def moved(question: str, log: EventLog, task: Task) -> Explanation:
    """Whether a motion was handed to a controller for the task, and how far I went where positions say it."""
    end = worked_until(log, task)
    name = task_name(task, log)
    if task.skills and all(run.time_of("running") is None for run in task.skills):
        return Explanation(explainer="planner", text=f"No: no step of {name} started, so I did not move.",
                           causes=["planner.plan_ok"], evidence=line_evidence([], task))
    if positions(log, task.created, end)[0]:
        return far(log, task, question)
    if any(run.skill == BEHAVIOR_SKILL for run in task.skills):  # a spin or backup drives the base itself
        return Explanation.not_enough("planner", f"My recording holds no position of mine, and {name} drives my base "
                                                 "without handing a path to a controller, so it does not show how far "
                                                 "I moved.")
    handed: list[LogLine] = [ln for ln in log.logs if ln.t <= end and HANDED.match(ln.msg.strip())]
    if handed:
        text = (f"A motion was handed to my controllers for {name}: {quote(handed, False, False)}. My recording "
                f"holds no position of mine, so it does not show how far I moved.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence(handed, task))
    if task.outcome == "failed":  # it failed before any motion was handed on: most likely none was made
        text = (f"No line of my log hands a path or a trajectory to a controller before {name} failed, so most "
                f"likely I did not move; my recording holds no position of mine to confirm it.")
    else:  # an excerpt may lack the lines that would show a motion: their absence is not told as "I did not move"
        text = (f"No line of my log up to the end of {name} hands a path or a trajectory to a controller, and my "
                f"recording holds no position of mine, so it does not show that I moved.")
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=line_evidence([], task))
