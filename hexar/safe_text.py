"""The one output layer for recorded text: nothing a robot recorded reaches a terminal, file or page raw.

A recording is written by whoever can publish on the robot, so its strings are untrusted: an escape sequence in
a log line can recolour the terminal, set its title or (OSC 52) write the user's clipboard, and rich markup such
as `[/]` breaks or restyles the output. Every command prints recorded strings through these functions:

- `visible(text)`: control characters, escape sequences, bidirectional overrides and lone surrogates become their
  visible escapes (`\\x1b[31m`), for plain `print`, files and web pages (which escape HTML on top);
- `safe(text)`: `visible` plus rich markup escaped, for anything handed to a rich Console, Table or Panel;
- `json_dumps(obj)`: strict JSON (`allow_nan=False`); a non-finite number becomes null and the enclosing
  top-level object gets a `warnings` entry naming where it was; with `clean=True` (the page, MCP,
  /hexar/answer) every string in it goes through `visible` (newlines kept), so the VALUES another program
  parses (a dashboard, a robot's TTS, an MCP client) hold no escape sequence or bidi override either.

This module imports nothing heavy, so a web page or a live node can use it without the CLI.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

# Every character of Unicode 14's categories Cc (C0/C1 controls, DEL), Cf (invisible format characters that
# reorder or hide text: bidi overrides, zero-width, tag characters), Cs (lone surrogates, which cannot even be
# encoded for a UTF-8 terminal), Zl and Zp (line/paragraph separators); newline is added or not per call.
_UNSAFE = re.compile(
    "[\x00-\x09\x0b-\x1f\x7f-\x9f\xad\u0600-\u0605\u061c\u06dd\u070f\u0890-\u0891\u08e2\u180e\u200b-\u200f"
    "\u2028-\u202e\u2060-\u2064\u2066-\u206f\ud800-\udfff\ufeff\ufff9-\ufffb\U000110bd\U000110cd"
    "\U00013430-\U00013438\U0001bca0-\U0001bca3\U0001d173-\U0001d17a\U000e0001\U000e0020-\U000e007f]"
)
_UNSAFE_WITH_NEWLINE = re.compile(_UNSAFE.pattern.replace("\x0b", "\x0a\x0b", 1))
_MARKUP = re.compile(r"(\\*)(\[[a-z#/@][^[]*?])")
_NAMED = {"\n": "\\n", "\t": "\\t", "\r": "\\r"}


def _escape_char(m: re.Match[str]) -> str:
    ch = m.group(0)
    named = _NAMED.get(ch)
    if named is not None:
        return named
    code = ord(ch)
    return f"\\x{code:02x}" if code <= 0xFF else (f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}")


def visible(text: object, keep_newlines: bool = False) -> str:
    """`text` with every control or invisible character shown as its escape; newlines kept only if asked."""
    s = text if isinstance(text, str) else str(text)
    pattern = _UNSAFE if keep_newlines else _UNSAFE_WITH_NEWLINE
    return pattern.sub(_escape_char, s)


def escape_markup(text: str) -> str:
    """Rich markup shown literally: `[bold]` prints as `[bold]`, `[/]` no longer closes a style."""
    # The same rule as rich.markup.escape, kept here so that this module needs no rich import.
    out = _MARKUP.sub(lambda m: f"{m.group(1)}{m.group(1)}\\{m.group(2)}", text)
    if out.endswith("\\") and not out.endswith("\\\\"):
        out += "\\"
    return out


def clip(text: str, limit: int = 300) -> str:
    """At most `limit` characters for a table or a heading, with the length of what was left out: a
    recorded 10 MB instruction is shown as its start, not wrapped into 100,000 terminal lines."""
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text) - limit} more characters)"


def safe(text: object, keep_newlines: bool = False) -> str:
    """Recorded text ready for a rich Console, Table or Panel: controls visible and markup escaped."""
    return escape_markup(visible(text, keep_newlines))


def finite(obj: Any, where: str = "", found: list[str] | None = None, clean: bool = False) -> Any:
    """A copy of `obj` with NaN and infinities replaced by None (their paths appended to `found`); with `clean`
    every string, keys included, made `visible` with its newlines kept."""
    if isinstance(obj, str):
        return visible(obj, keep_newlines=True) if clean else obj
    if isinstance(obj, float):
        if math.isfinite(obj):
            return obj
        if found is not None:
            found.append(f"{where or 'value'} was {obj!r}")
        return None
    if isinstance(obj, dict):
        return {finite(k, clean=clean): finite(v, f"{where}.{k}" if where else str(k), found, clean)
                for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [finite(v, f"{where}[{i}]", found, clean) for i, v in enumerate(obj)]
    return obj


def finite_with_warnings(obj: Any, clean: bool = False) -> Any:
    """`finite(obj)`; a dict also gets a `warnings` entry for each non-finite number replaced."""
    found: list[str] = []
    out = finite(obj, "", found, clean)
    if found and isinstance(out, dict):
        notes = [f"non-finite number replaced by null: {visible(f)}" for f in found]
        old = out.get("warnings")
        out["warnings"] = [*old, *notes] if isinstance(old, list) else notes
    return out


def json_dumps(obj: Any, indent: int | None = None, clean: bool = False) -> str:
    """Strict JSON of `obj`: never NaN or Infinity; a list's objects get their own `warnings`. `clean` for JSON
    that leaves HEXAR to be read by others (the page, MCP, /hexar/answer): string values made `visible` too.
    Without it (`--json`, the dialogue log) strings stay exact: JSON escapes every control character."""
    out = ([finite_with_warnings(v, clean) for v in obj] if isinstance(obj, list | tuple)
           else finite_with_warnings(obj, clean))
    return json.dumps(out, indent=indent, allow_nan=False, default=str)
