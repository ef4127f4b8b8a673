""""Which node threw this? The log line has no node name.", "which node logged these lines?": a console's line that
names no logger (a process's own output, an exception printed on stderr, an excerpt pasted without it) still has
words someone's code wrote. The mined catalogue of the stack (explainers/stack/) says whose: the package and source
file that log or raise those words. The answer gives that, and the node of the nearest named line before it; it
never names a node the log does not."""

from __future__ import annotations

import re

from hexar.agent.focus import pointed_lines
from hexar.agent.logs import line_evidence
from hexar.events.log import EventLog
from hexar.events.records import ERROR, LogLine, hms
from hexar.events.tasks import Task
from hexar.explainers.base import Explanation
from hexar.explainers.stack import stack_catalogue

UNNAMED = re.compile(
    r"\b(which|what|whose) (node|process|component|package|program|code)( of mine)? (logged|threw|printed|raised|"
    r"wrote|emitted|produced|sent|said|says|throws|logs|prints|raises) (this|these|that|those|it|the (line|error|"
    r"exception|warning|message)s?)\b|\b(has|have|had|with|gives?) no (node|logger)?( ?name)\b|"
    r"\bwho (logged|threw|printed|raised|wrote) (this|these|that|those|it)\b")
SHOWN = 2


def unnamed_kind(q: str) -> str | None:
    return "unnamed" if UNNAMED.search(q) else None


def _whose(line: LogLine) -> str:
    entry = stack_catalogue().match(line.msg)
    if entry is None:
        return "no catalogue of mine holds its words, so I can't tell whose code wrote it"
    where = entry.source.split(" (")[0]
    did = "raises" if entry.form == "throw" else "logs"
    return f"its words are what {entry.package} {did} ({where})"


def unnamed(question: str, log: EventLog, task: Task) -> Explanation:
    """Whose words the line (or lines) the question points at are, for lines that name no node."""
    pointed = [ln for ln in pointed_lines(question, log, None, by_words=True) if not ln.name]
    # errors first, then the lines whose words a catalogue knows
    lines = pointed or sorted((ln for ln in log.logs if not ln.name),
                              key=lambda ln: (-ln.level, stack_catalogue().match(ln.msg) is None, ln.t))
    if not lines:
        text = "Every line of my log names the node that logged it; none is without a name."
        return Explanation(explainer="planner", text=text, causes=["planner.plan_ok"], enough_information=False)
    shown = sorted(lines[:SHOWN], key=lambda ln: ln.t)
    said = []
    for ln in shown:
        level = " (ERROR)" if ln.level >= ERROR else ""
        part = f"at {hms(ln.t)}{level} \"{' '.join(ln.msg.split())[:100]}\" names no node; {_whose(ln)}"
        at = next(i for i, b in enumerate(log.logs) if b is ln)
        named = next((b for b in reversed(log.logs[:at]) if b.name), None)
        if named is not None:
            part += f"; the nearest named line before it came from {named.name}"
        said.append(part)
    more = len(lines) - len(shown)
    text = "; ".join(said) + (f". {more} more line{'s' if more > 1 else ''} name no node." if more > 0 else ".")
    return Explanation(explainer="planner", text=text[0].upper() + text[1:], causes=["planner.plan_ok"],
                       evidence=line_evidence(shown, task))


__all__ = ["UNNAMED", "unnamed", "unnamed_kind"]
