"""The ros2_control message catalogue (ros2_control_catalogue.json, mined by scripts/mine_modules.py from
ros-controls/ros2_control and ros-controls/ros2_controllers, and the drivers and simulators people run under it:
the UR driver and its client library, gazebo_ros2_control, gz_ros2_control, Kinova's ros2_kortex, the KUKA LBR
stack, KUKA's drivers, Franka's (and libfranka's texts), Dynamixel, Robotiq, MuJoCo, xArm and
topic_based_ros2_control): controller_manager, the spawners, hardware interfaces and the stock controllers. A
driver's line also names the hardware_interface callbacks that log it (explainers/control/driver_roles.py)."""

from __future__ import annotations

from functools import cache

from hexar.explainers.logcause import ModuleCatalogue, load

# the joint trajectory controller's refusal of a goal while it is not active ("Can't accept new action goals.
# Controller is not running."): it ends the goal it refuses, and says that the controller is not active, never why
REFUSED = "joint_trajectory_controller.can_t_accept_new_action_goals"
# its checks of a goal's trajectory (validate_trajectory_msg@kilted, from goal_received_callback): one of these lines
# rejects the goal it has just received, and says why (scripts/modules_mining.yaml gives each its cause)
INVALID = frozenset(f"joint_trajectory_controller.{key}" for key in (
    "time_between_points_and_is_not", "mismatch_between_joint_names_and_at", "mismatch_between_joint_names_size_and",
    "empty_trajectory_received", "velocity_of_last_trajectory_point_of", "received_trajectory_with_non_zero_start",
    "the_given_trajectory_has_no_position", "joints_on_incoming_trajectory_don_t", "incoming_joint_doesn_t_match_the",
    "empty_joint_names_on_incoming_trajectory"))


@cache
def catalogue() -> ModuleCatalogue:
    return load("hexar.explainers.control", "ros2_control_catalogue.json")

