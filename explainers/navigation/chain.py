"""The chain of evidence beyond Nav2's own words: lines of the ROS 2 stack under it, nodes that never came up, and
the decisive error to quote when no catalogued line explains a failure.

- A line the Nav2 catalogue does not know is read through the mined stack catalogue (hexar.explainers.stack):
  a transform or clock fault of tf2/tf_help/message filters supports navigation.transform_error like Nav2's own
  lines; other mined causes (a rule-given meaning, not a hand-checked one) count as weak evidence only.
- A node that never came up (bringup_findings: a params file rcl could not parse, a lifecycle transition that
  failed or threw, a process that died) before or during the goal explains every later failure: it is the first
  link of the chain, unless a catalogued configuration line says why the node failed (then it is that
  configuration error, and the answer says which node never became active).
- When nothing catalogued decides, the decisive ERROR/FATAL line (the last before the goal ended that is neither a
  symptom nor noise) is quoted with its node and time, never "the logs do not show why" while it is there; a line
  whose words read as another cause is told by node and time only (wording.quotable).
- Over-reading guards: a transform wait logged before a later "Managed nodes are active" ended at bring-up
  (`unresolved`); with no goal and no end, warnings of the background layers alone are quoted (`only_warned`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import replace

from hexar.events.bringup import ABORT
from hexar.events.records import ERROR, TRACEBACK, WARN, LogLine, clock
from hexar.explainers.base import Evidence
from hexar.explainers.navigation import states
from hexar.explainers.navigation.catalogue import Entry, catalogue
from hexar.explainers.navigation.detectors import INITIAL_POSE, UNEXPLAINED, Finding, Run, pose_set_after
from hexar.explainers.navigation.diagnose import NO_PROGRESS, TRANSFORM
from hexar.explainers.navigation.wording import SYMPTOMS, quotable
from hexar.explainers.stack import bringup_findings, stack_catalogue
from hexar.explainers.stack.bringup import LAUNCH_ANY, LAUNCH_NAV, PROCESS_SUFFIX, BringupFinding
from hexar.explainers.stack.catalogue import StackEntry
from hexar.explainers.stack.loader import loader_failure
from hexar.explainers.stack.middleware import dropped_messages, dropped_said, fastdds_meaning
from hexar.explainers.stack.middleware import text as dds_text

BRINGUP = "navigation.bringup_failure"
CONFIGURATION = "navigation.configuration_error"
# Stack-level cause ids of the mined catalogue -> the navigation explainer's words. Commands that never reach the
# base are never read from logs (only /cmd_vel against /odom shows them); bring-up has its own reading.
STACK_TO_NAV = {
    "stack.transform_error": "navigation.transform_error",
    "stack.off_costmap": "navigation.off_costmap",
    "stack.goal_unreachable": "navigation.goal_unreachable",
    "stack.start_in_obstacle": "navigation.start_in_obstacle",
    "stack.collision_ahead": "navigation.collision_ahead",
    "stack.docking_failure": "navigation.docking_failure",
    "stack.localisation": "navigation.poor_localisation",
    "stack.configuration_error": CONFIGURATION,
    "stack.controller_failure": "navigation.controller_failure",
}
# Mined causes decided by the source's own words for a fault (transforms), not by a keyword rule: strong.
STRONG_STACK = frozenset({"stack.transform_error"})
# Lines that say which configuration was wrong, as opposed to the lifecycle manager's "Failed to change state for
# node", a process that died, or a server that is not there / not active (what a node that never came up produces).
_GENERIC_BRINGUP_IDS = frozenset({"lm.bringup_failed", "launch.process_died", "bt.action_unavailable",
                                  "bt.action_server_inactive", "beh.inactive"})
# Configuration lines that come from bring-up itself: a plugin library that cannot be loaded (loaded in
# on_configure), the lifecycle manager aborting the bring-up, a process that died.
_AT_BRINGUP_IDS = frozenset({"bt.plugin_load", "lm.bringup_failed", "launch.process_died"})
NEVER_CAME_UP = "never_came_up"
# Words that tie a launch to the navigation: Nav2's packages, servers and the plugins they load.
NAVIGATION = re.compile(r"nav2|navigation|bt_navigator|planner_server|controller_server|behavior_server|amcl|costmap|"
                         r"waypoint_follower|velocity_smoother|collision_monitor|docking_server|slam_toolbox|"
                         r"lifecycle_manager", re.IGNORECASE)
_END = ("Goal failed", "Goal was aborted", "Aborting handle", "Navigation failed")


def stack_entry(line: LogLine) -> StackEntry | None:
    return stack_catalogue().match(line.msg)


def _as_nav(entry: StackEntry) -> Entry | None:
    cause = STACK_TO_NAV.get(entry.cause or "")
    if cause is None or entry.role == "noise":
        return None
    strong = entry.cause in STRONG_STACK and entry.role == "cause"
    return Entry(id=f"stack:{entry.source}", role=entry.layer, meaning=entry.text, cause=cause, kind="cause",
                 strength="strong" if strong else "weak", distros=entry.distros, source=entry.source,
                 raw=entry.pattern)


def stack_notes(tagged: list[tuple[LogLine, Entry | None]], raw: Iterable[LogLine] = ()
                ) -> list[tuple[LogLine, Entry]]:
    """Kept lines the Nav2 catalogue gives no cause, read through the mined stack catalogue; and the warnings and
    errors the filter dropped (e.g. nav2_util's tf_help, whose role the filter does not keep) that it reads as a
    cause: a decisive line is never dropped unread."""
    kept = {id(line) for line, _ in tagged}
    dropped: list[tuple[LogLine, Entry | None]] = [(ln, None) for ln in raw if id(ln) not in kept and ln.level >= WARN]
    out = []
    for line, entry in sorted([*tagged, *dropped], key=lambda p: p[0].t):
        if entry is not None and (entry.cause is not None or entry.kind != "info"):
            continue
        mined = stack_entry(line)
        nav = _as_nav(mined) if mined is not None else None
        if nav is not None:
            out.append((line, nav))
    return out


def config_specific(notes: Iterable[tuple[LogLine, Entry]]) -> list[LogLine]:
    """Lines that name a configuration fault (not merely that a node did not come up)."""
    return [ln for ln, e in notes if e.cause == CONFIGURATION and e.id not in _GENERIC_BRINGUP_IDS]


def bringup(logs: Iterable[LogLine], until: int | None) -> Finding | None:
    """The first node that never came up (before `until`, the goal's end), with its decisive line: a bring-up
    failure, or a configuration error when it is a lifecycle transition that failed (notes: what failed), or the
    transform it waited for in vain when that made the transition fail (`_transform_waits`)."""
    logs_list = [ln for ln in logs if until is None or ln.t <= until]
    found = bringup_findings(logs_list)
    if not found:
        return None
    first = found[0]
    if any("Managed nodes are active" in ln.msg and ln.t > first.t for ln in logs_list):
        return None  # the stack was brought up again after the failure: the node did come up
    waited = _transform_waits(logs_list, first)
    if waited:
        return _transform_first(first, waited)
    # A lifecycle transition that failed is what the configuration_error words ("not brought up", "lifecycle
    # nodes not active") were made for; a params file rcl could not parse and a process that died are not.
    cause = CONFIGURATION if first.kind in ("lifecycle_transition", "node_failed") else BRINGUP
    finding = Finding(cause, [Evidence.of_log(cause, f.line) for f in found[:3]])
    finding.notes = [_told(f) for f in found[:3]]
    if first.kind == "launch_failed" and not any(NAVIGATION.search(f"{ln.name} {ln.msg}") for ln in logs_list):
        # Launch stopped before any node ran, and no line names the navigation: the launch may be any robot's
        # (an arm's driver, a lidar's), so the answer does not say it was the navigation's.
        finding.notes[0] = finding.notes[0].replace(LAUNCH_NAV, LAUNCH_ANY)
    last = last_words(logs_list, first) if first.kind == "process_died" else None
    if last is not None:
        who = "it" if CONTAINER.search(first.node) is None else last.name.strip("/").split("/")[-1]
        finding.notes[0] += f" right after {who} logged '{last.msg.strip().splitlines()[0]}'"
        finding.evidence.insert(0, Evidence.of_log(cause, last))
    # its last words an uncaught exception (libstdc++'s "terminate called after throwing …", or a Python traceback):
    # that is why it died, quoted above
    thrown = last is not None and (ABORT in last.msg or _python_death(last))
    if first.kind == "process_died" and not loader_failure(first.line) and not thrown and not [
            ln for ln in decisive_errors(logs_list, first.line.t) if ln.t < first.line.t]:
        # launch reports the exit code only: with no error before it, nothing says why the process died
        finding.notes[0] += "; nothing in my logs says why it died"
    elif first.kind == "process_died" and thrown:
        finding.notes[0] += ", an exception nothing caught, which ends a program"
    finding.facts[NEVER_CAME_UP] = 1.0
    return finding


_FRAMES = re.compile(r"transform from (?P<a>\S+) to (?P<b>\S+?)[ .,]")


def _python_death(line: LogLine) -> bool:
    """A Python traceback's record (explainers/stack/thrown.py), looked for only in a line that holds its header: the
    exception reader is not loaded for every navigation question."""
    if TRACEBACK not in line.msg:
        return False
    from hexar.explainers.stack.thrown import python_exception

    return python_exception(line) is not None


def _transform_waits(logs: list[LogLine], first: BringupFinding) -> list[LogLine]:
    """The strong transform lines the bring-up never got past (`unresolved`), at or before `first`, when `first` is
    a node that failed a transition: a costmap waits for its robot-to-global transform in on_activate, logging "Timed
    out waiting for transform from … to … to become available" every half second, and past its
    initial_transform_timeout logs "Failed to activate … because transform from … to … did not become available
    before timeout" and fails the transition (nav2_costmap_2d/src/costmap_2d_ros.cpp:285-306@jazzy); the lifecycle
    manager then aborts the bring-up. The transform is then the first link of the chain."""
    if first.kind not in ("lifecycle_transition", "node_failed"):
        return []
    cat = catalogue()
    # the costmap's own failed activation names the transform too, where a paste holds no wait before it
    return unresolved([ln for ln in logs if ln.t <= first.t and (_NO_TRANSFORM_IN_TIME.match(ln.msg.strip()) or (
        (e := cat.match(ln.msg)) is not None and e.cause == TRANSFORM and e.strength == "strong"))], logs)


# costmap_2d_ros.cpp:306@jazzy (on_activate): "Failed to activate %s because transform from %s to %s did not become
# available before timeout"
_NO_TRANSFORM_IN_TIME = re.compile(r"^Failed to activate \S+ because transform from \S+ to \S+ did not become "
                                   r"available before timeout")


def _transform_first(first: BringupFinding, waited: list[LogLine]) -> Finding:
    """The transform told as the cause, the aborted start as what it led to."""
    frames = _FRAMES.search(first.line.msg) or _FRAMES.search(waited[0].msg)
    what = f"the transform from {frames['a']} to {frames['b']}" if frames else "a transform"
    out = Finding(TRANSFORM, [Evidence.of_log(TRANSFORM, ln) for ln in (waited[0], first.line)])
    # in words that claim no second cause: the aborted start is the transform's consequence
    out.notes = [f"my navigation waited for {what} until its time ran out, so my navigation's start was aborted"]
    return out


# rclcpp_components' containers, which host nodes of other names (Nav2's bring-up composes its servers into one)
CONTAINER = re.compile(r"(?:^|_)container(?:_mt|_isolated)?$")


def last_words(logs: list[LogLine], died: BringupFinding) -> LogLine | None:
    """The node's own last line before launch reported its process dead (what it was doing when it died), or for a
    component container the last line of any node but launch, unless it is a line a catalogue reads (a symptom or a
    cause, told on its own) or one that reads as another cause."""
    if not died.node:
        return None
    cat = catalogue()
    composed = CONTAINER.search(died.node) is not None
    before = [ln for ln in logs if ln.t <= died.t and ln is not died.line
              and (PROCESS_SUFFIX.sub("", ln.name.strip("/").split("/")[-1]) == died.node
                   or (composed and ln.name not in ("", "launch")))
              and not ln.msg.startswith("process started with pid")]
    line = before[-1] if before else None
    if line is None or cat.match(line.msg) is not None or stack_entry(line) is not None or not quotable(line.msg):
        return None
    return line


def _told(found: BringupFinding) -> str:
    """What failed, with its detail (the original error, the exit code) unless the detail reads as another cause."""
    said = found.describe()
    return said if quotable(said, (BRINGUP, CONFIGURATION)) else replace(found, detail="").describe()


def unresolved(transform_lines: list[LogLine], logs: Iterable[LogLine]) -> list[LogLine]:
    """Transform lines the stack's bring-up did not resolve: a costmap's activation waits in a loop, logging
    "Timed out waiting for transform ... to become available" until the transform exists (costmap_2d_ros.cpp:281
    @humble, on_activate), so a transform fault logged before the lifecycle manager's later "Managed nodes are
    active" was a wait at start-up that ended, not the reason a goal failed after it."""
    active = [ln.t for ln in logs if ln.msg.startswith("Managed nodes are active")]
    return [ln for ln in transform_lines if not any(t > ln.t for t in active)]


def never_came_up(notes: Iterable[tuple[LogLine, Entry]], logs: Iterable[LogLine]) -> bool:
    """Whether a configuration error kept a node from coming up: Nav2 loads its plugins (BT node libraries,
    planners, controllers) in on_configure, and the lifecycle manager says when a bring-up was aborted; or a
    node's lifecycle transition / params file / process failed (the stack catalogue)."""
    if any(e.id in _AT_BRINGUP_IDS for _, e in notes):
        return True
    logs_list = list(logs)
    return bool(bringup_findings(logs_list)) and not any("Managed nodes are active" in ln.msg for ln in logs_list)


def with_bringup(finding: Finding) -> list[tuple[str, list[Evidence]]]:
    """The finding's cause ids with their evidence: a configuration error that kept a node from coming up is a
    bring-up failure too (navigation.bringup_failure implies navigation.configuration_error), said with it."""
    out = [(finding.cause, finding.evidence)]
    if finding.cause == CONFIGURATION and finding.facts.get(NEVER_CAME_UP):
        out.append((BRINGUP, [e.model_copy(update={"cause": BRINGUP}) for e in finding.evidence]))
    return out


def decisive_errors(logs: Iterable[LogLine], until: int | None) -> list[LogLine]:
    """ERROR/FATAL lines up to `until` that neither catalogue reads as a symptom, noise or a goal's end: the lines
    to quote when nothing catalogued explains a failure (oldest first)."""
    out = []
    cat = catalogue()
    for line in logs:
        if line.level < ERROR or (until is not None and line.t > until) or any(k in line.msg for k in _END):
            continue
        nav = cat.match(line.msg)
        if nav is not None and (nav.kind not in ("cause", "info") or states.state_of(nav, line.msg) is not None):
            continue  # a goal's begin/end, a recovery, a planner that found no path, a reported state: symptoms
        mined = stack_entry(line)
        if mined is not None and mined.role != "cause":
            continue
        out.append(line)
    return out


def quote_last_error(lines: list[LogLine], gave_up: bool = True) -> str:
    """'the last error before I gave up came from amcl: '...' (at 10:33:12.345 UTC)' (or '... my logs show ...'
    when the recording does not show the goal ending)."""
    line = lines[-1]
    who = line.speaker
    when = "before I gave up" if gave_up else "my logs show"
    if not quotable(line.msg):
        return f"the last error {when} came from {who} (at {clock(line.t)} UTC; the line itself is in my evidence)"
    return f"the last error {when} came from {who}: '{line.msg.strip()}' (at {clock(line.t)} UTC)"


def only_warned(found: Finding, run: Run) -> Finding | None:
    """For a recording with no goal and no end: an honest finding quoting the last warning, when the finding's cause
    rests on warnings only (None when an ERROR/FATAL line supports it, or it is already an honest one)."""
    if (found.cause in (UNEXPLAINED, NO_PROGRESS) and states.of_finding(found.facts) is None) \
            or found.facts.get(NEVER_CAME_UP):
        return None
    times = {e.t for e in found.evidence}
    notes = {id(n.line): n.entry for n in run.notes}
    lines = [ln for ln in run.lines + [n.line for n in run.notes] if ln.t in times]
    if not lines or any(ln.level >= ERROR or _decisive(notes.get(id(ln))) or _stuck_activation(ln, run.lines)
                        or _clock_gap(ln.msg) > CLOCK_GAP_S for ln in lines):
        return None
    last = max(lines, key=lambda ln: ln.t)
    honest = Finding(UNEXPLAINED, [Evidence.of_log(UNEXPLAINED, ln) for ln in sorted(set(lines), key=lambda x: x.t)])
    honest.notes.append(_warned(last))
    return honest


def _warned(line: LogLine) -> str:
    """'the last warning my logs show came from X: '...' (at ...)', quoted when the line reads as no cause."""
    said = f": '{line.msg.strip()}'" if quotable(line.msg) else ""
    return f"{WARNED} came from {line.speaker}{said} (at {clock(line.t)} UTC)"


WARNED = "the last warning my logs show"
# Whose warnings decide without a goal's end: the servers that answer a goal say why they fail it (the planner's
# "Planning will always fail", RPP's collision exception that the controller server answers by terminating the
# action, controller_server.cpp:422@humble), the lifecycle manager says what did not come up, the collision monitor
# says it held the robot. Costmaps, TF, AMCL and the velocity smoother warn in healthy runs too.
DECIDING_ROLES = frozenset({"bt_navigator", "planner_server", "controller_server", "docking_server",
                            "lifecycle_manager", "collision_monitor"})
# ... and a clock that jumped back (tf2_ros buffer, "Detected jump back in time"): a clock fault stated, not a wait.
DECIDING_IDS = frozenset({"tf.time_jump"})


def _decisive(entry: Entry | None) -> bool:
    return entry is not None and entry.cause is not None and (entry.role in DECIDING_ROLES
                                                              or entry.id in DECIDING_IDS)
# A transform's requested time and its data's time this far apart is a clock mismatch, not a lookup that came a
# little early (transform tolerances are tenths of a second): e.g. sim time 0.2 s against wall time 1.6e9 s.
CLOCK_GAP_S = 1.0
_TIMES = re.compile(r"Requested time (?P<a>\d+(?:\.\d+)?) but the (?:earliest|latest) data is at time "
                    r"(?P<b>\d+(?:\.\d+)?)")


def _clock_gap(msg: str) -> float:
    m = _TIMES.search(msg)
    return abs(float(m["a"]) - float(m["b"])) if m else 0.0


def _stuck_activation(line: LogLine, lines: list[LogLine]) -> bool:
    """A costmap waiting for its transform in on_activate (costmap_2d_ros.cpp:281@humble, logged each loop) with no
    later "Managed nodes are active": the stack never finished coming up, which decides by itself."""
    return line.msg.startswith("Timed out waiting for transform from") and "to become available" in line.msg \
        and not any(ln.t > line.t and ln.msg.startswith("Managed nodes are active") for ln in lines)


def with_last_error(found: Finding, raw: list[LogLine], run: Run) -> Finding:
    """An honest finding (no progress, no path, unexplained) with the decisive error line quoted, if there is one."""
    if found.cause not in (UNEXPLAINED, NO_PROGRESS):
        return found
    until = run.end.t if run.end is not None else None
    cat = catalogue()
    for line in run.lines:
        entry = cat.match(line.msg)
        said = SYMPTOMS.get(entry.id) if entry is not None else None
        if entry is not None and entry.id == INITIAL_POSE and pose_set_after(line, run.lines):
            said = None
        if said is not None and said not in found.notes:
            found.notes.append(said)
    errors = decisive_errors(raw, until)
    if errors:
        note = quote_last_error(errors, gave_up=run.outcome == "failed")
        dropped = dropped_messages(raw, errors[-1].t)
        if dropped:
            note += f"; before it, {dropped_said(dropped, raw)}"
            found.evidence.append(Evidence.of_log(found.cause, dropped[0]))
        found.notes.append(note)
        found.evidence.append(Evidence.of_log(found.cause, errors[-1]))
    return found


def _warns(line: LogLine) -> bool:
    """A line the mined catalogue knows as logged at WARN or above, whatever level it came with (a console pasted
    without levels is read as INFO): MPPI's "Inconsistent configuration in collision checking" is a warning."""
    entry = stack_entry(line)
    return entry is not None and entry.level in ("WARN", "ERROR", "FATAL")


def last_warning(lines: list[LogLine]) -> str:
    """' The last warning my logs show came from X: '...' (at ...).' for the last warning of `lines` (by its level or
    the catalogue's), quoted when it reads as no cause; "" when there is none."""
    warned = [ln for ln in lines if ln.level >= WARN or _warns(ln)]
    if not warned:
        return ""
    said = _warned(warned[-1])
    return f" {said[0].upper()}{said[1:]}."


# A Nav2 server's own words as it is taken down (nav2_util lifecycle_node.cpp: "Destroying bond (%s) to lifecycle
# manager.", "Running Nav2 LifecycleNode rcl preshutdown (%s)"; each server's on_deactivate, on_cleanup and
# destructor: "Deactivating", "Cleaning up", "Destroying", "Shutting down"), and launch's word that a process ended
# (execute_local.py, "process has finished cleanly [pid %d]"): lines that show no work done
TEARDOWN = re.compile(r"^(?:Destroying|Cleaning up|Deactivating|Shutting down|Running Nav2 LifecycleNode rcl "
                      r"preshutdown|process has finished cleanly)\b")


def ran_quietly(lines: list[LogLine], started: Iterable[LogLine] = ()) -> tuple[str, list[LogLine]] | None:
    """A stack that came up and ran with no goal's end recorded: which Nav2 nodes logged their work, when none of
    them logged a warning or an error (None otherwise, or when no Nav2 node logged at all). `started`: the lines
    before the window, where the middleware's own errors at start are looked for too."""
    cat = catalogue()
    own = [ln for ln in lines if ln.name and cat.role(ln.name) is not None]
    if not own or any(ln.level >= WARN or _warns(ln) for ln in own) or all(TEARDOWN.match(ln.msg) for ln in own):
        return None
    nodes = list(dict.fromkeys(cat.role(ln.name) or ln.name for ln in own))
    said = "logged their work and none of them logged" if len(nodes) > 1 else "logged its work and did not log"
    text = (f"As far as my recording shows, my navigation went normally: {', '.join(nodes[:4])} {said} a warning "
            "or an error. The recording shows no goal ending here, so it does not show whether I reached one.")
    dds = next((ln for ln in [*started, *lines] if ln.level >= WARN and fastdds_meaning(ln)), None)
    if dds is not None:
        # Fast DDS's own errors (no node name): what they mean, from its source (explainers/stack/middleware.py)
        text += f" My DDS middleware logged errors on the way (“{dds_text(dds)}” at {clock(dds.t)}): " \
                f"{fastdds_meaning(dds).replace('my DDS middleware (Fast DDS) ', 'it ', 1)}."
    elif any(ln.level >= WARN or _warns(ln) for ln in lines):  # a node that is not Nav2's, or not named, did warn
        text += last_warning(lines)
    return text, [own[0], own[-1]]
