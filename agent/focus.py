"""The log lines a developer's question points at by their own words: "why did it fail with 'Transform data too
old'?", "what's wrong with voxel_layer.plugin?", "why did the clear_entirely_local_costmap call time out?".

A finding names the cause in the explainer's words; a question that quotes a line, names an identifier of the stack
(a node, a parameter, a service, a plugin type, a device) or a node of the log asks about those lines as well. They
are found by what the question and a line share, never by what the question means: a quoted phrase found in the
line, an identifier found in it or naming its node, and the question's other words the line repeats. A question in
a person's words (no identifier, no quote, no node's name) points at no line, so a home user's answer stays as it was.
"""

from __future__ import annotations

import re

from hexar.agent.logs import quote
from hexar.agent.measures import worked_until
from hexar.events.log import EventLog
from hexar.events.records import LogLine
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation
from hexar.explainers.stack.bringup import PROCESS_SUFFIX

# 'Transform data too old', "Init lds lidar fail!", ‘…’: what a developer copied from the log
_QUOTED = re.compile(r"'([^']{6,})'|\"([^\"]{6,})\"|‘([^’]{6,})’|“([^”]{6,})”")
# voxel_layer.plugin, /base_driver, nav2_navfn_planner/NavfnPlanner, ttyACM0, BaseObstacle, dwb_core::DWBLocalPlanner
_IDENT = re.compile(r"(?<![\w/.:-])/?[A-Za-z][\w]*(?:(?:[./]|::)[A-Za-z_][\w]*)*")
_WORD = re.compile(r"[a-z][a-z0-9]+")
# words every question and many lines hold: they point at nothing
_COMMON = frozenset({"about", "after", "again", "also", "before", "being", "could", "does", "doing", "done",
    "during", "error", "errors", "fail", "failed", "fails", "failing", "failure", "from", "have", "happen",
    "happened", "into", "just", "keep", "kept", "line", "lines", "logs", "made", "make", "never", "node", "nodes",
    "only", "other", "problem", "really", "said", "says", "should", "still", "than", "that", "their", "them", "then",
    "there", "these", "they", "this", "those", "time", "times", "went", "were", "what", "when", "where", "which",
    "while", "whole", "with", "would", "wrong", "your", "robot"})
TOP = 3  # lines told at once
# what every node of a bring-up prints (nav2_util's lifecycle_node.cpp, launch's execute_local.py): it names the node,
# and says nothing of what was asked about it
_ROUTINE = re.compile(r"lifecycle node launched|^Creating bond|^process started with pid|^(Configuring|Activating|"
                      r"Cleaning up|Deactivating)$")


def _identifiers(question: str, nodes: set[str]) -> list[str]:
    """The question's identifiers: a word of the stack's spelling (an underscore, a dot or slash inside, '::', a
    capital after a lower-case letter, letters with digits), or a word that is the name of a node of the log."""
    out = []
    for m in _IDENT.finditer(question):
        word = m.group(0).strip("/.:")
        shaped = re.search(r"[_./]|::|[a-z][A-Z]|[A-Za-z]\d", word) is not None
        if len(word) >= 4 and (shaped or word.lower() in nodes) and word.lower() not in out:
            out.append(word.lower())
    return out


def _node(line: LogLine) -> str:
    """A line's node as a question names it: launch's process name without its number ("controller_server-2")."""
    return PROCESS_SUFFIX.sub("", line.name.rsplit(".", 1)[-1].strip("/").lower())


def _norm(text: str) -> str:
    return " ".join(text.lower().split())


def _stem(word: str) -> str:
    """A word without the endings a log's own form of it may not share ("passed" of "Passing", "brake" of
    "Braking")."""
    for end in ("ing", "ed", "es", "e", "s"):
        if word.endswith(end) and len(word) - len(end) >= 4:
            return word[: -len(end)]
    return word


def _quoted_in(quote: str, msg: str) -> bool:
    """A quote is in a line, a quote shortened with "..." or "…" when its parts are, in order ('No position
    interface found... Skipping sync!')."""
    if quote in msg:
        return True
    parts = [p.strip() for p in re.split(r"\.{3}|…", quote) if len(p.strip()) >= 6]
    if not parts or parts == [quote.strip()]:  # no "..." in it: it is not in the line
        return False
    at = 0
    for part in parts:
        at = msg.find(part, at)
        if at < 0:
            return False
        at += len(part)
    return True


def _holds(msg: str, ident: str) -> bool:
    """An identifier in a line, not as the start of a longer one ("arm_controller" is not in "arm_controllers.yaml")."""
    at = msg.find(ident)
    while at >= 0:
        after = msg[at + len(ident):at + len(ident) + 1]
        if not (after.isalnum() or after == "_"):
            return True
        at = msg.find(ident, at + 1)
    return False


_SEEN: list[tuple[list[LogLine], list[tuple[LogLine, str, str]]]] = []


def _rows(lines: list[LogLine]) -> list[tuple[LogLine, str, str]]:
    """(line, its words lower-cased, its node) for a log's lines, kept for the last few logs asked about: every
    question of a conversation reads the same log, and a real one holds hundreds of thousands of lines."""
    for seen, rows in _SEEN:
        if seen is lines and len(rows) == len(lines):
            return rows
    rows = [(ln, _norm(ln.msg), _node(ln) if ln.name else "") for ln in lines]
    _SEEN.insert(0, (lines, rows))
    del _SEEN[4:]
    return rows


def pointed_lines(question: str, log: EventLog, until: int | None = None, by_words: bool = False) -> list[LogLine]:
    """The log's lines (up to `until`) the question points at by a quote, an identifier or a node's name, with
    the question's other words they repeat: the strongest, at most TOP, in time order, warnings before routine lines
    of the same strength. `by_words`: a line that repeats two of the question's words counts too (a developer's
    question on a log read without a plan of the robot's). Empty when the question names nothing of the log."""
    return sorted(ranked_lines(question, log, until, by_words)[:TOP], key=lambda ln: ln.t)


def ranked_lines(question: str, log: EventLog, until: int | None = None, by_words: bool = False,
                 least: int = 2, slack: int = 1) -> list[LogLine]:
    """pointed_lines' candidates, strongest first (within `slack` points of the best); `least`: the fewest of the
    question's words that point at a line without a quote or an identifier."""
    rows = [row for row in _rows(log.logs) if until is None or row[0].t <= until]
    if not rows:
        return []
    nodes = {node for _, _, node in rows if node}
    quotes = [_norm(next(g for g in m.groups() if g)) for m in _QUOTED.finditer(question)]
    idents = _identifiers(question, nodes)
    bare = _QUOTED.sub(" ", question.lower())
    # "controller" of controller_server counts once; the words of one that names nothing of the log count as words
    # ("free/occupied threshold warnings")
    parts = {w for i in idents if any(_holds(msg, i) or i in node for _, msg, node in rows) for w in _WORD.findall(i)}
    words = {w for w in _WORD.findall(bare) if len(w) >= 4 and w not in _COMMON} - parts
    stems = [(w, _stem(w)[:6]) for w in sorted(words)]  # "configure" in "Configuring", "brake" in "Braking"
    if not quotes and not idents and not (by_words and len(words) >= least):
        return []
    scored = []
    for ln, msg, node in rows:
        score = 3 * sum(1 for q in quotes if _quoted_in(q, msg)) + \
            2 * sum(1 for i in idents if _holds(msg, i) or i == node)
        shared = sum(1 for w, stem in stems if stem in msg or w in node)
        # without a quote or an identifier, two of the question's own words in one line point at it
        if score == 0 and (not by_words or shared < least):
            continue
        scored.append((score + shared - (_ROUTINE.search(ln.msg) is not None), ln.level, ln))
    if not scored:
        return []
    best = max(s for s, _, _ in scored)
    kept = [x for x in scored if x[0] >= best - slack]
    kept.sort(key=lambda x: (-x[0], -x[1], -len(x[2].msg)))  # the longer of two errors says more
    return [ln for _, _, ln in kept]


def with_pointed(text: str, question: str, log: EventLog, task: Task) -> str:
    """The answer with the lines the question points at that it does not quote already: "… What my log says of
    it: at 07:39:52, tf_help (ERROR) "…"."."""
    until = worked_until(log, task)
    told = _norm(text)
    fresh = [ln for ln in pointed_lines(question, log, until, by_words=task.derived) if _norm(ln.msg)[:60] not in told]
    if not fresh:
        return text
    text = f"{text} What my log says of it: {quote(with_repeats(fresh, log, until), False, True)}."
    if re.match(r"\s*(and |so |but )?why\b", question.lower()):
        # "why did P5 cap max_v?": what the same node logged just before the line is what says why, if anything
        before = just_before(fresh[0], log, {id(ln) for ln in fresh})
        if before:
            text += f" Just before it, the same node logged: {quote(before, True, False)}."
    return text.strip()


def just_before(line: LogLine, log: EventLog, skip: set[int], within_ns: int = 2_000_000_000) -> list[LogLine]:
    """The last few lines the line's own node logged in the seconds before it (the line itself and `skip` left
    out), oldest first."""
    at = next((i for i, ln in enumerate(log.logs) if ln is line), None)
    if at is None:
        return []
    out = [ln for ln in log.logs[max(0, at - 40):at] if ln.name == line.name and id(ln) not in skip
           and line.t - ln.t <= within_ns and ln.msg != line.msg]
    return out[-2:]


def with_repeats(lines: list[LogLine], log: EventLog, until: int | None = None) -> list[LogLine]:
    """Every line of the log (up to `until`) that repeats one of `lines`, node and words: quoted, their count is the
    log's ("Passing new path to controller." (5 times)), not the few the search kept."""
    said = {(ln.name, ln.msg) for ln in lines}
    return [ln for ln in log.logs if (ln.name, ln.msg) in said and (until is None or ln.t <= until)]


def when_untold(exp: Explanation, question: str, log: EventLog, task: Task) -> Explanation:
    """An answer from the recording that could not tell ("my position is not recorded"), with the lines the question
    points at ("Robot is out of bounds of the costmap!"); one that could, as it was."""
    if exp.enough_information:
        return exp
    text = with_pointed(exp.text, question, log, task)
    return exp if text == exp.text else exp.model_copy(update={"text": text})
