"""The faults of blind Nav2 set 24, run by scripts/nav2_faults.py (`--set 24`): set 20's bring-up (NavFn, Regulated
Pure Pursuit, the base's perfect localisation) with nav2_bringup's waypoint follower beside it, sent a list of three
waypoints as nav2_simple_commander's followWaypoints sends them. One fault each of a waypoint's place, the follower's
stop-on-failure setting, its task executor plugin and the task at each waypoint, its lifecycle, the waypoints' frame
and an obstacle; two runs with nothing wrong, one of them slow. Written, with their causes and the labelling rule of
nav2_faults.label(), before any of them was run.
"""

from __future__ import annotations

from typing import Any

from nav2_faults import BRINGUP, CONFIG, NOMINAL, TRANSFORM, Fault

UNREACHABLE, BLOCKED = "navigation.goal_unreachable", "navigation.blocked_path"
ROUTE = ((4.0, 2.5), (4.0, 5.5), (9.0, 4.0))  # two in the first room, one through the doorway in the other
FOLLOWER = ("waypoint_follower",)


def follower(**extra: Any) -> dict[str, dict[str, Any]]:
    """nav2_bringup's waypoint_follower parameters (params@kilted) with `extra` merged in."""
    wait = {"plugin": "nav2_waypoint_follower::WaitAtWaypoint", "enabled": True, "waypoint_pause_duration": 200}
    values: dict[str, Any] = {"loop_rate": 20, "stop_on_failure": False,
                              "waypoint_task_executor_plugin": "wait_at_waypoint", "wait_at_waypoint": wait}
    values.update(extra)
    return {"waypoint_follower": values}


FAULTS24 = (
    Fault("waypoints-nominal", NOMINAL, "Nothing was wrong: the three waypoints were free and reachable.",
          params=follower(), servers=FOLLOWER, waypoints=ROUTE),
    Fault("waypoints-long-pause", NOMINAL, "Nothing was wrong; the follower waited 12 s at each waypoint "
          "(wait_at_waypoint's waypoint_pause_duration 12000 ms), so the trip was slow.",
          params=follower(wait_at_waypoint={"plugin": "nav2_waypoint_follower::WaitAtWaypoint", "enabled": True,
                                            "waypoint_pause_duration": 12000}),
          servers=FOLLOWER, waypoints=ROUTE, slow=True),
    Fault("waypoint-in-wall-skip", UNREACHABLE, "The second waypoint was inside the wall between the rooms; the "
          "follower (stop_on_failure false) skipped it and went on.",
          params=follower(), servers=FOLLOWER, waypoints=((4.0, 2.5), (6.1, 2.0), (9.0, 4.0))),
    Fault("waypoint-in-wall-stop", UNREACHABLE, "The second waypoint was inside the wall between the rooms, and "
          "the follower had stop_on_failure true, so it gave up there.",
          params=follower(stop_on_failure=True), servers=FOLLOWER, waypoints=((4.0, 2.5), (6.1, 2.0), (9.0, 4.0))),
    Fault("waypoint-off-map", UNREACHABLE, "The last waypoint was outside the map.",
          params=follower(), servers=FOLLOWER, waypoints=((4.0, 2.5), (4.0, 5.5), (16.0, 4.0))),
    Fault("waypoint-executor-misspelt", CONFIG, "The waypoint task executor's class was misspelt "
          "(nav2_waypoint_follower::WaitAtWaypoints), so the follower could not create it.",
          params=follower(wait_at_waypoint={"plugin": "nav2_waypoint_follower::WaitAtWaypoints", "enabled": True,
                                            "waypoint_pause_duration": 200}),
          servers=FOLLOWER, waypoints=ROUTE),
    Fault("waypoint-photo-no-camera", CONFIG, "The task at each waypoint was PhotoAtWaypoint on "
          "/camera/color/image_raw, which nothing publishes (this robot has no camera there), so no photo could be "
          "taken and every waypoint's task failed.",
          params=follower(waypoint_task_executor_plugin="photo_at_waypoint",
                          photo_at_waypoint={"plugin": "nav2_waypoint_follower::PhotoAtWaypoint", "enabled": True,
                                             "image_topic": "/camera/color/image_raw", "image_format": "png"}),
          servers=FOLLOWER, waypoints=ROUTE),
    Fault("waypoint-follower-unmanaged", BRINGUP, "The launch file started waypoint_follower but left it out of the "
          "lifecycle manager's node_names, so it was never configured or activated and its action server never "
          "came up.", params=follower(), servers=FOLLOWER, unmanaged=FOLLOWER, waypoints=ROUTE),
    Fault("waypoints-frame-unknown", TRANSFORM, "The waypoints were given in frame odom_combined (robot_pose_ekf's "
          "name, from an old script), a frame nothing publishes.",
          params=follower(), servers=FOLLOWER, waypoints=ROUTE, frame="odom_combined"),
    Fault("waypoints-doorway-blocked", BLOCKED, "A box was put in the doorway after the robot passed the second "
          "waypoint, so the last waypoint, in the other room, could not be reached.",
          params=follower(), servers=FOLLOWER, waypoints=ROUTE, base={"boxes": [4.6, 5.9, 3.4, 6.5, 4.6]}),
)

HEADER24 = """\
# Blind Nav2 set 24: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) with its waypoint follower, sent three waypoints, each run with one fault
# and started by the real ros2launch: written by scripts/nav2_faults.py --set 24, whose faults
# (scripts/nav2_faults24.py) and labelling rule were written before any run was made. Output is kept as printed, less
# ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before anything was
# tuned on it. Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 24 --out FILE
"""
