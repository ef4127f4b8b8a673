"""Tasks derived from MoveIt's and the arm controllers' goals, for recordings that have no `/task_info`.

As with Nav2 goals (events/nav_goals.py), each goal becomes a task of one step: a MoveIt goal (`move_action`,
`execute_trajectory`) a `move_arm` step explained by `manipulation`, a joint trajectory controller's own goal
(`follow_joint_trajectory`, sent without MoveIt) a `follow_joint_trajectory` step explained by `control`.
Sources, best first: the lines that begin and end a goal in MoveGroupInterface's and move_group's words and the
joint trajectory controller's (the mined catalogues, kinds begin/succeeded/failed/canceled), then the actions'
status topics, then activity: lines of the catalogues that carry a cause (a controller that never loaded, a
joint state that never came) with no goal line at all, one task failed at the first error.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from hexar.events import contract as c
from hexar.events.records import ERROR, WARN, GoalStatus, LogLine, SkillStep, TaskUpdate
from hexar.events.tasks import SkillRun, StatusChange, Task

if TYPE_CHECKING:
    from hexar.events.bringup import BringUp
    from hexar.explainers.logcause import ModuleCatalogue

MOVE_ARM = "move_arm"
FOLLOW = "follow_joint_trajectory"
GRIP = "command_gripper"
# the gripper action controllers' own packages (gripper_controllers, parallel_gripper_controller): their "Received &
# accepted new action goal" begins a GripperCommand goal, not a trajectory
_GRIPPERS = frozenset({"gripper_controllers", "parallel_gripper_controller"})
BRING_UP = "bring_up_controllers"
_STATUS_END = {4: "succeeded", 5: "canceled", 6: "failed"}
_BEGIN, _END = {"begin", "begin_server"}, {"succeeded", "failed", "canceled", "end_server"}
# move_group's "Execution completed: <status>" names how the execution ended (moveit_controller_manager's
# ExecutionStatus::asString: SUCCEEDED, PREEMPTED, TIMED_OUT, ABORTED, FAILED, UNKNOWN, RUNNING)
_EXECUTION_END = {"SUCCEEDED": "succeeded", "PREEMPTED": "canceled"}
_SAME_END_NS = 1_000_000_000


@dataclass
class _Goal:
    skill: str
    start: int
    via: str
    end: int | None = None
    state: str = "running"
    error: str = ""


def _kind(line: LogLine) -> tuple[str, str] | None:
    """(skill, kind) of a goal line in either catalogue, else None."""
    from hexar.explainers.control.catalogue import INVALID, REFUSED
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    code = line.msg.strip()
    if code in moveit().error_codes and "move_group" in line.name:
        # getActionResultString's own word for a code it has no sentence for ("CONTROL_FAILED"), logged by
        # move_action as the goal ends (scripts/modules_mining.yaml, return_files)
        return MOVE_ARM, "failed"
    for skill, cat in ((MOVE_ARM, moveit()), (FOLLOW, control())):
        entry = cat.match(line.msg)
        if entry is None:
            refined = cat.refinement(line.msg) if skill == FOLLOW else None
            if refined is not None and refined.cause == "control.tolerance_violated" and line.msg.startswith("Aborted"):
                # "Aborted due to goal_time_tolerance exceeding by 1.0 seconds" (kilted's words, a refinement's text
                # that no mined entry matches): the controller ends the goal it was following
                return skill, "failed"
            continue
        kind = entry.kind
        if kind == "end_server":
            status = line.msg.rsplit(":", 1)[-1].strip()
            kind = _EXECUTION_END.get(status, "failed")
        elif skill == FOLLOW and entry.cause == "control.tolerance_violated" and entry.strength == "strong" \
                and line.msg.startswith("Aborted"):
            kind = "failed"  # the controller aborts the goal it was following
        elif skill == FOLLOW and (entry.id == REFUSED or entry.id in INVALID):
            kind = "failed"  # the controller refuses the goal it has just received: not active, or not a fit
        if kind in _BEGIN and entry.role in _GRIPPERS:
            return GRIP, "begin"
        if kind in _BEGIN or kind in _END:
            return skill, ("begin" if kind in _BEGIN else kind)
    return None


def _events(logs: list[LogLine]) -> list[tuple[int, str, str, str]]:
    """(t, skill, kind, line) of the goal lines; a MoveIt goal's lines hide its controller's goal lines."""
    out = []
    for line in logs:
        found = _kind(line)
        if found is not None:
            out.append((line.t, found[0], found[1], line.msg))
    if any(skill == MOVE_ARM for _, skill, _, _ in out):
        out = [e for e in out if e[1] == MOVE_ARM]
    return out


def _status_events(statuses: list[GoalStatus]) -> list[tuple[int, str, str, str]]:
    moveit = [s for s in statuses if s.topic in {c.MOVE_ACTION_STATUS, c.EXECUTE_TRAJECTORY_STATUS}]
    chosen = moveit or [s for s in statuses if c.topic_key(s.topic) == c.FJT_STATUS]
    skill = MOVE_ARM if moveit else FOLLOW
    seen: dict[str, str] = {}
    out: list[tuple[int, str, str, str]] = []
    for s in chosen:
        state = _STATUS_END.get(s.status, "running")
        if s.goal_id in seen and (seen[s.goal_id] == state or seen[s.goal_id] != "running"):
            continue
        if s.goal_id not in seen:
            out.append((s.accepted or s.t, skill, "begin", s.topic))
        if state != "running":
            out.append((s.t, skill, state, f"{s.topic}: goal {state}"))
        seen[s.goal_id] = state
    return out


def _pair(events: list[tuple[int, str, str, str]], first_t: int, via: str) -> list[_Goal]:
    goals: list[_Goal] = []
    open_goals: dict[str, _Goal] = {}  # a gripper's goal may run beside an arm's
    for t, skill, kind, msg in sorted(events, key=lambda e: (e[0], e[2] != "begin")):
        if kind == "begin":
            if skill not in open_goals:
                open_goals[skill] = _Goal(skill, t, via)
                goals.append(open_goals[skill])
            continue  # the server's and the client's begin lines of one goal
        if skill == FOLLOW and FOLLOW not in open_goals and GRIP in open_goals:
            skill = GRIP  # the controllers' shared words for a cancel ("Got request to cancel goal") end the gripper's
        open_goal = open_goals.pop(skill, None)
        if open_goal is None:
            if goals and goals[-1].end is not None and t - goals[-1].end < _SAME_END_NS:
                continue  # another line (or the status topic) telling the same end
            open_goal = _Goal(skill, min(first_t, t), via)  # began before the recording did
            goals.append(open_goal)
        open_goal.end, open_goal.state = t, kind
        open_goal.error = msg if kind != "succeeded" else ""
    return goals


def _activity(logs: list[LogLine]) -> list[_Goal]:
    """No goal line: catalogued cause lines make one goal (MoveIt's a move_arm, ros2_control's a
    follow_joint_trajectory), failed at the first error; without them, the robot's own errors (a bring-up
    failure, a driver that cannot open its device: explainers/stack_causes.py) and the start of its software make
    one `bring_up_controllers` goal (events/bringup.py), unless the recording is a Nav2 robot's (navigation explains
    those)."""
    from hexar.events.bringup import ABORT, bring_up, notice
    from hexar.events.nav_goals import python_death_alone
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    active: list[tuple[LogLine, str]] = []
    for line in logs:
        for skill, cat in _readers(line):
            if cat.cause_of(line.msg, cat.match(line.msg)) is not None:  # a catalogued text or one built in code
                active.append((line, skill))
                break
    if active and ABORT in active[0][0].msg:
        # a C++ exception nobody caught ended the process while it was starting (a hardware plugin that could not
        # load): the robot's start failed there, whatever the catalogues say of the exception's text
        start = bring_up(logs)
        if start is not None and start.state == "failed":
            return [_start_goal(start)]
    if not active:
        # an error the arm's own software logs in its own words (a catalogued text with no cause of its own, e.g.
        # a controller left unconfigured) still shows that the arm had something to do: the explainer then quotes it
        # launch's and rcl's own bring-up lines are not the arm's words, whatever short text of MoveIt they contain
        # (conversions.cpp's "Caught %s" matches launch's "Caught exception in launch")
        active = [(line, skill) for line in logs
                  if line.level >= ERROR and not _stack_bringup(line) and not notice(line)
                  for skill, cat in _readers(line) if cat.match(line.msg) is not None][:1]
    if not active:
        if _nav2_robot(logs) and not python_death_alone(logs):
            return []  # a Nav2 robot's errors are navigation's to explain (events/nav_goals.py)
        start = bring_up(logs)
        if start is None:
            return []  # no start shown: a lone error may be anybody's, and no task is claimed from it
        return [_start_goal(start)]
    skill = MOVE_ARM if any(s == MOVE_ARM for _, s in active) else FOLLOW
    # the step began with the first warning or error of the arm's own software (its words, or its node), so that
    # a warning it logged before (a controller manager waiting for its robot description) is in the explained window
    first = next((ln.t for ln in logs if ln.level >= WARN and ln.t <= active[0][0].t
                  and (_arms_logger(ln.name) or any(cat.match(ln.msg) is not None for cat in (moveit(), control())))),
                 active[0][0].t)
    goal = _Goal(skill, first, "log (no goal line)")
    failed = next((ln for ln, _ in active if ln.level >= ERROR), None)
    if failed is None:
        # a cause told at WARN (a controller manager still waiting for its robot description) and then a
        # catalogued error that follows from it (a spawner that could not reach the controller manager)
        failed = next((ln for ln in logs if ln.level >= ERROR and ln.t >= active[0][0].t and _symptom(ln)), None)
    if failed is not None:
        goal.end, goal.state, goal.error = max(active[-1][0].t, failed.t), "failed", failed.msg
    return [goal]


def _start_goal(start: BringUp) -> _Goal:
    """The robot's start as a `bring_up_controllers` goal (events/bringup.py)."""
    return _Goal(BRING_UP, start.start, "bring-up lines (no goal line)", start.end, start.state, start.error)


def _symptom(line: LogLine) -> bool:
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    entries = (cat.match(line.msg) for cat in (moveit(), control()))
    return any(e is not None and e.kind in {"symptom", "failed"} for e in entries)


def _goals(logs: list[LogLine], statuses: list[GoalStatus]) -> list[_Goal]:
    first = logs[0].t if logs else 0
    events = _events(logs)
    if any(kind == "begin" for _, _, kind, _ in events) or not statuses:
        goals = _pair(events, first, "log")
    else:
        goals = _pair([e for e in events if e[2] != "begin"] + _status_events(statuses), first, "action status")
    return goals or _activity(logs)


def derive_arm_tasks(logs: list[LogLine], statuses: list[GoalStatus]) -> list[Task]:
    """One task per MoveIt (or controller) goal, in time order; empty when the recording shows none."""
    arm_statuses = [s for s in statuses if c.topic_key(s.topic) in c.ARM_STATUS_TOPICS]
    tasks = []
    for order, goal in enumerate(_goals(logs, arm_statuses), start=1):
        source = {MOVE_ARM: "moveit", FOLLOW: "ros2_control", GRIP: "ros2_control", BRING_UP: "bringup"}[goal.skill]
        params: dict[str, object] = {"source": source, "derived_from": goal.via}
        instruction = {MOVE_ARM: "Move the arm (derived from MoveIt)",
                       FOLLOW: "Follow a joint trajectory (derived from ros2_control)",
                       GRIP: "Open or close the gripper (derived from ros2_control)",
                       BRING_UP: "Start the robot (derived from its start lines)"}[goal.skill]
        history = [StatusChange(goal.start, "running", "")]
        if goal.end is not None:
            history.append(StatusChange(goal.end, goal.state, goal.error))
        run = SkillRun(0, goal.skill, params, tuple(history))
        task_id = f"{source}-goal-{order}"
        updates = [TaskUpdate(ch.t, task_id, instruction, "valid", "",
                              (SkillStep(goal.skill, params, ch.status, ch.error_msg),), raw="") for ch in history]
        last = max((ln.t for ln in logs), default=goal.start)
        if goal.end is None and last > goal.start:
            updates.append(TaskUpdate(last, task_id, instruction, "valid", "",
                                      (SkillStep(goal.skill, params, "running", ""),), raw=""))
        tasks.append(Task(task_id, instruction, tuple(updates), (run,), order, derived=True))
    return tasks


def _arms_line(task: Task) -> bool:
    """A Nav2 task found from activity alone whose failing line the arm's catalogues tie to a cause."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    run = task.skills[0]
    if run.params.get("derived_from") != "Nav2 log (no goal line)" or not run.error_msg:
        return False
    return any(cat.cause_of(run.error_msg, cat.match(run.error_msg)) is not None for cat in (moveit(), control()))


# launch's "process has died [pid N, exit code N, cmd '<prefix>/lib/<package>/<executable> ...']"
# (launch/launch/actions/execute_local.py): the package and executable of the process that died
_DIED_PACKAGE = re.compile(r"process has died \[.*?cmd '\S*/lib/([^/\s]+)/([^/\s']+)")


def _arms_process(task: Task) -> bool:
    """A Nav2 task found from activity alone whose failing line is a process of the arm's catalogued packages
    (controller_manager's ros2_control_node, MoveIt's move_group) dying: no Nav2 node is involved."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    run = task.skills[0]
    found = _DIED_PACKAGE.search(run.error_msg or "")
    if run.params.get("derived_from") != "Nav2 log (no goal line)" or found is None:
        return False
    return any(cat.role(name) is not None for cat in (moveit(), control()) for name in found.groups())


def _readers(line: LogLine) -> tuple[tuple[str, ModuleCatalogue], ...]:
    """The arm catalogues that may read `line`, with their skills: its logger's own one alone
    (explainers/logcause.own_catalogue), else both, MoveIt's first."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.logcause import own_catalogue
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    both = ((MOVE_ARM, moveit()), (FOLLOW, control()))
    own = own_catalogue(line, [cat for _, cat in both])
    return tuple(pair for pair in both if pair[1] is own) if own is not None else both


def _stack_bringup(line: LogLine) -> bool:
    """A line the stack catalogue reads as launch's (launch, launch_ros) or rcl's own."""
    from hexar.explainers.stack.catalogue import stack_catalogue

    entry = stack_catalogue().match(line.msg)
    return entry is not None and entry.layer in {"launch", "rcl"}


def _nav2_own(line: LogLine, nav2_logged: bool) -> bool:
    """A line of Nav2 itself: its logger (or launch's process name) has a Nav2 role, or its text is a Nav2 message
    logged by no logger of the arm's software (launch's generic "process has died" is anybody's)."""
    from hexar.events.nav_goals import own_manager
    from hexar.explainers.navigation.catalogue import catalogue as nav2
    from hexar.explainers.stack.thrown import python_exception

    if _nav2_logger(line.name):
        # a robot's own lifecycle manager of its drivers is named as Nav2's is (events/nav_goals.own_manager)
        return not own_manager(line, nav2_logged)
    if _arms_logger(line.name):
        return False  # e.g. the resource manager's pluginlib error: a text Nav2 shares, logged by ros2_control
    if python_exception(line) is not None:
        return False  # a Python program's uncaught exception: Nav2's servers are C++ programs
    entry = nav2().match(line.msg)
    return entry is not None and not entry.id.startswith("launch.")


def _nav2_robot(logs: list[LogLine]) -> bool:
    """Whether any line of `logs` is Nav2's own (_nav2_own)."""
    from hexar.events.nav_goals import nav2_nodes

    nav2_logged = nav2_nodes(logs)
    return any(_nav2_own(ln, nav2_logged) for ln in logs)


def _nav2_logger(name: str) -> bool:
    """A logger (or launch's process name for one) with a Nav2 role: amcl, controller_server-6, bt_navigator."""
    from hexar.events.nav_goals import any_robots
    from hexar.explainers.navigation.catalogue import catalogue as nav2
    from hexar.explainers.stack.bringup import PROCESS_SUFFIX

    cat = nav2()
    if any_robots(PROCESS_SUFFIX.sub("", name)):
        return False  # robot_state_publisher runs on every robot, an arm alone too: no sign of Nav2
    return cat.role(name) is not None or cat.role(PROCESS_SUFFIX.sub("", name)) is not None


def _arms_logger(name: str) -> bool:
    """A logger with a role in the arm's catalogues (controller_manager, resource_manager, spawner, move_group)."""
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    return bool(name) and any(cat.role(name) is not None for cat in (moveit(), control()))


def _only_arms_nodes(task: Task, logs: list[LogLine] | None) -> bool:
    """A Nav2 task found from activity alone in a recording whose only named loggers of either catalogue are the
    arm's (controller_manager, resource_manager, move_group): its lines that name no node (a process's stderr, such
    as "terminate called after throwing ...  what(): Failed to configure 'hsrb'") matched Nav2's catalogue by
    words alone, and the nodes that did log are the arm's."""
    if logs is None or task.skills[0].params.get("derived_from") != "Nav2 log (no goal line)":
        return False
    return not any(_nav2_logger(ln.name) for ln in logs) and any(_arms_logger(ln.name) for ln in logs)


def _others_lifecycle(task: Task, logs: list[LogLine] | None) -> bool:
    """A Nav2 task found from activity alone whose first bring-up finding is a lifecycle transition of a node with
    no Nav2 role, in a recording where no line is Nav2's own: a driver's or another robot's lifecycle node."""
    from hexar.explainers.navigation.catalogue import catalogue as nav2
    from hexar.explainers.stack import bringup_findings

    if logs is None or task.skills[0].params.get("derived_from") != "Nav2 log (no goal line)":
        return False
    findings = bringup_findings(logs)
    if not findings or findings[0].kind != "lifecycle_transition" or not findings[0].node:
        return False
    node = findings[0].node.strip("/").rsplit("/", 1)[-1]
    return nav2().role(node) is None and not _nav2_robot(logs)


def merge_tasks(nav: list[Task], arm: list[Task], logs: list[LogLine] | None = None) -> list[Task]:
    """Nav2's and the arm's derived tasks in time order. Without a Nav2 task, the arm's are all there is. With
    one, only arm tasks of goal lines or statuses join it (activity is Nav2's to explain), and a Nav2 task
    found only from activity gives way to arm goals (its lines were probably no Nav2 goal at all)."""
    if not nav or not arm:
        return nav or arm
    arm_goals = [t for t in arm if "no goal line" not in str(t.skills[0].params.get("derived_from"))]
    if not arm_goals and len(nav) == 1 and _arms_line(nav[0]) and arm[0].skills[0].skill != BRING_UP:
        return arm  # Nav2's "activity" was a line of the arm's catalogues (a controller that failed to activate)
    if not arm_goals and len(nav) == 1 and _arms_process(nav[0]):
        return arm  # the only failure was a process of the arm's packages (ros2_control_node, move_group) dying
    if not arm_goals and len(nav) == 1 and _others_lifecycle(nav[0], logs):
        return arm  # e.g. a drone's or a driver's lifecycle node that failed its transition: not navigation's
    if not arm_goals and len(nav) == 1 and _only_arms_nodes(nav[0], logs):
        return arm  # a line of no node ("terminate called ...") in words Nav2 shares, where only the arm's logged
    if not arm_goals:
        return nav
    real_nav = [t for t in nav if t.skills[0].params.get("derived_from") != "Nav2 log (no goal line)"]
    merged = sorted(real_nav + arm_goals, key=lambda t: t.created)
    return [dataclasses.replace(t, order=i) for i, t in enumerate(merged, start=1)]
