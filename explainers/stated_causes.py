"""Causes a driver's or controller's error line states in standard words that no module catalogue holds.

A driver prints its own sentence ("System cannot communicate with servo motors. Error message: …") but the why in
it is often the C library's strerror text or a client library's wording, the same in every driver:
- strerror texts (explainers/stack/strerror.json, mined from glibc by scripts/mine_strerror.py): "Permission
  denied" is the operating system refusing the device (system.device_permission), "Address already in use" another
  program on the port (a set-up conflict), "Connection refused" a device that could not be reached (the hardware
  interface failed to reach it); "No such file or directory" names no single cause, so only its candidates are told;
- set-up words (explainers/stack/setup_phrases.json, each grounded in real source strings): a version that does not
  match, a parameter that is empty, missing, undeclared or of the wrong type, a driver's address it was never given;
- a device library's own result texts (the same file, kind `device`: the Dynamixel SDK's bus results), each with
  the cause it states, or none when it leaves several open (a servo that sends no status packet); a node's words
  for a file it could not open (kind `file`), which leave the path or the install open.

Such a text is a cause only on a decisive line: an ERROR or FATAL line, or the `what():` text of a C++ exception
that ended a process (launch prints it under the process's name, whatever the level of the line it follows), at or
before the failure. An INFO or WARN line with the same words states nothing (a healthy robot prints "Operation not
permitted" when it may not raise its thread priority), and a parameter line whose node goes on with a default
("Using default value") reports a fallback, not a failure.
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from hexar.events.records import ERROR, WARN, LogLine
from hexar.explainers.errors import ExplainerError
from hexar.explainers.logcause import Diagnosis, Reading, at
from hexar.explainers.stack.catalogue import clean

PERMISSION = "system.device_permission"
BRINGUP = "bringup.configuration_error"
CONTROL_SETUP = "control.configuration_error"
HARDWARE = "control.hardware_failure"
_THROWN = re.compile(r"^what\(\):\s*(?P<text>.+)$")
# an errno printed as its number alone ("open device error | device: /dev/ttyACM0, errno: 13"; "error number <13>")
_ERRNO_NUMBER = re.compile(r"\berrno\b\s*[:=]?\s*<?(?P<n>\d{1,3})\b|\berror number\s*<(?P<m>\d{1,3})>", re.I)
_PATH = re.compile(r"(?<![\w.:/])(/[\w.+-]+){2,}")
# the parameters a launch file hands a node (the robot description and its kinematics), never the node's own
_DESCRIPTION = re.compile(r"robot_description|kinematics|urdf|srdf", re.I)
# "the hardware interface": its logger (FrankaHardwareInterface, resource_manager's hardware) or the other side named
_HARDWARE_SIDE = re.compile(r"hardware|_hw$|driver", re.I)
_REMOTE = re.compile(r"\b(server|robot|firmware|controller box)\b", re.I)
_CONTROLLER_NAMED = re.compile(r"(?:Loading|Configuring|Activating) controller:? '(?P<name>[^']+)'")
_DEFAULT = re.compile(r"\bdefault\b", re.I)
_TYPE_HINT = {"array": " (a list in square brackets, not one value)", "double": " (a double written as 1.0, not 1)"}
_NAME_GROUPS = ("quoted", "named", "param", "description")
_MISSING_KINDS = ("parameter.empty", "parameter.cannot_be_empty", "parameter.not_initialized",
                  "parameter.not_declared", "parameter.not_found")


class StatedDataError(ExplainerError):
    """The strerror or set-up phrase data is missing or malformed."""


@dataclass(frozen=True)
class Phrase:
    """One standard text: a strerror (kind `errno`) or a set-up wording (kind `version`, `parameter`, `address`,
    `manifest`, `section`, `simulation` or `device`)."""

    id: str
    kind: str
    pattern: re.Pattern[str]
    cause: str | None = None  # strerror: the cause it states; None: candidates only
    meaning: str = ""
    fix: str = ""
    source: str = ""
    number: int | None = None  # an errno's Linux number

    def search(self, part: str) -> re.Match[str] | None:
        """Its words in the part, or (an errno) its number printed alone."""
        found = self.pattern.search(part)
        if found is not None or self.number is None:
            return found
        return next((m for m in _ERRNO_NUMBER.finditer(part) if int(m["n"] or m["m"]) == self.number), None)


def _read(name: str) -> dict[str, Any]:
    try:
        raw = json.loads(resources.files("hexar.explainers.stack").joinpath(name).read_text("utf-8"))
    except (OSError, json.JSONDecodeError) as err:
        raise StatedDataError(f"cannot read {name}: {err}") from err
    if not isinstance(raw, dict):
        raise StatedDataError(f"malformed {name}: not a mapping")
    return raw


@cache
def phrases() -> tuple[Phrase, ...]:
    """The strerror texts first (the most specific why), then the set-up wordings."""
    try:
        errnos = [Phrase(str(e["errno"]), "errno", re.compile(str(e["pattern"]), re.I), e.get("cause"),
                         str(e["meaning"]), str(e["fix"]), str(e["source"]),
                         None if e.get("number") is None else int(e["number"]))
                  for e in _read("strerror.json")["errnos"]]
        setup = [Phrase(str(p["id"]), str(p["kind"]), re.compile(str(p["pattern"]), re.I), p.get("cause"),
                        str(p.get("meaning") or ""), str(p.get("fix") or ""), "; ".join(p["sources"]))
                 for p in _read("setup_phrases.json")["phrases"]]
    except (KeyError, TypeError, re.error) as err:
        raise StatedDataError(f"malformed stated-cause data: {err}") from err
    return (*errnos, *setup)


@dataclass(frozen=True)
class Statement:
    """What a decisive line states: its cause (None: only candidates), in plain words, and the words it says it in."""

    line: LogLine
    part: str  # the part of the message that says it (a what() text of a multi-line message)
    phrase: Phrase
    cause: str | None
    meaning: str
    fix: str

    def reading(self) -> Reading:
        return Reading(self.line, None, self.cause, "stated", self.meaning)

    def quote(self, start: int) -> str:
        """The line quoted as the log's words, “[node] …”, with its time."""
        return f"“[{self.line.name or 'unnamed node'}] {_short(self.part)}” at {at(self.line, start)}"


def _short(text: str, limit: int = 200) -> str:
    """At most `limit` characters, cut after a sentence where one ends in time (a driver's advice follows its why)."""
    if len(text) <= limit:
        return text
    end = text.rfind(". ", 0, limit)
    return text[:end + 1] if end > limit // 3 else text[:limit] + "…"


def decisive_parts(line: LogLine, floor: int = ERROR) -> list[str]:
    """The parts of a line that can state a cause: all of a line at `floor` or above (ERROR, FATAL), and any
    exception's what() text."""
    out = []
    for part in (p.strip() for p in clean(line.msg).split("\n")):
        thrown = _THROWN.match(part)
        if thrown:
            out.append(thrown["text"].strip())
        elif part and line.level >= floor:
            out.append(part)
    return out


# A first line this short is a tag (the function that logs, "LdsLidar *GetInstance"), and its next line says what
# went wrong: both are quoted.
SHORT_TAG = 32


def quoted_part(line: LogLine) -> str:
    """The words to quote of a line: its what() text when a lower-level line carries an exception, else its first
    line (and the next after a short tag)."""
    parts = decisive_parts(line)
    first = [ln.strip() for ln in clean(line.msg).strip().splitlines() if ln.strip()]
    if parts and line.level < ERROR:
        return parts[0]
    if len(first) > 1 and len(first[0]) < SHORT_TAG:  # "LdsLidar *GetInstance\nparse summary info failed, ..."
        return f"{first[0]} {first[1]}"
    return first[0] if first else ""


def _param(m: re.Match[str]) -> str:
    """The parameter a set-up wording names, if it names one (a type mismatch names only the two types)."""
    return next((str(v) for k, v in m.groupdict().items() if v and k in _NAME_GROUPS), "")


def _setup(line: LogLine, part: str, phrase: Phrase, m: re.Match[str], prefix: str,
           controllers: frozenset[str]) -> tuple[str | None, str, str] | None:
    """(cause, meaning, fix) of a set-up wording, by who said it and what it names."""
    own = f"{prefix}configuration_error" if prefix in ("control.", "manipulation.") else BRINGUP
    if phrase.kind in ("device", "file"):  # a device library's words for the exchange that failed (Dynamixel SDK),
        # a node's for a file it could not open
        return (phrase.cause, phrase.meaning, phrase.fix)  # None: the words name only candidates
    if phrase.kind == "address":  # a driver's own words for an address it was never given (an empty parameter)
        who = line.name.strip("/").split("/")[-1] or "my driver"
        return (phrase.cause, f"{who} {phrase.meaning.removeprefix('it ')}", phrase.fix)
    if phrase.kind == "section":  # a node's own list of what one section of its configuration lacks
        from hexar.events.bringup import moveit_logger

        listed = ", ".join(p.strip(" '") for p in m["params"].split(",") if p.strip(" '"))
        own = "manipulation.configuration_error" if moveit_logger(line.name) else own  # MoveIt's own settings
        return (own, f"the settings under '{m['section']}' lack parameters it needs ({listed})", phrase.fix)
    if phrase.kind in ("manifest", "simulation"):  # pluginlib's unreadable manifest, a physics engine's lack: the
        # meaning names what the line names (its pattern's groups)
        return (own, phrase.meaning.format(**m.groupdict()), phrase.fix)
    if phrase.kind == "version":
        if _HARDWARE_SIDE.search(line.name) or _REMOTE.search(part):
            return (HARDWARE, "the version of my driver's library and the version of the robot's own software do "
                              "not match, a set-up to fix by updating one of them",
                    "Install the library version the robot's software supports (its compatibility table), or "
                    "update the robot's software.")
        return (own, "two of its software parts have versions that do not match",
                "Build or install matching versions of the packages the line names.")
    name = _param(m)
    node = line.name.strip("/").split("/")[-1]
    if phrase.id not in _MISSING_KINDS:  # it reached the node, with a wrong value or type
        if phrase.id == "parameter.type_mismatch":  # rclcpp's ParameterTypeException names the types only
            return (own, f"one of its parameters has a value of the wrong type ({m['expected']} expected, "
                         f"{m['actual']} given)",
                    f"Find the parameter the node reads as {m['expected']} in the YAML file that sets it and give "
                    f"it that type{_TYPE_HINT.get(m['expected'].split('_')[-1], '')}.")
        return (own, f"its parameter '{name}' has a value of the wrong type or out of its range",
                "Fix that parameter's value in the YAML file that sets it (a double written as 1.0, not 1).")
    if _DESCRIPTION.search(name) or not (prefix == "control." and (
            node in controllers or node.endswith(("controller", "broadcaster")))):
        return (BRINGUP, f"'{name}' was empty or missing when {node or 'the node'} needed it",
                "Pass that parameter to the node (its launch file, parameter file, namespace), or publish the "
                "robot description where the node reads it.")
    return (CONTROL_SETUP, f"its parameter '{name}' had no value, so its settings did not get to {node}",
            "Put the controller's parameters under its own name in the controllers YAML (joints, interfaces), "
            "at the level the controller manager reads.")


def _statement(line: LogLine, prefix: str, controllers: frozenset[str], floor: int = ERROR) -> Statement | None:
    for part in decisive_parts(line, floor):
        for phrase in phrases():
            if floor < ERROR and phrase.kind != "errno":
                continue
            m = phrase.search(part)
            if m is None:
                continue
            if phrase.kind != "errno":
                said = _setup(line, part, phrase, m, prefix, controllers)
                if said is not None:
                    return Statement(line, part, phrase, *said)
                continue
            if phrase.id == "EACCES" and any(not p[0].startswith("/dev/") for p in _PATH.finditer(part)):
                continue  # a file's permission, not a device's: a cause this project has no id for
            return Statement(line, part, phrase, phrase.cause, phrase.meaning, phrase.fix)
    return None


def stated_cause(lines: Sequence[LogLine], prefix: str, before: int | None = None) -> Statement | None:
    """The earliest decisive line at or before `before` that states a cause (or its candidates) in standard words."""
    ordered = sorted((ln for ln in lines if before is None or ln.t <= before), key=lambda ln: ln.t)
    controllers = frozenset(m["name"] for ln in ordered for m in _CONTROLLER_NAMED.finditer(ln.msg))
    for i, line in enumerate(ordered):
        found = _statement(line, prefix, controllers)
        if found is None:
            continue
        if found.phrase.kind == "parameter" and any(
                f.name == line.name and _DEFAULT.search(f.msg) for f in ordered[i + 1:i + 4]):
            continue  # the node goes on with a default value: a fallback, not the failure
        return found
    # else the first warning of the window, when it carries a strerror text: a driver that cannot open its device
    # may say so once at WARN and then only fail
    warning = next((ln for ln in ordered if ln.level == WARN), None)
    return _statement(warning, prefix, controllers, WARN) if warning is not None else None


def first_thrown(lines: Sequence[LogLine], before: int | None = None) -> LogLine | None:
    """The first line below ERROR that carries an exception's what() text: the error that ended a process, which a
    console prints behind the process's name at no level."""
    return next((ln for ln in sorted(lines, key=lambda ln: ln.t) if (before is None or ln.t <= before)
                 and ln.level < ERROR and any(_THROWN.match(p.strip()) for p in clean(ln.msg).split("\n"))), None)


def adopt(d: Diagnosis, found: Statement | None) -> None:
    """Rank a stated cause with the diagnosis's evidence: it decides when it is the earliest decisive line (or the
    only strong one) and no catalogue gave the same line a cause of its own; a text with only candidates is the
    first error to quote when nothing else explains."""
    if found is None:
        return
    if found.cause is None:
        if d.cause is None and (d.unknown is None or found.line.t <= d.unknown.t):
            d.unknown, d.candidates = found.line, found.meaning
        return
    decisive = d.decisive
    if decisive is not None and (decisive.line == found.line or (decisive.strong and decisive.line.t <= found.line.t)) \
            and not _why_of_transition(decisive, found):
        return  # a catalogue's own cause for this very line, or an earlier decisive line, says more
    prior = [decisive] if decisive is not None else []
    d.symptoms = [r for r in [*prior, *d.symptoms] if r.line.t >= found.line.t and r.line is not found.line][:2]
    d.cause, d.decisive, d.support = found.cause, found.reading(), []


def _why_of_transition(decisive: Reading, found: Statement) -> bool:
    """The stated cause is the "Original error: …" that rclcpp_lifecycle logs right after "Caught exception in
    callback for transition …" of the same node (lifecycle_node_interface_impl.cpp): the why of that failed
    transition, so it is the deeper link of the chain."""
    return (decisive.cause == "bringup.lifecycle_transition_failed" and found.line.name == decisive.line.name
            and found.part.startswith("Original error:") and 0 <= found.line.t - decisive.line.t <= 1_000_000_000)

CLAUSES = {
    PERMISSION: "the operating system denied my driver access to its device",
    CONTROL_SETUP: "a controller or its driver was set up wrongly",
    HARDWARE: "a hardware interface could not work with its device",
    BRINGUP: "a parameter never reached the node that needs it",
    "manipulation.configuration_error": "my motion planning system was set up wrongly",
}


def stated_words(d: Diagnosis, what: str, prefix: str, start: int) -> tuple[str, str | None, list[str]] | None:
    """(sentence, fix, details) when the decisive line states its cause in standard words; None otherwise."""
    r = d.decisive
    if r is None or r.catalogue != "stated" or d.cause not in CLAUSES:
        return None
    found = _statement(r.line, prefix, frozenset())
    if found is None:
        return None
    head = f"{what[:1].upper()}{what[1:]} failed because {CLAUSES[d.cause]}"
    text = f"{head}: {r.note}. The line that says so: {found.quote(start)}."
    details = [f"Its words are standard ones ({found.phrase.id}; {found.phrase.source.split(';')[0]})."]
    return text, found.fix, details
