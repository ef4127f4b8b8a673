"""The Nav2 message catalogue (nav2_catalogue.json): what a Nav2 line means and which cause it supports.

Lines are matched by their text, never dropped for an unknown logger; the logger's role (bt_navigator,
controller_server, ...) is looked up separately, across namespaces and the names of older distros. The file is
parsed once, on first use (JSON: a couple of milliseconds), and each pattern is compiled only when a line holds
its literal, so importing the explainer stays cheap.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cache, cached_property
from importlib import resources
from typing import Any

from hexar.explainers.errors import ExplainerError
from hexar.explainers.stack.catalogue import clean, unwrapped

END_KINDS = frozenset({"succeeded", "failed", "canceled"})
GOAL_KINDS = END_KINDS | {"begin"}
# every goal line of bt_navigator starts with one of these, in every distro: a cheap test before the catalogue's
GOAL_PREFIXES = ("Begin navigating", "Goal ", "Navigation ")
# entries read by id: the controller server's "Reached the goal!" (controller_server.cpp:411@humble), which ends a
# path it followed, and its "Unable to transform robot pose into global plan's frame" family
REACHED = "ctrl.reached"
TRANSFORM_PLAN = "ctrl.transform_plan"


class CatalogueError(ExplainerError):
    """nav2_catalogue.json is malformed."""


@dataclass(frozen=True)
class Entry:
    id: str
    role: str
    meaning: str
    cause: str | None
    kind: str
    strength: str
    distros: tuple[str, ...]
    source: str
    raw: str

    @cached_property
    def keys(self) -> tuple[str, ...]:
        return _keys(self.raw)

    @cached_property
    def pattern(self) -> re.Pattern[str]:
        # Compiled on first need: most patterns are never tried because their literal is absent.
        return re.compile(self.raw)

    def search(self, text: str) -> re.Match[str] | None:
        if self.keys and not any(k in text for k in self.keys):
            return None
        return self.pattern.search(text)


def _literal_runs(pattern: str) -> tuple[list[str], list[str]] | None:
    """(literal runs at depth 0, top-level alternatives), or None when the pattern holds a construct the
    scanner does not follow."""
    runs, alternatives, current, depth, start, i = [""], [], "", 0, 0, 0
    while i < len(pattern):
        ch = pattern[i]
        nxt = pattern[i + 1] if i + 1 < len(pattern) else ""
        if ch == "\\":
            literal = nxt if nxt and not nxt.isalnum() else None
            i += 2
        elif ch in "([":
            if ch == "[":
                close = pattern.find("]", i + 2)
                if close < 0:
                    return None
                i = close + 1
            else:
                depth += 1
                i += 1
            literal = None
        elif ch == ")":
            depth -= 1
            i += 1
            literal = None
        elif ch == "|" and depth == 0:
            alternatives.append(pattern[start:i])
            start = i + 1
            i += 1
            literal = None
        elif ch in ".^$*+?{}":
            literal = None
            i += 1
        else:
            literal = ch
            i += 1
        optional = i < len(pattern) and pattern[i] in "?*{"
        if literal is not None and depth == 0 and not optional:
            current += literal
        else:
            runs.append(current)
            current = ""
    runs.append(current)
    if alternatives:
        alternatives.append(pattern[start:])
    return runs, alternatives


def _keys(pattern: str) -> tuple[str, ...]:
    """Literals one of which every match contains (empty: no cheap test)."""
    scanned = _literal_runs(pattern)
    if scanned is None:
        return ()
    runs, alternatives = scanned
    if alternatives:
        keys = [_keys(alt) for alt in alternatives]
        return tuple(k for ks in keys for k in ks) if all(keys) else ()
    best = max(runs, key=len)
    if len(best) >= 4:
        return (best,)
    inner = pattern.strip("^$")
    if inner.startswith("(") and inner.endswith(")") and _balanced(inner[1:-1]):
        return _keys(inner[1:-1])
    return ()


def _balanced(text: str) -> bool:
    depth = 0
    for i, ch in enumerate(text):
        if ch == "\\" or (i and text[i - 1] == "\\"):
            continue
        depth += (ch == "(") - (ch == ")")
        if depth < 0:
            return False
    return depth == 0


def _distros(spec: Any, order: list[str]) -> tuple[str, ...]:
    if isinstance(spec, list):
        return tuple(str(d) for d in spec)
    text = str(spec)
    if text.endswith("+"):
        return tuple(order[order.index(text[:-1]):])
    if ".." in text:
        lo, hi = text.split("..")
        return tuple(order[order.index(lo):order.index(hi) + 1])
    return (text,)


class Catalogue:
    """The parsed catalogue: entries in file order and the logger-role table."""

    def __init__(self, raw: dict[str, Any]) -> None:
        try:
            self.distros: list[str] = list(raw["distros"])
            self._role_patterns: dict[str, list[str]] = {str(k): list(v) for k, v in raw["roles"].items()}
            self.entries: tuple[Entry, ...] = tuple(
                Entry(id=str(m["id"]), role=str(m["role"]), raw=str(m["pattern"]),
                      meaning=str(m["meaning"]), cause=m.get("cause"), kind=str(m.get("kind", "cause")),
                      strength=str(m.get("strength", "strong")), distros=_distros(m["distros"], self.distros),
                      source=str(m["source"]))
                for m in raw["messages"])
        except (KeyError, TypeError, ValueError, AttributeError) as err:
            raise CatalogueError(f"malformed Nav2 catalogue: {err}") from err
        self._role_cache: dict[str, str | None] = {}
        self._seen: dict[str, Entry | None] = {}

    @cached_property
    def _literals(self) -> list[tuple[str, int]]:
        """(literal, entry index) pairs: a line holding none of an entry's literals cannot match it. Built on
        first use, like each entry's regex, so that loading stays a parse."""
        return [(k, i) for i, e in enumerate(self.entries) for k in e.keys]

    @cached_property
    def _keyless(self) -> list[Entry]:
        return [e for e in self.entries if not e.keys]

    def match(self, msg: str) -> Entry | None:
        """The first entry with a cause whose pattern the message holds, else the first entry that matches."""
        if msg in self._seen:  # Nav2 repeats its lines (replanning at 1 Hz, recoveries, warnings in loops)
            return self._seen[msg]
        text = clean(msg)
        found = self._find(text)
        if found is None and (joined := unwrapped(text)) is not None:
            found = self._find(joined)
        if len(self._seen) > 20_000:
            self._seen.clear()
        self._seen[msg] = found
        return found

    def goal(self, msg: str) -> Entry | None:
        """The entry of bt_navigator's goal begin or end line, when the message is one. match() prefers a cause's
        entry, and Kilted's end line quotes the error ("Goal failed error_code:203 error_msg:'... Start Coordinates
        of(...) was outside bounds'"): that is still the goal's end."""
        if not msg.startswith(GOAL_PREFIXES):
            return None
        text = clean(msg)
        return next((e for e in self._candidates(text) if e.kind in GOAL_KINDS and e.search(text)), None)

    def _candidates(self, text: str) -> list[Entry]:
        """The entries the text can match, in file order: those whose literals it holds, and those without any."""
        hits = {i for k, i in self._literals if k in text}
        return [e for i, e in enumerate(self.entries) if i in hits or not e.keys] if hits else self._keyless

    def _find(self, text: str) -> Entry | None:
        return self._scan(text, self._candidates(text))

    @staticmethod
    def _scan(text: str, entries: Iterable[Entry]) -> Entry | None:
        first: Entry | None = None
        for entry in entries:
            if entry.search(text):
                if entry.cause is not None:
                    return entry  # e.g. a planner's exception text quoted inside "plugin failed to plan"
                first = first or entry
        return first

    @cached_property
    def _roles(self) -> list[tuple[str, re.Pattern[str]]]:
        return [(role, re.compile("|".join(pats))) for role, pats in self._role_patterns.items()]

    def role(self, logger: str) -> str | None:
        """The Nav2 role of a logger name, e.g. `robot1.controller_server` -> controller_server."""
        if logger in self._role_cache:
            return self._role_cache[logger]
        name = logger.strip("/")
        if name.endswith("_rclcpp_node"):
            # BT plugins log from `<navigator>_<action>_rclcpp_node`; the navigator is the one that runs them.
            name = "bt_navigator" if name.startswith(("bt_navigator", "navigate_")) else name[:-12]
        found = None
        candidates = [name, *re.split(r"[./]", name)[1:]]
        for candidate in candidates[:1] + candidates[:0:-1]:
            found = next((role for role, pat in self._roles if pat.search(candidate)), None)
            if found is not None:
                break
        self._role_cache[logger] = found
        return found

    def sizes(self) -> dict[str, dict[str, int]]:
        """Patterns per distro and role (for the report and the README)."""
        out: dict[str, dict[str, int]] = {d: {} for d in self.distros}
        for entry in self.entries:
            for distro in entry.distros:
                out[distro][entry.role] = out[distro].get(entry.role, 0) + 1
        return out


@cache
def catalogue() -> Catalogue:
    text = resources.files("hexar.explainers.navigation").joinpath("nav2_catalogue.json").read_text("utf-8")
    try:
        raw = json.loads(text)
    except json.JSONDecodeError as err:
        raise CatalogueError(f"malformed Nav2 catalogue: {err}") from err
    if not isinstance(raw, dict):
        raise CatalogueError("malformed Nav2 catalogue: not a mapping")
    return Catalogue(raw)
