"""The dynamic loader's words when it stops a program before its node exists (a library missing, or built against
other versions of what it links than the ones found at run time), read as what stopped the process."""

from __future__ import annotations

import re

from hexar.events.records import LogLine

# the dynamic loader's own words, written to the process's stderr as it gives up (glibc elf/dl-lookup.c:808@master
# "symbol lookup error" with "undefined symbol: %s%s%s", elf/dl-catch.c:85@master "error while loading shared
# libraries"): the program exits before its node exists, at no log level
_LOADER = re.compile(r"^(?P<exe>/\S+): (?P<what>symbol lookup error|error while loading shared libraries): (?P<why>.+)",
                     re.S)


def loader_said(line: LogLine) -> tuple[str, str, str] | None:
    """The loader's words in `line`: the program's file name, what failed ("symbol lookup error" or "error while
    loading shared libraries") and why, on one line; None for any other line."""
    found = _LOADER.search(line.msg)
    if found is None:
        return None
    return found["exe"].rsplit("/", 1)[-1], found["what"], " ".join(found["why"].split())


def loader_failure(line: LogLine) -> bool:
    """The dynamic loader could not start the program of `line` (a library missing or built against another)."""
    return _LOADER.search(line.msg) is not None


# The Itanium C++ ABI's mangled names as far as a person needs them: _Z, then a nested name N <length><name>... up to
# a constructor (C1-C3), a destructor (D0-D2) or its end (E); std:: is abbreviated St.
_MANGLED = re.compile(r"_?Z(?P<nested>N)?[rVK]*")
_ENDS = {"C1": "ctor", "C2": "ctor", "C3": "ctor", "D0": "dtor", "D1": "dtor", "D2": "dtor"}


def cpp_name(symbol: str) -> str | None:
    """The qualified C++ name a mangled symbol stands for ("flexiv::Robot::Robot(…)"), or None when it is not a
    plain nested name (templates, operators and other forms are left mangled)."""
    m = _MANGLED.match(symbol)
    if m is None:
        return None
    i, parts = m.end(), []
    if m["nested"] and symbol.startswith("St", i):
        parts.append("std")
        i += 2
    while (d := re.match(r"\d+", symbol[i:])) is not None:
        i += len(d[0])
        parts.append(symbol[i : i + int(d[0])])
        i += int(d[0])
        if not m["nested"]:
            return f"{parts[0]}(…)" if parts[0] else None
    end = _ENDS.get(symbol[i : i + 2])
    if not parts or not m["nested"] or (end is None and not symbol.startswith("E", i)):
        return None
    if end is not None:
        parts.append(parts[-1] if end == "ctor" else f"~{parts[-1]}")
    return f"{'::'.join(parts)}(…)"


def needed(why: str, with_symbol: bool = True) -> tuple[str, str] | None:
    """For the loader's "LIBRARY: undefined symbol: SYMBOL": the library's file name and what it needs in words (the
    C++ name when the symbol is a plain nested one, with the symbol's start if asked); None for other words."""
    lib, _, symbol = why.partition(": undefined symbol: ")
    if not symbol:
        return None
    name = cpp_name(symbol)
    if name is None:
        return lib.rsplit("/", 1)[-1], f"the symbol {symbol[:90]}"
    return lib.rsplit("/", 1)[-1], f"{name} (symbol {symbol[:32]}…)" if with_symbol else name


def loader_words(line: LogLine) -> tuple[str, str] | None:
    """What the dynamic loader said as it stopped the program of `line`, in words, and what to check; None for any
    other line."""
    said = loader_said(line)
    if said is None:
        return None
    exe, what, why = said
    if what == "symbol lookup error" and (lacked := needed(why)) is not None:
        return (f"the dynamic loader stopped {exe}, because {lacked[0]} needs {lacked[1]}, which no library loaded "
                "with it defines",
                "The library was built against other versions of what it links than the ones found at run time: "
                "rebuild it against the libraries installed here (a clean build), check which copy of each library "
                "is found first (ldd on the library, LD_LIBRARY_PATH), and that any prebuilt library in it matches "
                "this OS and processor.")
    return (f"the dynamic loader could not start {exe}: {why[:160]}",
            "A library it needs is not installed or not on the loader's path: install the package that holds it, "
            "or source the workspace that built it (LD_LIBRARY_PATH).")
