"""The waypoint follower's task at each waypoint (nav2_waypoint_follower's task executor plugins), when the trips
themselves went well.

The follower runs its task executor at every waypoint it reaches and logs "Task execution at waypoint %i failed!"
when the task did not work (waypoint_follower.cpp:355-358@kilted); with stop_on_failure false it goes on to the next
waypoint and ends the whole goal as succeeded, the failed tasks only in its result's missed_waypoints. So a run whose
every trip reached its waypoint can still be one whose job was not done. PhotoAtWaypoint says why its task failed:
"Couldn't take photo at waypoint %i! Caught exception: %s \\nMake sure that the image topic named: %s is valid and
active!" (photo_at_waypoint.cpp:127-131@kilted), which follows from a camera topic that gave it no image: a topic the
camera does not publish, or a camera that does not run. Another executor's failure is quoted, and no cause is
claimed from it.
"""

from __future__ import annotations

import re

from hexar.events.records import ERROR, LogLine
from hexar.explainers.base import Evidence
from hexar.explainers.navigation.detectors import UNEXPLAINED, Finding
from hexar.explainers.navigation.diagnose import CONFIGURATION

TASK_FAILED = re.compile(r"^Task execution at waypoint (?P<index>\d+) failed!?$")
_PHOTO = re.compile(r"Couldn't take photo at waypoint (?P<index>\d+)!.*?Make sure that the image topic named: "
                    r"(?P<topic>\S+) is valid and active", re.S)
FACT = "waypoint_tasks"  # the finding's fact: how many waypoints' tasks failed
TOPIC_NOTE = "image topic "  # a note that starts so names the camera topic


def tasks_failed(raw: list[LogLine]) -> Finding | None:
    """The waypoints whose task failed, with the executor's error just before the first: a camera topic that gave
    PhotoAtWaypoint no image is a set-up that does not fit (configuration_error); any other is quoted."""
    failed = [ln for ln in raw if TASK_FAILED.match(ln.msg.strip())]
    if not failed:
        return None
    first = failed[0]
    said = next((ln for ln in reversed(raw) if ln.t <= first.t and ln.level >= ERROR), None)
    photo = _PHOTO.search(said.msg) if said is not None else None
    cause = CONFIGURATION if photo is not None else UNEXPLAINED
    lines = [ln for ln in (said, first) if ln is not None]
    found = Finding(cause, [Evidence.of_log(cause, ln) for ln in lines])
    found.facts[FACT] = float(len({m["index"] for ln in failed if (m := TASK_FAILED.match(ln.msg.strip()))}))
    if photo is not None:
        found.notes.append(f"{TOPIC_NOTE}{photo['topic']}")
    return found
