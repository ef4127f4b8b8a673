"""The robot's start as a task, for recordings with no `/task_info`, no goal (Nav2 or arm) and no catalogued cause.

Most recordings of a robot that never got a goal show its software starting: ros2_control's controller manager,
resource manager, hardware components and spawners, MoveIt's move_group, and drivers logging their own lines. That
start is one `bring_up_controllers` step:
- failed at its first decisive error: a bring-up or device line (explainers/stack_causes.py), else the first ERROR or
  FATAL line (or a C++ abort: libstdc++'s "terminate called after throwing an instance of") of a start the recording
  shows, i.e. of the starting software or of a device driver, after an earlier, lesser line of that start;
- succeeded when a line says the start completed (ros2_control's own words: the spawner's "Configured and activated",
  "Successful initialization of hardware", the resource manager "successfully initialized") and no error followed;
- running when the software started and neither happened (the recording ends before a line says how it went).
A lone error, an error of a node that is neither (a robot's behaviour node), or lines of nodes that start nothing,
make no task: such an error may be anybody's, and a start it followed is not told as a success either.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import TYPE_CHECKING

from hexar.events.records import ERROR, LogLine

if TYPE_CHECKING:
    from hexar.explainers.logcause import ModuleCatalogue

# libstdc++-v3/libsupc++/vterminate.cc (__gnu_cxx::__verbose_terminate_handler): a C++ exception nobody caught
_ABORT = "terminate called after throwing an instance of"
# ros2_control drivers name their logger after the class that implements hardware_interface's SystemInterface
# (Universal_Robots_ROS2_Driver: rclcpp::get_logger("URPositionHardwareInterface"); kuka_drivers: their
# KukaEkiRsiHardwareInterface); the resource manager names each component's logger
# "<controller manager>.resource_manager.hardware_component.<type>.<name>" (ros2_control jazzy and after)
_HARDWARE_LOGGER = re.compile(r"HardwareInterface$|(^|\.)hardware_component\.")
# MoveIt's own loggers: move_group and its capabilities, and moveit2's "moveit.<package>.<part>" child loggers
_MOVEIT_LOGGER = re.compile(r"move_group\b|moveit[._]")
# ros2_control's lines that tell a part of the start completed; read from the mined catalogue's texts below
_DONE_TEXT = re.compile(r"^(Successful(ly)? (initialization|'…' of hardware|switched)|Configured and activated|"
                        r"Resource Manager has been successfully initialized)")


@dataclass(frozen=True)
class BringUp:
    start: int
    state: str  # failed, succeeded or running
    end: int | None = None
    error: str = ""


def _catalogues() -> tuple[ModuleCatalogue, ModuleCatalogue]:
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    return control(), moveit()


@cache
def _done_ids() -> frozenset[str]:
    """The control catalogue's entries that tell the start (or a part of it) completed: the spawner's nominal kind,
    and ros2_control's "Successful …"/"successfully initialized" texts (never a deactivation or an unload)."""
    raw = json.loads(resources.files("hexar.explainers.control").joinpath("ros2_control_catalogue.json")
                     .read_text(encoding="utf-8"))
    return frozenset(str(m["id"]) for m in raw["messages"]
                     if m.get("level") == "INFO" and (m.get("kind") == "nominal" or _DONE_TEXT.search(str(m["text"]))))


def starting(line: LogLine) -> bool:
    """A line of the robot's starting software, by its logger: ros2_control's (a logger with a role in its catalogue:
    controller manager, resource manager, spawners; a hardware interface's own; gazebo's or gz's ros2_control
    plugin), MoveIt's own (move_group, moveit.*), or a line ros2_control's catalogue says completes a start. A
    generic text ("Waiting for …") of another node is no start: a client sending trajectories is not starting."""
    name = line.name
    if _HARDWARE_LOGGER.search(name) or _MOVEIT_LOGGER.match(name) or "ros2_control" in name:
        return True
    return _catalogues()[0].role(name) is not None or completed(line)


def completed(line: LogLine) -> bool:
    """A line of ros2_control that tells a part of the start completed."""
    entry = _catalogues()[0].match(line.msg)
    return line.level < ERROR and entry is not None and entry.id in _done_ids()


def _error(line: LogLine) -> bool:
    return line.level >= ERROR or _ABORT in line.msg


def _driver(name: str, logs: list[LogLine]) -> bool:
    """A node that drives a device: its name says so (ROS packages name device drivers `*_driver`: ur_robot_driver,
    ydlidar_ros2_driver), or one of its lines names a device file. A node that only runs the robot's behaviour
    (a turtlebot4_node undocking, then missing a camera service) is no start of the robot."""
    return "driver" in name.lower() or any(ln.name == name and "/dev/" in ln.msg for ln in logs)


def _shown(line: LogLine, before: list[LogLine], logs: list[LogLine]) -> bool:
    """The error belongs to a start the recording shows: an error of the starting software after a lesser line of
    it, a driver's error after a lesser line of its own, or a start line that goes on to tell an abort (a console's
    "Loading hardware '…'" whose next line is the abort)."""
    own = starting(line)
    if not own and not _driver(line.name, logs):
        return False
    if line.level < ERROR:
        return bool(line.msg.split(_ABORT, 1)[0].strip())
    return any(ln.level < ERROR and not _error(ln) and (ln.name == line.name or (own and starting(ln)))
               for ln in before)


def bring_up(logs: list[LogLine]) -> BringUp | None:
    """The start of the robot in `logs` (time-ordered), or None when they show no start at all."""
    from hexar.explainers.stack_causes import stack_cause

    if not logs:
        return None
    last = max(ln.t for ln in logs)
    stack = stack_cause(logs)
    if stack is not None:
        return BringUp(stack.line.t, "failed", last, stack.line.msg)
    first = next((ln for ln in logs if starting(ln)), None)
    failed = next((ln for i, ln in enumerate(logs) if _error(ln) and _shown(ln, logs[:i], logs)), None)
    if failed is not None:
        # the step began with the start the error belongs to: its node's first line, or the software's
        began = [failed.t, *(ln.t for ln in logs if ln.name == failed.name), *([first.t] if first else [])]
        return BringUp(min(began), "failed", last, failed.msg)
    if first is None or any(_error(ln) for ln in logs):
        return None  # an error the recording does not show a start of (one line of MoveIt's): not told either way
    done = [ln for ln in logs if completed(ln)]
    if done:
        return BringUp(first.t, "succeeded", done[-1].t)
    return BringUp(first.t, "running")
