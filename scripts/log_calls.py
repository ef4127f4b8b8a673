"""The log calls of a C++ or Python source, as (level, line, pieces) for scripts/mine_modules.py: RCLCPP_/RCUTILS_
log macros (also _STREAM/_THROTTLE/_ONCE/_EXPRESSION) and the UR client library's URCL_LOG_*, `throw X("...")`
texts, fmt::format messages logged or thrown just after, Python `logger.error/warn/info(...)` and `raise X(...)`,
and the literals a function returns for its caller to log. A piece is a literal run of text, or None for an
expression the format does not fix (printf conversions,
streamed and `+`-joined expressions, f-string and str.format fields)."""

from __future__ import annotations

import re
from collections.abc import Iterator

# URCL_LOG_*: the UR client library's printf-style macros (no logger argument), printed by the UR driver
CPP_MACRO = re.compile(r"\b(RCLCPP|RCUTILS_LOG|URCL_LOG)_(DEBUG|INFO|WARN|ERROR|FATAL)(\w*)\s*\(")
CPP_THROW = re.compile(r"\bthrow\s+(?:[\w:]+)\s*[({]")
PY_LOG = re.compile(r"\.(error|warn|warning|fatal|info)\(")
PY_RAISE = re.compile(r"\braise\s+\w+\(")
PRINTF = re.compile(r"%[-+ #0]*(?:\d+|\*)?(?:\.(?:\d+|\*))?(?:hh|h|ll|l|z|j|t|L|PRI\w+)?[diouxXeEfFgGcsp]")
ESCAPES = {"n": "\n", "t": "\t", '"': '"', "'": "'", "\\": "\\", "r": "", "0": ""}


def _walk(text: str, start: int = 0) -> Iterator[tuple[int, str, int]]:
    """(index, character, bracket depth after it) from `start`, string and char literals skipped."""
    depth, i = 0, start
    while i < len(text):
        ch = text[i]
        if ch in "\"'":
            i = _skip_literal(text, i)
            continue
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        yield i, ch, depth
        i += 1


def _close(text: str, start: int) -> int:
    """Index of the bracket closing the one before `start`, skipping string and char literals."""
    return next((i for i, _, depth in _walk(text, start) if depth < 0), len(text))


def _skip_literal(text: str, i: int) -> int:
    quote = text[i]
    i += 1
    while i < len(text) and text[i] != quote:
        i += 2 if text[i] == "\\" else 1
    return i + 1


ANSI = re.compile(r"\x1b\[[0-9;]*m")


def _unescape(body: str) -> str:
    """A literal's text, without the ANSI colours some spawners wrap it in (the explainers match lines with their
    colour codes removed)."""
    out, i = [], 0
    while i < len(body):
        if body[i:i + 2] == "\\x" and re.match(r"[0-9a-fA-F]{2}", body[i + 2:i + 4]):
            out.append(chr(int(body[i + 2:i + 4], 16)))
            i += 4
        elif body[i] == "\\" and i + 1 < len(body):
            out.append(ESCAPES.get(body[i + 1], body[i + 1]))
            i += 2
        else:
            out.append(body[i])
            i += 1
    return ANSI.sub("", "".join(out))


def _split_args(text: str) -> list[str]:
    args, start = [], 0
    for i, ch, depth in _walk(text):
        if ch == "," and depth == 0:
            args.append(text[start:i])
            start = i + 1
    args.append(text[start:])
    return args


_CPP_LIT = re.compile(r'(?:u8|u|U|L)?"((?:[^"\\\n]|\\.)*)"')


def _cpp_pieces(expr: str, printf: bool) -> list[str | None]:
    """Literal runs of a C++ expression (adjacent literals join), None for whatever lies between them."""
    pieces: list[str | None] = []
    pos = 0
    for m in _CPP_LIT.finditer(expr):
        between = expr[pos:m.start()]
        if re.sub(r"[\s<+]", "", between) or (pieces and "<<" in between and re.search(r"\w", between)):
            pieces.append(None)
        elif pieces and pieces[-1] is None and not between.strip():
            pass
        text = _unescape(m[1])
        if printf:
            parts = PRINTF.split(text.replace("%%", "\x00"))
            for k, part in enumerate(parts):
                if k:
                    pieces.append(None)
                pieces.append(part.replace("\x00", "%"))
        else:
            pieces.append(text)
        pos = m.end()
    if re.sub(r"[\s<+;)]", "", expr[pos:]):
        pieces.append(None)
    return pieces


def cpp_calls(text: str) -> Iterator[tuple[str, int, list[str | None]]]:
    for m in CPP_MACRO.finditer(text):
        level, suffix, first = m[2], m[3], 0 if m[1] == "URCL_LOG" else 1
        body = text[m.end():_close(text, m.end())]
        args = _split_args(body)
        line = text.count("\n", 0, m.start()) + 1
        if "STREAM" in suffix:
            pieces = _cpp_pieces(args[-1] if len(args) > 1 else body, printf=False)
        else:
            fmt_at = next((k for k, a in enumerate(args) if k >= first and _CPP_LIT.match(a.strip())), None)
            if fmt_at is None:
                continue
            fmt = args[fmt_at]
            pieces = _cpp_pieces(fmt, printf=True)
        yield level, line, pieces
    for m in CPP_THROW.finditer(text):
        body = text[m.end():_close(text, m.end())]
        if '"' not in body:
            continue
        line = text.count("\n", 0, m.start()) + 1
        yield "THROW", line, _cpp_pieces(body, printf="%" in body and "format" in body)


# fmt::format messages (ros2_control 5.x builds most of its messages so, then logs them with RCLCPP_X(logger, "%s",
# message.c_str()) or throws them): the literal with {} fields as values, at the level of the log call that follows
# within a few lines (THROW for a throw), since the "%s" of that call holds nothing to recognise a line by
CPP_FMT = re.compile(r"\bfmt::format\s*\(")
FMT_FIELD = re.compile(r"\{[^{}]*\}")
FMT_REACH = 8  # lines from the format to the call that logs or throws it


def fmt_calls(text: str) -> Iterator[tuple[str, int, list[str | None]]]:
    for m in CPP_FMT.finditer(text):
        args = _split_args(text[m.end():_close(text, m.end())])
        first = re.sub(r"^\s*FMT_COMPILE\s*\(([\s\S]*)\)\s*$", r"\1", args[0])
        if not _CPP_LIT.match(first.strip()):
            continue
        line = text.count("\n", 0, m.start()) + 1
        after = "\n".join(text[m.end():].split("\n")[:FMT_REACH])
        used = re.search(r"\b(?:RCLCPP|RCUTILS_LOG)_(DEBUG|INFO|WARN|ERROR|FATAL)\w*\s*\(|\bthrow\b", after)
        if used is None:
            continue
        pieces: list[str | None] = []
        for piece in _cpp_pieces(first, printf=False):
            if piece is None:
                pieces.append(None)
                continue
            for k, part in enumerate(FMT_FIELD.split(piece.replace("{{", "\x00").replace("}}", "\x01"))):
                if k:
                    pieces.append(None)
                pieces.append(part.replace("\x00", "{").replace("\x01", "}"))
        yield used[1] or "THROW", line, pieces


_PY_LIT = re.compile(r'(f?)("""|"|\')((?:(?!\2)[^\\]|\\.)*)\2', re.S)


def py_calls(text: str) -> Iterator[tuple[str, int, list[str | None]]]:
    for regex, fixed in ((PY_LOG, None), (PY_RAISE, "THROW")):
        for m in regex.finditer(text):
            body = text[m.end():_close(text, m.end())]
            level = fixed or m[1].upper()
            pieces: list[str | None] = []
            pos = 0
            for lit in _PY_LIT.finditer(body):
                if re.sub(r"[\s+()]", "", body[pos:lit.start()]):
                    pieces.append(None)
                value = _unescape(lit[3])
                # f-string fields, str.format's {} and %-conversions are all values the format does not fix
                fields = r"\{[^{}]*\}" if lit[1] else r"\{\}|" + PRINTF.pattern
                for k, part in enumerate(re.split(fields, value)):
                    if k:
                        pieces.append(None)
                    pieces.append(part)
                pos = lit.end()
            if re.sub(r"[\s+()]", "", body[pos:]):
                pieces.append(None)
            if pieces:
                yield level, text.count("\n", 0, m.start()) + 1, pieces


_RETURN_LIT = re.compile(r'\breturn\s+"((?:[^"\\\n]|\\.)*)"\s*;')


def returned(text: str) -> Iterator[tuple[str, int, list[str | None]]]:
    """The string literals a function returns for its caller to log ("%s"): move_group's getActionResultString
    texts, logged at INFO as each goal ends."""
    for m in _RETURN_LIT.finditer(text):
        yield "INFO", text.count("\n", 0, m.start()) + 1, [_unescape(m[1])]
