"""Real console output of the ROS 2 stack installed here (ROS 2 Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from
PyPI, and ros2/launch run from a checkout), each run with one fault that bites once the nodes are up, or that a
launch reports: publishers and subscribers whose QoS do not match (reliability, durability, deadline), two types on
one topic in one process, lifecycle transitions asked in the wrong state, a security keystore without enclaves, a
Fast DDS discovery server that cannot be parsed, a log folder that cannot be made, a topic name a parameter got
wrong, and processes that a launch saw die (killed, segfault) or could not start.

A second set beside scripts/stack_faults.py (held-out set 22), written the same way: every fault is run for real, the
output kept as printed less ANSI colours and with this machine's folders replaced by fixed names, and each excerpt's
cause is the fault injected, written here before any output was read.

    .venv/bin/python scripts/runtime_faults.py --launch LAUNCH_CHECKOUT/launch --launch-python PY --out FILE.yaml

--launch is the `launch` package folder of ros2/launch; --launch-python a Python that has launch's dependencies
(osrf_pycommon, lark, PyYAML); the nodes it starts run with the Python running this script.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

from stack_faults import CONFIG, NODE, Fault, scrub, write_set

QOS = """\
import sys
import time
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, qos_profile_sensor_data
from rclpy.duration import Duration

rclpy.init()
driver, user = Node(sys.argv[2]), Node(sys.argv[3])
if sys.argv[1] == 'reliability':
    from nav_msgs.msg import Odometry as Msg
    offered, requested, topic = qos_profile_sensor_data, QoSProfile(depth=10), 'odom'
elif sys.argv[1] == 'durability':
    from nav_msgs.msg import OccupancyGrid as Msg
    offered, topic = QoSProfile(depth=1), 'map'
    requested = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
else:
    from geometry_msgs.msg import Twist as Msg
    offered, requested, topic = QoSProfile(depth=10), QoSProfile(depth=10, deadline=Duration(seconds=0.1)), 'cmd_vel'
pub = driver.create_publisher(Msg, topic, offered)
user.create_subscription(Msg, topic, lambda msg: user.get_logger().info(f'{topic} received'), requested)
executor = SingleThreadedExecutor()
executor.add_node(driver)
executor.add_node(user)
end = time.monotonic() + 1.5
while time.monotonic() < end:
    pub.publish(Msg())
    executor.spin_once(timeout_sec=0.1)
rclpy.shutdown()
"""

LIFECYCLE = """\
import sys
import rclpy
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn


class Driver(LifecycleNode):
    def on_configure(self, state):
        self.get_logger().info('serial port opened')
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        self.get_logger().info('publishing scans')
        return super().on_activate(state)


rclpy.init()
driver = Driver('lidar_driver')
if sys.argv[1] == 'activate-first':
    driver.trigger_activate()
else:
    driver.trigger_configure()
    driver.trigger_configure()
rclpy.shutdown()
"""

TYPES = """\
import rclpy
from rclpy.node import Node
from std_msgs.msg import String
from nav_msgs.msg import Odometry

rclpy.init()
status, ekf = Node('base_status'), Node('ekf_filter')
status.create_publisher(String, 'odom', 10)
ekf.create_subscription(Odometry, 'odom', lambda msg: None, 10)
rclpy.spin_once(ekf, timeout_sec=0.2)
rclpy.shutdown()
"""

TOPIC = """\
import rclpy
from rclpy.node import Node
from nav_msgs.msg import Odometry

rclpy.init()
node = Node('scan_filter')
node.declare_parameter('odom_topic', 'wheel odom')
node.create_subscription(Odometry, node.get_parameter('odom_topic').value, lambda msg: None, 10)
rclpy.spin_once(node, timeout_sec=0.2)
rclpy.shutdown()
"""

CHILD = """\
import ctypes
import os
import signal
import sys
import rclpy
from rclpy.node import Node

rclpy.init()
node = Node('scan_filter')
node.get_logger().info('filtering scans at 10 Hz')
rclpy.spin_once(node, timeout_sec=0.2)
if sys.argv[1] == 'killed':
    os.kill(os.getpid(), signal.SIGKILL)
ctypes.string_at(0)
"""

LAUNCH = """\
import sys
import launch
from launch.actions import ExecuteProcess

python, mode = sys.argv[1], sys.argv[2]
cmd = [python, 'child.py', mode] if mode != 'missing' else ['scan_filter_node', '--ros-args', '-p', 'scan_rate:=10']
process = ExecuteProcess(cmd=cmd, name='scan_filter', output='screen')
service = launch.LaunchService()
service.include_launch_description(launch.LaunchDescription([process]))
sys.exit(service.run())
"""

PROGRAMS = {"node": NODE, "qos": QOS, "lifecycle": LIFECYCLE, "types": TYPES, "topic": TOPIC, "launch": LAUNCH}
LIFECYCLE_CAUSE = "bringup.lifecycle_transition_failed"
DIED = "bringup.process_died"
FAULTS = (
    Fault("qos-odom-reliability", "bringup", CONFIG,
          "The base driver publishes odometry best effort (sensor-data QoS) and the EKF subscribes reliable, so no "
          "odometry reaches the EKF.", ("reliability", "base_driver", "ekf_filter"), program="qos"),
    Fault("qos-map-durability", "bringup", CONFIG,
          "The map is published volatile and the costmap subscribes transient local, so the costmap never gets "
          "the map.", ("durability", "map_server", "global_costmap"), program="qos"),
    Fault("qos-cmd-vel-deadline", "bringup", CONFIG,
          "The base asks for a velocity command deadline of 0.1 s that the teleop publisher does not offer, so no "
          "commands reach the base.", ("deadline", "teleop", "base_controller"), program="qos"),
    Fault("two-types-one-topic", "bringup", CONFIG,
          "Two nodes in one process use the topic odom with different message types (a String status and the "
          "EKF's Odometry), so the EKF's subscription is not created and the process dies.", program="types"),
    Fault("topic-parameter-with-space", "bringup", CONFIG,
          "The odom_topic parameter holds a name with a space ('wheel odom'), which is not a valid topic name, so "
          "the node dies creating its subscription.", program="topic"),
    Fault("lifecycle-activate-before-configure", "bringup", LIFECYCLE_CAUSE,
          "The bring-up asks the lidar driver to activate before it was configured, so the transition is refused "
          "and the driver never becomes active.", ("activate-first",), program="lifecycle"),
    Fault("lifecycle-configure-twice", "bringup", LIFECYCLE_CAUSE,
          "The bring-up asks the lidar driver to configure a second time, when it is already inactive, so the "
          "transition is refused.", ("configure-twice",), program="lifecycle"),
    Fault("security-keystore-without-enclaves", "bringup", CONFIG,
          "Security is enabled and enforced, but ROS_SECURITY_KEYSTORE names a folder that holds no enclaves (no "
          "keys were generated there), so the node cannot start.",
          env={"ROS_SECURITY_ENABLE": "true", "ROS_SECURITY_STRATEGY": "Enforce",
               "ROS_SECURITY_KEYSTORE": "/home/robot/keystore"}),
    Fault("log-dir-under-a-file", "bringup", CONFIG,
          "ROS_LOG_DIR names a folder inside a path that is a regular file, so rcl cannot create its log folder "
          "and the node does not start.", env={"ROS_LOG_DIR": "settings.yaml/log"},
          files={"settings.yaml": "use_sim_time: false\n"}),
    Fault("discovery-server-host-unresolvable", "system", "system.network",
          "ROS_DISCOVERY_SERVER names a host name that does not resolve, so the node does not use the discovery "
          "server and never finds the nodes that do.", env={"ROS_DISCOVERY_SERVER": "robot-base.local:11811"}),
    Fault("discovery-server-address-invalid", "system", "system.network",
          "ROS_DISCOVERY_SERVER holds an IPv4 address with an octet past 255, so the server list is not loaded and "
          "the node never finds the nodes behind the server.", env={"ROS_DISCOVERY_SERVER": "192.168.1.300:11811"}),
    Fault("launch-process-killed", "bringup", DIED,
          "The scan filter was killed with SIGKILL after it started, as the kernel's out-of-memory killer does, "
          "and its launch reports the death.", ("killed",), program="launch"),
    Fault("launch-process-segfault", "bringup", DIED,
          "The scan filter read memory at address 0 (a segmentation fault) after it started, and its launch "
          "reports the death.", ("segfault",), program="launch"),
    Fault("launch-executable-missing", "bringup", CONFIG,
          "The launch description names an executable (scan_filter_node) that is not installed, so the node is "
          "never started.", ("missing",), program="launch"),
)
HEADER = """\
# Held-out set 23 of real console excerpts (issue 23's format): printed by the real ROS 2 stack installed on this
# project's machine (ROS 2 Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from PyPI; ros2/launch from a checkout),
# each run with one runtime or launch fault injected: written by scripts/runtime_faults.py, which states each
# excerpt's cause (the fault) before it runs anything. Output is kept as printed, less ANSI colours, with this
# machine's folders replaced by /opt/venv/... and /home/robot/ws. Frozen and measured once before anything was tuned
# on it. Regenerate with the command in scripts/runtime_faults.py's docstring.
"""


def run(fault: Fault, work: Path, launch: Path, launch_python: str) -> tuple[str, int]:
    for name, text in fault.files.items():
        (work / name).write_text(text, encoding="utf-8")
    # not launch.py: the script's folder comes first on sys.path, and that name would hide the launch package
    script = work / ("bringup_launch.py" if fault.program == "launch" else f"{fault.program}.py")
    script.write_text(PROGRAMS[fault.program], encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "RMW_", "FASTDDS_", "CYCLONEDDS_"))}
    env.update(fault.env)
    command = [sys.executable, script.name, *fault.args]
    if fault.program == "launch":
        (work / "child.py").write_text(CHILD, encoding="utf-8")
        env["PYTHONPATH"] = str(launch)
        env["ROS_HOME"] = str(work / ".ros")  # launch's log folder, kept out of this machine's home
        command = [launch_python, script.name, sys.executable, *fault.args]
    done = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True, timeout=60, check=False)
    return done.stdout + done.stderr, done.returncode


def local_names(launch: Path, launch_python: str) -> list[tuple[str, str]]:
    """This machine's folders that the output prints, longest first, each with the fixed name written instead."""
    launch_prefix = subprocess.run([launch_python, "-c", "import sys; print(sys.prefix, sys.base_prefix)"],
                                   capture_output=True, text=True, check=True).stdout.split()
    names = [(sys.executable, "/opt/venv/bin/python"), (str(Path(sys.executable).parent.parent), "/opt/venv"),
             (str(launch), "/opt/ros/launch"), (launch_prefix[0], "/opt/launch-venv"), (launch_prefix[1], "/usr"),
             (sys.base_prefix, "/usr")]
    return sorted(names, key=lambda pair: -len(pair[0]))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--launch", type=Path, required=True, help="the `launch` package folder of ros2/launch")
    parser.add_argument("--launch-python", required=True, help="a Python with launch's dependencies")
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    launched = re.search(r"<version>(.+?)</version>", (args.launch / "package.xml").read_text(encoding="utf-8"))
    stack = f"rclpy {version('ros-kilted-rclpy')}, ros2/launch {launched.group(1) if launched else 'checkout'}"
    names = local_names(args.launch.absolute(), args.launch_python)

    def run_one(fault: Fault, work: Path) -> tuple[str, int]:
        text, code = run(fault, work, args.launch.absolute(), args.launch_python)
        lines = scrub(text, work)
        for local, fixed in names:
            lines = lines.replace(local, fixed)
        return lines, code

    write_set(args.out, HEADER, "runtime_faults.py", stack, FAULTS, run_one)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
