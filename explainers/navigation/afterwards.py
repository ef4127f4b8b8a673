"""What failed after the navigation goal was reached, when no reading of this package knows the step.

A goal reached is not a task done: a following server's FollowObject, a route tracker, a coverage server or a
robot's own server built on Nav2's SimpleActionServer may run after the trip and fail. Their servers share one
line for it, nav2_util's (kilted: nav2_ros_common's) simple_action_server.hpp, "[<action>] [ActionServer] Aborting
handle." with, since Jazzy, the result's error code and message. A server this package reads on its own (the
navigator, planner, controller, smoother, behaviours, waypoint follower, docking) is told by its own reading; for any
other the answer is that server's own words, never "I reached it without any problem".

And where /task_info says the navigation step failed while the logs show its goal reached, the record of the task
is told beside the logs: neither is dropped for the other.
"""

from __future__ import annotations

import re

from hexar.events.records import ERROR, LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import worded
from hexar.explainers.navigation.catalogue import catalogue
from hexar.explainers.navigation.detectors import UNEXPLAINED, Finding, Run
from hexar.explainers.navigation.wording import quote

# simple_action_server.hpp: log("[%s] [ActionServer] " + msg) over "Aborting handle.", "Aborting handle.
# error_code:%d." and "Aborting handle. error_code:%d, error_msg:'%s'."
ABORT = re.compile(r"^\[(?P<action>[A-Za-z0-9_/]+)\] \[ActionServer\] Aborting handle\."
                   r"(?: error_code:\s*(?P<code>-?\d+)(?:, error_msg:'(?P<msg>.*)')?\.?)?\s*$", re.S)
# Actions whose servers this package reads on its own (Nav2's navigators, planner, controller, smoother, behaviours,
# waypoint follower and docking, every distro's names)
READ = frozenset({"navigate_to_pose", "navigate_through_poses", "follow_path", "compute_path_to_pose",
                  "compute_path_through_poses", "smooth_path", "spin", "backup", "back_up", "drive_on_heading",
                  "wait", "assisted_teleop", "follow_waypoints", "follow_gps_waypoints", "dock_robot",
                  "undock_robot"})


def _unread(m: re.Match[str]) -> str | None:
    """The aborted action's name, where no reading of this package covers its server."""
    action = m["action"].rsplit("/", 1)[-1]
    return None if action in READ else action


def _action(line: LogLine) -> str | None:
    m = ABORT.match(line.msg.strip())
    return None if m is None else _unread(m)


def aborted(run: Run, logs: list[LogLine], place: str) -> Finding | None:
    """The first goal of a server this package has no reading of that was aborted after `run`'s goal was reached
    (and before the navigator began another), with that server's last error before it."""
    if run.outcome != "reached" or run.end is None:
        return None
    cat = catalogue()
    after = [ln for ln in logs if ln.t > run.end.t]
    # up to the next goal the navigator began: what failed after it is that goal's to tell
    after = after[:next((i for i, ln in enumerate(after) if (e := cat.goal(ln.msg)) is not None and e.kind == "begin"),
                        len(after))]
    found = next(((ln, m, a) for ln in after
                  if (m := ABORT.match(ln.msg.strip())) is not None and (a := _unread(m)) is not None), None)
    if found is None:
        return None
    end, m, action = found
    said = next((ln for ln in reversed(after) if ln.t < end.t and ln.level >= ERROR and ln.name == end.name), None)
    why = f" with '{m['msg'].strip()}'" if m["msg"] else ""
    code = f" (error code {m['code']})" if m["code"] not in (None, "0") else ""
    text = (f"I reached {place}, but then my {action.replace('_', ' ')} goal failed: {end.speaker} aborted it"
            f"{why}{code}.")
    if said is not None and (not m["msg"] or m["msg"].strip() not in said.msg):
        text += f" The last error it logged before that was {quote(said)}."
    text += " That server is not one I know, so I can't tell why beyond its own words."
    lines = [ln for ln in (said, end) if ln is not None]
    return worded.finding(UNEXPLAINED, lines, text, None, end.speaker)


def task_disagrees(run: Run, place: str, record: list[Evidence]) -> Finding:
    """A step /task_info reports failed whose goal the logs show reached: both told, no cause claimed."""
    why = f" ('{record[0].item}')" if record and record[0].item.strip().lower() != "failed" else ""
    text = (f"My logs show that I reached {place}, but my task reports that step failed{why}, and my logs do not "
            "show why.")
    lines = [run.end] if run.end is not None else []
    return worded.finding(UNEXPLAINED, lines, text, None, "My navigation", more=record)
