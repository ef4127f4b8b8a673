"""The faults of blind Nav2 set 28, run by scripts/nav2_faults.py (`--set 28`): set 20's bring-up (NavFn, Regulated
Pure Pursuit, the base's perfect localisation, the behaviour server's spin, backup, drive_on_heading and wait), sent
no navigation goal but one goal of a behaviour server action, as a script of nav2_simple_commander's spin(),
backup(), driveOnHeading() or wait() sends it. One fault each of a spin beside a wall, a backup toward a box, a spin's
time allowance, a behaviour plugin's class, the server's robot frame, its costmap topic, the base's command topic and
the lifecycle manager's node list; four runs with nothing wrong. Written, with their causes and the labelling rule of
nav2_faults.label() (a behaviour that succeeded is navigation.nominal), before any of them was run.
"""

from __future__ import annotations

import math
from typing import Any

from nav2_faults import BRINGUP, CONFIG, NOMINAL, TRANSFORM, Fault

AHEAD = "navigation.collision_ahead"
SERVER = ("behavior_server",)
# a rectangular robot, 0.7 m long and 0.4 m wide, as a costmap's footprint is written
RECTANGLE = {f"{c}/{c}": {"footprint": "[[0.35, 0.2], [0.35, -0.2], [-0.35, -0.2], [-0.35, 0.2]]"}
             for c in ("local_costmap", "global_costmap")}


def spin(angle: float, allowance: float = 10.0) -> tuple[Any, ...]:
    return ("spin", {"angle": angle, "allowance": allowance})


def backup(distance: float, speed: float, allowance: float = 10.0) -> tuple[Any, ...]:
    return ("backup", {"distance": distance, "speed": speed, "allowance": allowance})


def behaviors(**values: Any) -> dict[str, dict[str, Any]]:
    return {"behavior_server": values}


FAULTS28 = (
    Fault("spin-nominal", NOMINAL, "Nothing was wrong: the robot turned a quarter turn in the middle of its room.",
          behavior=spin(math.pi / 2)),
    Fault("backup-nominal", NOMINAL, "Nothing was wrong: the robot backed up 0.3 m at 0.1 m/s with nothing behind "
          "it.", behavior=backup(0.3, 0.1)),
    Fault("drive-nominal", NOMINAL, "Nothing was wrong: the robot drove 0.5 m ahead at 0.2 m/s with nothing in front "
          "of it.", behavior=("drive_on_heading", {"distance": 0.5, "speed": 0.2, "allowance": 10.0})),
    Fault("wait-nominal", NOMINAL, "Nothing was wrong: the robot waited 3 s as asked.",
          behavior=("wait", {"seconds": 3})),
    Fault("spin-beside-wall", AHEAD, "A rectangular robot (0.7 m by 0.4 m) stood sideways 0.1 m from the wall "
          "between the rooms and was asked to turn a quarter turn toward it, which would have swept its front into "
          "the wall.", params=RECTANGLE, base={"x": 5.7, "y": 2.0, "yaw": math.pi / 2},
          behavior=spin(-math.pi / 2)),
    Fault("backup-toward-box", AHEAD, "A box stood 0.3 m behind the robot, which was asked to back up 1 m.",
          base={"boxes": [0.0, 1.3, 3.7, 1.5, 4.3]}, behavior=backup(1.0, 0.15, 15.0)),
    Fault("spin-time-allowance", CONFIG, "The Spin goal allowed 4 s for a half turn, which at the behaviour "
          "server's max_rotational_vel of 0.4 rad/s takes about 8 s.",
          params=behaviors(max_rotational_vel=0.4), behavior=spin(math.pi, 4.0)),
    Fault("behavior-plugin-misspelt", CONFIG, "The spin behaviour's class was misspelt (nav2_behaviors::Spinn), so "
          "behavior_server could not load it and did not configure.",
          params=behaviors(spin={"plugin": "nav2_behaviors::Spinn"}), behavior=spin(math.pi / 2)),
    Fault("behavior-base-frame", TRANSFORM, "The behaviour server's robot_base_frame was base_footprint, a frame "
          "nothing publishes (the robot's frame is base_link).",
          params=behaviors(robot_base_frame="base_footprint"), behavior=spin(math.pi / 2)),
    Fault("behavior-costmap-topic", CONFIG, "The behaviour server's local_costmap_topic was costmap_raw, which "
          "nothing publishes (the local costmap publishes local_costmap/costmap_raw), so its collision checker had no "
          "costmap.", params=behaviors(local_costmap_topic="costmap_raw"), behavior=spin(math.pi / 2)),
    Fault("behavior-cmd-vel", "navigation.commands_not_reaching_base", "The base listened on /base/cmd_vel while "
          "the behaviour server published on /cmd_vel, so the robot never moved.",
          base={"cmd_vel_topic": "/base/cmd_vel"}, behavior=backup(0.3, 0.1), silent=True),
    Fault("behavior-unmanaged", BRINGUP, "behavior_server was left out of the lifecycle manager's node list, so it "
          "was never configured and its actions never came up.", unmanaged=SERVER, behavior=spin(math.pi / 2)),
)

HEADER28 = """\
# Blind Nav2 set 28: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI), sent one goal of a behaviour server action (spin, backup,
# drive_on_heading or wait) as nav2_simple_commander sends it, each run with one fault and started by the real
# ros2launch: written by scripts/nav2_faults.py --set 28, whose faults (scripts/nav2_faults28.py) and labelling rule
# were written before any run was made. Output is kept as printed, less ANSI colours, with this machine's folders
# replaced by fixed names. Frozen and measured once before anything was tuned on it. Regenerate inside a ROS 2
# environment with Nav2: python3 scripts/nav2_faults.py --set 28 --out FILE
"""
