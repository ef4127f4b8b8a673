"""The faults of blind Nav2 set 27, run by scripts/nav2_faults.py (`--set 27`): set 20's bring-up (NavFn, Regulated
Pure Pursuit, the base's perfect map -> odom) with, where a fault needs them, robot_localization's EKF publishing
odom -> base_link from the wheel odometry (as a robot whose driver leaves that transform to the filter), a speed
filter as Nav2's speed-limit tutorial sets it up (a scale-mode mask served by map_server, costmap_filter_info_server
of type 1, a SpeedFilter in the global costmap), and the smoother server (nav2_bringup's SimpleSmoother, params@kilted)
called from a behaviour tree that smooths each plan before the controller follows it. One fault each of the EKF's
input topic, its world frame, its rate, a speed zone that crawls, the smoother's plugin class, the tree's smoother id
and smoothing time; three runs with nothing wrong, one slowed on purpose by a speed zone. Written, with their causes
and the labelling rule of nav2_faults.label(), before any of them was run.
"""

from __future__ import annotations

from typing import Any

from nav2_faults import CONFIG, NOMINAL, TRANSFORM, Fault

EKF = ("ekf_filter_node",)
SPEED = ("speed_filter_mask_server", "speed_costmap_filter_info_server")
SMOOTHER = ("smoother_server",)
ZONE = ((3.0, 0.0, 9.0, 8.0),)  # across the doorway: most of the way from the start to the goal
NO_ODOM_TF = {"publish_odom_tf": False}


def ekf(**values: Any) -> dict[str, dict[str, Any]]:
    """robot_localization's EKF in 2D on the wheel odometry (its pose and twist), publishing odom -> base_link."""
    config = [True, True, False, False, False, True, True, True, False, False, False, True, False, False, False]
    return {"ekf_filter_node": {"frequency": 30.0, "two_d_mode": True, "publish_tf": True, "map_frame": "map",
                                "odom_frame": "odom", "base_link_frame": "base_link", "world_frame": "odom",
                                "odom0": "/odom", "odom0_config": config, "odom0_differential": False, **values}}


def speed(percent: int) -> dict[str, dict[str, Any]]:
    """The speed filter of Nav2's speed-limit tutorial; the mask's zone is `percent` of the robot's speed."""
    layer = {"plugin": "nav2_costmap_2d::SpeedFilter", "enabled": True,
             "filter_info_topic": "speed_costmap_filter_info", "speed_limit_topic": "speed_limit"}
    return {"global_costmap/global_costmap": {"filters": ["speed_filter"], "speed_filter": layer},
            "speed_filter_mask_server": {"topic_name": "speed_filter_mask",
                                         "yaml_filename": f"@work/maps/speed_mask_{percent}.yaml"},
            "speed_costmap_filter_info_server": {"type": 1, "filter_info_topic": "speed_costmap_filter_info",
                                                 "mask_topic": "speed_filter_mask", "base": 100.0,
                                                 "multiplier": -1.0}}


SMOOTH_BT = """<root BTCPP_format="4" main_tree_to_execute="MainTree">
  <BehaviorTree ID="MainTree">
    <PipelineSequence name="NavigateWithSmoothing">
      <RateController hz="1.0">
        <Sequence name="PlanAndSmooth">
          <ComputePathToPose goal="{{goal}}" path="{{path}}" planner_id="GridBased"/>
          <SmoothPath unsmoothed_path="{{path}}" smoothed_path="{{smoothed}}" smoother_id="{smoother}"
                      max_smoothing_duration="{duration:.6f}" check_for_collisions="false"/>
        </Sequence>
      </RateController>
      <FollowPath path="{{smoothed}}" controller_id="FollowPath"/>
    </PipelineSequence>
  </BehaviorTree>
</root>
"""


def smoothing(smoother: str = "simple_smoother", duration: float = 3.0, plugin: str = "nav2_smoother::SimpleSmoother"
              ) -> dict[str, Any]:
    """The smoother server of nav2_bringup (params@kilted) and a behaviour tree that smooths every plan."""
    return {"params": {"smoother_server": {"smoother_plugins": ["simple_smoother"],
                                           "simple_smoother": {"plugin": plugin, "tolerance": 1.0e-10,
                                                               "max_its": 1000, "refinement_num": 2,
                                                               "enforce_path_inversion": True,
                                                               "do_refinement": True}},
                       "bt_navigator": {"default_nav_to_pose_bt_xml": "@work/navigate_smooth.xml"}},
            "files": {"navigate_smooth.xml": SMOOTH_BT.format(smoother=smoother, duration=duration)},
            "servers": SMOOTHER}


FAULTS27 = (
    Fault("ekf-nominal", NOMINAL, "Nothing was wrong: robot_localization's EKF published odom -> base_link from the "
          "wheel odometry.", params=ekf(), base=NO_ODOM_TF, servers=EKF, unmanaged=EKF),
    Fault("ekf-input-missing", TRANSFORM, "The EKF's odom0 was /wheel/odometry, a topic nobody publishes (the base "
          "publishes /odom), so it never published odom -> base_link.",
          params=ekf(odom0="/wheel/odometry"), base=NO_ODOM_TF, servers=EKF, unmanaged=EKF),
    Fault("ekf-world-map", TRANSFORM, "The EKF's world_frame was map instead of odom, so it published map -> odom "
          "(beside the static one) and nothing published odom -> base_link.",
          params=ekf(world_frame="map"), base=NO_ODOM_TF, servers=EKF, unmanaged=EKF),
    Fault("ekf-slow", TRANSFORM, "The EKF ran at 2 Hz, so odom -> base_link was up to half a second old, more than "
          "the costmaps' and the controller's transform tolerance.",
          params=ekf(frequency=2.0), base=NO_ODOM_TF, servers=EKF, unmanaged=EKF),
    Fault("speed-zone-slow", NOMINAL, "Nothing was wrong; a speed zone across the doorway limited the robot to 20 % "
          "of its speed, so the trip was slow.", params=speed(20), servers=SPEED, speed=ZONE, speed_percent=20,
          slow=True),
    Fault("speed-zone-crawl", CONFIG, "A speed zone across the doorway limited the robot to 5 % of its speed "
          "(0.025 m/s), slower than the progress checker's 0.5 m in 10 s.",
          params=speed(5), servers=SPEED, speed=ZONE, speed_percent=5),
    Fault("smoother-nominal", NOMINAL, "Nothing was wrong: the behaviour tree smoothed every plan with the smoother "
          "server's simple_smoother.", **smoothing()),
    Fault("smoother-plugin-misspelt", CONFIG, "The smoother plugin's class was misspelt "
          "(nav2_smoother::SimpleSmoothr), so smoother_server could not load it and did not configure.",
          **smoothing(plugin="nav2_smoother::SimpleSmoothr")),
    Fault("smoother-id-wrong", CONFIG, "The behaviour tree's SmoothPath asked for smoother_id smooth_path, while the "
          "smoother server's only smoother is simple_smoother.", **smoothing(smoother="smooth_path")),
    Fault("smoother-time-short", CONFIG, "The behaviour tree's SmoothPath allowed 0.00001 s of smoothing "
          "(max_smoothing_duration), less than any smoothing takes.", **smoothing(duration=0.00001)),
)

HEADER27 = """\
# Blind Nav2 set 27: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI) with, where a fault needs them, robot_localization's EKF, a speed filter
# and the smoother server, each run with one fault and started by the real ros2launch: written by
# scripts/nav2_faults.py --set 27, whose faults (scripts/nav2_faults27.py) and labelling rule were written before any
# run was made. Output is kept as printed, less ANSI colours, with this machine's folders replaced by fixed names.
# Frozen and measured once before anything was tuned on it. Regenerate inside a ROS 2 environment with Nav2 and
# robot_localization: python3 scripts/nav2_faults.py --set 27 --out FILE
"""
