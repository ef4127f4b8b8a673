"""Real console output of the ROS 2 navigation stack (Nav2), each run with one fault: a goal in a wall or off the
map, a start in a wall or off the map, a box that closes the only doorway or appears right ahead, a params file that
does not parse, a map file that is not there, a planner plugin misspelt, a behaviour tree with a node nobody
registers, a lifecycle manager waiting for a node that never started, no map -> odom transform, sim time with no
clock, velocity commands the base never hears, a costmap listening to a scan topic nobody publishes, a controller
rate the computer cannot keep; and two goals that went well.

A run is what `ros2 launch` of a robot's navigation bring-up prints: map_server, planner_server (NavFn),
controller_server (Regulated Pure Pursuit), behavior_server, bt_navigator and lifecycle_manager, with the robot's
base (scripts/nav2_world.py: odometry, TF, a laser ray-cast on a two-room map, a static map -> odom as a perfect
localisation), started by ros2launch; a goal sent from outside the console, as from RViz; Ctrl-C two seconds after
its result (or after the time a person would wait). The cause of each run is the fault injected, written here before
any run was made, by the rule of `label()`. Output is kept as printed, less ANSI colours, with this machine's folders
replaced by fixed names. Writes real_nav2-format excerpts (evals/data/real_nav2/README.md).

Run inside a ROS 2 environment with Nav2 (e.g. `source /opt/ros/kilted/setup.bash`):

    python3 scripts/nav2_faults.py --out FILE.yaml [--only ID ...]

Where ros2launch is not importable, `--launch-path` names folders holding launch, launch_ros and ros2launch
(checkouts of ros2/launch and ros2/launch_ros) and osrf_pycommon.
"""

from __future__ import annotations

import copy
import importlib
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from launch_runs import arguments, install, kept, run_launch, runs, write_set
from nav2_world import BASE, BEHAVIOR, DOCK, GOAL, WAYPOINTS, write_map, write_mask

START, GOAL_XY = (2.0, 4.0), (10.0, 4.0)
COSTMAPS = ("local_costmap/local_costmap", "global_costmap/global_costmap")
NAV2 = ("map_server", "planner_server", "controller_server", "behavior_server", "bt_navigator")
PACKAGES = {"map_server": "nav2_map_server", "planner_server": "nav2_planner", "controller_server": "nav2_controller",
            "behavior_server": "nav2_behaviors", "bt_navigator": "nav2_bt_navigator", "amcl": "nav2_amcl",
            "velocity_smoother": "nav2_velocity_smoother", "collision_monitor": "nav2_collision_monitor",
            "waypoint_follower": "nav2_waypoint_follower", "keepout_filter_mask_server": "nav2_map_server",
            "keepout_costmap_filter_info_server": "nav2_map_server", "docking_server": "opennav_docking",
            "ekf_filter_node": "robot_localization", "smoother_server": "nav2_smoother",
            "speed_filter_mask_server": "nav2_map_server", "speed_costmap_filter_info_server": "nav2_map_server"}
# nodes whose program has another name (nav2_bringup's keepout_zone_launch.py starts map_server as the mask's server)
EXECUTABLES = {"keepout_filter_mask_server": "map_server",
               "keepout_costmap_filter_info_server": "costmap_filter_info_server",
               "docking_server": "opennav_docking", "ekf_filter_node": "ekf_node",
               "speed_filter_mask_server": "map_server",
               "speed_costmap_filter_info_server": "costmap_filter_info_server"}
# Nav2's own bring-up (nav2_bringup navigation_launch.py@kilted) when the velocity smoother is in the chain: the
# controller and the behaviours publish cmd_vel_nav, the smoother turns it into cmd_vel_smoothed, and the collision
# monitor (or, without one, the smoother's output remapped) gives the base its cmd_vel
CHAIN_REMAPS = {"controller_server": [("cmd_vel", "cmd_vel_nav")], "behavior_server": [("cmd_vel", "cmd_vel_nav")],
                "velocity_smoother": [("cmd_vel", "cmd_vel_nav")]}
WAIT_S = 40.0  # how long a person waits for the stack to come up before sending the goal anyway
RUN_S = 90.0  # how long they wait for the robot to get there


@dataclass(frozen=True)
class Fault:
    id: str
    cause: str  # the cause when the goal fails; label() says what a run that reached its goal is
    quote: str  # what was wrong, as the cause_quote
    params: dict[str, dict[str, Any]] = field(default_factory=dict)  # merged into the params file per node
    base: dict[str, Any] = field(default_factory=dict)  # the base's parameters
    goal: tuple[float, float] = GOAL_XY
    params_text: str | None = None  # the params file as written, when it is not YAML at all
    missing: tuple[str, ...] = ()  # nodes the lifecycle manager waits for that are never started
    files: dict[str, str] = field(default_factory=dict)
    manager: dict[str, Any] = field(default_factory=dict)  # the lifecycle manager's parameters beyond the node list
    amcl: bool = False  # AMCL localises the robot (map -> odom) instead of the base's perfect static transform
    initial: tuple[float, float, float] | None = (*START, 0.0)  # AMCL's initial pose; None: none is given
    hit: tuple[str, str, float] | None = None  # (node, signal, s): sent to a node's process that long into the goal
    silent: bool = False  # logs_show_cause false: nothing in any process's console could show it
    slow: bool = False  # a goal reached slowly on purpose: outcome "slow"
    chain: tuple[str, ...] = ()  # nodes between the controller and the base: velocity_smoother, collision_monitor
    unmapped: tuple[str, ...] = ()  # nodes of the chain started without their remapping (a launch file's slip)
    servers: tuple[str, ...] = ()  # more Nav2 servers the launch starts (waypoint_follower)
    unmanaged: tuple[str, ...] = ()  # of those, the ones left out of the lifecycle manager's node list
    waypoints: tuple[tuple[float, float], ...] = ()  # sent to the waypoint follower instead of one goal
    frame: str = "map"  # the frame the waypoints are given in
    through: bool = False  # the waypoints go to bt_navigator's NavigateThroughPoses instead of the waypoint follower
    keepout: tuple[tuple[float, float, float, float], ...] = ()  # keepout zones (x0, y0, x1, y1) of a filter mask
    dock_id: str = ""  # a DockRobot goal for this dock of the docking server's database instead of a goal
    speed: tuple[tuple[float, float, float, float], ...] = ()  # speed zones (x0, y0, x1, y1) of a speed filter mask
    speed_percent: int = 100  # the robot's speed in them
    behavior: tuple[Any, ...] = ()  # (action, values): a behaviour server goal (set 28) instead of a goal
    sent: dict[str, Any] = field(default_factory=dict)  # the goal as a script sends it (set 29's GOAL_SENT)


BAD_BT = """<root BTCPP_format="4" main_tree_to_execute="MainTree">
  <BehaviorTree ID="MainTree">
    <PipelineSequence name="NavigateWithReplanning">
      <ComputePathToPose goal="{goal}" path="{path}" planner_id="GridBased"/>
      <CheckBatteryLevel min_battery="0.2"/>
      <FollowPath path="{path}" controller_id="FollowPath"/>
    </PipelineSequence>
  </BehaviorTree>
</root>
"""

NOMINAL, TRANSFORM, BRINGUP, CONFIG = ("navigation.nominal", "navigation.transform_error",
                                       "navigation.bringup_failure", "navigation.configuration_error")
FAULTS = (
    Fault("nominal", NOMINAL, "Nothing was wrong: the goal in the other room was reachable through the doorway."),
    Fault("slow", NOMINAL, "Nothing was wrong; the controller's speed was set to 0.12 m/s, so the trip was slow.",
          params={"controller_server": {"FollowPath": {"desired_linear_vel": 0.12}}}, goal=(4.5, 4.0), slow=True),
    Fault("params-parse", BRINGUP, "The params file has a YAML syntax error (a list not closed), so no Nav2 node "
          "could read its parameters and none came up.", params_text="broken"),
    Fault("map-missing", BRINGUP, "map_server's yaml_filename names a map file that is not there, so map_server "
          "failed to configure and the bring-up was aborted.",
          params={"map_server": {"yaml_filename": "maps/two_room.yaml"}}),
    Fault("planner-plugin", CONFIG, "The planner plugin's class is misspelt (nav2_navfn_planner::NavfnPlaner), so "
          "planner_server could not load it and did not configure.",
          params={"planner_server": {"GridBased": {"plugin": "nav2_navfn_planner::NavfnPlaner"}}}),
    Fault("bt-unknown-node", CONFIG, "The behaviour tree XML uses a node (CheckBatteryLevel) that no loaded plugin "
          "registers, so bt_navigator could not load its tree.",
          params={"bt_navigator": {"default_nav_to_pose_bt_xml": "@work/navigate.xml"}},
          files={"navigate.xml": BAD_BT}),
    Fault("lifecycle-missing-node", BRINGUP, "The lifecycle manager's node list names velocity_smoother, which "
          "the launch file never starts, so the bring-up never completed.", missing=("velocity_smoother",)),
    Fault("no-map-tf", TRANSFORM, "Nothing published the map -> odom transform (no localisation running), so the "
          "global costmap and the planner had no robot pose in the map frame.", base={"publish_map_odom": False}),
    Fault("no-clock", TRANSFORM, "Every Nav2 node had use_sim_time true but nothing published /clock (no "
          "simulator), while the base stamped with the computer's clock.",
          params={n: {"use_sim_time": True} for n in (*NAV2, *COSTMAPS)},
          manager={"use_sim_time": True}),
    Fault("goal-in-wall", "navigation.goal_unreachable", "The goal was inside the wall between the rooms.",
          goal=(6.1, 2.0)),
    Fault("goal-off-map", "navigation.goal_unreachable", "The goal was outside the map.", goal=(16.0, 4.0)),
    Fault("start-in-wall", "navigation.start_in_obstacle", "The robot started inside the wall between the rooms, "
          "on occupied cells.", base={"x": 6.1, "y": 2.0}),
    Fault("start-off-map", "navigation.off_costmap", "The robot's pose was outside the map (it started 2 m beyond "
          "the map's edge).", base={"x": -2.0, "y": 4.0}),
    Fault("doorway-blocked", "navigation.blocked_path", "A box was put in the doorway, the only way into the other "
          "room, as the robot drove toward it (2 m before it).", base={"boxes": [4.0, 5.9, 3.4, 6.5, 4.6]}),
    Fault("box-ahead", "navigation.collision_ahead", "A box appeared 0.6 m in front of the robot in the middle of "
          "the first room, while it drove.", base={"boxes": [3.0, 3.6, 3.5, 4.1, 4.5]}),
    Fault("cmd-vel-remapped", "navigation.commands_not_reaching_base", "The base listened on /base/cmd_vel while "
          "the controller published on /cmd_vel, so the robot never moved.",
          base={"cmd_vel_topic": "/base/cmd_vel"}, silent=True),
    Fault("scan-topic-wrong", CONFIG, "Both costmaps' obstacle layers subscribe to /scan_front, which nothing "
          "publishes (the laser publishes /scan), so they see no obstacle but the map's.",
          params={f"{c}/{c}": {"obstacle_layer": {"scan": {"topic": "/scan_front"}}}
                  for c in ("local_costmap", "global_costmap")}),
    Fault("rate-too-high", "navigation.controller_failure", "controller_frequency was set to 200 Hz, more than "
          "this 2-core computer can keep beside the rest of the stack.",
          params={"controller_server": {"controller_frequency": 200.0}}),
)


def label(fault: Fault, reached: bool) -> tuple[str, str]:
    """The rule written before any run: a goal reached is 'succeeded' (or 'slow' for the run slowed on purpose)
    with cause navigation.nominal, whatever the fault; a goal not reached is 'failed' with the fault's cause. A list
    of waypoints (set 24) is reached when the follower succeeded and missed none of them; a dock (set 26) when the
    DockRobot goal succeeded; a behaviour (set 28) when its action succeeded."""
    if reached:
        return ("slow" if fault.slow else "succeeded"), NOMINAL
    return "failed", fault.cause


def params(fault: Fault, work: Path, map_yaml: Path) -> dict[str, Any]:
    costmap = {"robot_base_frame": "base_link", "robot_radius": 0.22, "resolution": 0.05,
               "obstacle_layer": {"plugin": "nav2_costmap_2d::ObstacleLayer", "enabled": True,
                                  "observation_sources": "scan",
                                  "scan": {"topic": "/scan", "data_type": "LaserScan", "marking": True,
                                           "clearing": True, "obstacle_max_range": 2.5, "raytrace_max_range": 3.0,
                                           "max_obstacle_height": 2.0}},
               "inflation_layer": {"plugin": "nav2_costmap_2d::InflationLayer", "inflation_radius": 0.55,
                                   "cost_scaling_factor": 3.0}, "always_send_full_costmap": True}
    nodes: dict[str, Any] = {
        "map_server": {"yaml_filename": str(map_yaml)},
        "planner_server": {"expected_planner_frequency": 20.0, "planner_plugins": ["GridBased"],
                           "GridBased": {"plugin": "nav2_navfn_planner::NavfnPlanner", "tolerance": 0.5,
                                         "use_astar": False, "allow_unknown": True}},
        "controller_server": {
            "controller_frequency": 20.0, "enable_stamped_cmd_vel": True, "failure_tolerance": 0.3,
            "progress_checker_plugins": ["progress_checker"], "goal_checker_plugins": ["general_goal_checker"],
            "controller_plugins": ["FollowPath"],
            "progress_checker": {"plugin": "nav2_controller::SimpleProgressChecker", "required_movement_radius": 0.5,
                                 "movement_time_allowance": 10.0},
            "general_goal_checker": {"plugin": "nav2_controller::SimpleGoalChecker", "xy_goal_tolerance": 0.25,
                                     "yaw_goal_tolerance": 0.25, "stateful": True},
            "FollowPath": {"plugin": "nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController",
                           "desired_linear_vel": 0.5, "lookahead_dist": 0.6, "min_lookahead_dist": 0.3,
                           "max_lookahead_dist": 0.9, "use_velocity_scaled_lookahead_dist": False,
                           "use_collision_detection": True, "max_allowed_time_to_collision_up_to_carrot": 1.0,
                           "use_rotate_to_heading": True, "rotate_to_heading_min_angle": 0.785,
                           "rotate_to_heading_angular_vel": 1.8, "max_angular_accel": 3.2, "allow_reversing": False}},
        "local_costmap/local_costmap": {**copy.deepcopy(costmap), "global_frame": "odom", "rolling_window": True,
                                        "width": 3, "height": 3, "update_frequency": 5.0, "publish_frequency": 2.0,
                                        "plugins": ["obstacle_layer", "inflation_layer"]},
        "global_costmap/global_costmap": {
            **copy.deepcopy(costmap), "global_frame": "map", "update_frequency": 1.0, "publish_frequency": 1.0,
            "track_unknown_space": True, "plugins": ["static_layer", "obstacle_layer", "inflation_layer"],
            "static_layer": {"plugin": "nav2_costmap_2d::StaticLayer", "map_subscribe_transient_local": True}},
        "behavior_server": {"local_costmap_topic": "local_costmap/costmap_raw",
                            "local_footprint_topic": "local_costmap/published_footprint",
                            "global_costmap_topic": "global_costmap/costmap_raw",
                            "global_footprint_topic": "global_costmap/published_footprint",
                            "cycle_frequency": 10.0, "enable_stamped_cmd_vel": True,
                            "behavior_plugins": ["spin", "backup", "drive_on_heading", "wait"],
                            "spin": {"plugin": "nav2_behaviors::Spin"}, "backup": {"plugin": "nav2_behaviors::BackUp"},
                            "drive_on_heading": {"plugin": "nav2_behaviors::DriveOnHeading"},
                            "wait": {"plugin": "nav2_behaviors::Wait"}, "local_frame": "odom",
                            "global_frame": "map", "robot_base_frame": "base_link", "transform_tolerance": 0.1,
                            "simulate_ahead_time": 2.0, "max_rotational_vel": 1.0, "min_rotational_vel": 0.4,
                            "rotational_acc_lim": 3.2},
        "bt_navigator": {"global_frame": "map", "robot_base_frame": "base_link", "odom_topic": "odom",
                         "bt_loop_duration": 10, "default_server_timeout": 100, "wait_for_service_timeout": 1000,
                         "navigators": ["navigate_to_pose"],
                         "navigate_to_pose": {"plugin": "nav2_bt_navigator::NavigateToPoseNavigator"}},
    }
    if fault.amcl:
        nodes["amcl"] = {"base_frame_id": "base_link", "global_frame_id": "map", "odom_frame_id": "odom",
                         "scan_topic": "scan", "robot_model_type": "nav2_amcl::DifferentialMotionModel",
                         "laser_model_type": "likelihood_field", "laser_max_range": 8.0, "laser_min_range": -1.0,
                         "max_particles": 2000, "min_particles": 500, "tf_broadcast": True,
                         "transform_tolerance": 1.0, "update_min_d": 0.25, "update_min_a": 0.2,
                         "set_initial_pose": fault.initial is not None}
        if fault.initial is not None:
            x, y, yaw = fault.initial
            nodes["amcl"]["initial_pose"] = {"x": x, "y": y, "z": 0.0, "yaw": yaw}
    for node, extra in fault.params.items():
        _merge(nodes.setdefault(node, {}), extra)
    tree: dict[str, Any] = {}
    for node, values in nodes.items():  # "local_costmap/local_costmap": a node in a namespace, as Nav2 writes it
        *space, name = node.split("/")
        at = tree
        for part in space:
            at = at.setdefault(part, {})
        at[name] = {"ros__parameters": values}
    text = yaml.safe_dump(tree, sort_keys=False)
    return yaml.safe_load(text.replace("@work", str(work)))


def _merge(into: dict[str, Any], extra: dict[str, Any]) -> None:
    for key, value in extra.items():
        if isinstance(value, dict) and isinstance(into.get(key), dict) and not _other_plugin(into[key], value):
            _merge(into[key], value)
        else:
            into[key] = value


def _plugin_package(values: dict[str, Any]) -> str:
    return str(values.get("plugin", "")).split("::")[0]


def _other_plugin(old: dict[str, Any], new: dict[str, Any]) -> bool:
    """A plugin of another package (DWB for Regulated Pure Pursuit) replaces its predecessor's parameters; a
    misspelt class of the same package keeps them."""
    return "plugin" in new and _plugin_package(new) != _plugin_package(old)


LAUNCH = """\
from launch import LaunchDescription
from launch_ros.actions import Node

PARAMS = {params!r}
BASE = {base!r}
NODES = {nodes!r}
MANAGER = {manager!r}


def generate_launch_description():
    actions = [Node(package='robot_base', executable='base_driver', name='base_driver', output='screen',
                    parameters=[BASE])]
    for name, package, executable, remaps in NODES:
        actions.append(Node(package=package, executable=executable, name=name, output='screen', parameters=[PARAMS],
                            remappings=remaps))
    actions.append(Node(package='nav2_lifecycle_manager', executable='lifecycle_manager',
                        name='lifecycle_manager_navigation', output='screen', parameters=[MANAGER]))
    return LaunchDescription(actions)
"""
BROKEN = ("planner_server:\n  ros__parameters:\n    planner_plugins: [\"GridBased\"\n"
          "    expected_planner_frequency: 20.0\n")


def setup(fault: Fault, work: Path) -> tuple[Path, Path]:
    """The fault's work folder: the map, the params file, the base as an installed program, the launch file."""
    map_yaml = write_map(work / "maps")
    if fault.keepout:
        write_mask(work / "maps", list(fault.keepout))
    if fault.speed:
        write_mask(work / "maps", list(fault.speed), f"speed_mask_{fault.speed_percent}", fault.speed_percent)
    for name, text in fault.files.items():
        (work / name).write_text(text, encoding="utf-8")
    params_file = work / "nav2_params.yaml"
    if fault.params_text is not None:
        params_file.write_text(BROKEN, encoding="utf-8")
    else:
        params_file.write_text(yaml.safe_dump(params(fault, work, map_yaml), sort_keys=False), encoding="utf-8")
    prefix = work / "install"
    install(prefix, "robot_base", "base_driver", BASE)
    base = {"x": START[0], "y": START[1], "map_image": str(map_yaml.with_suffix(".pgm")), **fault.base}
    if "boxes" in base:
        base["boxes"] = [float(v) for v in base["boxes"]]
    stack = (*((NAV2[0], "amcl", *NAV2[1:]) if fault.amcl else NAV2), *fault.chain, *fault.servers)
    if fault.amcl:
        base["publish_map_odom"] = False
    managed = [n for n in stack if n not in fault.unmanaged]
    manager = {"autostart": True, "bond_timeout": 4.0, "node_names": [*managed, *fault.missing], **fault.manager}
    launch = work / "navigation.launch.py"
    launch.write_text(LAUNCH.format(params=str(params_file), base=base, manager=manager,
                                    nodes=[(n, PACKAGES[n], EXECUTABLES.get(n, n), _remaps(fault, n)) for n in stack]),
                 encoding="utf-8")
    return launch, prefix


def _remaps(fault: Fault, node: str) -> list[tuple[str, str]]:
    if "velocity_smoother" not in fault.chain or node in fault.unmapped:
        return []
    if node == "velocity_smoother" and "collision_monitor" not in fault.chain:
        return [*CHAIN_REMAPS[node], ("cmd_vel_smoothed", "cmd_vel")]
    return CHAIN_REMAPS.get(node, [])


def run(fault: Fault, work: Path, launch_path: list[Path]) -> tuple[str, dict[str, Any]]:
    """Launch the stack, send the goal from outside it, Ctrl-C two seconds after the result: the console and the
    goal's result."""
    launch, prefix = setup(fault, work)
    result_file = work / "goal.json"
    run_s = str(RUN_S * (2 if fault.slow else 1))
    if fault.sent:
        from nav2_faults29 import GOAL_SENT
        client = (GOAL_SENT, [json.dumps(fault.sent), str(WAIT_S), run_s, str(result_file)])
    elif fault.behavior:
        client = (BEHAVIOR, [fault.behavior[0], json.dumps(fault.behavior[1]), str(WAIT_S), run_s, str(result_file)])
    elif fault.dock_id:
        client = (DOCK, [fault.dock_id, str(WAIT_S), str(2 * RUN_S), str(result_file)])  # retries take their time
    elif fault.waypoints:
        points = ";".join(f"{x},{y}" for x, y in fault.waypoints)
        client = (WAYPOINTS, [points, fault.frame, str(WAIT_S), run_s, str(result_file),
                              *(["through"] if fault.through else [])])
    else:
        client = (GOAL, [*map(str, fault.goal), str(WAIT_S), run_s, str(result_file), *map(str, fault.hit or ())])
    return run_launch(launch, prefix, work, launch_path, client, result_file, WAIT_S + 3 * RUN_S)


HEADER = """\
# Blind Nav2 set 20: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI), each run with one fault and started by the real ros2launch: written by
# scripts/nav2_faults.py, whose faults and labelling rule were written before any run was made. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before
# anything was tuned on it. Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --out FILE
"""


def _sent(fault: Fault) -> str:
    if fault.sent:
        return f"NavigateToPose as sent {json.dumps(fault.sent)}"
    if fault.behavior:
        return f"{fault.behavior[0]} goal {json.dumps(fault.behavior[1])}"
    if fault.dock_id:
        return f"DockRobot for dock {fault.dock_id}"
    if fault.waypoints:
        points = ", ".join(f"({x:g}, {y:g})" for x, y in fault.waypoints)
        return f"{'Poses through' if fault.through else 'Waypoints'} {points} in frame {fault.frame}"
    return f"Goal ({fault.goal[0]:g}, {fault.goal[1]:g})"


def main() -> int:
    parser = arguments(__doc__)
    parser.add_argument("--set", type=int, choices=(20, 21, 22, 23, 24, 25, 26, 27, 28, 29), default=20,
                        help="20: bring-up, goals, starts; 21: AMCL, transforms, processes, the base; 22: the "
                             "velocity smoother and collision monitor, DWB, the controller's checkers; 23: MPPI, the "
                             "rotation shim, the graceful controller, Theta*; 24: the waypoint follower; 25: "
                             "NavigateThroughPoses and keepout zones; 26: the docking server; 27: "
                             "robot_localization's EKF, a speed filter, the smoother server; 28: the "
                             "behaviour server's actions; 29: the goal as a script sends it")
    parser.add_argument("--nav2-version", default="kilted", help="as the header names it")
    args = parser.parse_args()
    faults, header = FAULTS, HEADER
    faults_file = "nav2_faults.py" if args.set == 20 else f"nav2_faults{args.set}.py"  # where each fault is written
    if args.set != 20:  # nav2_faults21.py's FAULTS21 and HEADER21, ...
        module = importlib.import_module(f"nav2_faults{args.set}")
        faults, header = getattr(module, f"FAULTS{args.set}"), getattr(module, f"HEADER{args.set}")
    entries = []
    for fault, lines, result in runs(faults, args, run):
        # action_msgs/GoalStatus SUCCEEDED; a waypoint follower's success may still have missed waypoints
        reached = result.get("status") == 4 and not result.get("missed")
        outcome, cause = label(fault, reached)
        if kept(fault.id, outcome, cause, NOMINAL):
            entries.append({
                "id": f"kilted-nav2-{fault.id}", "source": f"scripts/nav2_faults.py on Nav2 {args.nav2_version}",
                "url": f"scripts/{faults_file}#{fault.id}", "distro": "kilted", "outcome": outcome, "cause": cause,
                "cause_quote": fault.quote, "logs_show_cause": not fault.silent or reached,
                "notes": f"{_sent(fault)}: {json.dumps(result)}.", "lines": lines})
    write_set(args.out, header.format(nav2=args.nav2_version), entries)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
