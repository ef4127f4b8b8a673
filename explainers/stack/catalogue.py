"""The mined catalogue of the ROS 2 stack (stack_catalogue.json, written by scripts/mine_catalogue.py).

One entry per logged format string (WARN/ERROR/FATAL logging calls, thrown/raised exception texts, rcl error
messages) of the repositories and distro branches listed in sources.yaml:

    pattern  Python regex of the message: literal text escaped, each printf/`{}` field a lazy `.*?` (searched,
             not anchored: an exception text arrives wrapped in other messages, e.g. "Original error: <text>")
    text     the message as written, each field shown as `…`
    level    WARN | ERROR | FATAL (exception texts and rcl error messages: ERROR)
    form     log | throw | error_msg | reason (a string constant printed by a log call elsewhere)
    layer    nav2, rcl, rclcpp, lifecycle, tf, message_filters, launch, robot_localization, slam_toolbox, twist_mux,
             ros_gz
    package  the package folder it was read from
    source   file:line@branch (the newest branch that holds it)
    distros  the ROS 2 distros whose branch holds it
    role     cause (a line that can explain a failure) | symptom (what a failure produces; never told as its cause)
             | noise (printed by healthy systems too)
    cause    a stack-level cause id (stack.bringup_failure, stack.transform_error, ...) or null: for role `cause`,
             null means a decisive line whose meaning is not catalogued (quote it, do not interpret it)

Any explainer may load it (`stack_catalogue()`), match lines (`match`) and map the stack-level cause ids onto its own
cause words. Loading is a JSON parse; each pattern is compiled only when a line holds its longest literal.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cache, cached_property
from importlib import resources
from operator import itemgetter
from typing import Any

from hexar.explainers.stack.errors import StackCatalogueError

ROLES = ("cause", "symptom", "noise")
LEVELS = ("WARN", "ERROR", "FATAL")
FILE = "stack_catalogue.json"
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
# A message hard-wrapped onto indented lines (a terminal's or a document's paste, a logger that wraps) is read as
# one line: the mined literals hold spaces where the wrap put a line break.
_WRAP = re.compile(r"[ \t]*\r?\n[ \t]*")
# A message cut short is read as its entry only with this much of the entry's literal text (and this much of the
# piece it stops in): less would read any sentence that shares a few words with a mined message.
CUT_MIN_LITERAL = 30
CUT_MIN_TAIL = 4
_LITERAL = re.compile(r"(?:\\.|[^\\.*?()\[\]{}|+^$])+")
_ESCAPE = re.compile(r"\\(.)")
_FIELDS = frozenset({"pattern", "text", "level", "form", "layer", "package", "source", "distros", "role"})


@dataclass(frozen=True)
class StackEntry:
    """One mined format string (fields: see the module's docstring)."""

    pattern: str
    text: str
    level: str
    form: str
    layer: str
    package: str
    source: str
    distros: tuple[str, ...]
    role: str
    cause: str | None

    @cached_property
    def regex(self) -> re.Pattern[str]:
        return re.compile(self.pattern, re.S)

    @cached_property
    def key(self) -> str:
        """The pattern's longest literal run (unescaped): a message without it cannot match."""
        return literal_key(self.pattern)

    @cached_property
    def pieces(self) -> tuple[str, ...]:
        """The pattern's literal text between its fields (unescaped), in order."""
        return literal_pieces(self.pattern)

    def cut_match(self, text: str) -> bool:
        """Whether `text` is this message cut short (a console line pasted at its terminal's width, a note that
        stops mid-sentence): its literal pieces in order up to the cut, then the start of the next piece (at
        least CUT_MIN_TAIL characters of it), with at least CUT_MIN_LITERAL literal characters matched."""
        pieces = self.pieces
        at, matched = 0, 0
        for i, piece in enumerate(pieces):
            found = text.find(piece, at) if piece else at
            if found < 0 or (i == 0 and piece and found != text.find(piece)):
                if i == 0:
                    return False
                tail = cut_tail(text[at:].rstrip(" .…"), piece, max(CUT_MIN_TAIL, CUT_MIN_LITERAL - matched))
                return tail > 0
            at, matched = found + len(piece), matched + len(piece)
        return False

    @cached_property
    def specificity(self) -> int:
        """Letters and digits of the pattern's literal text: of two matching entries the more specific one is the
        reading (a helper's "[…] [ActionServer] …" frame says less than the "Aborting handle." it carries)."""
        return sum(ch.isalnum() for ch in re.sub(r"\.\*\?", "", self.pattern))


def cut_tail(rest: str, piece: str, least: int) -> int:
    """The longest start of `piece` (short of all of it, at least `least` characters) that `rest` ends with, in
    characters; 0 if none. Found where `rest` holds the first `least` characters, not by trying every length."""
    least = max(least, 1)
    if least > min(len(piece) - 1, len(rest)):
        return 0
    head = piece[:least]
    p = rest.find(head, max(0, len(rest) - (len(piece) - 1)))
    while 0 <= p <= len(rest) - least:
        if piece.startswith(rest[p:]):
            return len(rest) - p
        p = rest.find(head, p + 1)
    return 0


def _unescaped(text: str) -> str:
    # itemgetter(1) is the group itself, taken in C: a template ("\\1") is expanded in Python for each escape
    return _ESCAPE.sub(itemgetter(1), text) if "\\" in text else text


def literal_key(pattern: str) -> str:
    """A pattern's longest literal run (unescaped)."""
    return max((_unescaped(r) for r in _LITERAL.findall(pattern)), key=len, default="")


def literal_pieces(pattern: str) -> tuple[str, ...]:
    """A pattern's literal text between its fields (unescaped), in order."""
    return tuple(_unescaped(p) for p in pattern.split(".*?"))


def clean(msg: str) -> str:
    """The message without the ANSI colour codes the lifecycle manager wraps its lines in."""
    return _ANSI.sub("", msg) if "\x1b" in msg else msg


def unwrapped(text: str) -> str | None:
    """A message of several lines read as one (its line breaks as spaces), or None for a one-line message: the
    reading to try when its lines match nothing, so that a hard wrap does not hide a mined message."""
    return _WRAP.sub(" ", text) if "\n" in text else None


class Needles:
    """Strings to look for in a text, found without testing each one: indexed by their first GRAM characters, so
    a text is read once and only the strings starting somewhere in it are tested."""

    GRAM = 4

    def __init__(self, needles: Iterable[str]) -> None:
        self.needles = list(needles)
        self._starts: dict[str, list[int]] = {}
        self._short: list[int] = []  # shorter than a gram: always tested
        for n, needle in enumerate(self.needles):
            if len(needle) < self.GRAM:
                self._short.append(n)
            else:
                self._starts.setdefault(needle[: self.GRAM], []).append(n)

    def found_in(self, text: str) -> list[int]:
        """The positions, in order, of the strings `text` holds."""
        starts = self._starts
        tried = set(self._short)
        for i in range(len(text) - self.GRAM + 1):
            if (hit := starts.get(text[i : i + self.GRAM])) is not None:
                tried.update(hit)
        return [n for n in sorted(tried) if self.needles[n] in text]

    def starting_with(self, prefix: str) -> list[int]:
        """The positions, in order, of the strings that start with `prefix`."""
        tried = self._starts.get(prefix[: self.GRAM], []) if len(prefix) >= self.GRAM else range(len(self.needles))
        return [n for n in tried if self.needles[n].startswith(prefix)]


def _rank(e: StackEntry) -> tuple[bool, int]:
    return e.cause is not None, e.specificity


def _entry(raw: Any) -> StackEntry:
    entry = StackEntry(pattern=str(raw["pattern"]), text=str(raw["text"]), level=str(raw["level"]),
                       form=str(raw["form"]), layer=str(raw["layer"]), package=str(raw["package"]),
                       source=str(raw["source"]), distros=tuple(str(d) for d in raw["distros"]),
                       role=str(raw["role"]), cause=None if raw.get("cause") is None else str(raw["cause"]))
    if entry.role not in ROLES or entry.level not in LEVELS:
        raise ValueError(f"entry {entry.source}: role {entry.role!r} / level {entry.level!r}")
    return entry


class StackCatalogue:
    """The parsed catalogue, with a matcher that reads a message as its most specific entry."""

    def __init__(self, raw: Any) -> None:
        try:
            self.distros: tuple[str, ...] = tuple(raw["distros"])
            self.mined: tuple[str, ...] = tuple(raw["mined"])
            self._raw: list[Any] = list(raw["entries"])
            for e in self._raw:
                if not e.keys() >= _FIELDS:
                    raise KeyError(f"entry {e.get('source')} lacks {sorted(_FIELDS - e.keys())}")
                if e["role"] not in ROLES or e["level"] not in LEVELS:
                    raise ValueError(f"entry {e.get('source')}: role {e['role']!r} / level {e['level']!r}")
        except (KeyError, TypeError, ValueError, AttributeError) as err:
            raise StackCatalogueError(f"malformed stack catalogue: {err}") from err
        # An entry is built when a message holds its key (or it is asked for): a question reads a few dozen
        # lines, and building all five thousand is most of a cold start's catalogue time.
        self._built: dict[int, StackEntry] = {}
        self._seen: dict[str, StackEntry | None] = {}

    def _at(self, i: int) -> StackEntry:
        if (entry := self._built.get(i)) is None:
            try:
                entry = self._built[i] = _entry(self._raw[i])
            except (KeyError, TypeError, ValueError, AttributeError) as err:
                raise StackCatalogueError(f"malformed stack catalogue: {err}") from err
        return entry

    @cached_property
    def entries(self) -> tuple[StackEntry, ...]:
        return tuple(self._at(i) for i in range(len(self._raw)))

    @cached_property
    def _by_key(self) -> dict[str, list[int]]:
        out: dict[str, list[int]] = {}
        for i, e in enumerate(self._raw):
            # the miner stores each pattern's key ("key", literal_key of the pattern): computing five thousand of
            # them was a tenth of a cold `hexar ask`
            out.setdefault(str(e["key"]) if "key" in e else literal_key(str(e["pattern"])), []).append(i)
        return out

    @cached_property
    def _keys(self) -> tuple[Needles, list[list[int]]]:
        """The literal keys to look for, and the entries of each."""
        return Needles(self._by_key), list(self._by_key.values())

    @cached_property
    def _first_pieces(self) -> list[tuple[str, int]]:
        return [(_unescaped(str(e["pattern"]).split(".*?", 1)[0]), i) for i, e in enumerate(self._raw)]

    @cached_property
    def _first_needles(self) -> Needles:
        return Needles(first for first, _ in self._first_pieces)

    def _held(self, text: str) -> Iterable[int]:
        """The entries whose key `text` holds, in the catalogue's order of keys."""
        needles, entries = self._keys
        return (i for n in needles.found_in(text) for i in entries[n])

    def match(self, msg: str) -> StackEntry | None:
        """The entry whose pattern the message (ANSI colours removed) holds: one with a cause id before one without
        (an rcl parse error quoted inside "Couldn't parse params file: ..."), then the most specific; else the entry
        the message is a cut-short copy of (StackEntry.cut_match), or the whole first sentences of; else None."""
        if msg in self._seen:
            return self._seen[msg]
        text = clean(msg)
        best = self._best(text)
        if best is None and (joined := unwrapped(text)) is not None:
            best = self._best(joined)
        if best is None and len(text.rstrip(" .…")) >= CUT_MIN_LITERAL:
            pieces = self._first_pieces
            cut = [e for n in self._first_needles.found_in(text) if pieces[n][0]
                   if (e := self._at(pieces[n][1])).cut_match(text)]
            best = max(cut, key=_rank, default=None)
        if best is None and len(text) >= CUT_MIN_LITERAL and text.rstrip().endswith((".", "!")):
            # the message's first sentences alone: a console that broke the line after them (MPPI's "Inconsistent
            # configuration in collision checking." with its "Please verify ..." on a line of its own)
            said = text.strip()
            first = [self._at(self._first_pieces[n][1]) for n in self._first_needles.starting_with(f"{said} ")]
            best = max(first, key=_rank, default=None)
        if len(self._seen) > 20_000:
            self._seen.clear()
        self._seen[msg] = best
        return best

    def _best(self, text: str) -> StackEntry | None:
        best: StackEntry | None = None
        for i in self._held(text):
            e = self._at(i)
            if (best is None or _rank(e) > _rank(best)) and e.regex.search(text):
                best = e
        return best

    def matches(self, msg: str) -> list[StackEntry]:
        """Every entry the message holds, best reading first (a message may quote several: an exception's text
        inside the line that caught it)."""
        text = clean(msg)
        found = [e for i in self._held(text) if (e := self._at(i)).regex.search(text)]
        return sorted(found, key=_rank, reverse=True)

    def with_cause(self, cause: str) -> list[StackEntry]:
        return [e for e in self.entries if e.cause == cause]

    def layers(self) -> dict[str, int]:
        out: dict[str, int] = {}
        for e in self.entries:
            out[e.layer] = out.get(e.layer, 0) + 1
        return out


def load(text: str) -> StackCatalogue:
    """A catalogue from its JSON text (StackCatalogueError when it is not one)."""
    try:
        raw = json.loads(text)
    except json.JSONDecodeError as err:
        raise StackCatalogueError(f"malformed stack catalogue: {err}") from err
    return StackCatalogue(raw)


@cache
def stack_catalogue() -> StackCatalogue:
    """The catalogue shipped with HEXAR (parsed once)."""
    return load(resources.files("hexar.explainers.stack").joinpath(FILE).read_text("utf-8"))


def compile_all(entries: Iterable[StackEntry]) -> list[str]:
    """The sources of entries whose pattern does not compile (empty when all do)."""
    bad = []
    for e in entries:
        try:
            re.compile(e.pattern)
        except re.error:
            bad.append(e.source)
    return bad
