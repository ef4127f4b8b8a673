"""The sentences of the arm's log explainers (manipulation, control), one table per module: (clause, fix) per cause.

A clause follows the module's head ("I couldn't finish picking up the cup because", "My controllers could not
run because"); `{meaning}` in it stands for what the decisive line means (its catalogue entry's meaning when that
entry states this very cause, else the table's default), so a general cause such as a configuration error is told
in the words of the line that showed it. Every answer quotes the decisive line in its details, the way `verbatim`
sets a line apart from the answer's own words.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from hexar.events.records import ERROR, WARN, LogLine
from hexar.explainers.logcause import Diagnosis, at, said
from hexar.explainers.stated_causes import quoted_part

Worded = tuple[str, str | None, list[str]]


@dataclass(frozen=True)
class Wording:
    head: str  # with {what}, the step: "I couldn't finish {what} because"
    quoted_by: str  # "MoveIt", "ros2_control"
    clauses: Mapping[str, tuple[str, str]]  # cause -> (clause, fix)
    meanings: Mapping[str, str] = field(default_factory=dict)  # cause -> {meaning} when the line has none
    nominal: Callable[[str], Worded] | None = None
    # causes whose {meaning} comes only from a code-built note (a refinement): their entries' meanings restate the
    # clause ("a controller could not be activated (...)"), so a line without a note takes the default
    notes_only: frozenset[str] = frozenset()
    # causes that strike once the step is under way, with their own head ("{what} could not go on because")
    heads: Mapping[str, str] = field(default_factory=dict)
    # cause -> (the start of a line's meaning, clause, fix): such a line is told with its own clause ("a trajectory
    # the controller rejected" is the sender's set-up, not the controller's)
    by_meaning: Mapping[str, tuple[str, str, str]] = field(default_factory=dict)

    def __call__(self, cause: str, d: Diagnosis, what: str) -> Worded:
        if cause.endswith(".nominal") and self.nominal is not None:
            return self.nominal(what)
        seen = [f"{self.quoted_by} said: '{said(d.decisive.line)}'"] if d.decisive is not None else []
        head = self.heads.get(cause, self.head).format(what=what)
        head = head[:1].upper() + head[1:]
        if cause not in self.clauses:
            return f"{head} of a problem my logs name ({cause}).", None, seen
        clause, fix = self.clauses[cause]
        entry = d.decisive.entry if d.decisive is not None else None
        own = entry.meaning if entry is not None and entry.cause == cause else ""
        if d.decisive is not None and d.decisive.note and d.decisive.cause == cause:
            own = d.decisive.note  # a code-built text in the line says more than the line's mined entry
        elif cause in self.notes_only:
            own = ""
        if cause in self.by_meaning and own.startswith(self.by_meaning[cause][0]):
            prefix, clause, fix = self.by_meaning[cause]
            own = own.removeprefix(prefix).lstrip(": ")
        if own and "{meaning}" not in clause:
            seen.append(f"That line means: {own}.")
        return f"{head} {clause.format(meaning=own or self.meanings.get(cause, ''))}", fix, seen


def verbatim(line: LogLine) -> str:
    """A log line quoted in an answer's sentence: its first line, set in “…” behind its node, so that a reader (and
    hexar/claims.py) takes its words as the log's, never as the answer's claim ("operation time out" on a lidar's
    line is no text-to-speech timeout)."""
    return f"“[{line.name or 'unnamed node'}] {quoted_part(line)[:200]}”"


def warned_on_the_way(lines: Sequence[LogLine], start: int) -> str:
    """'My logs show a warning on the way, which did not stop it: “[node] …” at 3.0 s (3 like it).' for the last
    warning or error of the module's own lines (not Nav2's), quoted; "" when there is none."""
    warned = [ln for ln in lines if ln.level >= WARN and not nav2_logger(ln)]
    if not warned:
        return ""
    last = warned[-1]
    alike = sum(1 for ln in warned if ln.name == last.name and _shape(ln.msg) == _shape(last.msg))
    kind = "an error" if last.level >= ERROR else "a warning"
    return (f"My logs show {kind} on the way, which did not stop it: {verbatim(last)} at {at(last, start)}"
            + (f" ({alike} like it)." if alike > 1 else "."))


def _shape(msg: str) -> str:
    """A line with its numbers left out: a warning repeated with new figures is the same warning."""
    return "".join("#" if ch.isdigit() else ch for ch in msg.strip())


def nav2_logger(line: LogLine) -> bool:
    """A line of a Nav2 node (by its logger's role): navigation's, whatever its words."""
    from hexar.explainers.navigation.catalogue import catalogue as nav2

    return nav2().role(line.name) is not None
