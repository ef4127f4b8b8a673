"""The faults of blind Nav2 set 26, run by scripts/nav2_faults.py (`--set 26`): set 20's bring-up (NavFn, Regulated
Pure Pursuit, the base's perfect localisation) with nav2_bringup's docking_server (opennav_docking's
SimpleChargingDock, params@kilted), sent one DockRobot goal for a dock of its database as nav2_simple_commander's
dockRobotByID sends it: the docking server drives the robot to the dock's staging pose through bt_navigator, finds
the dock with the detector's poses, drives onto it with its own controller and, where the battery is read, waits for
the charge. One fault each of the dock asked for, the dock's pose in the database, the detector, the detector's frame,
the server's fixed frame, the dock plugin's class, the database file, the battery's driver, a box before the dock and
a box in the doorway on the way to it; two runs with nothing wrong. Written, with their causes and the labelling rule
of nav2_faults.label() (a dock reached is navigation.nominal), before any of them was run.
"""

from __future__ import annotations

import math
from typing import Any

from nav2_faults import BRINGUP, CONFIG, NOMINAL, TRANSFORM, Fault

DOCKING, BLOCKED, AHEAD = "navigation.docking_failure", "navigation.blocked_path", "navigation.collision_ahead"
HOME = (0.5, 2.0, math.pi)  # against the first room's west wall: the robot faces the wall on it
FAR = (11.5, 6.0, 0.0)  # against the second room's east wall, through the doorway
SERVER = ("docking_server",)


def docking(pose: tuple[float, float, float] = HOME, server: dict[str, Any] | None = None, **dock: Any
            ) -> dict[str, dict[str, Any]]:
    """nav2_bringup's docking_server parameters (params@kilted) with one dock, home_dock, in the params file as its
    README shows; the detector reports the pose the robot docks at, so the detection offsets are zero."""
    plugin = {"plugin": "opennav_docking::SimpleChargingDock", "docking_threshold": 0.05, "staging_x_offset": -0.7,
              "use_external_detection_pose": True, "use_battery_status": False, "use_stall_detection": False,
              "dock_direction": "forward", "external_detection_timeout": 1.0,
              "external_detection_translation_x": 0.0, "external_detection_translation_y": 0.0,
              "external_detection_rotation_roll": 0.0, "external_detection_rotation_pitch": 0.0,
              "external_detection_rotation_yaw": 0.0, "filter_coef": 0.1, **dock}
    values = {"controller_frequency": 50.0, "initial_perception_timeout": 5.0, "wait_charge_timeout": 5.0,
              "dock_approach_timeout": 30.0, "undock_linear_tolerance": 0.05, "undock_angular_tolerance": 0.1,
              "max_retries": 3, "base_frame": "base_link", "fixed_frame": "odom", "dock_prestaging_tolerance": 0.5,
              "enable_stamped_cmd_vel": True, "dock_plugins": ["simple_charging_dock"],
              "simple_charging_dock": plugin, "docks": ["home_dock"],
              "home_dock": {"type": "simple_charging_dock", "frame": "map", "pose": list(pose)},
              "controller": {"k_phi": 3.0, "k_delta": 2.0, "v_linear_min": 0.15, "v_linear_max": 0.15,
                             "use_collision_detection": True, "costmap_topic": "local_costmap/costmap_raw",
                             "footprint_topic": "local_costmap/published_footprint", "transform_tolerance": 0.1,
                             "projection_time": 5.0, "simulation_step": 0.1, "dock_collision_threshold": 0.3}}
    return {"docking_server": {**values, **(server or {})}}


def world(pose: tuple[float, float, float] = HOME, **base: Any) -> dict[str, Any]:
    """The dock where it physically is, its detector and, where asked, the battery's driver."""
    return {"dock": list(pose), "detector": True, **base}


FAULTS26 = (
    Fault("dock-nominal", NOMINAL, "Nothing was wrong: the dock was in the robot's room and the detector saw it.",
          params=docking(), base=world(), servers=SERVER, dock_id="home_dock"),
    Fault("dock-far-charging", NOMINAL, "Nothing was wrong: the dock was in the other room, and the battery's driver "
          "reported the charge once the robot was on it.",
          params=docking(FAR, use_battery_status=True), base=world(FAR, battery=True), servers=SERVER,
          dock_id="home_dock"),
    Fault("dock-not-in-database", DOCKING, "The DockRobot goal asked for kitchen_dock, which is not in the docking "
          "server's database (only home_dock is).", params=docking(), base=world(), servers=SERVER,
          dock_id="kitchen_dock"),
    Fault("dock-yaw-reversed", DOCKING, "The dock's yaw in the database was 0 instead of pi, so its staging pose lay "
          "0.7 m behind the dock, outside the map, and the robot could not be driven there.",
          params=docking((HOME[0], HOME[1], 0.0)), base=world(), servers=SERVER, dock_id="home_dock"),
    Fault("detector-off", DOCKING, "The dock detector was not running (nothing published detected_dock_pose), so the "
          "docking server never saw the dock.", params=docking(), base=world(detector=False), servers=SERVER,
          dock_id="home_dock"),
    Fault("detector-frame", TRANSFORM, "The dock detector stamped its poses in camera_link, a frame with no transform "
          "to the robot (the camera's link missing from the robot's description).",
          params=docking(), base=world(dock_frame="camera_link"), servers=SERVER, dock_id="home_dock"),
    Fault("fixed-frame", TRANSFORM, "The docking server's fixed_frame was odom_combined, a frame nothing publishes.",
          params=docking(server={"fixed_frame": "odom_combined"}), base=world(), servers=SERVER, dock_id="home_dock"),
    Fault("dock-plugin-misspelt", CONFIG, "The dock plugin's class was misspelt (opennav_docking::SimpleChargingDok), "
          "so docking_server could not load it and did not configure.",
          params=docking(plugin="opennav_docking::SimpleChargingDok"), base=world(), servers=SERVER,
          dock_id="home_dock"),
    Fault("dock-database-missing", BRINGUP, "docking_server's dock_database named a file that is not there, so it "
          "failed to configure and the bring-up was aborted.",
          params=docking(server={"dock_database": "@work/docks.yaml"}), base=world(), servers=SERVER,
          dock_id="home_dock"),
    Fault("battery-silent", DOCKING, "The docking server waited for the battery to report charging "
          "(use_battery_status true), but nothing published battery_state, so the charge never seemed to start.",
          params=docking(use_battery_status=True), base=world(), servers=SERVER, dock_id="home_dock"),
    Fault("box-before-dock", AHEAD, "A box stood between the dock's staging pose and the dock, so the docking "
          "approach would have driven into it.",
          params=docking(), base=world(boxes=[0.0, 0.78, 1.92, 0.92, 2.08]), servers=SERVER, dock_id="home_dock"),
    Fault("far-doorway-blocked", BLOCKED, "A box was put in the doorway as the robot drove toward it, on its way to "
          "the staging pose of the dock in the other room.",
          params=docking(FAR), base=world(FAR, boxes=[4.0, 5.9, 3.4, 6.5, 4.6]), servers=SERVER,
          dock_id="home_dock"),
)

HEADER26 = """\
# Blind Nav2 set 26: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) with its docking server, sent one DockRobot goal, each run with one fault
# and started by the real ros2launch: written by scripts/nav2_faults.py --set 26, whose faults
# (scripts/nav2_faults26.py) and labelling rule were written before any run was made. Output is kept as printed, less
# ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before anything was
# tuned on it. Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 26 --out FILE
"""
