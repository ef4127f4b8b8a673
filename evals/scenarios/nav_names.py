"""Logger names and TIAGo navigation parameters shared by the navigation simulator and the robot state."""

from __future__ import annotations

BT, CTRL, PLAN, BEH = "bt_navigator", "controller_server", "planner_server", "behavior_server"
GCM, LCM, AMCL = "global_costmap.global_costmap", "local_costmap.local_costmap", "amcl"
JOY_RELAY = "joystick_relay"
MAX_VEL_X, MAX_VEL_THETA = 1.00, 1.00
SPEED_STATUS_NAME = "controller_server: velocity limits"
