""""What's failure_tolerance set to?", "is use_sim_time set?", "what is the transform tolerance?": every rclcpp and
rclpy node announces the parameters it declares, with their values, and every later change on /parameter_events. A
recording that holds that topic answers a question about a setting with the values themselves, node by node, as they
stood at the task's end; a setting that differs between nodes (use_sim_time true on some, false on one) is said as
such, since that difference is itself a finding. Without the topic, or where no recorded parameter is the one asked
for, the answer says so and the log's lines about it come next (agent/mentions.py).
"""

from __future__ import annotations

import re
from collections import defaultdict

from hexar.events import contract as c
from hexar.events.log import EventLog
from hexar.events.records import ParameterSample, hms
from hexar.explainers.base import Evidence

# a parameter's name as a question writes it: snake_case or dotted ("failure_tolerance", "FollowPath.max_vel_x")
IDENTIFIER = re.compile(r"(?<![\w.])[a-z][a-z0-9]*(?:[_.][a-z0-9]+)+(?![\w])")
# a quoted line of the log ("… actuate the specified joints"), not a parameter's name ('failure_tolerance'): its
# words are the line's
_LINE_QUOTED = re.compile(r"'[^']*\s[^']*'|\"[^\"]*\s[^\"]*\"|‘[^’]*\s[^’]*’|“[^”]*\s[^”]*”")
_NODES_SHOWN = 5
_NAMES_SHOWN = 4


def _last(name: str) -> str:
    return name.rsplit(".", 1)[-1].lower()


def _spaced(name: str) -> str:
    return re.sub(r"[_.]+", " ", _last(name)).strip()


def _word_char(ch: str) -> bool:
    return ch.isalnum() or ch == "_"


def _stands(q: str, word: str, dots: bool) -> bool:
    """Whether `word` stands in `q` as a whole: as (?<![\\w.])word(?!\\w) finds it with `dots`, else as \\bword(s)?\\b.
    A plain find per name: a robot's stack declares thousands of parameters, and one pattern each overflowed re's
    cache on every question (about 0.2 s a question with 2,000)."""
    i = q.find(word)
    while i >= 0:
        prev, j = q[i - 1] if i else "", i + len(word)
        if dots:
            if not (prev and (_word_char(prev) or prev == ".")) and not _word_char(q[j:j + 1]):
                return True
        elif _word_char(prev) != _word_char(word[0]):
            last, nxt = word[-1], q[j:j + 1]
            if (nxt == "s" and not _word_char(q[j + 1:j + 2])) or _word_char(last) != _word_char(nxt):
                return True
        i = q.find(word, i + 1)
    return False


def named(question: str, names: set[str], spaced: bool = True) -> list[str]:
    """The recorded parameter names a question names whole: "failure_tolerance", its dotted full name, its last part
    where that is an identifier of its own ("max_vel_x" of FollowPath.max_vel_x, not "trajectory" of
    constraints.arm_1_joint.trajectory, a word any question may hold), or, with `spaced`, its words spaced
    ("transform tolerance", "use sim time")."""
    q = _LINE_QUOTED.sub(" ", " ".join(question.lower().split()))
    return sorted(n for n in names
                  if _stands(q, n.lower(), True)
                  or ("_" in _last(n) and _stands(q, _last(n), True))
                  or (spaced and " " in _spaced(n) and _stands(q, _spaced(n), False)))


def asked_names(question: str, names: set[str], terms: list[str]) -> list[str]:
    """The recorded parameter names a question asks for: those it names whole (see named), else those under a part
    of a dotted name it names, else those whose name holds a word it asks for ("sim time" in use_sim_time,
    "tolerance" in xy_goal_tolerance)."""
    whole = named(question, names)
    if whole:
        return whole
    # a part of a dotted name ("arm_5_joint" of constraints.arm_5_joint.trajectory): every parameter under it
    parts = {m.group(0) for m in IDENTIFIER.finditer(" ".join(question.lower().split()))}
    under = sorted(n for n in names if parts & set(n.lower().split(".")[:-1]))
    if under:
        return under
    words = [t.replace("_", " ") for t in terms]
    return sorted(n for n in names
                  if any(re.search(r"(^| )" + re.escape(w) + r"( |$)", _spaced(n)) for w in words))


def _nodes(nodes: list[str]) -> str:
    shown = ", ".join(nodes[:_NODES_SHOWN])
    return shown + (f" and {len(nodes) - _NODES_SHOWN} more" if len(nodes) > _NODES_SHOWN else "")


def _one(name: str, held: list[ParameterSample]) -> str:
    """One parameter across the nodes that declared it: its value, or its values where the nodes differ."""
    by_value: dict[str, list[str]] = defaultdict(list)
    for p in sorted(held, key=lambda p: p.node):
        by_value[p.said].append(p.node)
    if len(held) == 1:
        p = held[0]
        return f"{p.node} has {name} = {p.said}"
    if len(by_value) == 1:
        value, nodes = next(iter(by_value.items()))
        return f"{name} = {value} on all {len(nodes)} nodes that declared it ({_nodes(nodes)})"
    parts = sorted(by_value.items(), key=lambda kv: -len(kv[1]))
    said = " but ".join(f"{value} on {len(nodes)} node{'s' if len(nodes) > 1 else ''} ({_nodes(nodes)})"
                        for value, nodes in parts)
    return f"{name} differs between my nodes: {said}"


def _changes(held: list[ParameterSample], log: EventLog) -> str:
    """The values set after a node declared them: a change at run time is often what a developer looks for."""
    changed = [p for p in held if p.change == "changed"]
    told = []
    for p in changed[:3]:
        first = next((q for q in log.parameters if (q.node, q.name) == (p.node, p.name) and q.change == "new"), None)
        was = f" (declared as {first.said})" if first is not None else ""
        told.append(f"{p.node} set {p.name} to {p.said} at {hms(p.t)}{was}")
    return f" Changed while running: {'; '.join(told)}." if told else ""


def parameter_values(question: str, log: EventLog, until: int, terms: list[str]) -> tuple[str, list[Evidence]] | None:
    """The recorded values of the parameters a question asks for, as they stood at `until`, with their evidence;
    None when the recording holds no parameter of that name."""
    held = log.settings(until)
    names = asked_names(question, {name for _, name in held}, terms)
    if not names:
        return None
    parts, evidence = [], []
    for name in names[:_NAMES_SHOWN]:
        these = [p for (_, n), p in held.items() if n == name]
        parts.append(_one(name, these))
        evidence += [_evidence(p) for p in these]
    more = f" ({len(names) - _NAMES_SHOWN} more parameters match)" if len(names) > _NAMES_SHOWN else ""
    nodes = len({node for node, _ in held})
    text = (f"My nodes' parameters, as they announced them on {c.PARAMETER_EVENTS} ({len(held)} parameters of "
            f"{nodes} node{'s' if nodes > 1 else ''}): {'; '.join(parts)}{more}."
            + _changes([p for (_, n), p in held.items() if n in names], log))
    return text, evidence


# "what parameters did amcl have?", "which parameters changed?", "what settings did you run with?"
LISTING = re.compile(r"^(and |so |but |ok )?(what|which|how many|list|show|were|was|did|any|are)\b.*"
                      r"\b(parameters|params|settings|parameter values)\b|\b(parameters?|params?|settings?) "
                      r"(changed|were changed|was changed|did you change|were set|did you use|did you run with)\b")
_CHANGED = re.compile(r"\b(chang|modif|set (while|during|at run)|updat)")
_LISTED = 12


# a question that asks for a value: its words may name a parameter spaced ("which nodes use sim time?"); elsewhere
# spaced words are the question's own ("the costmap missed its update rate")
_ASKS = re.compile(r"^(and |so |but )?(what|what's|whats|which|is|was|are|were|how|does|did)\b")


def asks_parameters(question: str, log: EventLog) -> bool:
    """Whether a question is about the recorded parameters: one it names, or the parameters as such. Only a
    recording that holds parameters answers from them; elsewhere the question takes its usual way."""
    if not log.parameters:
        return False
    q = " ".join(question.lower().split())
    return bool(named(q, {p.name for p in log.parameters}, spaced=_ASKS.search(q) is not None)) or \
        LISTING.search(q) is not None


def node_asked(question: str, log: EventLog) -> bool:
    """Whether a question names a node that announced parameters ("amcl", "the arm controller")."""
    q = " ".join(question.lower().split())
    return any(_names_node(q, node) for node in {p.node for p in log.parameters})


def _names_node(q: str, node: str) -> bool:
    last = node.rsplit("/", 1)[-1].lower()
    return re.search(r"(?<![\w/])(" + re.escape(last) + "|" + re.escape(last.replace("_", " ")) + r")(?![\w])",
                     q) is not None


def parameter_list(question: str, log: EventLog, until: int) -> tuple[str, list[Evidence]]:
    """The parameters of the node a question names, those changed while running, or what the recording holds."""
    q = " ".join(question.lower().split())
    held = log.settings(until)
    nodes = sorted({node for node, _ in held})
    asked = [n for n in nodes if _names_node(q, n)]
    if asked:
        shown = [p for (node, _), p in sorted(held.items()) if node in asked]
        more = f", and {len(shown) - _LISTED} more" if len(shown) > _LISTED else ""
        text = (f"{' and '.join(asked)} announced {len(shown)} parameters on {c.PARAMETER_EVENTS}: "
                + ", ".join(f"{p.name} = {p.said}" for p in shown[:_LISTED]) + more + ".")
        return text, [_evidence(p) for p in shown[:_LISTED]]
    changed = [p for p in held.values() if p.change == "changed"]
    if _CHANGED.search(q):
        if not changed:
            return (f"No parameter was changed while running: my {len(nodes)} nodes announced {len(held)} parameters "
                    f"on {c.PARAMETER_EVENTS} and set none of them afterwards.", [])
        return (f"{len(changed)} parameter{'s were' if len(changed) > 1 else ' was'} changed while running:"
                + _changes(changed, log).removeprefix(" Changed while running:"), [_evidence(p) for p in changed])
    text = (f"My recording holds {len(held)} parameters of {len(nodes)} nodes ({_nodes(nodes)}), as they announced "
            f"them on {c.PARAMETER_EVENTS}; {len(changed) or 'none'} changed while running. Ask me for one by its "
            "name (\"what is use_sim_time?\") or for a node's (\"what parameters did amcl have?\").")
    return text, [_evidence(p) for p in changed]


def _evidence(p: ParameterSample) -> Evidence:
    return Evidence(cause="planner.plan_ok", topic=c.PARAMETER_EVENTS, t=p.t,
                    item=f"{p.node}: {p.name} = {p.said} ({p.change})")


def not_held(question: str, log: EventLog, until: int) -> str:
    """Why the recording gives no value: it holds no /parameter_events, or none of the parameter named."""
    held = log.settings(until)
    if not held:
        return (f"my recording holds no parameter values (no {c.PARAMETER_EVENTS}; record it from before the "
                "bring-up and I can read each node's settings)")
    asked = [m.group(0) for m in IDENTIFIER.finditer(" ".join(question.lower().split()))]
    what = " or ".join(asked) if asked else "that"
    return (f"none of the {len(held)} parameters my nodes announced on {c.PARAMETER_EVENTS} is {what}")
