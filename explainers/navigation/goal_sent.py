"""The goal as it was sent: a goal bt_navigator could not put in its global frame, or one it rejected.

- "Failed to transform a goal pose provided with frame_id '%s' to the global frame '%s'." (navigate_to_pose.cpp:252
  @kilted: the goal's error message since Jazzy, inside "Setting internal error …" and the abort) after nav2_util's
  transformPoseInTargetFrame said why (robot_utils.cpp): a goal frame tf2 does not know ('"X" passed to
  lookupTransform argument source_frame does not exist'), no frame at all (frame_id ''), or a stamp older than the
  transforms bt_navigator keeps ("Lookup would require extrapolation into the past. Requested time T but the earliest
  data is at time E"): the goal's header, not the robot's TF tree,
  unless the frame missing is the global one.
- "Action server is inactive. Rejecting the goal." (simple_action_server.hpp:155@kilted) before the lifecycle
  manager's "Managed nodes are active": the goal came before the stack was up, and no goal began after it. Where a
  missing transform or a node that failed kept the stack from coming up, that is the reason, read before this.
"""

from __future__ import annotations

import re
from functools import partial

from hexar.events.records import LogLine
from hexar.explainers.navigation import worded
from hexar.explainers.navigation.detectors import Finding
from hexar.explainers.navigation.diagnose import CONFIGURATION, TRANSFORM

_GOAL_FRAME = re.compile(r"Failed to transform a goal pose provided with frame_id '(?P<frame>[^']*)' to the global "
                         r"frame '(?P<global_frame>[^']+)'")
_MISSING = re.compile(r'"(?P<frame>[^"]+)" passed to lookupTransform argument (?P<arg>source|target)_frame does not '
                      r"exist")
_PAST = re.compile(r"extrapolation into the past\.\s+Requested time (?P<asked>[\d.]+) but the earliest data is at "
                   r"time (?P<earliest>[\d.]+)")
_FUTURE = re.compile(r"extrapolation into the future")
REJECTED = re.compile(r"^Action server is inactive\. Rejecting the goal")
_BEGUN = re.compile(r"^Begin navigating")
_ACTIVE = re.compile(r"^Managed nodes are active")  # lifecycle_manager.cpp@humble on

_finding = partial(worded.finding, speaker="Nav2")


def framed(raw: list[LogLine]) -> Finding | None:
    """A goal of `raw` that bt_navigator could not put in its global frame, told by why; else None."""
    line = next((ln for ln in raw if _GOAL_FRAME.search(ln.msg)), None)
    return _framed(line, raw) if line is not None else None


def rejected(raw: list[LogLine]) -> Finding | None:
    """A goal turned away before the stack came up, when nothing else explains the failure (a stack kept from
    coming up by a missing transform or a node that failed is that reason, read first); else None."""
    rejected = next((ln for ln in raw if REJECTED.match(ln.msg.strip())), None)
    # the stack came up after the goal was turned away (one that never came up is the node that failed: chain)
    active = rejected is not None and any(ln.t > rejected.t and _ACTIVE.match(ln.msg.strip()) for ln in raw)
    if rejected is not None and active and not any(_BEGUN.match(ln.msg) and ln.t > rejected.t for ln in raw):
        return _finding(CONFIGURATION, [rejected], "My navigation never started: my stack was not brought up yet "
                        "when the goal came, so my navigator's action server, still inactive, rejected it.",
                        "Send goals once the lifecycle manager has activated the stack (nav2_simple_commander's "
                        "waitUntilNav2Active, or the lifecycle manager's is_active service).")
    return None


def _framed(framed: LogLine, raw: list[LogLine]) -> Finding:
    m = _GOAL_FRAME.search(framed.msg)
    assert m is not None
    frame, global_frame = m["frame"], m["global_frame"]
    before = [ln for ln in raw if ln.t <= framed.t and ln is not framed]
    why = next((ln for ln in reversed(before) if "lookupTransform" in ln.msg or "extrapolation" in ln.msg
                or ln.msg.startswith("Failed to transform from")), None)
    lines = [ln for ln in (why, framed) if ln is not None]
    fix = f"Send the goal in a frame the robot's TF tree has ({global_frame}, or the robot's own frame), stamped now."
    head = "I couldn't start toward my goal because of a transform (TF) error in the goal as it was sent: "
    if frame == "":
        return _finding(TRANSFORM, lines, head + f"it had no frame at all (an empty frame_id), so I could not put "
                        f"it in my global frame '{global_frame}'.", fix)
    missing = _MISSING.search(why.msg) if why is not None else None
    if missing is not None and missing["frame"] == frame:
        return _finding(TRANSFORM, lines, head + f"it was given in the frame '{frame}', which nothing publishes, "
                        f"so I could not put it in my global frame '{global_frame}'.", fix)
    past = _PAST.search(why.msg) if why is not None else None
    if past is not None:
        age = float(past["earliest"]) - float(past["asked"])
        return _finding(TRANSFORM, lines, head + f"it was given in the frame '{frame}' with a stamp {age:.0f} s "
                        "older than the oldest transform I keep, so I could not put it in my global frame "
                        f"'{global_frame}'.", "Stamp the goal when it is sent (or leave the stamp zero to use the "
                        "latest transform), not with the time the pose was saved.")
    if why is not None and _FUTURE.search(why.msg):
        return _finding(TRANSFORM, lines, head + f"its stamp, in the frame '{frame}', lay ahead of every transform "
                        "I had: it was stamped by another clock.", "Stamp the goal with the robot's clock "
                        "(use_sim_time alike on both sides).")
    return _finding(TRANSFORM, lines, f"I couldn't reach my goal because of a transform (TF) error: I could not put "
                    f"the goal, given in the frame '{frame}', in my global frame '{global_frame}'"
                    + (f" (tf2 said: '{why.msg.strip()[:160]}')." if why is not None else "."), fix)
