"""Bring-up problems any explainer can cite: a node of the stack that never came up (stable API).

    bringup_findings(lines, before=None) -> list[BringupFinding]
    client_gave_up(died, before) -> bool

A node that never came up explains every later failure that depends on it (a controller server whose params file
did not parse cannot follow a path; a move group whose configure callback threw cannot plan), so an explainer asks
for these first and cites them before anything it reads in its own logs. Each finding is one decisive log line,
read through the mined stack catalogue (its entries of cause `stack.bringup_failure`, and the rcl/lifecycle/launch
wordings below), with the node it concerns and its time:

    kind     params_file            rcl could not parse a `--params-file` (or another --ros-args rule): the node
                                    exits before it exists
             lifecycle_transition   a lifecycle transition failed or its callback threw (rclcpp_lifecycle's
                                    "Caught exception in callback for transition", with its "Original error: ..."),
                                    or a lifecycle manager could not bring its nodes up, or a Nav2 server's
                                    configure failed because it could not create a plugin (`configure_failed`)
             process_died           launch reports the node's process died (with its exit code)
             launch_failed          launch itself caught an exception while reading its descriptions (a YAML
                                    file it could not parse, a package it could not find) and shut down: the
                                    nodes it had not started yet never came up
             node_failed            another bring-up line of the catalogue (e.g. a costmap that failed to configure)
             no_program             launch's command was `ros2 run <package> <program>` and ros2run found no such
                                    program ("No executable found") or package: the process exited 1 before any
                                    node existed (a misspelt name, a command built without its spaces)
             lifecycle_wait         a Nav2 lifecycle manager kept waiting for a managed node's `get_state`
                                    service and, as far as the recording goes, never found it: it configures none
                                    of its nodes while it waits (the node is not running under that name)
    node     the node the line is about: the logger name, or the process launch names (`controller_server-3` ->
             `controller_server`), or the node a lifecycle manager names; "" when the line names none
    t        the line's time (ns), line: the LogLine itself, entry: its catalogue entry (source file:line@branch)
    detail   what the line adds: the original error, the exit code, the transition ("" when nothing)

Lines are taken in time order; `before` (ns) keeps only those at or before that time (a goal's start or end).
Repeats of one (kind, node) are folded into the first, which is the decisive one.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from hexar.events.records import ERROR, LogLine
from hexar.explainers.stack.catalogue import StackCatalogue, StackEntry, stack_catalogue
from hexar.explainers.stack.launched import exec_failed
from hexar.explainers.stack.loader import loader_said, needed

BRINGUP = "stack.bringup_failure"
DIED = "process has died"
KINDS = ("params_file", "lifecycle_transition", "process_died", "launch_failed", "node_failed", "no_program",
         "lifecycle_wait")

_PROCESS = re.compile(r"^(?P<node>[A-Za-z_][\w]*?)(?:-\d+)?$")
_EXIT = re.compile(r"exit code (?P<code>-?\d+)")
_NAMED_NODE = re.compile(r"(?:for node|node)[: ]+'?(?P<node>[/\w]+)'?")
_PROCESS_IN_MSG = re.compile(r"process\[(?P<node>[\w./-]+?)(?:-\d+)?\]")
_CMD_NODE = re.compile(r"cmd '[^']*?__node:=(?P<node>[A-Za-z_]\w*)")
_CMD_EXE = re.compile(r"cmd '(?:[^' ]*/)?(?P<node>[A-Za-z_]\w*)[ ']")
PROCESS_SUFFIX = re.compile(r"-\d+$")  # launch's process suffix: controller_server-6 -> controller_server
# ros2cli ros2run/command/run.py@rolling: `ros2 run` prints "No executable found" when the package has no program
# of that name, or raises "Package '<name>' not found", and exits 1; launch then reports the process died
_ROS2_RUN = re.compile(r"cmd '(?:\S*/)?ros2 run (?P<pkg>[^\s']+) (?P<exe>[^\s']+)")
_ORIGINAL = re.compile(r"Original error: (?P<error>.+)", re.S)
_TRANSITION = re.compile(r"transition (?P<id>\d+)")
# ros2_control's spawners are clients: they wait for the controller manager's services and, when none answers, say
# so and return 1 (controller_manager/spawner.py@humble: "Controller manager not available" then `return 1`,
# :225-226 before #1680 (8779757f7); since then ServiceNotFoundError's "Could not contact service …" logged FATAL,
# then `return 1`, :368-370@0941f73c3). Their process's death is then the controller manager's absence told by a
# client, not a node of the stack that failed to come up.
_SPAWNERS = ("spawner", "hardware_spawner")
# Nav2 servers whose on_configure logs FATAL "Failed to create … Exception: …" when pluginlib cannot create a plugin
# their parameters name, and then returns FAILURE, so the lifecycle manager's configure of that node fails
# (planner_server.cpp:121-127, controller_server.cpp:151/181/210, behavior_server.cpp:116 via loadBehaviorPlugins,
# bt_navigator.cpp:133, nav2_smoother.cpp:147 via loadSmootherPlugins, dock_database.cpp:177 via initialize, and
# route_server.cpp:116 catching edge_scorer.cpp:58 and graph_loader.cpp:57, all @jazzy; recovery_server.cpp@galactic;
# nav2_controller.cpp@foxy-devel). Not the rotation shim (its configure returns after the FATAL and its server goes
# on) nor the waypoint follower (waypoint_follower.cpp:123@jazzy cleans up, then returns SUCCESS).
_CONFIGURE_FAILS = ("nav2_planner/src/planner_server.cpp", "nav2_controller/src/controller_server.cpp",
                    "nav2_controller/src/nav2_controller.cpp", "nav2_behaviors/src/behavior_server.cpp",
                    "nav2_recoveries/src/recovery_server.cpp", "nav2_bt_navigator/src/bt_navigator.cpp",
                    "nav2_smoother/src/nav2_smoother.cpp", "nav2_docking/opennav_docking/src/dock_database.cpp",
                    "nav2_route/src/edge_scorer.cpp", "nav2_route/src/graph_loader.cpp")
_EXCEPTION = re.compile(r"\. Exception: (?P<error>.+)", re.S)
# A launch that drives a lifecycle node with the CLI (`ros2 lifecycle set <node> <transition>`, often behind
# `bash -c sleep N; ...`): the command exits 1 when the transition was not made, after printing why
# (ros2lifecycle/verb/set.py:52-89@humble: "Node not found" when no such node was discovered yet, "Unknown
# transition requested, available ones are:", "Transitioning failed"). Its process's death is that transition's
# failure, not a node of the robot that was lost.
_LIFECYCLE_SET = re.compile(r"cmd '[^']*\bros2 lifecycle set (?:--\S+ )*(?P<node>[/\w]+) (?P<transition>\w+)")
_LIFECYCLE_SAID = ("Node not found", "Unknown transition requested", "Transitioning failed",
                   "Exception while calling service of node")
_NO_MANAGER = ("Controller manager not available", "Could not contact service")
# What "transition N" means to a person. rcl_lifecycle's "Failed to finish transition 3" names a
# lifecycle_msgs/msg/Transition id (1 configure ... 5 shutdown); rclcpp_lifecycle's "Caught exception in callback for
# transition 13" names the transition *state* the callback ran in, a lifecycle_msgs/msg/State id
# (TRANSITION_STATE_CONFIGURING = 10 ... ERRORPROCESSING = 15): a real Nav2 console prints "... transition 13" and
# then "Failed to finish transition 3" (activate), and ros2_control's "... transition 14" then "Callback returned
# ERROR during the transition: deactivate".
TRANSITIONS = {1: "configure", 2: "cleanup", 3: "activate", 4: "deactivate", 5: "shutdown", 10: "configure",
               11: "cleanup", 12: "shutdown", 13: "activate", 14: "deactivate", 15: "error processing"}


# nav2_util's LifecycleServiceClient blocks the lifecycle manager that creates it until the managed node's
# get_state service exists, logging this INFO line after each failed 2 s wait (nav2_util/src/
# lifecycle_service_client.cpp:40-44 and 56-60@humble, @jazzy; include/nav2_util/lifecycle_service_client.hpp:50-53
# @main), called from lifecycle_manager.cpp:165-168@humble (createLifecycleServiceClients) before any node is
# configured. One wait is a node that starts a little later; repeats that are the manager's last words mean the
# node never appeared under that name (not started, died, or in another namespace than the manager's node_names).
_LIFECYCLE_WAIT = re.compile(r"Waiting for service (?P<service>(?:[/\w]*/)?(?P<node>\w+)/get_state)\.\.\.")
UNSERVED_WAITS = 2

# rcl/src/rcl/arguments.c (rcl_parse_arguments): "Couldn't parse params file: '--params-file …'. Error: …", and the
# same words for a remap rule, a log level, a parameter override rule, an external log config file, an enclave
_RCL_REFUSED = re.compile(r"Couldn't parse (?P<what>params file|remap rule|log level|parameter override rule|"
                          r"external log config file|enclave|[a-z ]+?): '(?P<arg>[^']*)'")


def rcl_refused(msg: str) -> tuple[str, str] | None:
    """(what rcl could not parse, the argument as given) of rcl's "Couldn't parse …: '…'" error; None otherwise."""
    m = _RCL_REFUSED.search(msg)
    return (m["what"], m["arg"]) if m is not None else None


# rcl_lifecycle's refusal of a transition its node's state has not ("Unable to start transition %u from current state
# %s: %s", rcl_lifecycle.c:355@jazzy, the line itself cites it): configure (transition 1) asked of a node already
# inactive or active. The node is up; something brought it up before this request (a second lifecycle manager that
# manages it, or the same launch started twice)
_AGAIN = re.compile(r"Unable to start transition 1 from current state (?P<state>inactive|active)\b")
AGAIN = "my lifecycle manager asked"

LAUNCH_NAV = "my launch stopped with an error before it had started my navigation nodes"
LAUNCH_ANY = "my launch stopped with an error before it had started any of my nodes"


@dataclass(frozen=True)
class BringupFinding:
    """One node that never came up (fields: see the module's docstring)."""

    kind: str
    node: str
    t: int
    line: LogLine
    entry: StackEntry | None
    detail: str = ""
    cause: str = BRINGUP
    unlaunched: tuple[str, ...] = ()  # for a wait: the processes launch started, none of them the node waited for

    def describe(self) -> str:
        """One sentence for a person: what failed, for which node."""
        who = self.node or "a node"
        if self.kind == "params_file":
            refused = rcl_refused(self.line.msg)
            if refused is not None and refused[0] != "params file":
                return (f"{who} could not parse its command-line arguments (the {refused[0]} '{refused[1]}'), so it "
                        "never started")
            return f"{who} could not parse its parameters file, so it never started"
        if self.kind == "launch_failed":
            why = f" ({self.detail})" if self.detail else ""
            return f"{LAUNCH_NAV}{why}"
        if self.kind == "process_died":
            code = f" ({self.detail})" if self.detail else ""
            return f"the process of {who} died{code}"
        if self.kind == "no_program":
            return f"the process of {who} never started: {self.detail}"
        if self.kind == "lifecycle_transition":
            why = f": {self.detail}" if self.detail else ""
            return f"{who} stopped in a lifecycle transition and never became active{why}"
        if self.kind == "lifecycle_again":
            return (f"{AGAIN} {who} to configure again while it was already {self.detail or 'configured'}, a "
                    "transition that state does not have: something had brought it up before (a second lifecycle "
                    "manager that manages it, or the same launch started twice)")
        if self.kind == "lifecycle_wait":
            said = (f"my lifecycle manager kept waiting for {who}'s lifecycle service ({self.detail}) and never "
                    f"found it, so it configured none of my nodes")
            if self.unlaunched:
                shown = ", ".join(self.unlaunched[:8]) + (", …" if len(self.unlaunched) > 8 else "")
                said += f"; my launch never started a process of {who} (it started {shown})"
            return said
        return f"{who} failed to come up"


def _kind(line: LogLine, entry: StackEntry) -> str:
    if entry.layer == "rcl" and ("params file" in entry.text or "parse" in entry.text):
        return "params_file"
    if entry.layer == "launch":
        if entry.text.startswith("Failed to make transition"):
            return "lifecycle_transition"  # launch_ros' LifecycleNode action: the node refused the transition
        return "launch_failed" if entry.text.startswith("Caught exception in launch") else "process_died"
    if entry.layer == "lifecycle" or "lifecycle" in entry.package or "bring up" in entry.text \
            or "Aborting bringup" in entry.text or "change state" in entry.text:
        return "lifecycle_transition"
    return "node_failed"


def _node(line: LogLine, kind: str) -> str:
    named = _NAMED_NODE.search(line.msg)
    if kind == "lifecycle_transition" and named and "lifecycle_manager" in line.name:
        return named["node"].strip("/").rstrip(".")
    inside = _PROCESS_IN_MSG.search(line.msg)
    if inside:
        return inside["node"]
    name = line.name.strip("/").split("/")[-1]
    if kind == "process_died" or name.endswith(tuple(f"-{i}" for i in range(10))):
        m = _PROCESS.match(name)
        if m and m["node"] not in ("launch", "rcl"):
            return m["node"]
    if kind == "process_died":
        # launch's line carries the command it ran ("cmd '.../bt_navigator --ros-args -r __node:=bt_navigator'"):
        # the node it names, else the executable, when the console prefix that named the process was lost
        m = _CMD_NODE.search(line.msg) or _CMD_EXE.search(line.msg)
        if m:
            return m["node"]
    return "" if name in ("", "launch", "rcl") else name


def configure_failed(entry: StackEntry) -> bool:
    """A Nav2 server's FATAL that fails its own configure transition (see _CONFIGURE_FAILS)."""
    return entry.level == "FATAL" and entry.source.split(":", 1)[0] in _CONFIGURE_FAILS \
        and entry.text.startswith("Failed to create")


def _configure_detail(line: LogLine) -> str:
    m = _EXCEPTION.search(line.msg)
    error = " ".join(m["error"].split())[:200] if m else ""
    return f"transition configure: {error}" if error else "transition configure"


def _lifecycle_cli(line: LogLine, entry: StackEntry, asked: tuple[str, str], before: list[LogLine]) -> BringupFinding:
    """The transition a `ros2 lifecycle set` command of the launch could not make, with what the command printed."""
    node, transition = asked
    said = next((s for ln in reversed(before) for s in _LIFECYCLE_SAID if ln.msg.strip().startswith(s)), "")
    detail = f"transition {transition}" + (f": the command said '{said}'" if said else "")
    return BringupFinding("lifecycle_transition", node.strip("/").split("/")[-1], line.t, line, entry, detail)


def lifecycle_cli(line: LogLine) -> tuple[str, str] | None:
    """(node, transition) when `line` is launch's death line of a `ros2 lifecycle set` command, else None."""
    asked = _LIFECYCLE_SET.search(line.msg) if DIED in line.msg else None
    return (asked["node"], asked["transition"]) if asked is not None else None


def _detail(line: LogLine, kind: str, following: list[LogLine]) -> str:
    if kind == "process_died":
        m = _EXIT.search(line.msg)
        return f"exit code {m['code']}" if m else ""
    if kind == "params_file":
        return line.msg.split("Error: ", 1)[1].strip() if "Error: " in line.msg else ""
    if kind == "launch_failed":
        # the exception's text follows the fixed words; a YAML error spans lines: its first line says what failed
        text = line.msg.split("traceback):", 1)[-1].strip()
        return " ".join(text.split())[:200]
    if kind == "lifecycle_transition":
        original = _ORIGINAL.search(line.msg) or next(
            (m for m in (_ORIGINAL.search(f.msg) for f in following if f.name == line.name) if m), None)
        transition = _TRANSITION.search(line.msg)
        parts = []
        if transition and int(transition["id"]) in TRANSITIONS:
            parts.append(f"transition {TRANSITIONS[int(transition['id'])]}")
        if original:
            parts.append(original["error"].strip())
        return ": ".join(parts)
    return ""


def _process_died(cat: StackCatalogue) -> StackEntry | None:
    """launch's process-died entry, for a line that keeps its fixed words but shortens its fields (a note's
    "process has died [exit code -6]" for "process has died [pid …, exit code …, cmd '…']."; launch's
    execute_local.py:596@rolling, execute_process.py:749@foxy)."""
    return next((e for e in cat.entries if e.layer == "launch" and e.text.startswith(DIED)), None)


def client_gave_up(died: LogLine, before: list[LogLine]) -> bool:
    """A spawner's process that ended after its own line said no controller manager answered (see _SPAWNERS)."""
    exe = _CMD_EXE.search(died.msg)
    if exe is None or exe["node"] not in _SPAWNERS:
        return False
    return any(ln.name.strip("/").split("/")[-1].startswith("spawner") and ln.msg.startswith(_NO_MANAGER)
               for ln in before)


def _ros2_run(died: LogLine, before: list[LogLine]) -> tuple[re.Match[str], LogLine] | None:
    """The `ros2 run` command of launch's death line `died`, and ros2run's own words before it (under the process's
    name, or none where a console lost it) that it found no such program or package."""
    cmd = _ROS2_RUN.search(died.msg)
    if cmd is None:
        return None
    words = ("No executable found", f"Package '{cmd['pkg']}' not found")
    said = next((ln for ln in reversed(before) if ln.t <= died.t and ln.name in ("", died.name)
                 and ln.msg.strip() in words), None)
    return (cmd, said) if said is not None else None


def ros2_run_said(died: LogLine, before: list[LogLine]) -> LogLine | None:
    """ros2run's line that it found no program or package for the command `died` reports dead (see _ros2_run)."""
    found = _ros2_run(died, before)
    return found[1] if found is not None else None


def ros2_run_failed(died: LogLine, before: list[LogLine]) -> str | None:
    """What ros2run did not find for the command of `died` (see _ros2_run), said for a person; None if nothing."""
    found = _ros2_run(died, before)
    if found is None:
        return None
    cmd, said = found
    pkg, exe = cmd["pkg"], cmd["exe"]
    if said.msg.strip() == "No executable found":
        return f"'ros2 run {pkg} {exe}' found no program named '{exe}' in the package {pkg}"
    return f"'ros2 run {pkg} {exe}' found no package named {pkg}"


def _loader_finding(line: LogLine) -> BringupFinding | None:
    loader = loader_said(line)
    if loader is None:
        return None
    exe, what, why = loader
    node = _node(line, "process_died")
    if not node or node == line.name:
        node = exe
    lacked = needed(why, with_symbol=False) if what == "symbol lookup error" else None  # the line has the symbol
    said = f"{lacked[0]} needs {lacked[1]}, which no library loaded with it defines" if lacked else why[:200]
    return BringupFinding("process_died", node, line.t, line, None, f"{what}: {said}")


def unserved_waits(ordered: list[LogLine]) -> list[BringupFinding]:
    """A lifecycle manager's waits for a node's get_state service (see _LIFECYCLE_WAIT), repeated and never followed
    by another line of that manager: one finding per service, at its last wait."""
    waits: dict[tuple[str, str], list[LogLine]] = {}
    for line in ordered:
        m = _LIFECYCLE_WAIT.fullmatch(line.msg.strip())
        if m is not None:
            waits.setdefault((line.name, m["service"]), []).append(line)
    out = []
    # launch's "process started with pid [N]", under the process's name ("map_server-2")
    started = [PROCESS_SUFFIX.sub("", ln.name) for ln in ordered if ln.msg.startswith("process started with pid")]
    for (who, service), said in waits.items():
        last = said[-1]
        moved_on = any(ln.t > last.t and ln.name == who and not ln.msg.strip().endswith(f"{service}...")
                       for ln in ordered)
        if len(said) < UNSERVED_WAITS or moved_on:
            continue
        span = (last.t - said[0].t) / 1e9
        over = f" over {span:.0f} s" if span >= 1 else ""
        node = service.rsplit("/", 2)[-2]
        unlaunched = tuple(started) if started and node not in started else ()
        out.append(BringupFinding("lifecycle_wait", node, last.t, last, None,
                                  f"'{service}', {len(said)} times{over}", unlaunched=unlaunched))
    return out


# CPython's asyncio (base_events.py default_exception_handler, "Task exception was never retrieved") prints the
# task: "future: <Task finished name='Task-2' coro=<LaunchService._process_one_event() done, defined at …>
# exception=SubstitutionFailure("executable '…' not found on the libexec directory '…'")>"
_LAUNCH_TASK = re.compile(r"^(future: )?<Task finished .*coro=<LaunchService\.\w+\(\) .*\bexception=\w+\("
                          r"(?P<q>['\"])(?P<text>.+)(?P=q)\)>$")


def bringup_findings(lines: Iterable[LogLine], before: int | None = None) -> list[BringupFinding]:
    """The bring-up problems in `lines` (see the module's docstring), oldest first, one per (kind, node)."""
    cat = stack_catalogue()
    ordered = sorted((ln for ln in lines if before is None or ln.t <= before), key=lambda ln: ln.t)
    out: list[BringupFinding] = unserved_waits(ordered)
    seen: set[tuple[str, str]] = set()
    for i, line in enumerate(ordered):
        # a console line "future: <Task …>" reads as logger "future"
        unretrieved = _LAUNCH_TASK.match(line.msg.strip()) if line.name in ("", "future") else None
        if unretrieved is not None and ("launch_failed", "") not in seen:
            # launch's event loop died on the exception before it could log "Caught exception in launch": asyncio
            # printed it instead ("Task exception was never retrieved", then the task and its exception)
            seen.add(("launch_failed", ""))
            detail = unretrieved["text"].replace('\\"', '"').strip()
            out.append(BringupFinding("launch_failed", "", line.t, line, None, detail))
            continue
        again = _AGAIN.search(line.msg) if line.level >= ERROR else None
        if again is not None:
            node = _node(line, "lifecycle_transition")
            if ("lifecycle_again", node) not in seen:
                seen.add(("lifecycle_again", node))
                out.append(BringupFinding("lifecycle_again", node, line.t, line, None, again["state"]))
            continue
        loader = _loader_finding(line)
        if loader is not None:
            if ("process_died", loader.node) not in seen:
                seen.add(("process_died", loader.node))
                out.append(loader)
            continue
        entry = cat.match(line.msg) or (_process_died(cat) if DIED in line.msg else None)
        if entry is not None and entry.cause != BRINGUP and "Failed to create" in line.msg:
            # another entry may match first (the generic "Failed to create (a )?(plugin|…)" rule)
            entry = next((e for e in cat.matches(line.msg) if configure_failed(e)), entry)
        if entry is not None and "Couldn't parse" in line.msg:
            # rclpy's RCLError quotes rcl's own "Couldn't parse params file" after its "failed to initialize rcl"
            entry = next((e for e in cat.matches(line.msg) if e.layer == "rcl" and e.text.startswith("Couldn't parse")),
                         entry)
        configure = entry is not None and configure_failed(entry)
        if entry is None or (entry.cause != BRINGUP and not configure) \
                or (line.level < ERROR and entry.level == "WARN"):
            continue
        if entry.text.startswith("Original error"):
            continue  # the second half of "Caught exception in callback ...": read as that line's detail
        kind = "lifecycle_transition" if configure else _kind(line, entry)
        if kind == "process_died" and client_gave_up(line, ordered[:i]):
            continue
        missing = ros2_run_failed(line, ordered[max(0, i - 8):i]) if kind == "process_died" else None
        missing = missing or exec_failed(line, ordered[i + 1:i + 3])
        if missing is not None:
            node = PROCESS_SUFFIX.sub("", line.name) or _node(line, kind)
            if ("no_program", node) not in seen:
                seen.add(("no_program", node))
                out.append(BringupFinding("no_program", node, line.t, line, entry, missing))
            continue
        asked = lifecycle_cli(line) if kind == "process_died" else None
        if asked is not None:
            finding = _lifecycle_cli(line, entry, asked, ordered[max(0, i - 4):i])
            if ("lifecycle_transition", finding.node) not in seen:
                seen.add(("lifecycle_transition", finding.node))
                out.append(finding)
            continue
        if kind == "params_file" and "Couldn't parse" not in line.msg:
            # rcl's "Failed to parse global arguments" comes first; the line naming the file and its error follows
            line = next((f for f in ordered[i:i + 5] if "Couldn't parse" in f.msg), line)
            entry = next((e for e in cat.matches(line.msg) if e.text.startswith("Couldn't parse")), entry)
        node = _node(line, kind)
        if (kind, node) in seen:
            continue
        seen.add((kind, node))
        detail = _configure_detail(line) if configure else _detail(line, kind, ordered[i + 1:i + 4])
        out.append(BringupFinding(kind, node, line.t, line, entry, detail))
    return sorted(out, key=lambda f: f.t)
