"""The robot's start as a task, for recordings with no `/task_info`, no goal (Nav2 or arm) and no catalogued cause.

Most recordings of a robot that never got a goal show its software starting: ros2_control's controller manager,
resource manager, hardware components and spawners, MoveIt's move_group, and drivers logging their own lines. That
start is one `bring_up_controllers` step:
- failed at its first decisive error: a bring-up or device line (explainers/stack_causes.py), else the first ERROR or
  FATAL line (or a C++ abort: libstdc++'s "terminate called after throwing an instance of") of a start the recording
  shows, i.e. of the starting software or of a device driver after an earlier, lesser line of that start, or a lone
  error that is the robot's start by itself: one of a hardware interface's or ros2_control's own loggers, of a device
  driver (`*_driver`, or a node whose lines name a device file), or a line that names a device or a parameter;
- succeeded when a line says the start completed (ros2_control's own words: the spawner's "Configured and activated",
  "Successful initialization of hardware", the resource manager "successfully initialized") and no error followed;
- running when the software started and neither happened (the recording ends before a line says how it went), and
  when a controller refused commands because it was not active (diff_drive_controller's "Can't accept new commands.
  subscriber is inactive"): it had been configured, but whether it was never activated or was deactivated later
  (on_deactivate makes it drop commands the same way) no line tells.
A lone error of another node (a robot's behaviour node, MoveIt's own: healthy arms print some), or lines of nodes
that start nothing, make no task: such an error may be anybody's, and a start it followed is not told as a success.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING

from hexar.events.records import ERROR, LogLine

if TYPE_CHECKING:
    from hexar.explainers.logcause import ModuleCatalogue

# libstdc++-v3/libsupc++/vterminate.cc (__gnu_cxx::__verbose_terminate_handler): a C++ exception nobody caught
ABORT = "terminate called after throwing an instance of"
# ros2_control drivers name their logger after the class that implements hardware_interface's SystemInterface
# (Universal_Robots_ROS2_Driver: rclcpp::get_logger("URPositionHardwareInterface"); kuka_drivers: their
# KukaEkiRsiHardwareInterface and KukaRSIHardwareInterfaceBase; dynamixel_hardware.cpp:29: "DynamixelHardware";
# ros2_kortex: "KortexMultiInterfaceHardware"; mujoco_ros2_control: "MujocoSystemInterface"; gz_ros2_control:
# "GazeboSimROS2ControlPlugin"); the resource manager names each component's logger
# "<controller manager>.resource_manager.hardware_component.<type>.<name>" (ros2_control jazzy and after)
_HARDWARE_LOGGER = re.compile(r"(Hardware(Interface(Base)?)?|SystemInterface)$|(^|\.)hardware_component\.|ROS2Control")
# MoveIt's own loggers: move_group and its capabilities, and moveit2's "moveit.<package>.<part>" child loggers
_MOVEIT_LOGGER = re.compile(r"move_group\b|moveit[._]")
# a device driver's own logger: ROS packages name device drivers `*_driver` (ur_robot_driver, ydlidar_ros2_driver),
# and the UR driver hands its client library's log to "UR_Client_Library:<tf_prefix>" (ur_robot_driver/src/
# urcl_log_handler.cpp:59@humble)
_DRIVER_LOGGER = re.compile(r"driver|^UR_Client_Library:", re.I)
# what only a node that talks to a device can say of it: its firmware, its serial number (rplidar_node's "RPLIDAR S/N:
# …" and "Firmware Ver: …", sllidar_node.cpp and rplidar_node.cpp@ros2; realsense's "Device with serial number …")
_DEVICE_SAID = re.compile(r"\bfirmware\b|\bS/N\b|\bserial (number|no\.?)\b", re.I)
# a line that names what a driver was set up with: a device (its file, serial port or baud rate, or the word itself:
# a driver's "No MTi device found.") or a parameter
_DEVICE = re.compile(r"/dev/\w|\bserial[ _]?port\b|\bbaud[ _]?rate\b|\bdevices?\b", re.I)
_PARAMETER = re.compile(r"\bparam(eter)?s?\b", re.I)
# diff_drive_controller.cpp:466@jazzy (354@humble, 420@foxy): a velocity command came while the controller was
# configured (on_configure makes its subscription) but not active (only on_activate sets subscriber_is_active_)
_REFUSED = re.compile(r"Can't accept new commands\. subscriber is inactive")
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
    control = _catalogues()[0]
    return frozenset(e.id for e in control.entries if control.mined[e.id].level == "INFO"
                     and (e.kind == "nominal" or _DONE_TEXT.search(control.mined[e.id].text)))


def starting(line: LogLine) -> bool:
    """A line of the robot's starting software, by its logger: ros2_control's (a logger with a role in its catalogue:
    controller manager, resource manager, spawners; a hardware interface's own; gazebo's or gz's ros2_control
    plugin), MoveIt's own (move_group, moveit.*), or a line ros2_control's catalogue says completes a start; or a
    controller's refusal of commands (it was configured, so the start got that far). A generic text ("Waiting for
    …") of another node is no start: a client sending trajectories is not starting. Nor is a driver's own line
    without an error: a GPS driver saying "NEO6M Driver Started" on a vehicle that then drives its route for
    minutes (a real recording) started fine, and its run is not a start still under way."""
    name = line.name
    if control_logger(name) or moveit_logger(name) or refused(line):
        return True
    return completed(line)


def moveit_logger(name: str) -> bool:
    """MoveIt's own loggers: move_group and its capabilities, moveit2's "moveit.<package>.<part>", moveit_servo's."""
    return _MOVEIT_LOGGER.match(name) is not None


def control_logger(name: str) -> bool:
    """ros2_control's own loggers and its hardware interfaces' (not MoveIt's)."""
    return bool(_HARDWARE_LOGGER.search(name)) or "ros2_control" in name or _catalogues()[0].role(name) is not None


def refused(line: LogLine) -> bool:
    """A controller that refused commands because it was not active (below ERROR: the robot goes on without it)."""
    return line.level < ERROR and _REFUSED.search(line.msg) is not None


def completed(line: LogLine) -> bool:
    """A line of ros2_control that tells a part of the start completed."""
    entry = _catalogues()[0].match(line.msg)
    return line.level < ERROR and entry is not None and entry.id in _done_ids()


# the rest of libstdc++'s words for an uncaught exception when a console split them from "terminate called …"
# ("what():  parameter '…' has invalid type"), and backward-cpp's trace of a crash (ROS 2 prints it on a crash,
# "Stack trace (most recent call last) in thread 4726:" from a thread other than the main one)
_ABORT_REST = re.compile(r"^\s*what\(\):\s|Stack trace \(most recent call last\)( in thread \d+)?:")


def aborted(line: LogLine) -> bool:
    """A C++ exception nobody caught, or a crash's stack trace, whatever level the console gave the line."""
    return ABORT in line.msg or _ABORT_REST.search(line.msg) is not None


def _error(line: LogLine) -> bool:
    return (line.level >= ERROR and not notice(line)) or aborted(line)


def notice(line: LogLine) -> bool:
    """An ERROR line of ros2_control's that tells a normal event (the joint limiter clamping a command: the control
    catalogue's kind "notice"), which healthy robots print."""
    from hexar.explainers.control.catalogue import catalogue as control

    entry = control().match(line.msg)
    return entry is not None and entry.kind == "notice"


def _driver(name: str, logs: list[LogLine]) -> bool:
    """A node that drives a device: its name says so (ROS packages name device drivers `*_driver`: ur_robot_driver,
    ydlidar_ros2_driver), or one of its lines names a device file or tells the device's firmware or serial number. A
    node that only runs the robot's behaviour (a turtlebot4_node undocking, then missing a camera service) is no
    start of the robot."""
    return _DRIVER_LOGGER.search(name) is not None or any(
        ln.name == name and ("/dev/" in ln.msg or _DEVICE_SAID.search(ln.msg) is not None) for ln in logs)


# pluginlib's ClassLoader (pluginlib/class_loader_imp.hpp: RCUTILS_LOG_*_NAMED("pluginlib.ClassLoader", ...)) and
# class_loader's own (class_loader/src/class_loader_core.cpp: "class_loader.impl")
_LIBRARY_LOGGER = re.compile(r"^(pluginlib\.ClassLoader|class_loader(\.\w+)*)$")


def _shown(line: LogLine, before: list[LogLine], logs: list[LogLine]) -> bool:
    """The error belongs to a start the recording shows: an error of the starting software after a lesser line of
    it, a driver's error after a lesser line of its own, or a start line that goes on to tell an abort (a console's
    "Loading hardware '…'" whose next line is the abort)."""
    # a console prints a process's uncaught C++ exception on stderr, which names no node: the line printed before
    # it is the only sign of whose it was
    if not line.name and ABORT in line.msg and before and starting(before[-1]):
        return True
    # a library's logger (pluginlib's class loader) logs inside whichever node loads through it: its error right
    # after a line of the starting software is that start's
    if _LIBRARY_LOGGER.match(line.name) and before and starting(before[-1]) and line.t - before[-1].t <= 1e9:
        return True
    own = starting(line)
    if not own and not _driver(line.name, logs):
        return False
    if line.level < ERROR and ABORT in line.msg and line.msg.split(ABORT, 1)[0].strip():
        return True  # "Loading hardware '…'" and the abort on one console line
    return any(ln.level < ERROR and not _error(ln) and (ln.name == line.name or (own and starting(ln)))
               for ln in before)


def _alone(line: LogLine, logs: list[LogLine]) -> bool:
    """An error with no earlier line of its start that is still the robot's start: one of ros2_control's own or a
    hardware interface's loggers (URPositionHardwareInterface failing to read from the robot), of a device driver, or
    a line that names a device or a parameter to check (a lidar driver's own words for its port). MoveIt's lone
    error, or a behaviour node's ("Service … unavailable" after the robot undocked), is no start: healthy robots
    print such lines too."""
    if aborted(line) and starting(line):
        return True  # a process of the starting software that crashed: healthy robots do not
    if line.level < ERROR:
        return False
    return control_logger(line.name) or _driver(line.name, logs) or names_device(line) or names_parameter(line)


def names_device(line: LogLine) -> bool:
    """The line names a device: its file, a serial port, a baud rate."""
    return _DEVICE.search(line.msg) is not None


def names_parameter(line: LogLine) -> bool:
    """The line names a parameter (its own word for it: parameter, param, params)."""
    return _PARAMETER.search(line.msg) is not None


# launch's line for a process that ended (launch/actions/execute_local.py): "process has died [pid %d, exit code %d,
# cmd '%s']."; a ROS node's command line carries "--ros-args", a command launch ran for the set-up (rm, mkdir) none
_DIED = re.compile(r"process has died \[pid \d+, exit code (?P<code>\d+), cmd '(?P<cmd>[^']*)'")


def helper_exit(line: LogLine, logs: list[LogLine]) -> bool:
    """A command launch ran that is no ROS node (its command line has no --ros-args: `rm /var/lock/lidar.lock`)
    ended with an error code, and the robot's nodes went on after it (a line of another process later): a set-up
    command's failure, not the start's."""
    m = _DIED.search(line.msg)
    if m is None or "--ros-args" in m["cmd"] or int(m["code"]) == 0:
        return False
    from hexar.explainers.stack.bringup import PROCESS_SUFFIX

    process = PROCESS_SUFFIX.sub("", line.name)
    return any(ln.t >= line.t and ln is not line and ln.level < ERROR and ln.name and
               PROCESS_SUFFIX.sub("", ln.name) != process and "process started" not in ln.msg for ln in logs)


def bring_up(logs: list[LogLine]) -> BringUp | None:
    """The start of the robot in `logs` (time-ordered), or None when they show no start at all."""
    from hexar.explainers.shutdown import before_shutdown
    from hexar.explainers.stack.bringup import ros2_run_said
    from hexar.explainers.stack_causes import launch_transition, stack_cause, transition_reason

    if not logs:
        return None
    last = max(ln.t for ln in logs)
    helpers = {id(ln) for ln in logs if helper_exit(ln, logs)}
    logs = [ln for ln in logs if id(ln) not in helpers]
    up = before_shutdown(logs)
    if len(up) < len(logs) and (first := next((ln for ln in up if starting(ln) or _driver(ln.name, up)), None)) \
            and not any(_error(ln) for ln in up) and stack_cause(up) is None:
        # stopped before anything failed (Ctrl-C): what its processes print on the way down is no failure of the
        # start (a Python node's KeyboardInterrupt traceback, launch's "process has died [..., exit code -2]")
        if any(completed(ln) for ln in up) and not any(refused(ln) for ln in up):
            # it had come up before it was stopped: its run goes on to the stop (warnings on the way are its own)
            return BringUp(first.t, "succeeded", up[-1].t)
        kept = {id(u) for u in up}
        stop = next(ln for ln in logs if ln.t >= up[-1].t and id(ln) not in kept)
        return BringUp(first.t, "canceled", stop.t, f"stopped: {' '.join(stop.msg.split())[:120]}")
    stack = stack_cause(logs)
    if stack is not None:
        # a transition launch saw fail began with the lifecycle's own reason for it, and a command ros2run could not
        # start with ros2run's words: the step must hold them
        reason = transition_reason(stack.line, logs) or ros2_run_said(stack.line, logs)
        return BringUp(reason.t if reason else stack.line.t, "failed", last, stack.line.msg)
    first = next((ln for ln in logs if starting(ln)), None)
    turned = next((ln for ln in logs if ln.level >= ERROR and launch_transition(ln)), None)
    if turned is not None:
        # launch_ros asked a node it started for a lifecycle transition and the node refused, saying nothing of why
        # (a reason logged before it is a stack cause, above): the start failed there all the same, from the node's
        # first line on
        node = launch_transition(turned)
        own = next((ln.t for ln in logs if ln.name.replace(".", "/").strip("/") == node), turned.t)
        return BringUp(min(own, turned.t), "failed", last, turned.msg)
    failed = next((ln for i, ln in enumerate(logs) if _error(ln) and (_shown(ln, logs[:i], logs) or _alone(ln, logs))),
                  None)
    if failed is not None:
        # the step began with the start the error belongs to: its node's first line, or the software's
        began = [failed.t, *(ln.t for ln in logs if ln.name == failed.name), *([first.t] if first else [])]
        return BringUp(min(began), "failed", last, failed.msg)
    if first is None or any(_error(ln) for ln in logs):
        return None  # an error the recording does not show a start of (one line of MoveIt's): not told either way
    done = [ln for ln in logs if completed(ln)]
    if done and not any(refused(ln) for ln in logs):  # a controller that refused commands did not come up as asked
        return BringUp(first.t, "succeeded", done[-1].t)
    return BringUp(first.t, "running")
