"""Evidence-ranked diagnosis over a mined module catalogue (MoveIt 2, ros2_control): the earliest decisive line.

Every line is read by its text through the module's catalogue (navigation's matcher: literal prefilter, lazy
regexes). A line states a cause (`kind: cause`), is a symptom (`kind: symptom`: "MoveGroupInterface::move()
failed or timeout reached", "Controller '…' failed with error …"), or is goal bookkeeping. The decision:
1. the earliest strong cause line; then the earliest weak one (a warning many healthy robots print);
2. else a symptom whose own words name a cause (an error code such as NO_IK_SOLUTION in it);
3. else the earliest ERROR/FATAL line that no catalogue explains, quoted with its node and time: an honest
   partial answer, never a guess; symptoms are never told as the cause when a decisive line precedes them.
Error-code names and texts built in code (`refinements`) refine a line's cause: "Planner '…' failed with error
code NO_IK_SOLUTION" is an IK failure, a state monitor whose latest state has time 0.000000 never got one.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, Literal

from hexar.events.records import ERROR, LogLine
from hexar.explainers.errors import ExplainerError
from hexar.explainers.navigation.catalogue import Catalogue, Entry
from hexar.explainers.stack.catalogue import clean

Outcome = Literal["succeeded", "failed", "canceled", "unknown"]
_SPACED = re.compile(r"[ \t]+([:;,])")
_CODE = re.compile(r"\b[A-Z][A-Z_]{5,}\b")
_NUMBER = re.compile(r"\d+(?:\.\d+)?")
GENERIC = frozenset({"manipulation.planning_failed"})


class ModuleCatalogueError(ExplainerError):
    """A mined module catalogue is missing or malformed."""


@dataclass(frozen=True)
class Refinement:
    contains: str
    cause: str
    source: str
    meaning: str = ""
    also: str = ""  # words the line must hold too: the library's name in a stack trace is no failure to load it
    # a number the line must give, right after these words, and its least value: diff_drive_controller's command
    # "older than the current time by 78786503.02 seconds" is another clock's, where 0.6 s may be a late message
    number_after: str = ""
    at_least: float = 0.0

    def applies(self, text: str) -> bool:
        if self.contains not in text or self.also not in text:
            return False
        if not self.number_after:
            return True
        _, found, rest = text.partition(self.number_after)
        m = _NUMBER.match(rest) if found else None
        return m is not None and float(m[0]) >= self.at_least


@dataclass(frozen=True)
class Mined:
    """What the miner recorded of an entry beyond what matching needs: its level and text, and for a line of a
    hardware class the callbacks that log it and the role they give it (explainers/control/driver_roles.py)."""

    level: str
    text: str
    hw_role: str | None = None
    functions: tuple[str, ...] = ()


class ModuleCatalogue(Catalogue):
    """A mined catalogue: messages (pattern, level, package, file:line@branch, kind, cause) plus the error-code
    names and code-built texts that name a cause, and the hardware roles of its drivers' callbacks."""

    def __init__(self, raw: dict[str, Any], name: str) -> None:
        try:
            super().__init__(raw)
            self.name = name
            self.error_codes: dict[str, str] = {str(k): str(v) for k, v in (raw.get("error_codes") or {}).items()}
            self.refinements = tuple(Refinement(str(r["contains"]), str(r["cause"]), str(r["source"]),
                                                str(r.get("meaning") or ""), str(r.get("also") or ""),
                                                str(r.get("number_after") or ""), float(r.get("at_least") or 0.0))
                                     for r in raw.get("refinements") or [])
            # kept from this one parse, so that no reader parses the file again for them
            self.mined: dict[str, Mined] = {
                str(m["id"]): Mined(str(m.get("level") or ""), str(m.get("text") or ""),
                                    None if m.get("hw_role") is None else str(m["hw_role"]),
                                    tuple(str(f) for f in m.get("functions") or ()))
                for m in raw["messages"]}
            self.hardware_roles: dict[str, Any] = dict(raw.get("hardware_roles") or {})
        except (ExplainerError, KeyError, TypeError, AttributeError, ValueError) as err:
            raise ModuleCatalogueError(f"malformed catalogue {name}: {err}") from err

    @staticmethod
    def _scan(text: str, entries: Iterable[Entry]) -> Entry | None:
        """The first matching entry with a cause, else the first the curated rules classified (a symptom, a goal
        line), else the first: "Waiting for data on 'robot_description' topic" is its own symptom, not the wider
        "Waiting for …" that also matches it."""
        kept: Entry | None = None
        for entry in entries:
            if entry.search(text):
                if entry.cause is not None:
                    return entry
                if kept is None or (kept.kind == "other" and entry.kind != "other"):
                    kept = entry
        return kept

    def match(self, msg: str) -> Entry | None:
        """The message's entry; for a multi-line message that matches nothing whole, its first line that does (a
        console may print a logger's header and its message on separate lines, and launch prints each line of a
        message behind its own prefix)."""
        found = super().match(msg)
        if found is None and _SPACED.search(msg):
            # releases moved the spaces around a message's punctuation ("an error : [" in the July 2024 commit of
            # ros2_control PR 1645, "an error: [" in controller_manager.cpp:3293@jazzy): the words decide
            found = super().match(_SPACED.sub(r"\1", msg))
        if found is not None or "\n" not in msg:
            return found
        for part in msg.split("\n"):
            if part.strip() and part.strip() != msg:
                found = super().match(part.strip())
                if found is not None:
                    return found
        return None

    def refinement(self, msg: str) -> Refinement | None:
        """The code-built text in the line, if any."""
        text = clean(msg)
        return next((r for r in self.refinements if r.applies(text)), None)

    def cause_of(self, msg: str, entry: Entry | None) -> str | None:
        """The cause a line states: a code-built text or an error-code name in it first, else its entry's."""
        text = clean(msg)
        refined = self.refinement(msg)
        if refined is not None:
            return refined.cause
        # a code refines a line that names no cause of its own, or only the pipeline's generic failure ("Planner
        # 'ompl' failed with error code NO_IK_SOLUTION" is an IK failure, not any planning failure)
        if self.error_codes and (entry is None or entry.kind != "cause" or entry.cause in GENERIC):
            for code in _CODE.findall(text):
                if code in self.error_codes:
                    return self.error_codes[code]
        return entry.cause if entry is not None else None


def load(package: str, filename: str) -> ModuleCatalogue:
    try:
        text = resources.files(package).joinpath(filename).read_text("utf-8")
        raw = json.loads(text)
    except (OSError, json.JSONDecodeError) as err:
        raise ModuleCatalogueError(f"cannot read catalogue {filename}: {err}") from err
    if not isinstance(raw, dict):
        raise ModuleCatalogueError(f"malformed catalogue {filename}: not a mapping")
    return ModuleCatalogue(raw, filename)


@dataclass(frozen=True)
class Reading:
    """One line and what a catalogue says of it."""

    line: LogLine
    entry: Entry | None
    cause: str | None
    catalogue: str | None  # the catalogue that recognised it
    note: str = ""  # what a code-built text in it means (a refinement's meaning)
    refined: bool = False  # a code-built text in it states its cause, whatever its entry's strength

    @property
    def kind(self) -> str:
        return self.entry.kind if self.entry is not None else "unknown"

    @property
    def strong(self) -> bool:
        return self.entry is None or self.entry.strength == "strong"


def own_catalogue(line: LogLine, catalogues: Sequence[ModuleCatalogue]) -> ModuleCatalogue | None:
    """The one catalogue of `catalogues` whose module the line's logger belongs to (a role in it), when it knows the
    line's text: that catalogue alone reads the line, cause or not (a spawner's "Controller : … parameters not found
    in parameter file" is ros2_control's, however MoveIt's looser "Controller … not found" also matches it)."""
    own = [cat for cat in catalogues if line.name and cat.role(line.name) is not None]
    return own[0] if len(own) == 1 and own[0].match(line.msg) is not None else None


def read(lines: Iterable[LogLine], catalogues: Sequence[ModuleCatalogue]) -> list[Reading]:
    """Each line with the first catalogue that recognises it (the order of `catalogues` is the explainer's
    own module first), or its logger's own module's catalogue alone (`own_catalogue`)."""
    out = []
    for line in lines:
        found: Reading | None = None
        own = own_catalogue(line, catalogues)
        for cat in (own,) if own is not None else catalogues:
            entry = cat.match(line.msg)
            cause = cat.cause_of(line.msg, entry)
            if entry is not None or cause is not None:
                refined = cat.refinement(line.msg)
                found = Reading(line, entry, cause, cat.name, refined.meaning if refined is not None else "",
                                refined is not None)
                if cause is not None:
                    break
        out.append(found or Reading(line, None, None, None))
    return out


@dataclass
class Diagnosis:
    """What the window's lines say: the decisive line and its cause, the symptoms told after it, or the first
    error no catalogue explains."""

    outcome: Outcome
    cause: str | None = None
    decisive: Reading | None = None
    support: list[Reading] = field(default_factory=list)
    symptoms: list[Reading] = field(default_factory=list)
    unknown: LogLine | None = None
    end: LogLine | None = None
    candidates: str = ""  # what the unknown line's standard words leave open (explainers/stated_causes.py)


GOAL_END = {"succeeded": "succeeded", "failed": "failed", "canceled": "canceled"}


def outcome_of(readings: Sequence[Reading], state: str | None) -> tuple[Outcome, LogLine | None]:
    """How the goal ended: its last end line, else the skill's status."""
    ends = [r for r in readings if r.kind in GOAL_END or r.kind == "end_server"]
    if ends:
        last = ends[-1]
        if last.kind == "end_server":
            status = last.line.msg.rsplit(":", 1)[-1].strip()
            return ("succeeded" if status == "SUCCEEDED" else "failed"), last.line
        return GOAL_END[last.kind], last.line  # type: ignore[return-value]
    if state in {"succeeded", "failed", "canceled"}:
        return state, None  # type: ignore[return-value]
    return "unknown", None


def diagnose(readings: Sequence[Reading], state: str | None) -> Diagnosis:
    """The decision of the module docstring (a control cause seen by the manipulation explainer is still the
    decisive line: the explainer then asks control)."""
    outcome, end = outcome_of(readings, state)
    found = Diagnosis(outcome, end=end)
    causes = [r for r in readings if r.cause is not None and r.kind not in {"symptom"}]
    strong = [r for r in causes if r.strong and (r.kind == "cause" or r.entry is None or r.kind == "other")]
    weak = [r for r in causes if r not in strong]
    symptoms = [r for r in readings if r.kind in {"symptom", "failed"} or (r.kind == "end_server" and outcome
                                                                                == "failed")]
    decisive = (strong or weak or [r for r in readings if r.kind == "symptom" and r.cause is not None
                                   and r.cause != (r.entry.cause if r.entry else None)])
    if decisive:
        first = decisive[0]
        found.decisive, found.cause = first, first.cause
        found.support = [r for r in causes if r.cause == first.cause and r is not first][:3]
        found.symptoms = [r for r in symptoms if r.line.t >= first.line.t and r is not first][:2]
        return found
    found.symptoms = symptoms[:2]
    explained = {id(r.line) for r in readings if r.entry is not None and r.kind != "other"}
    unknown = [r.line for r in readings if r.line.level >= ERROR and id(r.line) not in explained
               and r.kind not in {"symptom", "failed"}]
    found.unknown = unknown[0] if unknown else None
    # a plain symptom with a weak cause of its own (e.g. "move() failed") is kept for the wording, not claimed
    return found


def said(line: LogLine) -> str:
    """A line as a person reads it quoted: '[node] msg' at its time."""
    who = f"[{line.name}] " if line.name else ""
    return f"{who}{clean(line.msg).strip()}"


def at(line: LogLine, start: int) -> str:
    """The line's time, in seconds after `start` (the recording's or the task's start)."""
    return f"{max(line.t - start, 0) / 1e9:.1f} s"
