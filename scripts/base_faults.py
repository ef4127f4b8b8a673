"""Real console output of ros2_control driving a mobile base (controller_manager, joint_state_broadcaster,
diff_drive_controller on mock_components/GenericSystem wheels), each run with one fault of the base's bring-up or of
the program that sends it velocity commands: a wheel joint misspelt, no wheels named, no wheel radius, wheels that
take position commands or report no position, a command timeout shorter than the sender's period, a speed limit
below the command, commands stamped by another clock or sent unstamped; and three runs that went well.

A run is what `ros2 launch` of the base's control bring-up prints: a robot_description publisher (as
robot_state_publisher publishes it), ros2_control_node, the spawners of joint_state_broadcaster and
diff_drive_controller one after the other, and, for one fault, a recording played with its /clock. From outside the
console a teleop program waits for the controller's command subscription (30 s at most), sends 0.3 m/s forward for
3 s as geometry_msgs/TwistStamped and reads how far the controller's odometry moved; the drive succeeded when it moved
at least 80 % of the 0.9 m asked. Ctrl-C follows two seconds later. The cause of each run is the fault injected,
written here before any run was made, by the rule of `label()`. Output is kept as printed, less ANSI colours, with
this machine's folders replaced by fixed names. Writes real_modules-format excerpts (evals/data/real_modules/README.md).

Run inside a ROS 2 environment with ros2_control and ros2_controllers (e.g. `source /opt/ros/kilted/setup.bash`):

    python3 scripts/base_faults.py --out FILE.yaml [--only ID ...]
"""

from __future__ import annotations

import copy
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from control_faults import CONFIG, NOMINAL, module_set, write_bringup
from launch_runs import install, run_launch

LAUNCH_ARG = "bringup.configuration_error"
WHEELS = ("left_wheel_joint", "right_wheel_joint")
WAIT_S = 30.0  # how long the teleop waits for the controller's command subscription
DRIVE = (0.3, 3.0)  # m/s forward, for s
ENOUGH = 0.8  # of the distance asked, for the drive to have succeeded


@dataclass(frozen=True)
class Fault:
    id: str
    cause: str  # the cause when the drive fails; label() says what a drive that succeeded is
    quote: str  # what was wrong, as the cause_quote
    controller: dict[str, Any] = field(default_factory=dict)  # merged into diff_drive_controller's parameters
    command: str = "velocity"  # the wheels' command interface in the robot description
    states: tuple[str, ...] = ("position", "velocity")  # the wheels' state interfaces
    stamp: str = "now"  # how the teleop stamps its commands: now, zero, or sim (its use_sim_time, a recording's clock)
    message: str = "TwistStamped"  # or Twist, as teleops before Jazzy send
    rate_hz: float = 10.0  # the teleop's publishing rate
    silent: bool = False  # logs_show_cause false: nothing in any process's console could show it


FAULTS = (
    Fault("base-nominal", NOMINAL, "Nothing was wrong: the base drove 0.9 m forward as commanded."),
    Fault("base-zero-stamp", NOMINAL, "Nothing was wrong that stopped the base: the teleop left header.stamp empty, "
          "which the controller replaces by its own time.", stamp="zero"),
    Fault("base-velocity-feedback", NOMINAL, "Nothing was wrong: the wheels report velocity only, and the controller "
          "was set to compute odometry from velocity (position_feedback false).",
          controller={"position_feedback": False}, states=("velocity",)),
    Fault("base-wheel-misspelt", CONFIG, "diff_drive_controller's left_wheel_names named left_wheel_jiont "
          "(misspelt), a joint the robot description does not have.",
          controller={"left_wheel_names": ["left_wheel_jiont"]}),
    Fault("base-wheels-empty", CONFIG, "diff_drive_controller's left_wheel_names was an empty list.",
          controller={"left_wheel_names": []}),
    Fault("base-radius-missing", CONFIG, "diff_drive_controller's parameters gave no wheel_radius (it defaults to "
          "0.0, which its validation refuses).", controller={"wheel_radius": None}),
    Fault("base-position-command", CONFIG, "The robot description gave the wheels position command interfaces, "
          "while diff_drive_controller commands wheel velocities.", command="position"),
    Fault("base-no-position-state", CONFIG, "The robot description gave the wheels a velocity state only, while "
          "diff_drive_controller (position_feedback true by default) reads wheel positions.", states=("velocity",)),
    Fault("base-timeout-short", CONFIG, "diff_drive_controller's cmd_vel_timeout was 0.05 s while the teleop sent "
          "commands at 5 Hz, so the controller braked between commands.",
          controller={"cmd_vel_timeout": 0.05}, rate_hz=5.0),
    Fault("base-speed-limited", CONFIG, "diff_drive_controller's linear.x.max_velocity was 0.1 m/s, below the 0.3 m/s "
          "commanded, so the base covered a third of the distance.",
          controller={"linear": {"x": {"max_velocity": 0.1}}}, silent=True),
    Fault("base-sim-time-teleop", LAUNCH_ARG, "The teleop ran with use_sim_time while an old recording played its "
          "/clock, so its commands were stamped in 2024 and the controller (on wall time) ignored them as stale.",
          stamp="sim"),
    Fault("base-unstamped", LAUNCH_ARG, "The teleop sent geometry_msgs/Twist, while diff_drive_controller listens "
          "for TwistStamped on that topic, so the two never matched and no command arrived.", message="Twist",
          silent=True),
)


def label(fault: Fault, succeeded: bool) -> tuple[str, str]:
    """The rule written before any run: a drive that succeeded is 'succeeded' with cause control.nominal, whatever
    the fault; one that did not is 'failed' with the fault's cause."""
    return ("succeeded", NOMINAL) if succeeded else ("failed", fault.cause)


def urdf(fault: Fault) -> str:
    states = "".join(f'<state_interface name="{s}"/>' for s in fault.states)
    joints = "".join(f'<joint name="{j}"><command_interface name="{fault.command}"/>{states}</joint>'
                     for j in WHEELS)
    links = '<link name="base_link"/><link name="left_wheel"/><link name="right_wheel"/>'
    chain = "".join(
        f'<joint name="{j}" type="continuous"><parent link="base_link"/><child link="{c}"/>'
        f'<origin xyz="0 {y} 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>'
        for j, c, y in ((WHEELS[0], "left_wheel", 0.2), (WHEELS[1], "right_wheel", -0.2)))
    return (f'<?xml version="1.0"?><robot name="base">{links}{chain}<ros2_control name="BaseSystem" type="system">'
            f'<hardware><plugin>mock_components/GenericSystem</plugin>'
            f'<param name="calculate_dynamics">true</param></hardware>{joints}</ros2_control></robot>')


def params(fault: Fault) -> dict[str, Any]:
    base: dict[str, Any] = {
        "left_wheel_names": [WHEELS[0]], "right_wheel_names": [WHEELS[1]], "wheel_separation": 0.4,
        "wheel_radius": 0.1, "odom_frame_id": "odom", "base_frame_id": "base_link", "cmd_vel_timeout": 0.5,
        "linear": {"x": {"max_velocity": 1.0}}, "angular": {"z": {"max_velocity": 1.0}}}
    for key, value in copy.deepcopy(fault.controller).items():
        if value is None:
            base.pop(key)
        else:
            base[key] = value
    manager = {"update_rate": 100, "joint_state_broadcaster": {"type": "joint_state_broadcaster/JointStateBroadcaster"},
               "diff_drive_controller": {"type": "diff_drive_controller/DiffDriveController"}}
    return {"controller_manager": {"ros__parameters": manager},
            "diff_drive_controller": {"ros__parameters": base}}


# as `ros2 bag play --clock` of a recording made on 2024-06-01 publishes its /clock
CLOCK = """\
import time
import rclpy
from rclpy.executors import ExternalShutdownException
from rosgraph_msgs.msg import Clock

rclpy.init()
node = rclpy.create_node('rosbag2_player')
pub = node.create_publisher(Clock, '/clock', 10)
start, began = 1717236000.0, time.monotonic()


def tick():
    t = start + time.monotonic() - began
    msg = Clock()
    msg.clock.sec, msg.clock.nanosec = int(t), int((t % 1) * 1e9)
    pub.publish(msg)


node.create_timer(0.01, tick)
node.get_logger().info('Playing recording with its clock (rate 1.0)')
try:
    rclpy.spin(node)
except (KeyboardInterrupt, ExternalShutdownException):
    pass
"""

SEND = """\
import json
import sys
import time
import rclpy
from geometry_msgs.msg import Twist, TwistStamped
from nav_msgs.msg import Odometry
from rclpy.parameter import Parameter

wait_s, out, stamp, message, rate_hz = float(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
speed, drive_s = float(sys.argv[6]), float(sys.argv[7])
rclpy.init()
node = rclpy.create_node('base_teleop', parameter_overrides=[Parameter('use_sim_time', value=stamp == 'sim')])
kind = Twist if message == 'Twist' else TwistStamped
pub = node.create_publisher(kind, '/diff_drive_controller/cmd_vel', 10)
poses = []
node.create_subscription(Odometry, '/diff_drive_controller/odom',
                         lambda m: poses.append((m.pose.pose.position.x, m.pose.pose.position.y)), 10)
began = time.monotonic()
while pub.get_subscription_count() == 0 and time.monotonic() - began < wait_s:
    rclpy.spin_once(node, timeout_sec=0.1)
result = {'listener': pub.get_subscription_count() > 0, 'waited': round(time.monotonic() - began, 1)}
end = time.monotonic() + 1.0  # as a person starts to drive once the controller is up
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
start = poses[-1] if poses else None
began = time.monotonic()
while time.monotonic() - began < drive_s:
    if kind is Twist:
        msg = Twist()
        msg.linear.x = speed
    else:
        msg = TwistStamped()
        msg.header.frame_id = 'base_link'
        if stamp != 'zero':
            msg.header.stamp = node.get_clock().now().to_msg()
        msg.twist.linear.x = speed
    pub.publish(msg)
    stop = time.monotonic() + 1.0 / rate_hz
    while time.monotonic() < stop:
        rclpy.spin_once(node, timeout_sec=0.01)
end = time.monotonic() + 1.0  # the base stops once commands stop
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
last = poses[-1] if poses else None
result['odometry'] = bool(poses)
result['moved_m'] = round(((last[0] - start[0]) ** 2 + (last[1] - start[1]) ** 2) ** 0.5, 3) if start and last else 0.0
result['asked_m'] = round(speed * drive_s, 3)
json.dump(result, open(out, 'w'))
"""

LAUNCH = """\
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch_ros.actions import Node

PARAMS = {params!r}
URDF = {urdf!r}
CLOCK = {clock!r}


def generate_launch_description():
    actions = [Node(package='base_description', executable='describe', name='robot_description_publisher',
                    output='screen', arguments=[URDF]),
               Node(package='controller_manager', executable='ros2_control_node', output='screen',
                    parameters=[PARAMS])]
    if CLOCK:
        actions.append(Node(package='rosbag2_player', executable='play', name='rosbag2_player', output='screen'))
    broadcaster = Node(package='controller_manager', executable='spawner', output='screen',
                       arguments=['joint_state_broadcaster'])
    base = Node(package='controller_manager', executable='spawner', output='screen',
                arguments=['diff_drive_controller'])
    actions += [broadcaster, RegisterEventHandler(OnProcessExit(target_action=broadcaster, on_exit=[base]))]
    return LaunchDescription(actions)
"""


def run(fault: Fault, work: Path, launch_path: list[Path]) -> tuple[str, dict[str, Any]]:
    """Launch the base's bring-up, drive it from outside, Ctrl-C two seconds later: the console and the drive."""
    launch, prefix = write_bringup(work, "base", urdf(fault), params(fault), LAUNCH, clock=fault.stamp == "sim")
    install(prefix, "rosbag2_player", "play", CLOCK)
    result_file = work / "result.json"
    argv = [str(WAIT_S), str(result_file), fault.stamp, fault.message, str(fault.rate_hz), *map(str, DRIVE)]
    return run_launch(launch, prefix, work, launch_path, (SEND, argv), result_file, WAIT_S + 30.0)


HEADER = """\
# Held-out set 32 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, diff_drive_controller, mock_components/GenericSystem), built from source on ROS 2 Kilted's
# rclpy, rcl and Fast DDS from PyPI, each run with one fault of a mobile base's control bring-up or of its teleop and
# started by the real ros2launch: written by scripts/base_faults.py, whose faults and labelling rule were committed
# before any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders replaced by
# fixed names. Frozen and measured once before anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/base_faults.py --out FILE
"""


def main() -> int:
    return module_set(__doc__, FAULTS, run, "base_faults.py", HEADER, label,
                      lambda result: result.get("moved_m", 0.0) >= ENOUGH * DRIVE[0] * DRIVE[1],
                      lambda result: f"Teleop of {DRIVE[0]} m/s for {DRIVE[1]} s: {json.dumps(result)}.")


if __name__ == "__main__":
    raise SystemExit(main())
