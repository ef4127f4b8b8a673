"""Bring-up and system causes that any log explainer of the arm cites before its own module's lines.

Bring-up comes from the stack's `bringup_findings` (explainers/stack: a params file not parsed, a lifecycle
transition that failed, a process that died), each mapped onto this project's cause ids. A device the operating
system would not open is read from the C library's strerror(EACCES) text, "Permission denied", on a line that
names a device file (/dev/...). Network causes (DDS discovery, a firewall blocking a reverse connection) leave no
line of their own in the logs, so none is claimed from them.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence

from hexar.claims import read_claims
from hexar.events.bringup import ABORT
from hexar.events.records import ERROR, TRACEBACK, WARN, LogLine
from hexar.explainers.logcause import Diagnosis, Reading, said
from hexar.explainers.stack.actions import action_finding, action_words
from hexar.explainers.stack.bringup import PROCESS_SUFFIX
from hexar.explainers.stack.middleware import middleware_line, middleware_words
from hexar.explainers.stack.qos import qos_line, qos_words
from hexar.explainers.stack.refused import refused_words
from hexar.explainers.stack.signals import ended_by
from hexar.explainers.stack.thrown import PyException, exception_quoted, python_exception, thrown_words

KIND_CAUSE = {"params_file": "bringup.configuration_error", "launch_failed": "bringup.configuration_error",
              "lifecycle_transition": "bringup.lifecycle_transition_failed", "process_died": "bringup.process_died",
              "node_failed": "bringup.lifecycle_transition_failed", "no_program": "bringup.configuration_error"}
PERMISSION = "system.device_permission"
NETWORK = "system.network"
_DENIED = "Permission denied"  # strerror(EACCES)


# launch_ros/actions/lifecycle_node.py:123@rolling: "Failed to make transition '{}' for LifecycleNode '{}'"
_LAUNCH_TRANSITION = re.compile(r"Failed to make transition 'TRANSITION_(?P<transition>[A-Z_]+)' for LifecycleNode "
                                r"'(?P<node>[^']+)'")
# rcl_lifecycle's rcl_lifecycle_get_transition_by_label and _by_id (rcl_lifecycle.c:321 and 342@rolling):
# "No transition matching %s found for current state %s"
_NO_TRANSITION = re.compile(r"No transition matching (?P<label>\S+) found for current state (?P<state>\S+)")
_ONE_SHOT = re.compile(r"exit code [1-9]\d*, cmd '\S*(controller_manager/spawner|/unspawner) ")


# ABORT (libstdc++'s __verbose_terminate_handler, events/bringup.py) with the exception's type and what(): the
# handler prints them to stderr and calls abort(), so the process that threw it ends there
_UNCAUGHT = re.compile(re.escape(ABORT) + r" '(?P<type>[^']+)'(?:\s*what\(\):\s*(?P<what>[^\n]*))?")


def uncaught(lines: Sequence[LogLine], before: int | None = None) -> LogLine | None:
    """The first line that carries an uncaught C++ exception, its process's end, unless the line is an error of its
    own before it (a driver's "Open [/dev/…]: Bad file descriptor" and then the abort): that error is the first to
    tell, the death its consequence; or the record of a Python exception its process died of (explainers/stack/
    thrown.py)."""
    return next((ln for ln in sorted(lines, key=lambda ln: ln.t) if (before is None or ln.t <= before)
                 and ((((m := _UNCAUGHT.search(ln.msg)) is not None
                        and (ln.level < ERROR or not ln.msg[:m.start()].strip())))
                      or python_exception(ln) is not None)), None)


# CPython's FileNotFoundError text (strerror(ENOENT) with the path it was asked to open): a file the program was
# pointed at, by an argument or a parameter, is not there
_NO_FILE = re.compile(r"\[Errno 2\] No such file or directory: '(?P<path>[^']+)'")


def _missing_file(exc: PyException) -> str | None:
    """The path of a Python process's FileNotFoundError, or None for any other exception and for a device file
    (/dev/ttyACM0 not there is a device unplugged or named wrong, which a file's path does not tell apart)."""
    m = _NO_FILE.search(exc.text) if exc.name == "FileNotFoundError" else None
    return m["path"] if m is not None and not m["path"].startswith("/dev/") else None


def _configuration(line: LogLine, exc: PyException) -> bool:
    """A Python node's uncaught exception whose text the stack catalogue reads as a configuration error (rclpy's
    InvalidParameterTypeException: a parameter given a value of another type than the node declares; a setting rcl
    refused), or a file it was given that is not there (its settings never reached it: ros2_control's spawner with
    a --param-file that does not exist). Read as printed, line breaks kept: a message of the catalogue may hold one
    (rmw_fastrtps' "…security libraries\nPlease compile…"). A C++ one is left to the module catalogues, which read
    its what() in their words."""
    from hexar.explainers.stack.catalogue import stack_catalogue

    if _missing_file(exc) is not None:
        return True
    printed = line.msg.partition(f"\n{TRACEBACK}")[0]
    entry = stack_catalogue().match(printed) if exc.text else None
    return entry is not None and entry.cause == "stack.configuration_error"


# rcl's rosout publisher of a node name it already has (logging_rosout.c:229@rolling; "for provided node name" before)
_SAME_NAME = re.compile(r"Publisher already registered for (?:provided node name|node name: '(?P<name>[^']*)')")
# rclpy's InvalidParameterTypeException (exceptions.py): "Trying to set parameter '…' to '…' of type '…', expecting
# type '…'"; rclcpp's InvalidParameterTypeException: "parameter '…' has invalid type: …"
_PARAMETER_TYPE = re.compile(r"Trying to set parameter|has invalid type|expecting type")


def _uncaught_words(line: LogLine) -> str:
    """"of an uncaught C++ exception (std::invalid_argument), so the software it ran was gone: “[node] invalid argument
    passed”": the what() quoted as the log's words (hexar/claims.py reads none of them as the answer's claim)."""
    if (exc := python_exception(line)) is not None:
        return (f"of an uncaught Python exception ({exc.name}), so the software it ran was gone: "
                f"{exception_quoted(line, exc, 160)}")
    m = _UNCAUGHT.search(line.msg)
    kind = f" ({m['type']})" if m is not None else ""
    what = (m["what"] or "").strip() if m is not None else ""
    quoted = f": “[{line.name or 'unnamed node'}] {what[:160]}”" if what else ""
    return f"of an uncaught C++ exception{kind}, so the software it ran was gone{quoted}"


# rclcpp/src/rclcpp/time.cpp (operator==, <, -, +): "can't compare|subtract|add times with different time sources",
# since Iron with the two clock types ("[1 != 2]": RCL_ROS_TIME against RCL_SYSTEM_TIME). A node's clock is ROS time
# whether or not use_sim_time is set, so the other time came from code that built it on the system or steady clock.
_MIXED_CLOCKS = re.compile(r"can't (compare|subtract|add) times with different time sources")


def mixed_clocks(line: LogLine) -> str | None:
    """What rclcpp's exception for times of two clocks leaves open, in words no cause pattern reads as a claim; None
    for any other line. The process died of it, but the exception, not the death, says what went wrong."""
    if _MIXED_CLOCKS.search(line.msg) is None:
        return None
    return ("two times from different clocks met, which rclcpp does not allow (the process that threw it ended "
            "there, on that uncaught exception): ROS time (a node's clock) against a time built on the system or "
            "steady clock. Some code mixes the two, often only where simulated time is in use "
            "(use_sim_time set, or Gazebo's /clock bridged or not), so check which node's update threw it and how "
            "its times are made")


def one_shot_failed(msg: str) -> bool:
    """launch's death line of a controller spawner that exited with an error: the spawner is a one-shot command that
    returns 1 when its controller could not be loaded, configured or activated (ros2_control
    controller_manager/controller_manager/spawner.py:435@jazzy and after), so its death is that failure's
    symptom, never a process of the running robot that was lost."""
    return _ONE_SHOT.search(msg) is not None


def stack_cause(lines: Sequence[LogLine]) -> Reading | None:
    """The earliest bring-up or device-permission line, as a reading with its cause; None when there is none."""
    from hexar.explainers.stack import bringup_findings

    found: list[Reading] = []
    middleware = middleware_line(lines)
    if middleware is not None:
        # the DDS layer that kept a node from the others (system), or a middleware setting that never applied; first,
        # so that its reading of a line wins over a generic one of the same line (Fast DDS's "Error parsing '…'")
        line, cause = middleware
        found.append(Reading(line, None, cause, "system" if cause == NETWORK else "stack", "middleware"))
    findings = [f for f in bringup_findings(lines) if not _unexplained_request(f.line, lines)]
    if findings:
        f = findings[0]
        # a command ros2run could not start keeps what it did not find (the program, or the package) as its note
        note = f.detail if f.kind == "no_program" else ""
        found.append(Reading(f.line, None, KIND_CAUSE.get(f.kind, "bringup.configuration_error"), "stack", note))
    missing = next((ln for ln in lines if ln.level >= WARN and _params_missing(ln)), None)
    if missing is not None:
        found.append(Reading(missing, None, "bringup.configuration_error", "stack"))
    thrown = uncaught(lines)
    if thrown is not None and (exc := python_exception(thrown)) is not None:
        # a Python process that died of an exception (after the readings above: rcl's own error raised as RCLError
        # is theirs); one whose text is a parameter of the wrong type (rclpy's InvalidParameterTypeException) is
        # that configuration error, told with the process's end
        cause = "bringup.configuration_error" if _configuration(thrown, exc) else "bringup.process_died"
        found.append(Reading(thrown, None, cause, "stack", "thrown"))
    # an INFO line that mentions it reports nothing wrong (explainers/stated_causes.py reads the rest of such lines)
    denied = next((ln for ln in lines if ln.level >= WARN and _DENIED in ln.msg and "/dev/" in ln.msg), None)
    if denied is not None:
        found.append(Reading(denied, None, PERMISSION, "system"))
    if not found:
        return next((r for r in _told_last(lines) if r is not None), None)
    return min(found, key=lambda r: r.line.t)


def _told_last(lines: Sequence[LogLine]) -> Iterator[Reading | None]:
    """Readings told only when no other is, in this order, each found only if the ones before were not: each is a
    warning whose nodes go on running."""
    # a QoS mismatch may be any pair's (a viewer's subscription)
    qos = qos_line(lines)
    yield Reading(qos, None, "bringup.configuration_error", "stack", "qos") if qos is not None else None
    # two nodes of one name: rcl only warns and both run
    same = next((ln for ln in lines if _SAME_NAME.search(ln.msg)), None)
    yield Reading(same, None, "bringup.configuration_error", "stack") if same is not None else None
    # rcl_lifecycle refused a transition the node's state does not have, and the node stays where it was
    asked = next((ln for ln in lines if ln.level >= WARN and _NO_TRANSITION.search(ln.msg)), None)
    yield Reading(asked, None, "bringup.lifecycle_transition_failed", "stack") if asked is not None else None
    # two servers of one action name: both may execute a goal, and the client ignores the second's answers
    action = action_finding(lines)
    yield Reading(action.line, None, "bringup.configuration_error", "stack", "action") \
        if action is not None and action.kind == "two_servers" else None


def launch_transition(line: LogLine) -> str:
    """The node of launch_ros' "Failed to make transition '…' for LifecycleNode '/…'" (lifecycle_node.py), else ""."""
    asked = _LAUNCH_TRANSITION.search(line.msg)
    return asked["node"].strip("/") if asked is not None else ""


def _unexplained_request(line: LogLine, lines: Sequence[LogLine]) -> bool:
    """launch_ros' "Failed to make transition" with no reason before it: the transition failed, but the lines do not
    show its cause."""
    return bool(launch_transition(line)) and transition_reason(line, lines) is None


def transition_reason(line: LogLine, lines: Sequence[LogLine]) -> LogLine | None:
    """For launch_ros' "Failed to make transition", the first earlier line that says why: the lifecycle layer's at
    WARN or above (rcl_lifecycle's "No transition matching … for current state …"), or the node's own error (its
    callback returned FAILURE or ERROR after saying why); None for any other line."""
    if (asked := _LAUNCH_TRANSITION.search(line.msg)) is None:
        return None
    from hexar.explainers.stack.catalogue import stack_catalogue

    catalogue = stack_catalogue()
    node = asked["node"].strip("/")
    return next((ln for ln in lines if ln.t <= line.t and ln.level >= WARN and ln is not line
                 and (((e := catalogue.match(ln.msg)) is not None and e.layer == "lifecycle")
                      # a namespaced node's logger is robot1.lidar_driver for /robot1/lidar_driver
                      or (ln.level >= ERROR and ln.name.replace(".", "/").strip("/") == node))), None)


def _params_missing(line: LogLine) -> bool:
    """launch_ros' warning that a node's parameter file does not exist (the node starts on its defaults)."""
    from hexar.explainers.stack.catalogue import stack_catalogue

    entry = stack_catalogue().match(line.msg)
    return entry is not None and entry.layer == "launch" and entry.cause == "stack.configuration_error"


def _launch_failed(line: LogLine) -> str | None:
    """The exception's text when `line` is launch's own "Caught exception in launch" (launch read its description and
    shut down before starting the nodes it had not started yet), else None."""
    from hexar.explainers.stack import bringup_findings

    found = bringup_findings([line])
    return found[0].detail if found and found[0].kind == "launch_failed" else None


def stack_words(cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]] | None:
    """(sentence, fix, details) for a bring-up or system cause; None for a module's own cause."""
    from hexar.explainers.stack.bringup import lifecycle_cli, rcl_refused
    from hexar.explainers.stack.loader import loader_words

    line = [f"The log said: '{said(d.decisive.line)}'"] if d.decisive is not None else []
    head = f"{what[:1].upper()}{what[1:]} failed because"
    if d.decisive is not None and d.decisive.note == "middleware":
        happened, fix = middleware_words(d.decisive.line)
        return f"{head} {happened}.", fix, line
    if d.decisive is not None and d.decisive.note == "action" and (
            told := action_finding([*(r.line for r in d.support), d.decisive.line])) is not None:
        words = action_words(told, head)
        if words is not None:
            return words[0], words[1], line
    if d.decisive is not None and d.decisive.note == "qos":
        happened, fix = qos_words(d.decisive.line)
        return f"{head} {happened}.", fix, line
    if cause == "bringup.process_died" and d.decisive is not None and (
            _UNCAUGHT.search(d.decisive.line.msg) or python_exception(d.decisive.line) is not None):
        return (f"{head} one of my processes died {_uncaught_words(d.decisive.line)}.",
                "Read what the exception says and the lines just before it: the call that threw it (a parameter, "
                "a plugin or an interface that does not fit) is what to fix.", line)
    if cause == "bringup.process_died" and d.decisive is not None and (signal := ended_by(d.decisive.line.msg)):
        name = PROCESS_SUFFIX.sub("", d.decisive.line.name or "")  # launch's process name: scan_filter-1
        who = f"the process of {name}" if name else "it"
        return (f"{head} one of my processes died: {who} {signal.happened} (signal {signal.number}, {signal.name}).",
                signal.fix, line)
    if cause == "bringup.process_died" and d.decisive is not None and (loader := loader_words(d.decisive.line)):
        return f"{head} one of my processes died as it started: {loader[0]}.", loader[1], line
    if cause == "bringup.process_died":
        return (f"{head} one of my processes died during bring-up or the run, so the software it runs was gone.",
                "Read that process's last lines before it died (a crash, an exception, a missing library).", line)
    if cause == "bringup.lifecycle_transition_failed" and d.decisive is not None:
        asked = _LAUNCH_TRANSITION.search(d.decisive.line.msg)
        if asked is not None:
            # launch_ros tells that the node refused a transition it asked for, never why: that is the node's
            transition, node = asked["transition"].lower(), asked["node"]
            return (f"{head} a node's lifecycle transition failed: launch asked {node} to {transition}, and that "
                    "transition failed, so the node never became active.",
                    f"Read {node}'s own lines just before: why its {transition} failed (a device it could not open, "
                    "a parameter it rejected), or a transition asked in the wrong state.", line)
    if cause == "bringup.lifecycle_transition_failed" and d.decisive is not None and (
            no := _NO_TRANSITION.search(d.decisive.line.msg)) is not None:
        return (f"{head} a node's lifecycle transition failed: it was asked for the transition '{no['label']}', which "
                f"its current state ({no['state']}) does not have, so it stayed {no['state']}.",
                "Ask for a transition by its own label from the state the node is in (configure from unconfigured, "
                "activate from inactive: 'active' is a state, not a transition); `ros2 lifecycle list <node>` shows "
                "the ones its state has.", line)
    cli = lifecycle_cli(d.decisive.line) if d.decisive is not None else None
    if cause == "bringup.lifecycle_transition_failed" and cli is not None:
        node, transition = cli
        return (f"{head} a node's lifecycle transition failed: my launch ran 'ros2 lifecycle set' to {transition} "
                f"{node}, and that command failed, so the node never became active.",
                "If the command said 'Node not found', it ran before the node existed (or under another name): start "
                "the transitions when the node is up (launch_ros' LifecycleNode with its event handlers instead of a "
                "fixed delay) and check the node's namespace. Otherwise read the node's own lines around the "
                "transition.", line)
    if cause == "bringup.lifecycle_transition_failed":
        return (f"{head} a node's lifecycle transition (configure or activate) failed, so it never became active.",
                "Read the node's error around the transition and bring it up in order (configure, then activate).",
                line)
    thrown = d.decisive.line if d.decisive is not None and d.decisive.note == "thrown" else None
    exc = python_exception(thrown) if thrown is not None else None
    if cause == "bringup.configuration_error" and thrown and exc and (path := _missing_file(exc)) is not None:
        return (f"{head} my settings never reached my node: a file one of my programs was given is not there "
                f"('{path}'), and its process ended there ({thrown_words(thrown)}).",
                "Give the program the file's right path (a relative path is read from the folder the launch was "
                "started in: use the installed file's full path, e.g. from get_package_share_directory), or install "
                "the file under that name.", line)
    if cause == "bringup.configuration_error" and thrown and exc and not _PARAMETER_TYPE.search(exc.text):
        setting, fix = refused_words(exc.text)
        return (f"{head} my settings never reached my node: {setting}, and its process ended there "
                f"({thrown_words(thrown)}).", fix, line)
    if cause == "bringup.configuration_error" and d.decisive is not None and d.decisive.note == "thrown":
        return (f"{head} a parameter never reached one of my nodes as it should: its value was not of the type the "
                f"node declares, and its process ended there ({thrown_words(d.decisive.line)}).",
                "Give the parameter a value of the type the node declares (in its params file, launch file or "
                "overrides: quote a string, write 1.0 for a double), or declare it with the type you set.", line)
    if cause == "bringup.configuration_error" and d.decisive is not None and d.decisive.catalogue == "stack":
        if (same := _SAME_NAME.search(d.decisive.line.msg)) is not None:
            name = f" ('{same['name']}')" if same["name"] else ""
            return (f"{head} two of my nodes were started with the same name{name}, so ROS 2 cannot tell them apart: "
                    "parameters given for that name reach both, and their services and logs are mixed up.",
                    "Give each node a name of its own (name= in the launch file's Node action, or --ros-args -r "
                    "__node:=...), or a namespace of its own.", line)
        if _params_missing(d.decisive.line):
            path = d.decisive.line.msg.split(": ", 1)[-1].strip()
            return (f"{head} my launch was given a parameter file that does not exist ({path}), so it started the "
                    "node without it and the parameters in it never reached the node.",
                    "Point the launch file at the parameter file the package installs (check its name and the "
                    "package's install rules), or install the file under that name.", line)
        if d.decisive.note.startswith("'"):  # bringup's no_program: what ros2run or launch could not run
            return (f"{head} a command my launch ran never started: {d.decisive.note}, so no node of it "
                    "ever ran.",
                    "Fix the command in the launch file: the program's and package's names, and the spaces between "
                    "the program and its arguments (launch_ros' Node(package=..., executable=...) builds it for you); "
                    "or build and source the package that installs the program.", line)
        launch = _launch_failed(d.decisive.line)
        if launch is not None:
            # an exception's words that read as another cause ("Invalid parameter") stay in the evidence only
            why = f": {launch}" if launch and not read_claims(launch).causes - {cause} else ""
            return (f"{head} my launch stopped with an error before it had started my nodes, so none of them ran{why}.",
                    "Fix the launch file or argument the quoted exception names (run the launch with --debug for the "
                    "traceback).", line)
        refused = rcl_refused(d.decisive.line.msg)
        if refused is not None and refused[0] != "params file":
            return (f"{head} a node's command-line arguments could not be parsed (the {refused[0]} '{refused[1]}'), so "
                    "rcl stopped it before the node existed.",
                    f"Fix that {refused[0]} where the launch file or command gives it (a ROS name has letters, digits "
                    "and underscores only; a remap rule is from:=to; log levels are debug, info, warn, error, fatal).",
                    line)
        if "Error opening YAML file" in d.decisive.line.msg:
            # rcl_yaml_param_parser's parser.c: fopen() of the file named by --params-file failed
            return (f"{head} a parameter never reached one of my nodes: its parameter file could not be opened "
                    f"({refused[1] if refused else 'the --params-file'}), so rcl stopped it before the node existed.",
                    "Check the path the launch file or command gives to --params-file (relative paths are read from "
                    "the working directory), and that the file is installed.", line)
        return (f"{head} a parameter never reached one of my nodes: its parameter file could not be parsed.",
                "Fix the parameter file's YAML (the quoted error names the line) and the node's namespace in it.",
                line)
    if cause == PERMISSION:
        return (f"{head} the operating system denied access to a device: permission denied on its device file.",
                "Give the user (or the container) access to the device: its group (dialout, video) or a udev rule.",
                line)
    return None
