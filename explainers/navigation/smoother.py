"""The smoother server's time limit (nav2_smoother): a path smoother that was allowed no time at all.

SimpleSmoother and the Savitzky-Golay smoother stop when smoothing takes longer than the goal allows, with "Smoothing
time exceeded allowed duration of %0.2f." (simple_smoother.cpp:150, savitzky_golay_smoother.cpp:81@kilted) and the
server's error "Smoothing time exceed allowed duration"; the action fails, and a behaviour tree that smooths every
plan before following it gives up the goal. The duration is the SmoothPath node's max_smoothing_duration (3 s by
default). A limit that rounds to 0.00 s can be met by no smoothing: the smoother was set up with no time to work,
whatever the path. A real limit that ran out is a long path or a busy computer as much as a setting, and is quoted
by the honest answer instead.
"""

from __future__ import annotations

import re

from hexar.events.records import LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.detectors import Finding
from hexar.explainers.navigation.diagnose import CONFIGURATION

_EXCEEDED = re.compile(r"^Smoothing time exceeded allowed duration of (?P<s>-?\d+(?:\.\d+)?)")
NO_TIME_S = 0.005  # what "%0.2f" prints as 0.00
FACT = "smoother_no_time"  # a finding's fact: the allowed duration the smoother printed


def no_time(raw: list[LogLine]) -> Finding | None:
    """A smoother that gave up at a limit that rounds to no time at all, with the server's error after it."""
    said = next((ln for ln in raw if (m := _EXCEEDED.match(ln.msg.strip())) and abs(float(m["s"])) < NO_TIME_S), None)
    if said is None:
        return None
    error = next((ln for ln in raw if ln.t >= said.t and ln.msg.startswith("Smoothing time exceed allowed")), None)
    lines = [ln for ln in (said, error) if ln is not None]
    return Finding(CONFIGURATION, [Evidence.of_log(CONFIGURATION, ln) for ln in lines], {FACT: 1.0})


def template(f: Finding, place: str) -> tuple[str, str | None, list[str]] | None:
    """The answer of a no-time finding (FACT), or None for any other finding."""
    if FACT not in f.facts:
        return None
    return (f"I couldn't reach {place} because my path smoother was misconfigured: it was allowed no time at all "
            "to smooth my path (0.00 s), so it gave up on every plan and my navigation could not follow one.",
            "Give the behaviour tree's SmoothPath a real max_smoothing_duration (3 s by default).",
            [f"Nav2 said: {e.item}" for e in f.evidence[:1]])
