"""The faults of blind Nav2 set 22, run by scripts/nav2_faults.py (`--set 22`): the same bring-up with the chain a
Nav2 robot has between its controller and its base since Iron (nav2_bringup navigation_launch.py@kilted): the
velocity smoother, then the collision monitor; and the DWB controller in place of Regulated Pure Pursuit on two runs.
One fault each of the smoother, the collision monitor, the controller's plugins and checkers, or the behaviour tree.
Written, with their causes and the labelling rule of nav2_faults.label(), before any of them was run. Should the
collision monitor not build on this computer, its four faults are dropped before any run and the rest run with the
smoother's output remapped to cmd_vel (nav2_faults._remaps); the data header then says so.
"""

from __future__ import annotations

from typing import Any

from nav2_faults import CONFIG, NOMINAL, TRANSFORM, Fault

BRINGUP, COLLISION = "navigation.bringup_failure", "navigation.collision_ahead"
NOT_REACHING = "navigation.commands_not_reaching_base"
CHAIN = ("velocity_smoother", "collision_monitor")
# nav2_bringup's params@kilted for both, with this robot's frame (base_link) and a circle around it for the monitor
SMOOTHER: dict[str, Any] = {
    "smoothing_frequency": 20.0, "scale_velocities": False, "feedback": "OPEN_LOOP", "enable_stamped_cmd_vel": True,
    "max_velocity": [0.5, 0.0, 2.0], "min_velocity": [-0.5, 0.0, -2.0], "max_accel": [2.5, 0.0, 3.2],
    "max_decel": [-2.5, 0.0, -3.2], "odom_topic": "odom", "odom_duration": 0.1,
    "deadband_velocity": [0.0, 0.0, 0.0], "velocity_timeout": 1.0}
MONITOR: dict[str, Any] = {
    "base_frame_id": "base_link", "odom_frame_id": "odom", "cmd_vel_in_topic": "cmd_vel_smoothed",
    "cmd_vel_out_topic": "cmd_vel", "state_topic": "collision_monitor_state", "transform_tolerance": 0.2,
    "source_timeout": 1.0, "base_shift_correction": True, "stop_pub_timeout": 2.0, "enable_stamped_cmd_vel": True,
    "polygons": ["FootprintApproach"],
    "FootprintApproach": {"type": "polygon", "action_type": "approach",
                          "footprint_topic": "local_costmap/published_footprint", "time_before_collision": 1.2,
                          "simulation_time_step": 0.1, "min_points": 6, "visualize": False, "enabled": True},
    "observation_sources": ["scan"],
    "scan": {"type": "scan", "topic": "scan", "min_height": 0.15, "max_height": 2.0, "enabled": True}}
DWB: dict[str, Any] = {
    "plugin": "dwb_core::DWBLocalPlanner", "debug_trajectory_details": True, "min_vel_x": 0.0, "min_vel_y": 0.0,
    "max_vel_x": 0.5, "max_vel_y": 0.0, "max_vel_theta": 1.0, "min_speed_xy": 0.0, "max_speed_xy": 0.5,
    "min_speed_theta": 0.0, "acc_lim_x": 2.5, "acc_lim_y": 0.0, "acc_lim_theta": 3.2, "decel_lim_x": -2.5,
    "decel_lim_y": 0.0, "decel_lim_theta": -3.2, "vx_samples": 20, "vy_samples": 5, "vtheta_samples": 20,
    "sim_time": 1.7, "linear_granularity": 0.05, "angular_granularity": 0.025, "transform_tolerance": 0.2,
    "xy_goal_tolerance": 0.25, "trans_stopped_velocity": 0.25, "short_circuit_trajectory_evaluation": True,
    "stateful": True,
    "critics": ["RotateToGoal", "Oscillation", "BaseObstacle", "GoalAlign", "PathAlign", "PathDist", "GoalDist"],
    "BaseObstacle.scale": 0.02, "PathAlign.scale": 32.0, "PathAlign.forward_point_distance": 0.1,
    "GoalAlign.scale": 24.0, "GoalAlign.forward_point_distance": 0.1, "PathDist.scale": 32.0, "GoalDist.scale": 24.0,
    "RotateToGoal.scale": 32.0, "RotateToGoal.slowing_factor": 5.0, "RotateToGoal.lookahead_time": -1.0}


def chained(smoother: dict[str, Any] | None = None, monitor: dict[str, Any] | None = None,
            **others: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The params of a run with the chain: the smoother's and the monitor's defaults, the fault's values over them."""
    return {"velocity_smoother": {**SMOOTHER, **(smoother or {})}, "collision_monitor": {**MONITOR, **(monitor or {})},
            **others}


def _circle(action: str, radius: float, **extra: Any) -> dict[str, Any]:
    return {"polygons": ["Guard"], "Guard": {"type": "circle", "radius": radius, "action_type": action,
                                             "min_points": 4, "visualize": False, "enabled": True, **extra}}


FAULTS22 = (
    Fault("chain-nominal", NOMINAL, "Nothing was wrong: the goal in the other room was reachable, and the velocity "
          "smoother and the collision monitor passed the controller's commands on.", params=chained(), chain=CHAIN),
    Fault("smoother-decel-positive", CONFIG, "The velocity smoother's max_decel was written with positive values, "
          "so it refused to configure and the bring-up stopped there.",
          params=chained({"max_decel": [2.5, 0.0, 3.2]}), chain=CHAIN),
    Fault("smoother-not-remapped", NOT_REACHING, "The launch file started the velocity smoother without remapping its "
          "input to cmd_vel_nav, so it never heard the controller and nothing reached the base.",
          params=chained(), chain=CHAIN, unmapped=("velocity_smoother",), silent=True),
    Fault("smoother-closed-loop-no-odom", CONFIG, "The velocity smoother ran in CLOSED_LOOP on odometry from "
          "wheel_odom, a topic nothing publishes, so it limited each command from a standstill and the robot crept.",
          params=chained({"feedback": "CLOSED_LOOP", "odom_topic": "wheel_odom"}), chain=CHAIN, slow=True,
          silent=True),
    Fault("smoother-killed", BRINGUP, "The velocity smoother's process was killed (SIGKILL, as the kernel's "
          "out-of-memory killer does) 5 s into the goal, so the controller's commands stopped reaching the base.",
          params=chained(), chain=CHAIN, hit=("velocity_smoother", "SIGKILL", 5.0)),
    Fault("monitor-stop-circle", COLLISION, "The collision monitor had a stop circle of 1.2 m radius around the "
          "robot, wider than the doorway and the room's clearance, so it stopped the robot near walls.",
          params=chained(monitor=_circle("stop", 1.2)), chain=CHAIN),
    Fault("monitor-slowdown-circle", COLLISION, "The collision monitor had a slowdown circle of 1.0 m radius at 30 % "
          "speed, so the robot crawled wherever a wall was within a metre.",
          params=chained(monitor=_circle("slowdown", 1.0, slowdown_ratio=0.3)), chain=CHAIN, slow=True),
    Fault("monitor-base-frame", TRANSFORM, "The collision monitor's base_frame_id was base_footprint (nav2_bringup's "
          "default), a frame this robot does not have, so it could not transform the laser's data.",
          params=chained(monitor={"base_frame_id": "base_footprint"}), chain=CHAIN),
    Fault("monitor-scan-topic", CONFIG, "The collision monitor's scan source listened on /scan_front, which nothing "
          "publishes, so it had no data from its only source.",
          params=chained(monitor={"scan": {**MONITOR["scan"], "topic": "scan_front"}}), chain=CHAIN),
    Fault("dwb-nominal", NOMINAL, "Nothing was wrong: the DWB controller drove the robot to the goal in the other "
          "room.", params=chained(controller_server={"FollowPath": DWB}), chain=CHAIN),
    Fault("dwb-critic-misspelt", CONFIG, "One of DWB's critics was misspelt (BaseObstacl), so controller_server "
          "could not load it and did not configure.",
          params=chained(controller_server={"FollowPath": {**DWB, "critics": [
              "RotateToGoal", "Oscillation", "BaseObstacl", "GoalAlign", "PathAlign", "PathDist", "GoalDist"]}}),
          chain=CHAIN),
    Fault("progress-checker-strict", CONFIG, "The progress checker asked for 3 m of movement every 2 s, more than "
          "the robot's 0.5 m/s can give, so the controller gave up for want of progress while it drove.",
          params=chained(controller_server={"progress_checker": {"required_movement_radius": 3.0,
                                                                 "movement_time_allowance": 2.0}}),
          chain=CHAIN, silent=True),
    Fault("goal-tolerance-tiny", CONFIG, "The goal checker's tolerances were 1 mm and 0.001 rad, tighter than the "
          "robot can stop, so it never judged the goal reached.",
          params=chained(controller_server={"general_goal_checker": {"xy_goal_tolerance": 0.001,
                                                                     "yaw_goal_tolerance": 0.001}}),
          chain=CHAIN, silent=True),
    Fault("bt-xml-missing", CONFIG, "bt_navigator's default_nav_to_pose_bt_xml named a behaviour tree file that is "
          "not there (navigate_w_replanning.xml in the work folder), so it could not load its tree.",
          params=chained(bt_navigator={"default_nav_to_pose_bt_xml": "@work/navigate_w_replanning.xml"}),
          chain=CHAIN),
)
MONITOR_FAULTS = ("monitor-stop-circle", "monitor-slowdown-circle", "monitor-base-frame", "monitor-scan-topic")

HEADER22 = """\
# Blind Nav2 set 22: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) with the velocity smoother and the collision monitor between the
# controller and the base, as nav2_bringup has them, each run with one fault and started by the real ros2launch:
# written by scripts/nav2_faults.py --set 22, whose faults (scripts/nav2_faults22.py) and labelling rule were committed
# before any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders replaced by
# fixed names. Frozen and measured once, with nothing tuned on it.
# Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 22 --out FILE
"""
