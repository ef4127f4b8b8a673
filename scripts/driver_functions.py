"""Where a driver logs a line: the hardware_interface callback (on_init, on_configure, on_activate, read, write,
prepare/perform_command_mode_switch, ...) of a class implementing SystemInterface, ActuatorInterface or
SensorInterface that logs it, directly or through the class's own helpers (a `sendJointCommands()` that only
`write()` calls logs for `write()`). Facts for scripts/mine_modules.py, found by reading the C++ text: comments,
literals and preprocessor lines are blanked first, then braces are followed to tell namespace, class and function
blocks apart (the outermost function holds a lambda's line).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

HW_BASES = frozenset({"SystemInterface", "ActuatorInterface", "SensorInterface"})
# the callbacks hardware_interface calls (lifecycle transitions, the control loop, controller switches); foxy's
# interface (ros2_control 0.x, still xArm's) had configure(info), start() and stop() where later ones have on_init,
# on_activate and on_deactivate
CALLBACKS = ("on_init", "configure", "on_configure", "on_cleanup", "on_shutdown", "on_activate", "start",
             "on_deactivate", "stop", "on_error", "read", "write", "prepare_command_mode_switch",
             "perform_command_mode_switch", "export_state_interfaces", "export_command_interfaces",
             "on_export_state_interfaces", "on_export_command_interfaces")
_CLASS = re.compile(r"\b(?:class|struct)\s+(?:[A-Z_][A-Z0-9_]*\s+)*([A-Za-z_]\w*)\s*(?:final\s*)?:([^{;]*)\{")
_CLASS_HEAD = re.compile(r"\b(?:class|struct|union)\s+(?:[A-Z_][A-Z0-9_]*\s+)*([A-Za-z_]\w*)[^()]*$")
_FUNC_NAME = re.compile(r"(~?[A-Za-z_][\w:]*)\s*\(")


@dataclass(frozen=True)
class Function:
    start: int
    end: int
    cls: str  # the class it is a method of ("" for a free function)
    name: str


def blank(text: str) -> str:
    """`text` with comments, string and char literals and preprocessor lines replaced by spaces (newlines and
    offsets kept), so that braces and names can be followed."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True
    while i < n:
        ch = text[i]
        if line_start and ch == "#":
            j = i
            while j < n and text[j] != "\n":
                j += 2 if text[j] == "\\" and j + 1 < n else 1
            _fill(out, i, j)
            i = j
            continue
        if ch == "/" and text[i:i + 2] == "//":
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif ch == "/" and text[i:i + 2] == "/*":
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif ch in "\"'" and not (ch == "'" and i and text[i - 1].isalnum()):  # 1'000: a digit separator
            j = i + 1
            while j < n and text[j] != ch and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j += 1
        else:
            if ch == "\n":
                line_start = True
            elif not ch.isspace():
                line_start = False
            i += 1
            continue
        _fill(out, i, j)
        i = j
    return "".join(out)


def _fill(out: list[str], i: int, j: int) -> None:
    for k in range(i, min(j, len(out))):
        if out[k] != "\n":
            out[k] = " "


def functions(text: str) -> list[Function]:
    """The function bodies of a C++ text, outermost only, with their class (from `Cls::name` or the enclosing
    class block)."""
    code = blank(text)
    found: list[Function] = []
    stack: list[tuple[str, str, int]] = []  # (kind, name, start)
    head_start = 0
    for i, ch in enumerate(code):
        if ch == ";":
            head_start = i + 1
        elif ch == "{":
            in_function = any(kind == "function" for kind, _, _ in stack)
            stack.append(("inner", "", i) if in_function else _block(code[head_start:i], i))
            head_start = i + 1
        elif ch == "}":
            if stack:
                kind, name, start = stack.pop()
                if kind == "function":
                    cls = name.rsplit("::", 1)[0].rsplit("::", 1)[-1] if "::" in name else next(
                        (n for k, n, _ in reversed(stack) if k == "class"), "")
                    found.append(Function(start, i, cls, name.rsplit("::", 1)[-1]))
            head_start = i + 1
    return found


def _block(head: str, at: int) -> tuple[str, str, int]:
    if re.search(r"\bnamespace\b|\bextern\s*$", head):
        return "namespace", "", at
    m = _CLASS_HEAD.search(head)
    if m is not None:
        return "class", m[1], at
    if re.search(r"\benum\b", head) or "(" not in head:
        return "other", "", at
    name = _FUNC_NAME.search(head)
    return ("function", name[1], at) if name is not None else ("other", "", at)


def hardware_classes(texts: Iterable[str]) -> set[str]:
    """Classes that implement a hardware_interface interface, directly or through a base of the same sources
    (gazebo_ros2_control's GazeboSystem through GazeboSystemInterface)."""
    bases: dict[str, set[str]] = {}
    for text in texts:
        for m in _CLASS.finditer(blank(text)):
            names = {re.sub(r"<.*", "", b).strip().rsplit("::", 1)[-1].split()[-1]
                     for b in m[2].split(",") if b.strip()}
            bases.setdefault(m[1], set()).update(names)
    found = {c for c, bs in bases.items() if bs & HW_BASES}
    while True:
        more = {c for c, bs in bases.items() if bs & found} - found
        if not more:
            return found
        found |= more


def callbacks_of(text: str, classes: set[str]) -> dict[Function, tuple[str, ...]]:
    """Each method of a hardware class in `text` -> the callbacks it runs in: its own name when it is one, else
    the callbacks of the class's methods in the same text that call it (to a fixed point)."""
    code = blank(text)
    own = [f for f in functions(text) if f.cls in classes]
    reach: dict[Function, set[str]] = {f: {f.name} if f.name in CALLBACKS else set() for f in own}
    calls = {f: {g for g in own if g is not f and g.cls == f.cls and g.name not in CALLBACKS
                 and re.search(rf"(?<![\w.>]){re.escape(g.name)}\s*\(", code[f.start:f.end])} for f in own}
    changed = True
    while changed:
        changed = False
        for f, callees in calls.items():
            for g in callees:
                if not reach[f] <= reach[g]:
                    reach[g] |= reach[f]
                    changed = True
    return {f: tuple(c for c in CALLBACKS if c in names) for f, names in reach.items()}


def callbacks_at(table: dict[Function, tuple[str, ...]], offset: int) -> tuple[str, ...]:
    """The callbacks of the hardware method whose body holds `offset` (empty: none)."""
    return next((names for f, names in table.items() if f.start <= offset <= f.end), ())


def callbacks_by_line(texts: dict[str, str]) -> dict[str, dict[int, tuple[str, ...]]]:
    """For each C++ file of a repository's branch (path -> text), the callbacks each line of a hardware method runs
    in (1-based line numbers; lines outside such methods are absent)."""
    classes = hardware_classes(texts.values())
    out: dict[str, dict[int, tuple[str, ...]]] = {}
    for path, text in texts.items():
        table = callbacks_of(text, classes) if classes else {}
        for f, names in table.items():
            if names:
                first, last = text.count("\n", 0, f.start) + 1, text.count("\n", 0, f.end) + 1
                out.setdefault(path, {}).update({n: names for n in range(first, last + 1)})
    return out


def role_of(callbacks: Iterable[str], text: str, cfg: dict[str, Any] | None) -> str | None:
    """The first role of `cfg` (modules_mining.yaml's `hardware_roles`) whose callbacks hold all of the line's and
    whose `words` the line holds (`none`: none of them)."""
    names = set(callbacks)
    if not names or not cfg:
        return None
    held = {name for name, rx in cfg["words"].items() if re.search(rx, text, re.I)}
    for role, spec in cfg["roles"].items():
        words = spec.get("words")
        if names <= set(spec["callbacks"]) and (words is None or (words in held if words != "none" else not held)):
            return str(role)
    return None
