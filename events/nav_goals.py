"""Tasks derived from Nav2 navigation goals, for recordings that have no `/task_info`.

Most ROS 2 robots publish no HEXAR task messages, yet Nav2 says when a goal begins and ends. Each goal becomes a
task with one `navigate_to_pose` step whose params hold the goal coordinates, so "Why didn't you get there?"
works on an ordinary recording. Sources, best first: bt_navigator's begin/end lines in every distro's wording
(the Nav2 message catalogue), the NavigateToPose action status (`/navigate_to_pose/_action/status`), and goal
poses (`/goal_pose`). A new begin line while a goal runs is Nav2's goal preemption: the same goal, a new target.
A docking server's DockRobot goal and a behaviour server's goal that no navigation goal ran (events/nav_servers.py)
are tasks of their own.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from hexar.events.nav_servers import BEHAVIOR_SKILL, DOCK_SKILL, NO_GOAL_LINE, with_server_goals
from hexar.events.nav_servers import Goal as _Goal
from hexar.events.nav_servers import number as _number
from hexar.events.records import ERROR, GoalPose, GoalStatus, LogLine, SkillStep, TaskUpdate
from hexar.events.tasks import SkillRun, StatusChange, Task

if TYPE_CHECKING:
    from hexar.explainers.navigation.catalogue import Catalogue as NavCatalogue
    from hexar.explainers.navigation.catalogue import Entry as NavEntry

SOURCE = "nav2"
SKILL = "navigate_to_pose"
_STATUS_END = {4: "succeeded", 5: "canceled", 6: "failed"}
_KIND_STATE = {"succeeded": "succeeded", "failed": "failed", "canceled": "canceled"}


def _goal_events(logs: list[LogLine]) -> list[tuple[int, str, dict[str, object]]]:
    """(t, kind, details) of bt_navigator's begin/end lines (any distro, any namespace, unknown loggers too, where
    a Nav2 node logged in the recording (nav2_nodes): "Goal was canceled" is also what a program's own action client
    says)."""
    from hexar.explainers.navigation.catalogue import GOAL_KINDS, catalogue

    cat = catalogue()
    out: list[tuple[int, str, dict[str, object]]] = []
    nav2: bool | None = None
    for line in logs:
        entry = cat.goal(line.msg)
        role = cat.role(line.name)
        if entry is None or entry.kind not in GOAL_KINDS or role not in {"bt_navigator", None}:
            continue
        if role is None and line.name:
            nav2 = nav2_nodes(logs) if nav2 is None else nav2  # a robot's own lifecycle manager is no sign of Nav2
            if not nav2:
                continue
        m = entry.search(line.msg)
        details: dict[str, object] = {"msg": line.msg}
        if m is not None:
            details.update({k: v for k, v in m.groupdict().items() if v is not None})
        out.append((line.t, entry.kind, details))
    return out


def _from_statuses(statuses: list[GoalStatus]) -> list[tuple[int, str, dict[str, object]]]:
    seen: dict[str, str] = {}
    out: list[tuple[int, str, dict[str, object]]] = []
    for s in statuses:
        state = _STATUS_END.get(s.status, "running")
        if seen.get(s.goal_id) == state or (s.goal_id in seen and seen[s.goal_id] != "running"):
            continue
        if s.goal_id not in seen:
            out.append((s.accepted or s.t, "begin", {"goal_id": s.goal_id}))
        if state != "running":
            out.append((s.t, state, {"goal_id": s.goal_id}))
        seen[s.goal_id] = state
    return out


def _goals(logs: list[LogLine], statuses: list[GoalStatus], poses: list[GoalPose]) -> list[_Goal]:
    events = _goal_events(logs)
    via = "Nav2 log"
    if not any(kind == "begin" for _, kind, _ in events) and statuses:
        events = [e for e in events if e[1] != "begin"] + _from_statuses(statuses)
        via = "NavigateToPose status"
    if not any(kind == "begin" for _, kind, _ in events):
        events += [(p.t, "begin", {"x": p.x, "y": p.y, "pose": True}) for p in poses]
        via = "goal pose" if poses else via
    goals: list[_Goal] = []
    open_goal: _Goal | None = None
    for t, kind, details in sorted(events, key=lambda e: (e[0], e[1] != "begin")):
        if kind == "begin":
            x, y = _number(details.get("x")), _number(details.get("y"))
            if open_goal is not None and not details.get("pose"):
                # preemption (or the log line of a goal the status already opened): same goal, latest target
                open_goal.x, open_goal.y = x if x is not None else open_goal.x, y if y is not None else open_goal.y
                continue
            if open_goal is not None:
                open_goal.end, open_goal.state = t, "canceled"
            open_goal = _Goal(t, x, y, via)
            goals.append(open_goal)
            continue
        if open_goal is None:
            if goals and goals[-1].end is not None and t - goals[-1].end < 1_000_000_000:
                continue  # the status topic's copy of an end the log already gave
            # an end without a recorded begin: the goal started before the recording did
            first = logs[0].t if logs else t
            open_goal = _Goal(min(first, t), None, None, via)
            goals.append(open_goal)
        open_goal.end, open_goal.state = t, _KIND_STATE[kind]
        open_goal.error = str(details.get("error", "") or details.get("msg", "")) if kind != "succeeded" else ""
        open_goal = None
    return goals or _activity(logs)


def _bringup_node(line: LogLine) -> str | None:
    """For an error of a node of the stack that never came up (a params file rcl could not parse, a lifecycle
    transition that threw, a process that died: the mined stack catalogue), which the navigation explains too: the
    Nav2 node it is about, "" when it names none (launch's own exception, rcl's params file: may still be Nav2's).
    None when the line is no such error, or is about a node that is not Nav2's (a driver whose configure launch_ros
    saw fail)."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.navigation.chain import NAVIGATION
    from hexar.explainers.stack import bringup_findings
    from hexar.explainers.stack.catalogue import stack_catalogue
    from hexar.explainers.stack.loader import loader_failure

    if not loader_failure(line):  # the loader's words come at no level (stderr)
        if line.level < ERROR:
            return None
        entry = stack_catalogue().match(line.msg)
        if entry is None or entry.cause != "stack.bringup_failure":
            return None
    found = bringup_findings([line])
    if found and found[0].kind == "launch_failed" and not NAVIGATION.search(line.msg):
        return None  # launch itself failed on a description that names nothing of Nav2's: any robot's launch
    node = found[0].node.strip("/").split("/")[-1] if found else ""
    return node if not node or catalogue().role(node) is not None else None


# TF publishers every robot runs, an arm alone too (their own lines are no sign of Nav2; Nav2's TF helpers'
# loggers, transformPoseInTargetFrame and the like, are)
_ANY_ROBOTS = ("robot_state_publisher", "static_transform_publisher")


def any_robots(name: str) -> bool:
    """A logger of a node every robot runs (robot_state_publisher, static_transform_publisher)."""
    return name.strip("/").split("/")[-1].split(".")[-1].startswith(_ANY_ROBOTS)


# the plugin base classes of ros2_control and MoveIt 2 that pluginlib names when it cannot load a plugin
_ARMS_BASE = re.compile(r"with base class type (hardware_interface|controller_interface|transmission_interface|"
                        r"semantic_components|planning_interface|kinematics|moveit_controller_manager|move_group|"
                        r"collision_detection|constraint_samplers|planning_request_adapter)::")


def _arms_logger(line: LogLine) -> bool:
    """A line logged by a node the arm's catalogues name (controller_manager, resource_manager, move_group...):
    generic texts of such a node (pluginlib's "... does not exist", "Failed to configure") match Nav2's catalogue
    too, but no Nav2 node logged them."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit
    from hexar.explainers.stack.bringup import PROCESS_SUFFIX

    if _ARMS_BASE.search(line.msg):
        return True  # pluginlib's "... with base class type hardware_interface::SystemInterface does not exist"
    # launch's name for the process: the executable's, then "-<n>" (ros2_control_node-1, move_group-4)
    name = PROCESS_SUFFIX.sub("", line.name or "")
    return bool(name) and (any(cat.role(n) is not None for cat in (moveit(), control()) for n in {line.name, name})
                           or "ros2_control" in name)


_STARTED = "process started with pid ["


def _nav2_process(line: LogLine, cat: NavCatalogue) -> bool:
    """Whether launch's line is about a Nav2 process: its name has a Nav2 role (controller_server-3), or its words
    (the command it ran) name Nav2's packages, servers or plugins; a container's or a bare python3's name says
    nothing alone, so its command decides."""
    from hexar.explainers.navigation.chain import NAVIGATION
    from hexar.explainers.stack.bringup import PROCESS_SUFFIX

    name = PROCESS_SUFFIX.sub("", line.name or "")  # launch's process name: the executable's, then "-<n>"
    return not name or cat.role(name) is not None or NAVIGATION.search(f"{name} {line.msg}") is not None


def _worded(entry: NavEntry | None) -> bool:
    """A line in Nav2's own words: a catalogued cause, the progress checker's, a failure's, or "Reached the goal!"."""
    from hexar.explainers.navigation.catalogue import REACHED

    return entry is not None and (entry.cause is not None or entry.kind in {"progress", "failed"}
                                  or entry.id == REACHED)


def python_death_alone(logs: list[LogLine], thrown: list[bool] | None = None) -> bool:
    """A Python program died of an exception, and nothing else of the recording is Nav2's words or an error: loggers
    named like Nav2's nodes (a program's own "map_server") do not make that death a navigation's, since Nav2's servers
    are C++ programs. The death is what the recording tells (events/bringup.py). `thrown`: for each line, whether it
    is a Python exception, when the caller has read that already."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.stack.thrown import python_exception

    if thrown is None:
        thrown = [python_exception(line) is not None for line in logs]
    if not any(thrown):
        return False
    cat = catalogue()
    return not any(not py and (line.level >= ERROR or _worded(cat.match(line.msg)))
                   for line, py in zip(logs, thrown, strict=True))


# Roles whose node names any lifecycle system uses too (a robot's own manager of its drivers is a
# "lifecycle_manager"): where no other Nav2 node logged, such a logger's line is Nav2's only in Nav2's words (a
# catalogued line) or naming Nav2 (its servers, "nav2" or "navigation" in its name or words)
_GENERIC_ROLES = frozenset({"lifecycle_manager"})
_NAV2_NAMED = re.compile(r"nav2|navigation", re.IGNORECASE)
_WORD = re.compile(r"[A-Za-z_]\w{3,}")


def nav2_nodes(logs: list[LogLine]) -> bool:
    """Whether a logger (or launch's process) with a Nav2 role other than a generic one logged (a TF publisher every
    robot runs aside)."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.stack.bringup import PROCESS_SUFFIX

    cat = catalogue()
    names = {PROCESS_SUFFIX.sub("", ln.name) for ln in logs if ln.name}
    return any(cat.role(n) not in {None, *_GENERIC_ROLES} and not any_robots(n) for n in names)


def own_manager(line: LogLine, nav2_logged: bool) -> bool:
    """A line of a robot's own lifecycle manager, named as Nav2's is, when `nav2_logged` (nav2_nodes) is False."""
    from hexar.explainers.navigation.catalogue import catalogue

    cat = catalogue()
    if nav2_logged or cat.role(line.name) not in _GENERIC_ROLES or cat.match(line.msg) is not None:
        return False
    if _NAV2_NAMED.search(f"{line.name} {line.msg}") is not None:
        return False
    return not any(cat.role(word) not in {None, *_GENERIC_ROLES} for word in _WORD.findall(line.msg))


def _activity(logs: list[LogLine]) -> list[_Goal]:
    """Nav2 at work without any goal line (the recording began after the goal was sent, a node never came up so
    no goal could start, or only the stack's bring-up was recorded): one goal over the lines the catalogue ties to
    a cause or to the progress checker, the lines of Nav2's own nodes, and the bring-up errors of the stack
    catalogue (at any level: consoles pasted without levels are read as INFO); failed when Nav2 logged an error or
    an abort, else still running as far as the recording shows."""
    from hexar.explainers.navigation.catalogue import catalogue
    from hexar.explainers.navigation.chain import NAVIGATION
    from hexar.explainers.navigation.goal_sent import REJECTED
    from hexar.explainers.shutdown import before_shutdown
    from hexar.explainers.stack.loader import loader_failure
    from hexar.explainers.stack.thrown import python_exception

    thrown = [python_exception(line) is not None for line in logs]
    if python_death_alone(logs, thrown):
        return []
    cat = catalogue()
    active: list[LogLine] = []
    failed: LogLine | None = None
    own = arms = named = False
    nav2_logged = nav2_nodes(logs)
    # what a stack prints as it is stopped (launch escalating to SIGKILL, "process has died [..., exit code -9]") is
    # no failure of a goal: it ends the recording, not the navigation
    running = {id(line) for line in before_shutdown(logs)}
    # the processes (launch's names for them) that printed a Python traceback
    python_died = {line.name for line, py in zip(logs, thrown, strict=True) if py and line.name}
    # launch's "process started with pid [N]" for each process it started (launch/actions/execute_local.py): a
    # launch whose started processes show none of Nav2's is another module's; with no such line, nothing says so
    started = [line for line in logs if line.msg.startswith(_STARTED)]
    nav2_launch = not started or any(_nav2_process(line, cat) for line in started)
    for line, py in zip(logs, thrown, strict=True):
        if _arms_logger(line):
            arms = True
            continue  # ros2_control's or MoveIt's own node: its line is the arm's to explain, not Nav2's activity
        if py:
            continue  # a Python program's uncaught exception: Nav2's servers are C++ programs
        entry = cat.match(line.msg)
        # the controller server's "Reached the goal!" (controller_server.cpp:411@humble) ends a path it followed
        nav2 = _worded(entry)
        # a Nav2 node at work (its logger's role: planner_server, controller_server, amcl, ...), even with no
        # catalogued line: a stack that came up and ran normally has a navigation to tell about too; a TF
        # publisher's own line (robot_state_publisher's "Robot initialized") is not: every robot runs one
        nav2 = nav2 or (bool(line.name) and cat.role(line.name) is not None and not any_robots(line.name)
                        and not own_manager(line, nav2_logged))
        if nav2 and entry is not None and entry.id.startswith("launch.") and line.name in python_died:
            continue  # launch's word that a Python program died (its traceback above): Nav2's servers are C++
        if nav2 and entry is not None and entry.id.startswith("launch.") and not nav2_launch \
                and not _nav2_process(line, cat):
            continue  # launch's word about a process of a launch that started nothing of Nav2's
        own = own or nav2 or "[ActionServer] Aborting handle" in line.msg
        node = _bringup_node(line) if not nav2 and "[ActionServer] Aborting handle" not in line.msg else ""
        if node is None:
            continue
        # a bring-up error that names no node still ties to Nav2 when its words name one of its nodes or packages
        # (rcl's params file error quoting ".../planner_server.yaml")
        named = named or bool(node) or NAVIGATION.search(line.msg) is not None
        active.append(line)
        # a Nav2 server refusing a goal while it is not active (goal_sent.REJECTED, at INFO) ends the goal there too
        if failed is None and id(line) in running and (line.level >= ERROR or "Aborting handle" in line.msg
                                                        or REJECTED.match(line.msg.strip()) or loader_failure(line)):
            failed = line
    if not active or (not own and (arms or not named)):
        # bring-up errors that name no node (pluginlib's, launch's, rcl's) beside an arm's nodes at work and no Nav2
        # node, or with no Nav2 line at all: the robot's bring-up, which nothing ties to Nav2
        return []
    goal = _Goal(active[0].t, None, None, NO_GOAL_LINE)
    if failed is not None:
        goal.end, goal.state, goal.error = active[-1].t, "failed", failed.msg
    return [goal]


def _waypoint_tasks(goals: list[_Goal], logs: list[LogLine]) -> None:
    """A goal that reached its waypoint, and whose waypoint task then failed (before the next goal began), ends
    there as failed: the goal was one step of a waypoint follower's job, which it did not do
    (explainers/navigation/waypoints.py)."""
    from hexar.explainers.navigation.waypoints import TASK_FAILED

    failures = [ln for ln in logs if TASK_FAILED.match(ln.msg.strip())]
    for i, goal in enumerate(goals):
        if goal.state != "succeeded" or goal.end is None:
            continue
        after = goals[i + 1].start if i + 1 < len(goals) else None
        told = next((ln for ln in failures if goal.end <= ln.t and (after is None or ln.t < after)), None)
        if told is not None:
            goal.end, goal.state, goal.error = told.t, "failed", told.msg


def derive_tasks(logs: list[LogLine], statuses: list[GoalStatus], poses: list[GoalPose]) -> list[Task]:
    """One task per navigation goal, docking or behaviour goal, in time order; empty when the recording shows none."""
    tasks = []
    goals = _goals(logs, statuses, poses)
    _waypoint_tasks(goals, logs)
    goals = with_server_goals(goals, logs)
    for order, goal in enumerate(goals, start=1):
        params: dict[str, object] = {"source": SOURCE, "derived_from": goal.via}
        where = "an unrecorded goal"
        if goal.x is not None and goal.y is not None:
            params.update({"x": round(goal.x, 3), "y": round(goal.y, 3)})
            where = f"({goal.x:.2f}, {goal.y:.2f})"
        instruction = f"Navigate to {where} (derived from Nav2)"
        skill = SKILL
        if goal.dock is not None:
            skill, instruction = DOCK_SKILL, f"Dock at {goal.dock or where} (derived from Nav2's docking server)"
            if goal.dock:
                params["dock"] = goal.dock
        elif goal.behavior is not None:
            skill, instruction = BEHAVIOR_SKILL, f"Run {goal.behavior} (derived from Nav2's behaviour server)"
            params = {"source": SOURCE, "derived_from": goal.via, "behavior": goal.behavior}
        history = [StatusChange(goal.start, "running", "")]
        if goal.end is not None:
            history.append(StatusChange(goal.end, goal.state, goal.error))
        run = SkillRun(0, skill, params, tuple(history))
        task_id = f"nav2-goal-{order}"
        updates = [TaskUpdate(change.t, task_id, instruction, "valid", "",
                              (SkillStep(skill, params, change.status, change.error_msg),), raw="")
                   for change in history]
        last = max((ln.t for ln in logs), default=goal.start)
        if goal.end is None and last > goal.start:
            # still running when the recording ended: its window reaches the last line recorded
            updates.append(TaskUpdate(last, task_id, instruction, "valid", "",
                                      (SkillStep(skill, params, "running", ""),), raw=""))
        tasks.append(Task(task_id, instruction, tuple(updates), (run,), order, derived=True))
    return tasks
