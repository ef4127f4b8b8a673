"""The docking server's DockRobot (opennav_docking, Jazzy on): why a docking ended without the robot on its dock.

A DockRobot goal begins "Attempting to dock robot at %s." (or "... at position (%0.2f, %0.2f).",
docking_server.cpp:245-252@kilted) and ends "Docking was successful!" or "Robot is charging!" (:319-325), or with the
exception the server caught, logged as an ERROR and again in nav2_util's "[dock_robot] [ActionServer] Aborting
handle. error_code:%d, error_msg:'%s'.". An attempt that failed and is retried says "Docking failed, will retry: %s"
(:346), the last "Failed to dock, all retries have been used" (:343). The exception says which step failed; the
warnings before it say why:
- "Dock ID requested is not in database!" (dock_database.cpp:125): the dock asked for is not among the server's docks;
- "Dock requested has no valid plugin!" (:123): the dock's type names no dock plugin that was loaded;
- "Navigation request to staging pose failed." (navigator.cpp:96-111): the trip to the staging pose failed, which
  the navigation's own reading of that trip explains; a staging pose the planner cannot reach at all is the dock's
  (`staging`);
- "Failed initial dock detection" / "Failed dock detection" (:434, :508): after "Failed to transform detected dock
  pose" (simple_charging_dock.cpp:218-223) the detections came in a frame with no transform; after "Lost detection or
  did not detect: timeout exceeded" (:205) none came in time;
- "Transform error: %s" (:360): the dock's pose could not be transformed into the server's fixed frame;
- "Timed out waiting for charge to start" (:574): the robot made contact and nothing said it was charging;
- "Failed to get control" (:536, :644) after the docking controller's "Collision detected at pose: (%.2f, %.2f,
  %.2f) in frame %s" (controller.cpp:209): its collision check stopped the approach;
- any other: the docking failed, quoted.
"""

from __future__ import annotations

import re
from functools import partial

from hexar.events.nav_servers import spans
from hexar.events.records import ERROR, LogLine
from hexar.explainers.navigation import worded
from hexar.explainers.navigation.detectors import Finding
from hexar.explainers.navigation.diagnose import COLLISION_AHEAD, CONFIGURATION, DOCKING, GOAL_UNREACHABLE, TRANSFORM

_N = r"-?\d+(?:\.\d+)?"  # a number as "%.2f" prints it
BEGIN = re.compile(rf"^Attempting to dock robot at (?:position \((?P<x>{_N}), (?P<y>{_N})\)|(?P<dock>\S+?))\.$")
DOCKED = re.compile(r"^(Docking was successful!|Robot is charging!|Robot is already docked)")
ABORTED = re.compile(r"^\[dock_robot\] \[ActionServer\] Aborting handle\. error_code:\d+, error_msg:'(?P<msg>.*)'\.?$",
                     re.S)
_RETRY = re.compile(r"^Docking failed, will retry: ")
_STAGING = "Navigation request to staging pose"
_DETECTION = re.compile(r"^Failed (initial )?dock detection")
_UNSEEN = "Lost detection or did not detect"
_UNPLACED = "Failed to transform detected dock pose"
_FRAME = re.compile(r'Invalid frame ID "(?P<frame>[^"]+)" passed to canTransform')
_COLLISION = re.compile(rf"^Collision detected at pose: \((?P<x>{_N}), (?P<y>{_N}), {_N}\) in frame (?P<f>\S+)")
_STAGING_AT = re.compile(rf"Goal Coordinates of\((?P<x>{_N}), (?P<y>{_N})\)|to \((?P<gx>{_N}), (?P<gy>{_N})\)")
_CHECK_DOCK = ("Check the dock's pose in the docking server's database, its yaw too: the staging pose lies "
               "staging_x_offset behind the dock along the dock's heading.")

_finding = partial(worded.finding, speaker="The docking server")


def begins(line: LogLine) -> bool:
    """`line` begins a DockRobot goal."""
    return BEGIN.match(line.msg.strip()) is not None


def ends(begin: LogLine, line: LogLine) -> tuple[str, str] | None:
    """(state, error) when `line` ends the docking `begin` began: its success, or its abort and the abort's error."""
    msg = line.msg.strip()
    if (aborted := ABORTED.match(msg)) is not None:
        return "failed", aborted["msg"]
    return ("succeeded", "") if DOCKED.match(msg) else None


def docking(raw: list[LogLine]) -> tuple[LogLine, LogLine | None] | None:
    """The last DockRobot goal of `raw`: its begin line and the line that ended it (None while it ran on)."""
    found = spans(raw, "docking_server", begins, ends)
    return (found[-1].begin, found[-1].end) if found else None


def _said(end: LogLine) -> str:
    """What ended a docking: the abort's error message, else the line itself."""
    return (m["msg"] if (m := ABORTED.match(end.msg.strip())) else end.msg).strip()


def dock_failed(dock: tuple[LogLine, LogLine | None] | None, raw: list[LogLine]) -> Finding | None:
    """Why the last docking of `raw` (`dock`, as `docking` reads it) failed, from the server's lines; None when none
    failed, or when the trip to the staging pose failed (the navigation's reading of that trip tells why:
    `staging`)."""
    if dock is None:
        return None
    begin, end = dock
    if end is None or DOCKED.match(end.msg.strip()):
        return None
    during = [ln for ln in raw if begin.t <= ln.t <= end.t]
    said = _said(end)
    if said.startswith(_STAGING):
        return None
    asked = (BEGIN.match(begin.msg.strip()) or {"dock": None})["dock"] or "the pose I was given"
    tries = 1 + sum(1 for ln in during if _RETRY.match(ln.msg))
    if said.startswith("Dock ID requested is not in database"):
        return _finding(DOCKING, [begin, end], f"My docking failed: the dock I was asked to go to, {asked}, is not in "
                        "my list of docks, so I never set off.",
                        "Ask for a dock the docking server knows (its docks parameter or dock_database file), or add "
                        "this one to it.")
    if said.startswith("Dock requested has no valid plugin"):
        return _finding(CONFIGURATION, [begin, end], f"My docking failed: the type of the dock {asked} names no dock "
                        "plugin my docking server loaded, so it was misconfigured for this dock.",
                        "Give the dock a type that is one of the docking server's dock_plugins.")
    if _DETECTION.match(said):
        unplaced = [ln for ln in during if ln.msg.startswith(_UNPLACED)]
        if unplaced:
            frame = next((m["frame"] for ln in during if (m := _FRAME.search(ln.msg))), "")
            where = f"in the frame {frame}, which has no transform to my frames" if frame else \
                "in a frame I could not transform into mine"
            lines = [next(ln for ln in during if _FRAME.search(ln.msg)) if frame else unplaced[0], end]
            return _finding(TRANSFORM, lines, f"I didn't get onto my dock because of a missing transform: the dock's "
                            f"detections came {where}, so I could not place the dock.",
                            "Publish the transform of the detector's frame (the camera's link in the robot "
                            "description), or have the detector stamp its poses in a frame the robot has.")
        unseen = next((ln for ln in during if ln.msg.startswith(_UNSEEN)), None)
        return _finding(DOCKING, [ln for ln in (unseen, end) if ln is not None], "My docking failed: I never "
                        "detected the dock, since no detection of it came in time: its detector was not running, "
                        "or the dock was not in its view.",
                        "Check that the dock detector runs and publishes detected_dock_pose while the dock is in "
                        "view from the staging pose.")
    if said.startswith("Transform error:"):
        return _finding(TRANSFORM, [end], "I didn't get onto my dock because of a transform error: "
                        f"{said.removeprefix('Transform error:').strip()}",
                        "Check the docking server's frames (fixed_frame, base_frame) against the robot's TF tree.")
    if said.startswith("Timed out waiting for charge to start"):
        contact = [ln for ln in during if ln.msg.startswith("Made contact with dock")]
        times = f"{len(contact)} times" if len(contact) > 1 else "once"
        return _finding(DOCKING, [*contact[:1], end], f"My docking failed: I made contact with the dock {times}, "
                        "and nothing showed that the charge had started: my battery's state never reported current "
                        "flowing in.",
                        "Check that the battery's state is published and shows charging on the dock "
                        "(use_battery_status, charging_threshold), and that the dock has power.")
    hit = [m for ln in during if (m := _COLLISION.match(ln.msg))]
    if hit:
        first = next(ln for ln in during if _COLLISION.match(ln.msg))
        return _finding(COLLISION_AHEAD, [first, end], "I didn't get onto my dock: my docking controller detected a "
                        f"collision ahead on its approach, at ({hit[0]['x']}, {hit[0]['y']}) in frame {hit[0]['f']}, "
                        f"and would not drive on ({tries} attempts). My logs do not say what it saw: something in "
                        "front of the dock, or cost marked there.",
                        "Look at what stands between the staging pose and the dock; if nothing is there, check the "
                        "local costmap and dock_collision_threshold.")
    return _finding(DOCKING, [end], f"My docking failed: my docking server said '{said}'"
                    + (f" after {tries} attempts." if tries > 1 else "."),
                    "Check the docking server's log around that line.")


def staging(found: Finding, dock: tuple[LogLine, LogLine | None] | None, raw: list[LogLine]) -> Finding:
    """A docking (`dock`) whose trip to the staging pose failed because the planner cannot reach that pose at all is
    the dock's: its pose (or the staging offset) puts the staging pose outside the map or in an obstacle."""
    if dock is None or dock[1] is None or found.cause != GOAL_UNREACHABLE:
        return found
    end = dock[1]
    if not _said(end).startswith(_STAGING):
        return found
    at = next((m for e in found.evidence if (m := _STAGING_AT.search(e.item))), None)
    where = f" at ({float(at['x'] or at['gx']):.2f}, {float(at['y'] or at['gy']):.2f})" if at else ""
    lines = [ln for ln in raw if ln.t == end.t and ln.level >= ERROR][:1] or [end]
    docked = _finding(DOCKING, lines, f"My docking failed: I could not be driven to the dock's staging "
                      f"pose{where}, because my planner cannot reach it: it lies outside my map or inside an obstacle.",
                      _CHECK_DOCK)
    docked.evidence = found.evidence + docked.evidence
    return docked
