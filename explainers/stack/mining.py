"""Reading logged format strings out of C, C++ and Python source text (the parser behind scripts/mine_catalogue.py).

A call is found by its macro or method name (RCLCPP_ERROR, RCLCPP_WARN_THROTTLE, RCUTILS_LOG_ERROR_NAMED,
RCL_SET_ERROR_MSG_WITH_FORMAT_STRING, `throw X(...)`, `logger.error(...)`, `raise X(...)`, gzerr << ...), then read
to its closing parenthesis (or `;` for stream forms) across lines, with string literals, character literals and
comments skipped. The format argument becomes a regex: its literal text escaped, every printf/`{}` field and every
non-literal piece (a variable streamed or added in) a lazy wildcard.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

LEVELS = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")
# How many leading arguments of a logging macro come before its format (logger, clock, period, condition...).
_CPP_CALL = re.compile(
    r"\b(?P<macro>RCLCPP_(?P<l1>DEBUG|INFO|WARN|ERROR|FATAL)(?P<s1>_\w+)?"
    r"|RCUTILS_LOG_(?P<l2>DEBUG|INFO|WARN|ERROR|FATAL)(?P<s2>_\w+)?"
    r"|(?:RCL|RCUTILS|RMW)_SET_ERROR_MSG(?:_WITH_FORMAT_STRING)?"
    r"|throw\s+(?:[\w:]+(?:<[^<>;]*>)?)"
    r"|(?:gz|ign)(?P<l3>err|warn))\s*(?P<open>\(|\{|<<)")
_PY_CALL = re.compile(
    r"(?:\b\w*logger\w*(?:\(\))?|\blogging)\.(?P<lvl>warn|warning|error|fatal|critical|exception)\s*\("
    r"|\braise\s+[\w.]+\s*\("
    # an exception class that words its message where it is defined (rclpy's InvalidParameterTypeException:
    # `ParameterException.__init__(self, f"Trying to set parameter …")`): raised wherever, its text is here
    r"|\b\w*(?:Exception|Error)\.__init__\s*\(\s*self\s*,")
_PRINTF = re.compile(r"%[-+ #0]*(?:\d+|\*)?(?:\.(?:\d+|\*))?(?:hh|h|ll|l|L|z|j|t|q)?[diouxXeEfgGcspaA]")
_PYFIELD = re.compile(r"\{[^{}]*\}|%[-+ #0]*\d*(?:\.\d+)?[sdrfgixXeE]")
_ESCAPES = {"n": "\n", "t": "\t", "r": "", "\\": "\\", '"': '"', "'": "'", "0": ""}
WILD = "\x00"  # a field or a non-literal piece, later a lazy wildcard


@dataclass(frozen=True)
class Call:
    """One logging or throwing call: where it starts, its level, its form, and its message as literal/WILD text."""

    line: int
    level: str
    form: str  # log | throw | error_msg
    text: str  # literal text with WILD for every field


def _skip_string(src: str, i: int) -> tuple[int, str]:
    """From the opening quote at i: (index after the closing quote, decoded literal text)."""
    quote = src[i]
    triple = src[i:i + 3] in ('"""', "'''")
    end_mark = src[i:i + 3] if triple else quote
    i += 3 if triple else 1
    out: list[str] = []
    while i < len(src):
        if src.startswith(end_mark, i):
            return i + len(end_mark), "".join(out)
        ch = src[i]
        if ch == "\\" and i + 1 < len(src):
            nxt = src[i + 1]
            out.append(_ESCAPES.get(nxt, nxt if not nxt.isalnum() else WILD))
            i += 2
            continue
        if ch == "\n" and not triple:
            return i, "".join(out)  # an unterminated literal: stop at the line end
        out.append(ch)
        i += 1
    return i, "".join(out)


def _tokens(src: str, start: int, stop_at_semicolon: bool) -> tuple[list[tuple[str, str]], int]:
    """Top-level tokens of a call's argument list from `start` (just after its opener): ("str", text),
    ("comma", ","), ("other", text). Stops at the matching close (or `;` for stream forms)."""
    toks: list[tuple[str, str]] = []
    depth, i = 0, start
    other: list[str] = []

    def flush() -> None:
        if "".join(other).strip():
            toks.append(("other", "".join(other).strip()))
        other.clear()

    while i < len(src):
        ch = src[i]
        if src.startswith("//", i):
            i = src.find("\n", i)
            i = len(src) if i < 0 else i
            continue
        if src.startswith("/*", i):
            j = src.find("*/", i + 2)
            i = len(src) if j < 0 else j + 2
            continue
        if ch in "\"'":
            prefix = "".join(other).rstrip()
            fstring = bool(re.search(r"(?<![\w])[fF][rR]?$|(?<![\w])[rR][fF]$", prefix))
            if prefix[-1:] in "fFrRbBuUL8" and re.search(r"(?<![\w])(?:[fFrRbBuU]{1,2}|L|u8)$", prefix):
                other[:] = list(re.sub(r"(?:[fFrRbBuU]{1,2}|L|u8)$", "", prefix))
            i, text = _skip_string(src, i)
            if depth == 0:
                flush()
                if fstring:
                    text = re.sub(r"\{[^{}]*\}", WILD, text)
                toks.append(("str", text))
            else:
                other.append('"..."')
            continue
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            if depth == 0:
                flush()
                return toks, i
            depth -= 1
        elif ch == "," and depth == 0:
            flush()
            toks.append(("comma", ","))
            i += 1
            continue
        elif ch == ";" and depth == 0 and stop_at_semicolon:
            flush()
            return toks, i
        other.append(ch)
        i += 1
    flush()
    return toks, i


def _args(toks: list[tuple[str, str]]) -> list[list[tuple[str, str]]]:
    out: list[list[tuple[str, str]]] = [[]]
    for kind, text in toks:
        if kind == "comma":
            out.append([])
        else:
            out[-1].append((kind, text))
    return out


def _message(arg: list[tuple[str, str]], fields: re.Pattern[str]) -> str:
    """An argument's literal text: adjacent literals joined, fields and other pieces as WILD."""
    parts: list[str] = []
    for kind, text in arg:
        if kind == "str":
            if parts and parts[-1].endswith("%"):  # "%" PRIu64 style: the field's rest is a macro
                parts[-1] = parts[-1][:-1] + WILD
            parts.append(fields.sub(WILD, text.replace("%%", "\x01")).replace("\x01", "%"))
        elif parts and parts[-1].endswith("%") and text.strip():
            # "%" PRIu32 "…": the conversion's rest is the macro, so the field is where the "%" stands
            parts[-1] = parts[-1][:-1] + WILD
        elif parts and not text.startswith(".") and text.strip("<+ \n\t"):
            # a variable streamed (<<) or added (+) into the message; `.format(...)` adds none, nor does the bare
            # operator between two literals ("… over 232 or " << "portBase …")
            parts.append(WILD)
    text = "".join(parts)
    return re.sub(WILD + "+", WILD, text)


def _skip(macro: str, suffix: str) -> int:
    """Arguments before the format: the logger (rclcpp), the clock and period (THROTTLE), a condition
    (EXPRESSION) or function (FUNCTION), the name (RCUTILS _NAMED)."""
    n = 1 if macro.startswith("RCLCPP_") else 0
    n += 1 if "NAMED" in suffix else 0
    n += 2 if "THROTTLE" in suffix else 0
    n += 1 if "EXPRESSION" in suffix or "FUNCTION" in suffix else 0
    return n


def _wrapper_calls(src: str, wrappers: dict[str, str]) -> Iterator[Call]:
    """Calls of a repository's own logging helpers (e.g. Nav2's action server `warn_msg("Aborting handle.")`,
    printed as `[<action>] [ActionServer] <msg>`): their first string argument is the message."""
    if not wrappers:
        return
    names = "|".join(re.escape(w) for w in wrappers)
    for m in re.finditer(rf"(?<![\w.])(?P<name>{names})\s*\(", src):
        level = wrappers[m["name"]]
        if level in ("DEBUG", "INFO"):
            continue
        toks, _ = _tokens(src, m.end(), stop_at_semicolon=False)
        arg = next((a for a in _args(toks) if any(k == "str" for k, _ in a)), None)
        if arg is not None:
            yield Call(src.count("\n", 0, m.start()) + 1, level, "log", _message(arg, _PRINTF))


def cpp_calls(src: str, wrappers: dict[str, str] | None = None) -> Iterator[Call]:
    """Every WARN/ERROR/FATAL logging call, exception text and rcl error message of a C/C++ file (and the calls of
    the `wrappers`: helper name -> level)."""
    yield from _wrapper_calls(src, wrappers or {})
    for m in _CPP_CALL.finditer(src):
        macro = m["macro"]
        level = m["l1"] or m["l2"] or ("WARN" if m["l3"] == "warn" else "ERROR")
        if level in ("DEBUG", "INFO"):
            continue
        form = "throw" if macro.startswith("throw") else "error_msg" if "ERROR_MSG" in macro else "log"
        stream = m["open"] == "<<" or "STREAM" in (m["s1"] or m["s2"] or "")
        start = m.end() if m["open"] != "<<" else m.end() - 2
        toks, _ = _tokens(src, start, stop_at_semicolon=m["open"] == "<<")
        args = _args(toks)
        if form == "log" and macro.startswith(("RCLCPP_", "RCUTILS_")):
            args = args[_skip(macro, m["s1"] or m["s2"] or ""):]
        arg = next((a for a in args if any(k == "str" for k, _ in a)), None)
        if arg is None and form == "throw":
            arg, stream = _streamed(src, m.start(), args), True
        if arg is None:
            continue
        text = _message(arg, _PRINTF if not stream else re.compile(r"(?!)"))
        yield Call(src.count("\n", 0, m.start()) + 1, level, form, text)


_STR = re.compile(r"^(?P<name>\w+)\s*\.\s*str\s*\(\s*\)$")


def _streamed(src: str, at: int, args: list[list[tuple[str, str]]]) -> list[tuple[str, str]] | None:
    """A thrown message built in a string stream just before the throw (Fast DDS's ServerAttributes.cpp:
    `ss << "Wrong ipv4 address passed into the server's list " << address; throw std::invalid_argument(ss.str());`):
    the tokens streamed into it, read from its last `<<` statement in the 20 lines before; None for any other
    throw."""
    only = args[0] if len(args) == 1 and len(args[0]) == 1 else []
    m = _STR.match(only[0][1]) if only and only[0][0] == "other" else None
    if m is None:
        return None
    start = at
    for _ in range(20):
        start = max(0, src.rfind("\n", 0, start))
    last = None
    for found in re.finditer(rf"\b{re.escape(m['name'])}\s*<<", src[start:at]):
        last = found
    if last is None:
        return None
    toks, _ = _tokens(src, start + last.end() - 2, stop_at_semicolon=True)
    return toks if any(k == "str" for k, _ in toks) else None


def py_calls(src: str) -> Iterator[Call]:
    """Every warning/error logging call and raised exception text of a Python file."""
    for m in _PY_CALL.finditer(src):
        lvl = (m["lvl"] or "").lower()
        level = "WARN" if lvl.startswith("warn") else "FATAL" if lvl in ("fatal", "critical") else "ERROR"
        form = "throw" if m.group(0).startswith("raise") or "__init__" in m.group(0) else "log"
        toks, _ = _tokens(src, m.end(), stop_at_semicolon=False)
        args = _args(toks)
        arg = next((a for a in args if any(k == "str" for k, _ in a)), None)
        if arg is None:
            continue
        yield Call(src.count("\n", 0, m.start()) + 1, level, form, _message(arg, _PYFIELD))


def literals(src: str, regex: str) -> Iterator[tuple[int, str]]:
    """(line, text) of each string constant `regex` (one group) finds: messages built away from their log call."""
    for m in re.finditer(regex, src):
        # a C string's escapes ("…file %s\\n") decoded as the compiler does, and its printf fields wildcards
        text = re.sub(r"\\(.)", lambda e: _ESCAPES.get(e[1], e[1] if not e[1].isalnum() else WILD), m.group(1))
        if text.endswith("%") and not text.endswith("%%"):
            text = text[:-1] + WILD  # "… at least %" PRIu32 "…": the field's rest is a macro, the message goes on
        yield src.count("\n", 0, m.start()) + 1, _PYFIELD.sub(WILD, _PRINTF.sub(WILD, text))


def literal_length(text: str) -> int:
    return len(text.replace(WILD, "").strip())


def to_pattern(text: str) -> str:
    """The regex of a message: literal text escaped, each field a lazy wildcard, surrounding blanks trimmed (a
    console strips them, and a field at either end adds nothing to a search)."""
    pieces = [_escape(p) for p in text.strip().strip(WILD).strip().split(WILD)]
    return ".*?".join(pieces)


def _escape(text: str) -> str:
    # Spaces stay readable: re.escape's `\ ` means the same in a pattern.
    return re.escape(text).replace("\\ ", " ")


def to_display(text: str) -> str:
    """The message as a reader sees it in the catalogue: fields shown as `…`."""
    return text.replace(WILD, "…").strip()
