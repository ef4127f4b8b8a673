"""The ros2_control message catalogue (ros2_control_catalogue.json, mined by scripts/mine_modules.py from
ros-controls/ros2_control and ros-controls/ros2_controllers, and the drivers and simulators people run under it:
the UR driver and its client library, gazebo_ros2_control, gz_ros2_control, Kinova's ros2_kortex, the KUKA LBR
stack): controller_manager, the spawners, hardware interfaces and the stock controllers."""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache

from hexar.events.records import LogLine
from hexar.explainers.logcause import ModuleCatalogue, Reading, load

# controller_manager.cpp:777@jazzy, logged when the robot_description topic delivers; from then on the manager's
# "Waiting for data on 'robot_description' topic" and "Resource Manager is not initialized yet" (:769, :1866) mean
# that the resource manager failed to initialise with it (:789 keeps waiting), not that it never arrived
RECEIVED = "Received robot description from topic."
WAITING = ("Waiting for data on 'robot_description' topic", "Resource Manager is not initialized yet")


@cache
def catalogue() -> ModuleCatalogue:
    return load("hexar.explainers.control", "ros2_control_catalogue.json")


def description_arrived(readings: list[Reading], lines: Sequence[LogLine]) -> list[Reading]:
    """The readings, the controller manager's waiting lines stripped of their cause once it said (in `lines`, the
    whole recording's) that the robot description arrived: the decisive line is then the resource manager's own
    error, or none."""
    got = next((ln.t for ln in lines if RECEIVED in ln.msg), None)
    if got is None:
        return readings
    return [Reading(r.line, r.entry, None, r.catalogue)
            if r.line.t >= got and r.cause == "bringup.configuration_error" and any(w in r.line.msg for w in WAITING)
            else r for r in readings]
