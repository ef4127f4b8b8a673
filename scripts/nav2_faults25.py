"""The faults of blind Nav2 set 25, run by scripts/nav2_faults.py (`--set 25`): set 20's bring-up (NavFn, Regulated
Pure Pursuit, the base's perfect localisation) with bt_navigator's NavigateThroughPoses navigator, sent three poses as
nav2_simple_commander's goThroughPoses sends them, and, where a fault needs them, keepout zones as nav2_bringup's
keepout_zone_launch.py makes them (a filter mask served by map_server, costmap_filter_info_server, a KeepoutFilter
in both costmaps with nav2_bringup's params@kilted). One fault each of a pose's place, the navigator's list, a
keepout zone at the goal or at the start (with and without the lethal-cost override), the filter mask's file, the
filter info's base, and a box; two runs with nothing wrong. Written, with their causes and the labelling rule of
nav2_faults.label(), before any of them was run.
"""

from __future__ import annotations

from typing import Any

from nav2_faults import BRINGUP, CONFIG, NOMINAL, Fault

UNREACHABLE, BLOCKED = "navigation.goal_unreachable", "navigation.blocked_path"
START_IN = "navigation.start_in_obstacle"
ROUTE = ((4.0, 2.5), (4.0, 5.5), (9.0, 4.0))  # two in the first room, one through the doorway in the other
NAVIGATORS = {"bt_navigator": {"navigators": ["navigate_to_pose", "navigate_through_poses"],
                               "navigate_through_poses": {
                                   "plugin": "nav2_bt_navigator::NavigateThroughPosesNavigator"}}}
FILTERS = ("keepout_filter_mask_server", "keepout_costmap_filter_info_server")
CORNER = ((10.5, 6.5, 11.8, 7.8),)  # a keepout zone in the far corner of the second room, off every route


def keepout(override: bool = True, mask: str = "@work/maps/keepout_mask.yaml", base: float = 0.0
            ) -> dict[str, dict[str, Any]]:
    """The through-poses navigator and nav2_bringup's keepout zone parameters (params@kilted)."""
    layer = {"plugin": "nav2_costmap_2d::KeepoutFilter", "enabled": True,
             "filter_info_topic": "keepout_costmap_filter_info", "override_lethal_cost": override,
             "lethal_override_cost": 200}
    costmaps = {f"{c}/{c}": {"filters": ["keepout_filter"], "keepout_filter": dict(layer)}
                for c in ("local_costmap", "global_costmap")}
    return {**NAVIGATORS, **costmaps,
            "keepout_filter_mask_server": {"topic_name": "keepout_filter_mask", "yaml_filename": mask},
            "keepout_costmap_filter_info_server": {"type": 0, "filter_info_topic": "keepout_costmap_filter_info",
                                                   "mask_topic": "keepout_filter_mask", "base": base,
                                                   "multiplier": 1.0}}


FAULTS25 = (
    Fault("through-nominal", NOMINAL, "Nothing was wrong: the three poses were free and reachable.",
          params=NAVIGATORS, waypoints=ROUTE, through=True),
    Fault("through-keepout-nominal", NOMINAL, "Nothing was wrong: a keepout zone lay in a corner of the second room, "
          "off the route.", params=keepout(), servers=FILTERS, keepout=CORNER, waypoints=ROUTE, through=True),
    Fault("through-pose-off-map", UNREACHABLE, "The last pose was outside the map.",
          params=NAVIGATORS, waypoints=((4.0, 2.5), (4.0, 5.5), (16.0, 4.0)), through=True),
    Fault("through-navigator-missing", CONFIG, "bt_navigator's navigators listed navigate_to_pose only, so no "
          "navigate_through_poses action server existed for the poses.",
          waypoints=ROUTE, through=True, silent=True),
    Fault("keepout-goal", UNREACHABLE, "The last pose lay inside a 2 m keepout zone (x 8 to 10, y 3 to 5).",
          params=keepout(), servers=FILTERS, keepout=((8.0, 3.0, 10.0, 5.0),), waypoints=ROUTE, through=True),
    Fault("keepout-start", START_IN, "The robot started inside a keepout zone (x 1 to 3, y 3 to 5), with the "
          "filter's lethal-cost override on (nav2_bringup's default).",
          params=keepout(), servers=FILTERS, keepout=((1.0, 3.0, 3.0, 5.0),), waypoints=ROUTE, through=True),
    Fault("keepout-start-no-override", START_IN, "The robot started inside a keepout zone (x 1 to 3, y 3 to 5), "
          "with the filter's override_lethal_cost false, so every cell under it was lethal.",
          params=keepout(override=False), servers=FILTERS, keepout=((1.0, 3.0, 3.0, 5.0),), waypoints=ROUTE,
          through=True),
    Fault("keepout-mask-missing", BRINGUP, "The keepout filter mask server's yaml_filename named a file that is not "
          "there, so it failed to configure and the bring-up was aborted.",
          params=keepout(mask="@work/maps/keepout.yaml"), servers=FILTERS, keepout=CORNER, waypoints=ROUTE,
          through=True),
    Fault("keepout-info-base", CONFIG, "The keepout filter info's base was 1.0 instead of the 0.0 a keepout filter "
          "needs.", params=keepout(base=1.0), servers=FILTERS, keepout=CORNER, waypoints=ROUTE, through=True),
    Fault("through-doorway-blocked", BLOCKED, "A box was put in the doorway after the robot passed the second pose, "
          "so the last pose, in the other room, could not be reached.",
          params=NAVIGATORS, waypoints=ROUTE, through=True, base={"boxes": [4.6, 5.9, 3.4, 6.5, 4.6]}),
)

HEADER25 = """\
# Blind Nav2 set 25: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) sent three poses through NavigateThroughPoses, with keepout zones where
# a fault needs them, each run with one fault and started by the real ros2launch: written by scripts/nav2_faults.py
# --set 25, whose faults (scripts/nav2_faults25.py) and labelling rule were written before any run was made. Output
# is kept as printed, less ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once
# before anything was tuned on it. Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py
# --set 25 --out FILE
"""
