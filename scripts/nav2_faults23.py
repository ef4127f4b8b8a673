"""The faults of blind Nav2 set 23, run by scripts/nav2_faults.py (`--set 23`): the bring-up of set 22 (velocity
smoother and collision monitor between the controller and the base) with the other controllers and planners a Nav2
robot may run, built here in round 35: MPPI (nav2_bringup's default controller since Jazzy), the rotation shim, the
graceful controller and Theta*. One fault each of the controller's plugin, its load on this 2-core computer, its
odometry, the local costmap, a planner, an obstacle or localisation. Written, with their causes and the labelling
rule of nav2_faults.label(), before any of them was run.
"""

from __future__ import annotations

from typing import Any

from nav2_faults import CONFIG, NOMINAL, Fault
from nav2_faults22 import CHAIN, chained

COLLISION, CONTROLLER = "navigation.collision_ahead", "navigation.controller_failure"
UNREACHABLE, POOR = "navigation.goal_unreachable", "navigation.poor_localisation"
# nav2_bringup's params@kilted for MPPI (its FollowPath), the visualisation off
CRITICS = ["ConstraintCritic", "CostCritic", "GoalCritic", "GoalAngleCritic", "PathAlignCritic", "PathFollowCritic",
           "PathAngleCritic", "PreferForwardCritic"]
MPPI: dict[str, Any] = {
    "plugin": "nav2_mppi_controller::MPPIController", "time_steps": 56, "model_dt": 0.05, "batch_size": 2000,
    "ax_max": 3.0, "ax_min": -3.0, "ay_max": 3.0, "ay_min": -3.0, "az_max": 3.5, "vx_std": 0.2, "vy_std": 0.2,
    "wz_std": 0.4, "vx_max": 0.5, "vx_min": -0.35, "vy_max": 0.5, "wz_max": 1.9, "iteration_count": 1,
    "prune_distance": 1.7, "transform_tolerance": 0.1, "temperature": 0.3, "gamma": 0.015, "motion_model": "DiffDrive",
    "visualize": False, "publish_optimal_trajectory": False, "regenerate_noises": True, "critics": CRITICS,
    "ConstraintCritic": {"enabled": True, "cost_power": 1, "cost_weight": 4.0},
    "GoalCritic": {"enabled": True, "cost_power": 1, "cost_weight": 5.0, "threshold_to_consider": 1.4},
    "GoalAngleCritic": {"enabled": True, "cost_power": 1, "cost_weight": 3.0, "threshold_to_consider": 0.5},
    "PreferForwardCritic": {"enabled": True, "cost_power": 1, "cost_weight": 5.0, "threshold_to_consider": 0.5},
    "CostCritic": {"enabled": True, "cost_power": 1, "cost_weight": 3.81, "near_collision_cost": 253,
                   "critical_cost": 300.0, "consider_footprint": False, "collision_cost": 1000000.0,
                   "near_goal_distance": 1.0, "trajectory_point_step": 2},
    "PathAlignCritic": {"enabled": True, "cost_power": 1, "cost_weight": 14.0, "max_path_occupancy_ratio": 0.05,
                        "trajectory_point_step": 4, "threshold_to_consider": 0.5, "offset_from_furthest": 20,
                        "use_path_orientations": False},
    "PathFollowCritic": {"enabled": True, "cost_power": 1, "cost_weight": 5.0, "offset_from_furthest": 5,
                         "threshold_to_consider": 1.4},
    "PathAngleCritic": {"enabled": True, "cost_power": 1, "cost_weight": 2.0, "offset_from_furthest": 4,
                        "threshold_to_consider": 0.5, "max_angle_to_furthest": 1.0, "mode": 0}}
# Regulated Pure Pursuit as nav2_faults.params() has it, under the rotation shim (its primary controller)
RPP: dict[str, Any] = {
    "desired_linear_vel": 0.5, "lookahead_dist": 0.6, "min_lookahead_dist": 0.3, "max_lookahead_dist": 0.9,
    "use_velocity_scaled_lookahead_dist": False, "use_collision_detection": True,
    "max_allowed_time_to_collision_up_to_carrot": 1.0, "use_rotate_to_heading": False, "allow_reversing": False}
SHIM: dict[str, Any] = {
    "plugin": "nav2_rotation_shim_controller::RotationShimController",
    "primary_controller": "nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController",
    "angular_dist_threshold": 0.785, "forward_sampling_distance": 0.5, "rotate_to_heading_angular_vel": 1.8,
    "max_angular_accel": 3.2, "simulate_ahead_time": 1.0, "rotate_to_goal_heading": False, **RPP}
GRACEFUL: dict[str, Any] = {"plugin": "nav2_graceful_controller::GracefulController", "v_linear_max": 0.5,
                            "v_angular_max": 1.0, "max_robot_pose_search_dist": 5.0}
THETA: dict[str, Any] = {"plugin": "nav2_theta_star_planner::ThetaStarPlanner", "how_many_corners": 8,
                         "w_euc_cost": 1.0, "w_traversal_cost": 2.0, "use_final_approach_orientation": False}


def controller(follow: dict[str, Any], **more: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return chained(controller_server={"FollowPath": follow}, **more)


FAULTS23 = (
    Fault("mppi-nominal", NOMINAL, "Nothing was wrong: MPPI drove the robot to the goal in the other room.",
          params=controller(MPPI), chain=CHAIN),
    Fault("mppi-critic-misspelt", CONFIG, "One of MPPI's critics was misspelt (ObstaclesCritc), so controller_server "
          "could not load it and did not configure.",
          params=controller({**MPPI, "critics": [*CRITICS, "ObstaclesCritc"]}), chain=CHAIN),
    Fault("mppi-heavy", CONTROLLER, "MPPI was set to 8000 samples of 80 steps each, more than this 2-core computer "
          "can compute 20 times a second.", params=controller({**MPPI, "batch_size": 8000, "time_steps": 80}),
          chain=CHAIN),
    Fault("mppi-box-ahead", COLLISION, "A box appeared 0.6 m in front of the robot in the middle of the first room, "
          "while MPPI drove it.", params=controller(MPPI), chain=CHAIN, base={"boxes": [3.0, 3.6, 3.5, 4.1, 4.5]}),
    Fault("mppi-odom-topic", CONFIG, "controller_server's odom_topic was wheel_odom, which nothing publishes, so MPPI "
          "was always told the robot stood still.",
          params=chained(controller_server={"FollowPath": MPPI, "odom_topic": "wheel_odom"}),
          chain=CHAIN, silent=True),
    Fault("shim-nominal", NOMINAL, "Nothing was wrong: the rotation shim turned the robot toward its path, then "
          "Regulated Pure Pursuit drove it to the goal.", params=controller(SHIM), chain=CHAIN),
    Fault("graceful-nominal", NOMINAL, "Nothing was wrong: the graceful controller drove the robot to the goal.",
          params=controller(GRACEFUL), chain=CHAIN),
    Fault("theta-nominal", NOMINAL, "Nothing was wrong: Theta* planned the path to the goal.",
          params=chained(planner_server={"GridBased": THETA}), chain=CHAIN),
    Fault("theta-goal-in-wall", UNREACHABLE, "The goal was inside the wall between the rooms, and Theta* planned.",
          params=chained(planner_server={"GridBased": THETA}), chain=CHAIN, goal=(6.1, 2.0)),
    Fault("local-costmap-tiny", CONFIG, "The local costmap was 1 m by 1 m, hardly wider than the controller's "
          "lookahead (up to 0.9 m) and the robot's inflation (0.55 m).",
          params=chained(**{"local_costmap/local_costmap": {"width": 1, "height": 1}}), chain=CHAIN),
    Fault("amcl-laser-short", POOR, "AMCL's laser_max_range was 0.5 m, so it used almost none of the laser's beams "
          "and localised on odometry alone.", params=chained(amcl={"laser_max_range": 0.5}), chain=CHAIN, amcl=True),
)

HEADER23 = """\
# Blind Nav2 set 23: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) with the velocity smoother and the collision monitor, and MPPI, the
# rotation shim, the graceful controller or Theta*, each run with one fault and started by the real ros2launch: written
# by scripts/nav2_faults.py --set 23, whose faults (scripts/nav2_faults23.py) and labelling rule were committed before
# any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders replaced by fixed
# names. Frozen and measured once, with nothing tuned on it.
# Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 23 --out FILE
"""
