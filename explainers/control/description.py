"""A controller manager that waited for its robot description.

From Jazzy on, the controller manager reads the robot description only from its `robot_description` topic (Humble
and Iron still read a `robot_description` parameter and warn "[Deprecated] Passing the robot description parameter
directly to the control_manager node is deprecated": controller_manager.cpp:277-286@iron; Jazzy has no such read).
As it starts it logs "Subscribing to '<topic>' topic for robot description." (controller_manager.cpp:759@jazzy);
until a description arrives and its hardware loads, a wall timer warns once a second "Waiting for data on
'robot_description' topic to finish initialization" (:763-770); a description that arrives is logged "Received
robot description from topic." (:777).

The same warning goes on after a description arrived whose hardware failed to load (the callback's fallback,
:791-797), and a pasted excerpt often holds the warning alone. So:
- the description never arrived when the recording shows the controller manager subscribe, then wait, and holds
  no "Received robot description" and no error: the cause is told (bringup.configuration_error);
- with the warning alone (no subscription line before it, no line of a description received, no error), either no
  description arrived or the one that did named hardware that did not load: both are told, neither claimed.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.events.records import ERROR, LogLine
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.logcause import Reading, at
from hexar.explainers.module_wording import verbatim

_WAITING = re.compile(r"Waiting for data on 'robot_description' topic to finish initialization")
_SUBSCRIBED = re.compile(r"Subscribing to '[^']*' topic for robot description\.?$")
_RECEIVED = re.compile(r"Received robot description (from topic|file)")
BRINGUP = "bringup.configuration_error"
MEANING = ("my robot description never reached my controller manager: it subscribed to its 'robot_description' "
           "topic and waited, and nothing was published there (since Jazzy it reads no robot_description "
           "parameter; robot_state_publisher publishes the description on that topic)")
# in words no cause pattern of hexar/causes.yaml reads as a claim
CANDIDATES = ("Either no description arrived on its robot_description topic (since Jazzy it reads no "
              "robot_description parameter; robot_state_publisher publishes the description there), or the one that "
              "arrived named hardware that did not load, and the recording lacks that error.")


def waited(lines: Sequence[LogLine]) -> LogLine | None:
    """The first waiting line, when no line says a description arrived and no error was logged."""
    first = next((ln for ln in lines if _WAITING.search(ln.msg)), None)
    if first is None or any(ln.level >= ERROR or _RECEIVED.search(ln.msg) for ln in lines):
        return None
    return first


def never_arrived(lines: Sequence[LogLine], first: LogLine) -> bool:
    """The controller manager subscribed before `first`, the waiting line `waited` found (module docstring)."""
    return any(_SUBSCRIBED.search(ln.msg.strip()) and ln.t <= first.t for ln in lines)


def description_reading(readings: list[Reading]) -> list[Reading]:
    """The readings with the first waiting line read as the description that never arrived, when it did not."""
    lines = [r.line for r in readings]
    first = waited(lines)
    if first is None or not never_arrived(lines, first):
        return readings
    # the entry stays a symptom: it decides only when no line with a cause of its own does (explainers/logcause.py)
    return [Reading(r.line, r.entry, BRINGUP, r.catalogue, MEANING) if r.line is first else r for r in readings]


def waiting_answer(explainer: str, cause: str, head: str, line: LogLine, t0: int) -> Explanation:
    """The warning alone: `head` (what failed or did not complete), the controller manager still waiting, and the
    two readings of that, neither claimed (`cause` is the explainer's unexplained failure)."""
    return Explanation(
        explainer=explainer, causes=[cause], evidence=[Evidence.of_log(cause, line)], confidence=0.4,
        text=f"{head} My controller manager was still waiting for my robot description: {verbatim(line)} at "
             f"{at(line, t0)}, and no line says that a description arrived. {CANDIDATES}",
        fix="Check that robot_state_publisher runs with the description in the controller manager's namespace, and "
            "read the controller manager's lines from its start (a hardware error after 'Received robot "
            "description from topic.').",
        details=["controller_manager.cpp:763-770@jazzy warns once a second until a description arrives and its "
                 "hardware loads."])
