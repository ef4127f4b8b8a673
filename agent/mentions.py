""""What is my footprint?", "which critic rejected the trajectories?", "is use_sim_time set?", "which dock?": a
developer replaying a run asks for one thing of the stack by its name. Where the recording holds the nodes'
parameters (/parameter_events) and one of them is what was asked, its values answer (agent/parameters.py).
Otherwise the place such a thing shows is the log: the lines that name it, up to the task's end (bring-up before it
included), quoted with their node and time. Where no line names it, the answer says so, and why the recording holds
no value for it, instead of the task's finding with nothing on what was asked.
"""

from __future__ import annotations

import re
from functools import cache

from hexar.agent.cited import asks_specific
from hexar.agent.content import task_name
from hexar.agent.context import RunContext
from hexar.agent.logs import line_evidence, quote
from hexar.agent.measures import worked_until
from hexar.agent.overview import asks_fix
from hexar.agent.parameters import (
    IDENTIFIER,
    LISTING,
    asks_parameters,
    node_asked,
    not_held,
    parameter_list,
    parameter_values,
)
from hexar.agent.probes import finding, with_failure
from hexar.agent.state import AgentState
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import WARN, LogLine
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation

# The things of a ROS 2 stack a developer asks for by name; each with the spellings a log line uses for it.
_TERMS: dict[str, tuple[str, ...]] = {
    "footprint": ("footprint",), "tolerance": ("tolerance",), "threshold": ("threshold",),
    "timeout": ("timeout", "timed out", "time out"), "baud": ("baud",), "port": ("port",),
    "device": ("device", "/dev/"), "frame": ("frame",), "critic": ("critic",), "dock": ("dock",),
    "waypoint": ("waypoint",), "solver": ("solver",), "kinematics": ("kinematics", "ik "),
    "ik": ("kinematics", "ik "), "behavior tree": ("behavior tree", "behaviour tree", "bt ", "xml"),
    "bt": ("behavior tree", "bt ", "xml"), "xml": ("xml",), "file": ("file",), "trajectory": ("trajectory",),
    "namespace": ("namespace",), "use_sim_time": ("use_sim_time", "sim time", "sim_time"),
    "sim time": ("use_sim_time", "sim time", "sim_time"), "clock": ("clock",), "firewall": ("firewall",),
    "inflation": ("inflation",), "radius": ("radius",), "costmap": ("costmap",), "map": ("map",),
    "progress checker": ("progress", "movement time allowance"), "goal checker": ("goal checker", "goal_checker"),
    "transform": ("transform", "tf"), "tf": ("transform", "tf"), "urdf": ("urdf", "robot_description"),
    "robot description": ("robot_description", "robot description", "urdf"), "srdf": ("srdf",),
    "octomap": ("octomap",), "rate": ("rate", "hz", "frequency"), "frequency": ("frequency", "hz", "rate"),
    "velocity": ("velocity", "vel"), "speed": ("speed", "vel"), "baud rate": ("baud",),
    "controller": ("controller",), "joint": ("joint",), "version": ("version",), "distro": ("distro",),
    "hardware interface": ("hardware", "interface"), "interface": ("interface",), "pipeline": ("pipeline",),
    "gripper": ("gripper",), "group": ("group",), "topic": ("topic",), "parameter": ("param",),
    "initial pose": ("initial pose", "initialpose", "initial_pose"), "odometry": ("odom",), "odom": ("odom",),
    "lidar": ("lidar", "laser", "scan"), "laser": ("laser", "scan", "lidar"), "camera": ("camera", "image"),
    "imu": ("imu",), "package": ("package", "library", "librar"), "resource": ("resource", "claim"),
    "simulation": ("simulation", "simulator", "gazebo", "paused", "pause"), "permission": ("permission", "denied"),
    "plugin": ("plugin",), "library": ("librar",), "ekf": ("ekf",), "detector": ("detector", "detection"),
    "qos": ("qos", "durability", "reliability"), "behavior server": ("behavior_server", "behavior server"),
    "param": ("param",), "yaml": ("yaml",), "config": ("config", "yaml"),
}
_NAMES = "|".join(sorted((re.escape(t) for t in _TERMS), key=len, reverse=True))
_LEAD = r"^(and |so |but |ok |okay |now |then )?"
MENTIONS = re.compile(
    _LEAD + r"(which|what|what's|how many|how big|how long|how wide) (is |was |are |were )?((my|the|your|its|their|"
    # "what did the controllers do?" asks what a module did (its explainer's), not for a named thing
    r"that) )?((?!(did|do|does|has|have|had|can|could|would|will|should|happened|went|made|caused)\b)[a-z_]+ ){0,3}?"
    r"(" + _NAMES + r")s?\b|"
    + _LEAD + r"(is|was|are|were|did you set) ((my|the|your) )?(" + _NAMES + r")s?( [a-z]+)? "
    r"(set|on|true|false|enabled|published|publishing|running|working|alive|paused|"
    r"right|correct|ok|okay|configured|defined|loaded|missing|there)\b|"
    + _LEAD + r"(where|which one) (is|was|are|were) ((my|the|your) )?([a-z_]+ )?(" + _NAMES + r")s?\b|"
    + _LEAD + r"(is|was|are|were) ((my|the|your) )?[a-z_]+ (using|on|set to|publishing|reading|getting|receiving) "
    r"((my|the|your) )?(" + _NAMES + r")s?\b")
# The named things that are settings: where no line names one, the answer says where its value is kept.
_SETTINGS = frozenset({"footprint", "tolerance", "threshold", "timeout", "baud", "baud rate", "port", "use_sim_time",
                       "sim time", "inflation", "radius", "rate", "frequency", "velocity", "speed", "parameter",
                       "param", "yaml", "config", "progress checker", "goal checker", "namespace", "kinematics",
                       "solver", "ik", "initial pose"})


# "what's failure_tolerance set to?", "is use_sim_time true?", "what is max_vel_x?": a parameter asked for by its
# name, as the subject of the question ("did planner_server produce a path?" asks what a node did)
_ID = IDENTIFIER.pattern
VALUE_OF = re.compile(
    r"^(and |so |but |ok )?(what|what's|whats|which|how (big|long|large|high|low|much|fast) (is|was))"
    r"( (is|was|are|were))?( (the|my|your))?( value of)? " + _ID + r"( (value|values|parameter|param))?\W*$|"
    + _ID + r"( and " + _ID + r")? (is |was |are |were )?(set to|set at)\b|"
    r"(^|[.?!] )(is|was|are|were) " + _ID + r" (set|true|false|on|off|enabled|disabled)\b|"
    r"\bvalue of " + _ID + r"|"
    # "which xy_goal_tolerance / yaw_goal_tolerance values were in effect?"
    r"^(and |so |but |ok )?(which|what) " + _ID + r"(( ?/ ?| and | or )" + _ID + r")? (values?|settings?)\b")


# "which nodes use sim time?", "how many nodes had use_sim_time false?"
_WHICH_NODES = re.compile(r"^(and |so |but )?(which|what|how many) (nodes?|ones?|of them)\b.*\b(" + _NAMES + r"|"
                          + IDENTIFIER.pattern + r")")


# "which waypoint failed, and why?": the failure itself, which names its goal
_WHICH_FAILED = re.compile(r"^(and |so )?(which|what) (waypoint|goal|pose|step)s? (failed|went wrong|aborted|was "
                           r"(the one that )?(failed|aborted))\b")


def mentions_kind(q: str) -> str | None:
    """'mentions' for a question (lower case, spaces collapsed) that asks for a named thing of the stack or a
    parameter by its name, unless it asks for a specific of the failure the finding's own lines give
    (agent/cited.py) or for the fix ("which parameter should I change?")."""
    named = MENTIONS.search(q) or VALUE_OF.search(q) or _WHICH_NODES.search(q)
    return "mentions" if named and not asks_specific(q) and not asks_fix(q) and not _WHICH_FAILED.search(q) else None


def asked_terms(q: str) -> list[str]:
    """The named things a question asks for, longest first ("progress checker" before "progress")."""
    found = []
    for m in re.finditer(r"\b(" + _NAMES + r")s?\b", q):
        if m.group(1) not in found:
            found.append(m.group(1))
    return found


@cache
def _spelled(term: str) -> re.Pattern[str]:
    """A term's spellings at the start of a word ("port" in "ports", not in "support"; "vel" in "cmd_vel", not in
    "level"), a spelling that ends in a space a whole word ("ik")."""
    ways = []
    for s in _TERMS.get(term, (term,)):
        word = re.escape(s.strip().replace("_", " "))
        ways.append((r"\b" if s[0].isalnum() else "") + word + (r"\b" if s.endswith(" ") else ""))
    return re.compile("|".join(ways))


def _names(line: LogLine, term: str) -> bool:
    return _spelled(term).search(line.msg.lower().replace("_", " ")) is not None


def mentions(question: str, log: EventLog, task: Task) -> Explanation:
    """The log lines up to the task's end that name what was asked, or that none does."""
    q = " ".join(question.lower().split())
    terms = asked_terms(q)
    end = worked_until(log, task)
    # "what parameters did the arm controller announce?": its list; else the values of those named
    listing = asks_parameters(q, log) and LISTING.search(q) is not None and node_asked(q, log)
    values = parameter_list(q, log, end) if listing else parameter_values(q, log, end, terms)
    if values is None and asks_parameters(q, log):
        values = parameter_list(q, log, end)
    if values is not None:
        return Explanation(explainer="planner", text=values[0], causes=["planner.plan_ok"], evidence=values[1])
    if VALUE_OF.search(q):  # a parameter by its name: the lines that name it (a node's name is no parameter)
        nodes = {ln.name.rsplit(".", 1)[-1].lower() for ln in log.logs}
        terms = [m.group(0) for m in IDENTIFIER.finditer(q) if m.group(0) not in terms and m.group(0) not in nodes] \
            + terms
    name = task_name(task, log)
    named = {t: [ln for ln in log.logs if ln.t <= end and _names(ln, t)] for t in terms}
    found = [t for t in terms if named[t]]
    missing = " or ".join(t for t in terms if not named[t]) or "that"
    lines = sorted({id(ln): ln for t in found for ln in named[t]}.values(), key=lambda ln: ln.t)
    if not lines:
        where = f"no line of my log ({c.ROSOUT}) up to the end of {name} names {missing}" if log.logs else \
            f"my recording holds no log lines ({c.ROSOUT})"
        text = (f"I can't tell: {where}, and {not_held(q, log, end)}. The parameter files or `ros2 param get` on "
                "the robot give it.") if set(terms) & _SETTINGS or VALUE_OF.search(q) else f"I can't tell: {where}."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    # a start-up's routine lines ("waypoint_follower lifecycle node launched") say less than a warning about it
    routine = len(lines)
    lines = [ln for ln in lines if ln.level >= WARN] or lines
    routine -= len(lines)
    when = f"before I began on {name}" if all(ln.t < task.created for ln in lines) else f"up to the end of {name}"
    n = len(lines)
    level = f" at warning or error level ({routine} more at info level)" if routine else ""
    text = (f"My log names {' and '.join(found)} in {n} line{'s' if n > 1 else ''}{level} {when}: "
            f"{quote(lines, False, True)}.")
    if len(found) < len(terms):
        text += f" No line names {missing}."
    if set(terms) & _SETTINGS or VALUE_OF.search(q):
        text += f" As for its value: {not_held(q, log, end)}." if log.settings(end) else \
            f" My recording holds no parameter values (no {c.PARAMETER_EVENTS}), only what my nodes logged."
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=line_evidence(lines, task))


def mentioned(ctx: RunContext, state: AgentState, task: Task) -> Explanation:
    """The lines that name what was asked; where none does, that, then the task's finding, which is all the
    recording has on it. "Why?" after either goes on to the failure."""
    asked = mentions(state["question"], ctx.log, task)
    found = finding(ctx, state)  # of a failed task, the failure: with_failure's own answer, not asked twice
    told = with_failure(ctx, state, asked, found)
    if asked.evidence and all(e.topic == c.PARAMETER_EVENTS for e in asked.evidence) and found is not None:
        # the values were said: "why?" goes on to the failure's lines, not to the parameters again
        told = told.model_copy(update={"evidence": [*found.evidence, *asked.evidence]})
    if asked.enough_information or found is None:
        return told
    return told.model_copy(update={"text": f"{asked.text} {found.text}"})
