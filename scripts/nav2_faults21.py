"""The faults of blind Nav2 set 21, run by scripts/nav2_faults.py (`--set 21`): the same bring-up, now localised by
AMCL as a robot is (map -> odom from AMCL, not the base's perfect transform), with one fault each of localisation,
transforms, a process of the stack, its configuration or the base. Written, with their causes and the labelling
rule of nav2_faults.label(), before any of them was run.
"""

from __future__ import annotations

from nav2_faults import BRINGUP, CONFIG, COSTMAPS, NOMINAL, TRANSFORM, Fault

POOR = "navigation.poor_localisation"
FAULTS21 = (
    Fault("amcl-nominal", NOMINAL, "Nothing was wrong: AMCL was given the robot's true pose and the goal was "
          "reachable.", amcl=True),
    Fault("no-initial-pose", TRANSFORM, "AMCL was given no initial pose (set_initial_pose false, nobody set one in "
          "RViz), so it published no map -> odom transform.", amcl=True, initial=None),
    Fault("wrong-initial-pose", POOR, "AMCL was given an initial pose 2.1 m from where the robot stood, so it "
          "localised the robot in the wrong place.", amcl=True, initial=(3.5, 5.5, 0.0)),
    Fault("scan-frame-unknown", TRANSFORM, "The laser stamped its scans with frame laser_link, which no transform "
          "connects to the robot, so AMCL and the costmaps could not use them.", amcl=True,
          base={"scan_frame": "laser_link"}),
    Fault("odom-tf-stops", TRANSFORM, "The base stopped publishing the odom -> base_link transform after 2 m (its "
          "odometry topic went on), so the robot's pose went stale.", amcl=True, base={"tf_stop_after_m": 2.0}),
    Fault("controller-killed", BRINGUP, "controller_server was killed (SIGKILL, as the kernel's out-of-memory "
          "killer does) 5 s into the goal.", amcl=True, hit=("controller_server", "SIGKILL", 5.0)),
    Fault("behavior-plugin", CONFIG, "The spin behaviour's plugin class is misspelt (nav2_behaviors::Spinn), so "
          "behavior_server could not load it and did not configure.", amcl=True,
          params={"behavior_server": {"spin": {"plugin": "nav2_behaviors::Spinn"}}}),
    Fault("base-frame-wrong", TRANSFORM, "Both costmaps name base_footprint as the robot's frame, which this robot "
          "does not have (its frame is base_link).", amcl=True,
          params={c: {"robot_base_frame": "base_footprint"} for c in COSTMAPS}),
    Fault("robot-too-wide", CONFIG, "The costmaps' robot_radius was set to 0.6 m, wider than half the 1 m doorway, "
          "so no path led through it.", amcl=True, params={c: {"robot_radius": 0.6} for c in COSTMAPS}),
    Fault("base-slow", NOMINAL, "Nothing was wrong with the stack; the base drove at 30 % of the commanded speed "
          "(a low battery), so the trip was slow.", amcl=True, base={"speed_scale": 0.3}, slow=True),
    Fault("base-stalled", "navigation.commands_not_reaching_base", "The base drove at 2 % of the commanded speed "
          "(its motors barely turning), so the robot hardly moved.", amcl=True, base={"speed_scale": 0.02},
          silent=True),
)

HEADER21 = """\
# Blind Nav2 set 21: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI), localised by AMCL, each run with one fault and started by the real
# ros2launch: written by scripts/nav2_faults.py --set 21, whose faults (scripts/nav2_faults21.py) and labelling rule
# were committed before any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders
# replaced by fixed names. Frozen and measured once, with nothing tuned on it.
# Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 21 --out FILE
"""
