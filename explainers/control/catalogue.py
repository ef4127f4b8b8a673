"""The ros2_control message catalogue (ros2_control_catalogue.json, mined by scripts/mine_modules.py from
ros-controls/ros2_control and ros-controls/ros2_controllers): controller_manager, the spawners, hardware
interfaces and the stock controllers, joint_trajectory_controller first."""

from __future__ import annotations

from functools import cache

from hexar.explainers.logcause import ModuleCatalogue, load


@cache
def catalogue() -> ModuleCatalogue:
    return load("hexar.explainers.control", "ros2_control_catalogue.json")
