""""Did controller_manager crash after that or keep running?", "did move_group still start up?", "did docking_server
come up?": a developer asks what became of one node. The log says what it can: the node's own lines (how many, from
when to when, its last), what launch said of its process (finished cleanly, died with an exit code), and whether
its last line came at the recording's end. A node with no line is said to have none, never to have run or not.
"""

from __future__ import annotations

import re

from hexar.agent.logs import line_evidence, quote
from hexar.agent.measures import worked_until
from hexar.events.log import EventLog
from hexar.events.records import LEVEL_NAMES, LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation
from hexar.explainers.shutdown import before_shutdown

_NODE = r"(?P<node>[a-z][a-z0-9]*(?:_[a-z0-9]+)+|amcl|rviz2?|gazebo|ekf)"
NODE_STATUS = re.compile(
    r"^(and |so |but |ok )?(did|has|had|was|is|were|does) (the )?" + _NODE + r"( node| process| server)? (ever |still |"
    r"otherwise |actually |even |then )?(start(ed|ing)?( up)?|come up|came up|crash(ed)?|die|died|keep running|kept "
    r"running|stay up|stay alive|run|running|go active|become active|make it to active|get configured|configure|"
    r"activate|shut down|exit|exited|finish|finished|fail to (configure|activate|start)|bring up|brought up|active|"
    r"activated|configured|loaded|up|ok|okay|working|healthy)\b")
# another node's words about this one's state: a controller manager activating it, a lifecycle manager configuring it
_ABOUT = re.compile(r"activat|configur|switch|bond|\bactive\b|inactive|load|spawn|start|fail|crash|died|abort|shut",
                    re.I)
# launch's words for a process's end ("[move_group-1]: process has died [pid 4, exit code -6, ...]")
_ENDED = re.compile(r"process has (died|finished cleanly)|process started with pid")
# a C++ program's own last words on stderr, often folded into the node's last logged line
_ABORTED = re.compile(r"terminate called after throwing|Segmentation fault|Aborted \(core dumped\)|"
                      r"^\s*what\(\):|Stack trace \(most recent call last\)")


ABOUT = 3  # other nodes' lines about the node, the latest


def node_status_kind(q: str) -> str | None:
    return "node_status" if NODE_STATUS.search(q) else None


def _lines_of(log: EventLog, node: str) -> tuple[list[LogLine], list[LogLine]]:
    """The node's own lines (its logger, or one under it), and launch's lines about its process."""
    own = [ln for ln in log.logs if ln.name.lower() == node or ln.name.lower().startswith(node + ".")
           or ln.name.lower().endswith("." + node)]
    if not own:  # "lifecycle_manager" asked, "lifecycle_manager_navigation" logged
        own = [ln for ln in log.logs if ln.name.lower().startswith(node + "_")]
    # launch names a process after its executable: base_driver's is often "base_driver_node-1"
    launched = [ln for ln in log.logs if re.fullmatch(re.escape(node) + r"(_node)?-\d+", ln.name.lower())]
    process = [ln for ln in launched if _ENDED.search(ln.msg)]
    if not own:  # a console's output of the process, under launch's name for it ("move_group-4")
        own = [ln for ln in launched if not _ENDED.search(ln.msg)]
    return own, process


def node_status(question: str, log: EventLog, task: Task) -> Explanation:
    """What the log shows became of the node a question names."""
    m = NODE_STATUS.search(" ".join(question.lower().split()))
    node = m.group("node") if m else ""
    own, process = _lines_of(log, node)
    named = re.compile(rf"(?<![\w/]){re.escape(node)}(?!\w)") if node else None
    # up to the task's end: a stack's shutdown deactivates every controller, which says nothing of the task
    until = worked_until(log, task)
    its = {id(ln) for ln in (*own, *process)}
    about = [ln for ln in log.logs if named is not None and ln.t <= until and id(ln) not in its
             and named.search(ln.msg.lower()) and _ABOUT.search(ln.msg)]
    if not own and not process:
        if about:  # a hardware component or a controller has no logger of its own: what others said of it
            return Explanation(explainer="planner", causes=["planner.plan_ok"],
                               evidence=line_evidence(about[-ABOUT:], task),
                               text=f"My log holds no line of {node}'s own, but other nodes said of it: "
                                    f"{quote(about[-ABOUT:], False, True)}.")
        return Explanation(explainer="planner", causes=["planner.plan_ok"], enough_information=False,
                           text=f"My log holds no line from {node or 'that node'} and no word from launch about its "
                                "process: it may not have run, or its lines were not recorded; I can't tell.")
    parts = []
    if own:
        last = own[-1]
        when = f"at {hms(last.t)}" if len(own) == 1 else f"from {hms(own[0].t)} to {hms(last.t)}"
        parts.append(f"The node {node} logged {len(own)} line{'s' if len(own) > 1 else ''} {when}; its last "
                     f'({LEVEL_NAMES.get(last.level, str(last.level))}): "{" ".join(last.msg.split())[:200]}"')
        up = {id(ln) for ln in before_shutdown(log.logs)}
        before = [ln for ln in own if id(ln) in up]
        if before and before[-1] is not last:
            # what it was doing when the stack was stopped, apart from what it printed on the way down
            parts.append(f'its last line before my stack began to shut down came at {hms(before[-1].t)}: '
                         f'"{" ".join(before[-1].msg.split())[:160]}"')
    aborted = next(((ln, m) for ln in own if (m := _ABORTED.search(ln.msg)) is not None), None)
    ended = process[-1] if process else None
    if aborted is not None:
        parts.append(f'its output at {hms(aborted[0].t)} holds "{aborted[1].group(0)}": its process aborted there')
    elif ended is not None and "finished cleanly" in ended.msg:
        parts.append(f"launch said its process finished cleanly at {hms(ended.t)}")
    elif ended is not None and "started with pid" not in ended.msg:
        parts.append(f'its process ended at {hms(ended.t)}: "{" ".join(ended.msg.split())[:160]}"')
    else:
        tail = (log.end - own[-1].t) / 1e9 if own else 0.0
        parts.append("no line says its process ended" + (
            f"; its last line came {tail:.0f} s before my recording ends" if tail >= 1 else
            ", and its last line is the recording's last moment: what came after is not recorded"))
    if about:  # "Activating controllers: [ arm_controller ]", "Configuring controller_server"
        parts.append(f"other nodes said of it: {quote(about[-ABOUT:], False, True)}")
    text = "; ".join(parts) + "."
    return Explanation(explainer="planner", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                       evidence=line_evidence([*own[-2:], *process[-1:], *about[-ABOUT:]], task))
