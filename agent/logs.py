""""What errors were there?", "show me the logs", "which node failed?", "what was the last error?": the log lines a
developer replaying a run asks for, read from the recording (/rosout, and launch's log where it was recorded) in the
task's time, quoted with their node and time, instead of the finding told again.

Repeats of one message from one node are said once, with how often; at most a few distinct messages are quoted,
and the answer says how many more there are. An error before the task began (a node that failed at bring-up) is
told as that when the task's own time holds none.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass

from hexar.agent.content import task_name
from hexar.agent.measures import worked_until
from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import ERROR, WARN, LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.recorded import join_words
from hexar.explainers.stack.bringup import PROCESS_SUFFIX

_OPEN = r"^(and |so |but |ok |okay |now |then )?(please )?"
LOGS = re.compile(
    _OPEN + r"(what|which|any) (errors?|warnings?|error messages?|warning messages?)\b(?! (did|do|does) (it|that|"
    r"this) (mean|say))|"
    + _OPEN + r"(show|list|give|tell|read)( me)? (the |your |all (of )?(the |your )?)?(errors?|warnings?|logs?|"
    r"log lines|error messages?|warning messages?)\b|"
    + _OPEN + r"what (was|were|is|are) (the )?(last|first|latest|final) (errors?|warnings?|log lines?|messages?)\b|"
    + _OPEN + r"what (did|does) (the|your|my) logs? (say|show)\b|"
    + _OPEN + r"what('s| is) in (the|your|my) logs?\b|"
    + _OPEN + r"(did|were|was) (you get |you log |you see |there )?(any |an |a )?(errors?|warnings?)( logged| "
    r"recorded)?\W*$|"
    # "were there any WARN or ERROR lines at all?", "how many times did it warn?"
    + _OPEN + r"(were|was|are|is) there (any|many)( [a-z_]+)? (warn(ing)?s?|errors?)( or (warn(ing)?s?|errors?))?"
    r"( lines?| messages?)?\b|"
    r"\bhow many (times did (it|they|the node|[a-z_]+) (warn|complain|error|log it)|warnings|errors)\b|"
    # "did this run go cleanly, any warnings or errors at all?": a clause after the first asks for them
    r"[,;:] any (warn(ing)?s?|errors?)( or (warn(ing)?s?|errors?))?( at all)?\W*$|"
    + _OPEN + r"which (node|nodes|process|processes|component|components)( of yours)? (failed|crashed|died|"
    r"complained|errored|reported (an |any )?(errors?|problems?)|had (an |any )?(errors?|problems?))\b"
)
# the robot's start, before the task: "any warnings during bring-up?", "errors at startup?"
_BRINGUP = re.compile(r"\b(during|at|in|on) (the |my |your )?(bring-?up|start-?up|launch|boot)\b|\bbefore the goal\b")
QUOTED = 3  # distinct messages quoted in one answer; the rest are counted
# a span a log line states itself: "within 10.000000 seconds", "timed out after 5 seconds", "waited 2.5 s"
_STATED = re.compile(r"\b(within|after|waited|wait of|timeout of|timed out after)\s+\d+(\.\d+)?\s*"
                     r"(seconds?|secs?|s|ms|milliseconds?)\b", re.IGNORECASE)


@dataclass(frozen=True)
class _Asked:
    low: int  # the lowest level asked for
    high: int  # the highest
    noun: str  # "error", "warning" or "error or warning"
    one: str  # "last" or "first" for only that one, else ""
    nodes: bool  # which nodes
    yes_no: bool  # "any errors?"


def _asked(q: str) -> _Asked:
    warn = re.search(r"\bwarn(ings?|ed|s)?\b", q) is not None
    err = re.search(r"\berrors?\b|\b(failed|crashed|died|errored)\b", q) is not None
    if warn and not err:
        low, high, noun = WARN, WARN, "warning"
    elif warn:  # "any WARN or ERROR lines?": both
        low, high, noun = WARN, 100, "error or warning"
    elif err or not re.search(r"\blogs?\b|\blog lines\b|\bmessages?\b", q):
        low, high, noun = ERROR, 100, "error"
    else:
        low, high, noun = WARN, 100, "error or warning"
    one = "last" if re.search(r"\b(last|latest|final)\b", q) else "first" if re.search(r"\bfirst\b", q) else ""
    return _Asked(low, high, noun, one,
                  re.search(r"\bwhich (node|process|component)", q) is not None,
                  # "did it go cleanly, any warnings?": a yes would answer the first question, not the count
                  re.search(r"^(\w+ )?(any|did|were|was)\b", q) is not None and re.search(r"[,;:] any\b", q) is None)


def _speaker(line: LogLine) -> str:
    """A line's node; for a Python traceback that names none, the program its own frames point at."""
    from hexar.explainers.stack.thrown import python_exception

    if line.name:
        return line.name
    exc = python_exception(line)
    return f"a Python program of no node name ({exc.file})" if exc is not None and exc.file else "a node"


_PLURAL = {"error": "errors", "warning": "warnings", "error or warning": "errors or warnings"}


def _plural(n: int, noun: str) -> str:
    return f"{n} {noun}" if n == 1 else f"{n} {_PLURAL[noun]}"


def _said(msg: str, limit: int = 200) -> str:
    msg = " ".join(msg.split())
    return msg if len(msg) <= limit else msg[:limit].rstrip() + "…"


def _distinct(lines: list[LogLine]) -> list[LogLine]:
    """Each message of a node once (its first line), the worst first (errors before warnings), each level in the
    order first seen: the order the answer quotes them and cites them in."""
    first: dict[tuple[str, str], LogLine] = {}
    for ln in lines:
        first.setdefault((ln.name, ln.msg), ln)
    return sorted(first.values(), key=lambda ln: (-ln.level, ln.t))


def quote(lines: list[LogLine], one_node: bool, levels: bool) -> str:
    """'at 12:00:01, controller_server "..." (4 times)' for each distinct message (the node left out where every
    line came from the one already named, the level where only one was asked for)."""
    counts = Counter((ln.name, ln.msg) for ln in lines)
    distinct = _distinct(lines)
    parts = []
    for ln in distinct[:QUOTED]:
        n = counts[(ln.name, ln.msg)]
        times = f" ({n} times)" if n > 1 else ""
        who = "" if one_node else f" {ln.name or 'a node'}"
        level = f" ({ln.level_name})" if levels else ""
        parts.append(f'at {hms(ln.t)},{who}{level} "{_said(ln.msg)}"{times}')
    more = len(distinct) - QUOTED
    text = "; ".join(parts)
    return text + (f"; and {more} other message{'s' if more > 1 else ''}" if more > 0 else "")


def line_evidence(lines: list[LogLine], task: Task) -> list[Evidence]:
    return [Evidence(cause="planner.plan_ok", topic=ln.origin, t=ln.t, item=ln.render())
            for ln in _distinct(lines)[:QUOTED]] or \
        [Evidence(cause="planner.plan_ok", topic=c.TASK_INFO, t=task.created, item=task.instruction)]


# parts of node names that name no one node ("controller" names both controller_server and controller_manager: still
# a part a question may mean, but "server" or "node" alone is none)
_GENERIC_PARTS = frozenset({"server", "manager", "node", "nodes", "interface", "broadcaster", "publisher"})


def _named_nodes(q: str, log: EventLog) -> list[str]:
    """The log's nodes a question names ("any planner warnings?": planner_server), by a word that is a node's name
    or a part of it between underscores; empty when it names none."""
    # "... before bt_navigator said the goal succeeded?": a node after "before" is a moment, not whose lines
    asked = re.split(r"\b(before|after|until|till|when|while|since)\b", q)[0]
    words = {w for w in re.findall(r"[a-z][a-z0-9_]{3,}", asked)} - _GENERIC_PARTS
    out = []
    for name in sorted({ln.name for ln in log.logs if ln.name and not PROCESS_SUFFIX.search(ln.name)}):
        base = name.strip("/").split("/")[-1].split(".")[-1].lower()
        if base in words or any(part in words for part in base.split("_")):
            out.append(name)
    return out


def _select(log: EventLog, low: int, high: int, start: int, end: int) -> tuple[list[LogLine], bool]:
    """The lines of these levels in [start, end] (True), else those before `start` (False): a node that failed at
    bring-up explains the task that came after."""
    picked = [ln for ln in log.logs if low <= ln.level <= high and ln.t <= end]
    inside = [ln for ln in picked if start <= ln.t]
    return (inside, True) if inside else ([ln for ln in picked if ln.t < start], False)


def logs(question: str, log: EventLog, task: Task) -> Explanation:
    """The log lines asked for, in the task's time: counted, by node, the distinct ones quoted."""
    q = " ".join(question.lower().split())
    asked = _asked(q)
    name = task_name(task, log)
    if not log.logs:
        text = (f"My recording holds no log lines ({c.ROSOUT}), so I can't tell which {_PLURAL[asked.noun]} there "
                f"were for {name}.")
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence([], task), enough_information=False)
    start = task.created
    end = worked_until(log, task)
    if _BRINGUP.search(q) and log.logs[0].t < task.created:  # "any warnings during bring-up?": before the task
        start, end = log.logs[0].t, task.created - 1
    lines, inside = _select(log, asked.low, asked.high, start, end)
    times = f"at {hms(start)}" if hms(start) == hms(end) else f"{hms(start)} to {hms(end)}"
    span = f"while I worked on {name} ({times} UTC)" if end >= task.created else \
        f"while I came up, before {name} ({times} UTC)"
    named = _named_nodes(q, log)
    if named and lines:  # "were there any planner warnings?": those of the nodes it names
        theirs = [ln for ln in lines if ln.name in named]
        if not theirs:
            others = join_words(sorted({ln.name or "a node" for ln in lines}))
            text = (f"{'No. ' if asked.yes_no else ''}My log holds no {asked.noun} from {join_words(named)} {span}; "
                    f"the {_PLURAL[asked.noun]} there came from {others}.")
            return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                               evidence=line_evidence(lines, task))
        lines = theirs
    if not lines:
        text = f"{'No. ' if asked.yes_no else ''}My log holds no {asked.noun} {span}" + \
            (", nor before it." if end >= task.created else ".")
        warned, _ = _select(log, WARN, WARN, start, end) if asked.noun == "error" else ([], True)
        if warned:
            text += f' It holds {_plural(len(warned), "warning")}: ask "what warnings were there?" for them.'
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=line_evidence([], task))
    where = span if inside else f"before I began on {name}, at {hms(start)} UTC (none while I worked on it)"
    if asked.one:
        ln = lines[-1] if asked.one == "last" else lines[0]
        text = (f"The {asked.one} {asked.noun} {where} came at {hms(ln.t)} from {ln.name or 'a node'}: "
                f'"{_said(ln.msg)}".')
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"],
                           evidence=line_evidence([ln], task))
    by_node = Counter(_speaker(ln) for ln in lines)
    nodes = join_words([f"{node} ({n})" if len(by_node) > 1 else node for node, n in by_node.most_common()])
    if asked.nodes:
        ln = lines[0]
        first = f"from {_speaker(ln)}" if len(by_node) > 1 else "from it"
        text = (f"The {_PLURAL[asked.noun]} {where} came from {nodes}. The first, at {hms(ln.t)}, came {first}: "
                f'"{_said(ln.msg)}".')
    else:
        text = (f"{'Yes. ' if asked.yes_no else ''}My log holds {_plural(len(lines), asked.noun)} {where}, from "
                f"{nodes}: {quote(lines, len(by_node) == 1, len({ln.level for ln in lines}) > 1)}.")
    return Explanation(explainer="planner", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                       evidence=line_evidence(lines, task))


NODES = re.compile(
    _OPEN + r"(which|what) (nodes|processes)( of yours)? (were|are|was|did you have) (running|up|alive|active|there|"
    r"launched|started|online)\b|"
    + _OPEN + r"(list|show)( me)? (the |your |all (of )?(the |your )?)?(nodes|processes)\b|"
    + _OPEN + r"(what|which) (nodes|processes) (did|do) you (have|run|start|launch)\b")
NAMED = 8  # nodes named, most lines first; the rest are counted


def nodes(question: str, log: EventLog, task: Task) -> Explanation:
    """"Which nodes were running?": the nodes whose lines the log holds, over the whole recording, with their
    counts and errors. A node that never logged does not show, and the answer says so rather than "not running"."""
    if not log.logs:
        text = f"I can't tell: my recording holds no log lines ({c.ROSOUT}), and nodes show in my recording only there."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    lines = Counter(ln.name or "a node" for ln in log.logs)
    errors = Counter(ln.name or "a node" for ln in log.logs if ln.level >= ERROR)
    named = [f"{node} ({n} line{'s' if n > 1 else ''}" + (f", {errors[node]} error{'s' if errors[node] > 1 else ''}"
             if errors[node] else "") + ")" for node, n in lines.most_common(NAMED)]
    rest = len(lines) - NAMED
    if rest > 0:
        named.append(f"{rest} other node{'s' if rest > 1 else ''}")
    text = (f"My log holds lines from {len(lines)} node{'s' if len(lines) > 1 else ''}: {join_words(named)}. A node "
            "that never logged does not show here, and my log cannot tell whether one was still running at the end.")
    first: dict[str, LogLine] = {}
    for ln in log.logs:
        first.setdefault(ln.name or "a node", ln)
    shown = {node for node, _ in lines.most_common(NAMED)}
    evidence = [Evidence(cause="planner.plan_ok", topic=ln.origin, t=ln.t, item=ln.render())
                for node, ln in first.items() if node in shown]
    return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], evidence=evidence)


def stated_spans(log: EventLog, task: Task) -> str:
    """The spans the task's log lines state themselves ('"... within 10.000000 seconds." (hello_moveit, 21:08:24)'),
    for a "how long?" whose answer the recorded times alone do not give: a wait a node timed, whose start is
    before the recording or in no line. Only of a task read from the logs: a robot's own task has its times."""
    if not task.derived:
        return ""
    start, end = task.window()
    lines = [ln for ln in log.logs if start - 60_000_000_000 <= ln.t <= end and _STATED.search(ln.msg)]
    told = [f'"{_said(ln.msg)}" ({ln.name or "a node"}, {hms(ln.t)})' for ln in _distinct(lines)[:QUOTED]]
    return f" My log states how long itself: {join_words(told)}." if told else ""
