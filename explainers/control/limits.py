"""A joint commanded beyond its position limits, read from ros2_control's joint limiter (Kilted on).

The controller manager logs each joint's limits as it starts ("Using JointLimiter for joint '…' in hardware '…' :
'  has position limits: true [lo, hi] …", resource_manager.cpp@kilted) and, throttled to once a second, a command
it clamped ("Command of at least one joint is out of limits (throttled log). Joint: '…', (actual: [… position: …],
command: [… position: …], limited: [… position: …])", :1131). One such line is ordinary (a step in a command is
clamped to the joint's velocity limit on healthy robots: the catalogue's notice). A command whose position lies
beyond the joint's position limits is not: the joint was held at its limit, so a goal that failed while it was
failed because it asked for a position the robot description does not allow.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from hexar.events.records import LogLine, hms
from hexar.explainers.base import Evidence, Explanation

CAUSE = "control.configuration_error"
EPSILON = 1e-3  # rad (or m): a trajectory's interpolation grazes a limit by less on healthy arms
_N = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
_LIMITS = re.compile(rf"^Using JointLimiter for joint '(?P<joint>[^']+)'.*?has position limits: true "
                     rf"\[(?P<lo>{_N}), (?P<hi>{_N})\]", re.S)
_CLAMPED = re.compile(rf"^Command of at least one joint is out of limits \(throttled log\)\. Joint: '(?P<joint>[^']+)'"
                      rf".*?command: \[Joint: '[^']+', position: (?P<command>{_N})\], limited: \[Joint: '[^']+', "
                      rf"position: (?P<limited>{_N})\]", re.S)


@dataclass(frozen=True)
class Beyond:
    joint: str
    command: float
    low: float
    high: float
    limits: LogLine
    clamped: LogLine


def _clamped(lines: list[LogLine]) -> Iterator[tuple[re.Match[str], float, float, LogLine, LogLine]]:
    """Each clamped command of a joint whose limits were logged: (the clamp's match, the joint's low and high
    position limits, the line that logged them, the clamp's line)."""
    limits = {m["joint"]: (float(m["lo"]), float(m["hi"]), ln) for ln in lines if (m := _LIMITS.match(ln.msg))}
    for ln in lines:
        m = _CLAMPED.match(ln.msg)
        if m is not None and m["joint"] in limits:
            low, high, limit_line = limits[m["joint"]]
            yield m, low, high, limit_line, ln


def beyond_limits(lines: list[LogLine]) -> Beyond | None:
    """The clamped command that lies furthest beyond its joint's logged position limits (by more than a rounding's
    EPSILON), else None."""
    found: tuple[float, Beyond] | None = None
    for m, low, high, limit_line, ln in _clamped(lines):
        command = float(m["command"])
        excess = max(low - command, command - high)
        if excess > EPSILON and (found is None or excess > found[0]):
            found = excess, Beyond(m["joint"], command, low, high, limit_line, ln)
    return found[1] if found is not None else None


def answer(explainer: str, found: Beyond, what: str) -> Explanation:
    side = found.low if found.command < found.low else found.high
    return Explanation(
        explainer=explainer, causes=[CAUSE], confidence=0.8,
        evidence=[Evidence.of_log(CAUSE, found.limits), Evidence.of_log(CAUSE, found.clamped)],
        text=(f"{what[:1].upper()}{what[1:]} could not run because a controller was set up wrongly for my robot: "
              f"{found.joint} was commanded to {found.command:g} rad, beyond its position limits [{found.low:g}, "
              f"{found.high:g}] in my robot description, so my joint limiter held it at {side:g}."),
        fix=(f"Command {found.joint} within [{found.low:g}, {found.high:g}], or, if the joint really goes further, "
             "widen its limits in the robot description."),
        details=["ros2_control's joint limiter clamps every command to the limits of the robot description."])


@dataclass(frozen=True)
class Slowed:
    joint: str
    actual: float | None
    command: float
    limited: float
    low: float
    high: float
    clamped: LogLine


_ACTUAL = re.compile(rf"actual: \[Joint: '[^']+', position: (?P<actual>{_N})")


def slowed(lines: list[LogLine]) -> Slowed | None:
    """The first clamped command whose position lies inside its joint's logged position limits: the limiter held
    back how fast (or how hard) the joint was moved towards it, not where it went."""
    for m, low, high, _, ln in _clamped(lines):
        command = float(m["command"])
        if low - EPSILON <= command <= high + EPSILON:
            a = _ACTUAL.search(ln.msg)
            return Slowed(m["joint"], float(a["actual"]) if a else None, command, float(m["limited"]), low, high, ln)
    return None


def slowed_said(found: Slowed) -> str:
    """The clamped command in words: a notice, never a failure."""
    at = f" with the joint at {found.actual:g}" if found.actual is not None else ""
    return (f"ros2_control's joint limiter logged an ERROR at {hms(found.clamped.t)} because it clamped a command of "
            f"{found.joint}: asked for position {found.command:g}{at}, it sent {found.limited:g} on. That position "
            f"lies inside the joint's limits [{found.low:g}, {found.high:g}], so the limiter held back how fast the "
            "joint moved towards it (its velocity, acceleration or effort limits), not where it went; the line is a "
            "notice that comes with large steps in a command, not a failure.")
