"""The sentences of the arm's log explainers (manipulation, control), one table per module: (clause, fix) per cause.

A clause follows the module's head ("I couldn't finish picking up the cup because", "My controllers could not
run because"); `{meaning}` in it stands for what the decisive line means (its catalogue entry's meaning when that
entry states this very cause, else the table's default), so a general cause such as a configuration error is told
in the words of the line that showed it. Every answer quotes the decisive line in its details.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from hexar.explainers.logcause import Diagnosis, said

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

    def __call__(self, cause: str, d: Diagnosis, what: str) -> Worded:
        if cause.endswith(".nominal") and self.nominal is not None:
            return self.nominal(what)
        seen = [f"{self.quoted_by} said: '{said(d.decisive.line)}'"] if d.decisive is not None else []
        head = self.head.format(what=what)
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
        if own and "{meaning}" not in clause:
            seen.append(f"That line means: {own}.")
        return f"{head} {clause.format(meaning=own or self.meanings.get(cause, ''))}", fix, seen
