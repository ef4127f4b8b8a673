"""Real console output of ROS 2 bring-ups run by the real ros2/launch and ros2/launch_ros (from checkouts; ROS 2
Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from PyPI), each with one fault of its launch file: a launch argument
not given, or given with '=' for ':=', a misspelt LaunchConfiguration or package name, an included launch file that is
not there or does not parse, an unset environment variable, a condition given 'yes', a params file by a relative path,
an integer where the node declares a double, a parameter override rcl cannot parse, xacro not installed, a required
node that dies, a respawned node that crashes, a lifecycle configure that fails; and three bring-ups that did their job.

Written like scripts/stack_faults.py (held-out set 22) and the sets after it: every fault run for real, its output kept
as printed less ANSI colours, this machine's folders replaced by fixed names, each cause written here before the set
was run. A run is what `ros2 launch robot_bringup bringup.launch.py ARGS` does (ros2launch.api, a RuntimeError printed
as ros2cli prints it; ros2cli is not on PyPI) in a work folder with a small install prefix found through the ament
index: the launch files and rclpy node programs of robot_bringup, base_driver, lidar_driver, imu_driver, camera_driver
and robot_state_publisher. A bring-up still running after STOP seconds gets SIGINT, as Ctrl-C. launch_ros imports
composition_interfaces' service types, which are not on PyPI: a module of that name defining the three names it
imports is put on the path; no run loads a composable node, so none of them is ever called.

    git --git-dir=MIRROR/ros2+launch archive 3.7.1 | tar -x -C /tmp/ros_launch
    git --git-dir=MIRROR/ros2+launch_ros archive 0.28.0 | tar -x -C /tmp/ros_launch_ros
    .venv/bin/python -m pip install --no-deps --target /tmp/launchdeps osrf-pycommon==2.0.2
    .venv/bin/python scripts/launch_faults.py --launch /tmp/ros_launch --launch-ros /tmp/ros_launch_ros \\
        --deps /tmp/launchdeps --out FILE.yaml
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import socket
import subprocess
import sys
import textwrap
from importlib.metadata import version
from pathlib import Path

from stack_faults import CONFIG, Fault, scrub, write_set

SPIN = "try:\n    rclpy.spin(node)\nexcept (KeyboardInterrupt, ExternalShutdownException):\n    pass\n"
IMPORTS = "import rclpy\nfrom rclpy.executors import ExternalShutdownException\nfrom rclpy.node import Node\n"


def program(name: str, body: str, end: str = SPIN) -> str:
    """An rclpy node program: the node `name`, its start-up `body`, then `end` (spinning until shut down)."""
    return f"{IMPORTS}\nrclpy.init()\nnode = Node('{name}')\n{body}{end}"


BASE = program("base_driver", """port = node.declare_parameter('port', '/dev/ttyUSB0').value
baud = node.declare_parameter('baud_rate', 115200).value
speed = node.declare_parameter('max_speed', 0.5).value
node.get_logger().info(f'opened {port} at {baud} baud, max speed {speed} m/s')
""")
LIDAR = IMPORTS + """from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn


class LidarDriver(LifecycleNode):
    def __init__(self) -> None:
        super().__init__('lidar_driver')
        self.rate = self.declare_parameter('scan_frequency', 10.0).value
    def on_configure(self, state):
        if not 5.0 <= self.rate <= 15.0:
            self.get_logger().error(f'scan_frequency {self.rate} Hz is not supported (5-15 Hz)')
            return TransitionCallbackReturn.FAILURE
        self.get_logger().warn('intensities not requested, publishing ranges only')
        self.get_logger().info(f'motor spinning at {self.rate} Hz')
        return TransitionCallbackReturn.SUCCESS
    def on_activate(self, state):
        self.get_logger().info('publishing /scan')
        return super().on_activate(state)


rclpy.init()
node = LidarDriver()
""" + SPIN
PROGRAMS = {
    "base_driver/base_driver_node": BASE, "lidar_driver/lidar_node": LIDAR,
    "base_driver/odom_relay": program("odom_relay", "node.get_logger().info('relaying /wheel/odom to /odom')\n",
                                      "rclpy.spin(node)\n"),
    "imu_driver/imu_node": program("imu_driver", "node.get_logger().info('calibrating gyro bias')\n"
                                   "samples: list[float] = []\nbias = sum(samples) / len(samples)\n"),
    "camera_driver/camera_node": program("camera_driver", "fps = node.declare_paramter('fps', 30).value\n"
                                         "node.get_logger().info(f'streaming /dev/video0 at {fps} fps')\n"),
    "robot_state_publisher/robot_state_publisher": program(
        "robot_state_publisher", "urdf = node.declare_parameter('robot_description', '').value\n"
        "node.get_logger().info(f'robot description of {len(urdf)} characters')\n")}
HEAD = """\
import os

from launch import LaunchDescription
from launch.actions import (DeclareLaunchArgument, EmitEvent, ExecuteProcess, IncludeLaunchDescription,
                            RegisterEventHandler, Shutdown)
from launch.conditions import IfCondition
from launch.events import matches_action
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import LifecycleNode, Node
from launch_ros.descriptions import ParameterValue
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState
from launch_ros.substitutions import FindPackageShare
from lifecycle_msgs.msg import Transition


def generate_launch_description():
"""
SHARE = "install/share/robot_bringup"
BASE_NODE = "Node(package='base_driver', executable='base_driver_node', name='base_driver', output='screen'"
LIDAR_NODE = ("LifecycleNode(package='lidar_driver', executable='lidar_node', name='lidar_driver', namespace='',\n"
              "                      output='screen', parameters=[{{'scan_frequency': {rate}}}])")
LIFECYCLE = f"""lidar = {LIDAR_NODE}
configure = ChangeState(lifecycle_node_matcher=matches_action(lidar), transition_id=Transition.TRANSITION_CONFIGURE)
activate = ChangeState(lifecycle_node_matcher=matches_action(lidar), transition_id=Transition.TRANSITION_ACTIVATE)
return LaunchDescription([
    {BASE_NODE}),
    lidar,
    RegisterEventHandler(OnStateTransition(target_lifecycle_node=lidar, goal_state='inactive',
                                           entities=[EmitEvent(event=activate)])),
    EmitEvent(event=configure),
])
"""
SENSORS = f"""return LaunchDescription([
    {LIDAR_NODE.format(rate=10.0)}{{comma}}
    Node(package='imu_driver', executable='imu_node', name='imu_driver', output='screen'),
])
"""


def launch_file(body: str, name: str = "bringup.launch.py") -> dict[str, str]:
    return {f"{SHARE}/launch/{name}": HEAD + textwrap.indent(body, "    ")}


def with_base(close: str, *items: str, declare: tuple[str, ...] = (), before: str = "") -> dict[str, str]:
    """bringup.launch.py: `before`, then `declare`, the base driver (its Node call ended by `close`) and `items`."""
    entries = ",\n    ".join((*declare, BASE_NODE + close, *items))
    return launch_file(f"{before}return LaunchDescription([\n    {entries},\n])\n")


SERIAL = "DeclareLaunchArgument('serial_port', description='serial port of the base controller board')"
BY_PORT = ",\n         parameters=[{'port': LaunchConfiguration('serial_port')}])"
SENSORS_PATH = "sensors = PathJoinSubstitution([FindPackageShare('robot_bringup'), 'launch', 'sensors.launch.py'])\n"
XACRO = """urdf = PathJoinSubstitution([FindPackageShare('robot_bringup'), 'urdf', 'robot.urdf.xacro'])
description = ParameterValue(Command(['xacro ', urdf]), value_type=str)
"""
RSP_NODE = ("Node(package='robot_state_publisher', executable='robot_state_publisher', output='screen',\n"
            "         parameters=[{'robot_description': description}])")
INCLUDING = with_base(")", "IncludeLaunchDescription(PythonLaunchDescriptionSource(sensors))", before=SENSORS_PATH)
DIED, LIFECYCLE_CAUSE, NOMINAL = "bringup.process_died", "bringup.lifecycle_transition_failed", "control.nominal"
FAULTS = (
    Fault("launch-argument-not-given", "bringup", CONFIG,
          "The launch file declares serial_port without a default, and the bring-up was started without "
          "serial_port:=..., so launch stops before it starts the base driver.",
          files=with_base(BY_PORT, declare=(SERIAL,))),
    Fault("launch-argument-without-colon", "bringup", CONFIG,
          "The launch argument was typed with '=' instead of ':=' (serial_port=/dev/ttyACM0), so ros2 launch "
          "refuses it and starts nothing.", ("serial_port=/dev/ttyACM0",),
          files=with_base(BY_PORT, declare=(SERIAL,))),
    Fault("launch-configuration-misspelt", "bringup", CONFIG,
          "The launch file declares use_sim_time but the base driver's parameters read LaunchConfiguration"
          "('use_simtime'), a name never declared, so launch stops before it starts the driver.",
          files=with_base(",\n         parameters=[{'use_sim_time': LaunchConfiguration('use_simtime')}])",
                          declare=("DeclareLaunchArgument('use_sim_time', default_value='false')",))),
    Fault("find-package-share-misspelt", "bringup", CONFIG,
          "The params file of the base driver is looked up with FindPackageShare('robot_brinup'), a misspelt "
          "package name, so launch stops before it starts the driver.",
          files=with_base(",\n         parameters=[params])", before="params = PathJoinSubstitution("
                          "[FindPackageShare('robot_brinup'), 'config', 'base_driver.yaml'])\n")),
    Fault("include-launch-file-missing", "bringup", CONFIG,
          "The bring-up includes sensors.launch.py, but the file the package installs is sensor.launch.py, so "
          "the include fails and the sensors are never started.",
          files={**INCLUDING, **launch_file(SENSORS.replace("{comma}", ","), "sensor.launch.py")}),
    Fault("included-launch-file-syntax-error", "bringup", CONFIG,
          "The included sensors.launch.py lacks a comma between its lidar and IMU nodes, a Python syntax error, "
          "so the launch file cannot be loaded.",
          files={**INCLUDING, **launch_file(SENSORS.replace("{comma}", ""), "sensors.launch.py")}),
    Fault("launch-file-env-var-unset", "bringup", CONFIG,
          "The launch file reads os.environ['ROBOT_MODEL'], which was not exported in this shell, so "
          "generate_launch_description raises and nothing is started.",
          files=with_base(",\n         parameters=[{'robot_model': model}])",
                          before="model = os.environ['ROBOT_MODEL']\n")),
    Fault("if-condition-not-boolean", "bringup", CONFIG,
          "The lidar is started under IfCondition(use_lidar) and the bring-up was given use_lidar:=yes, which is "
          "not one of the values a condition accepts (true/false/1/0), so launch stops.", ("use_lidar:=yes",),
          files=with_base(")", "Node(package='lidar_driver', executable='lidar_node', name='lidar_driver',"
                          "\n         output='screen', condition=IfCondition(LaunchConfiguration('use_lidar')))",
                          declare=("DeclareLaunchArgument('use_lidar', default_value='true')",))),
    Fault("params-file-relative-path", "bringup", CONFIG,
          "The base driver's params file is given by a relative path (config/base_driver.yaml) that does not "
          "exist from the folder the bring-up was started in, so the driver runs on its default port "
          "/dev/ttyUSB0 instead of /dev/ttyACM0.",
          files={**with_base(",\n         parameters=['config/base_driver.yaml'])"),
                 f"{SHARE}/config/base_driver.yaml": "base_driver:\n  ros__parameters:\n    port: /dev/ttyACM0\n"}),
    Fault("parameter-dict-int-for-double", "bringup", CONFIG,
          "The launch file gives max_speed as the integer 1 where the base driver declares a double, so the "
          "driver refuses the parameter and dies at start.",
          files=with_base(",\n         parameters=[{'port': '/dev/ttyACM0', 'max_speed': 1}])")),
    Fault("ros-arguments-param-single-equals", "bringup", CONFIG,
          "The base driver's ros_arguments set the port with '=' instead of ':=' (-p port=/dev/ttyACM0), which rcl "
          "cannot parse, so the driver does not start.",
          files=with_base(",\n         ros_arguments=['-p', 'port=/dev/ttyACM0'])")),
    Fault("xacro-not-installed", "bringup", CONFIG,
          "robot_description is built by running xacro in a Command substitution, and xacro is not installed on "
          "this machine, so launch stops before robot_state_publisher starts.",
          files={**with_base(")", RSP_NODE, before=XACRO), f"{SHARE}/urdf/robot.urdf.xacro": "<robot name='rover'/>"}),
    Fault("required-node-died-shutdown", "bringup", DIED,
          "The IMU driver divides by the number of calibration samples, which is zero at start, and dies; it is "
          "launched with on_exit=Shutdown(), so its death takes the whole bring-up down with it.",
          files=with_base(")", "Node(package='imu_driver', executable='imu_node', name='imu_driver', output='screen',"
                          "\n         on_exit=Shutdown())")),
    Fault("respawn-crash-loop", "bringup", DIED,
          "The camera driver's code calls node.declare_paramter (a typo), which raises at start; it is launched "
          "with respawn=True, so launch starts it again and again and it dies each time.",
          files=with_base(")", "Node(package='camera_driver', executable='camera_node', name='camera_driver',"
                          "\n         output='screen', respawn=True, respawn_delay=1.0)")),
    Fault("lifecycle-configure-returns-failure", "bringup", LIFECYCLE_CAUSE,
          "The launch file sets the lidar's scan_frequency to 25 Hz, past the 15 Hz its driver supports, so the "
          "driver's configure callback returns FAILURE and the lidar is never configured or activated.",
          files=launch_file(LIFECYCLE.format(rate=25.0))),
    Fault("bringup-lifecycle-lidar-warning", "bringup", NOMINAL,
          "Nothing was wrong: the base driver came up and the lidar was configured and activated by the launch "
          "file; its warning about intensities is its normal start-up.",
          files=launch_file(LIFECYCLE.format(rate=10.0)), outcome="succeeded"),
    Fault("bringup-stale-lock-cleanup-exits-1", "bringup", NOMINAL,
          "Nothing was wrong: the launch file first removes a stale lidar lock file, which was not there, so rm "
          "exits 1 harmlessly, and the base driver came up.", outcome="succeeded",
          files=with_base(")", "ExecuteProcess(cmd=['rm', '/var/lock/lidar.lock'], output='screen')")),
    Fault("bringup-ctrl-c-traceback", "bringup", NOMINAL,
          "Nothing was wrong: the base driver and the odometry relay ran until the bring-up was stopped with "
          "Ctrl-C; the relay does not catch the shutdown, so it prints a traceback as it exits.",
          outcome="succeeded",
          files=with_base(")", "Node(package='base_driver', executable='odom_relay', output='screen')")),
)
RUNNER = """\
import sys
from ament_index_python.packages import PackageNotFoundError
from ros2launch.api import get_share_file_path_from_package, launch_a_launch_file

sys.stdout.reconfigure(line_buffering=True)
package, file_name, *arguments = sys.argv[1:]
try:
    try:
        path = get_share_file_path_from_package(package_name=package, file_name=file_name)
    except PackageNotFoundError as exc:
        raise RuntimeError(f"Package '{package}' not found: {exc}")
    except FileNotFoundError as exc:
        raise RuntimeError(str(exc))
    rc = launch_a_launch_file(launch_file_path=path, launch_file_arguments=arguments, noninteractive=True)
except RuntimeError as exc:  # as ros2cli's main does
    rc = str(exc)
sys.exit(rc)
"""
COMPOSITION = "class _Service:\n    Request = Response = object\n\n\nListNodes = LoadNode = UnloadNode = _Service\n"
STOP = 6.0  # seconds before a bring-up still running is stopped with SIGINT, as Ctrl-C
NOTES = {NOMINAL: "No bringup.nominal id exists; control.nominal ('the drivers and controllers started without a "
                  "problem') is the one that states this run: drivers brought up and running until stopped."}
HEADER = """\
# Held-out set 26 of real console excerpts (issue 23's format): printed by the real ROS 2 stack installed on this
# project's machine (ROS 2 Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from PyPI; ros2/launch 3.7.1 and
# ros2/launch_ros 0.28.0, Rolling's tags of the Kilted cycle and the newest the project's mirror holds, from checkouts,
# run as `ros2 launch` runs them), each run with one bring-up fault of a launch file: written by
# scripts/launch_faults.py, which states each excerpt's cause (the fault) before it runs anything. Three runs succeeded
# (a warning, a harmless nonzero exit, a traceback at Ctrl-C). Output is kept as printed, less ANSI colours, with this
# machine's folders replaced by /opt/venv/..., /opt/ros/... and /home/robot/ws. Frozen and measured once before
# anything was tuned on it. Regenerate with the command in scripts/launch_faults.py's docstring.
"""


def run(fault: Fault, work: Path, path: str, notes: dict[str, str]) -> tuple[str, int]:
    index = work / "install/share/ament_index/resource_index/packages"
    files = {**{f"install/lib/{name}": f"#!{sys.executable}\n{text}" for name, text in PROGRAMS.items()},
             **{str(index / name.split("/")[0]): "" for name in [*PROGRAMS, "robot_bringup/"]},
             ".interfaces/composition_interfaces/__init__.py": "",
             ".interfaces/composition_interfaces/srv.py": COMPOSITION,
             "ros2_launch.py": RUNNER, **fault.files}
    for name, text in files.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text, encoding="utf-8")
    for name in PROGRAMS:
        (work / "install/lib" / name).chmod(0o755)
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("ROS_", "RMW_", "FASTDDS_", "CYCLONEDDS_", "AMENT_", "PYTHONPATH"))}
    env.update(fault.env, AMENT_PREFIX_PATH=str(work / "install"), ROS_HOME=str(work / ".ros"),
               PYTHONPATH=os.pathsep.join((path, str(work / ".interfaces"))))
    command = [sys.executable, "ros2_launch.py", "robot_bringup", "bringup.launch.py", *fault.args]
    with subprocess.Popen(command, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, start_new_session=True) as proc:
        try:
            out, _ = proc.communicate(timeout=STOP)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGINT)
            stopped = f"Stopped with SIGINT after {STOP:g} s, as Ctrl-C."
            notes[fault.id] = f"{notes[fault.id]} {stopped}" if fault.id in notes else stopped
            out, _ = proc.communicate(timeout=60)
    return out, proc.returncode


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--launch", type=Path, required=True, help="a checkout of ros2/launch")
    parser.add_argument("--launch-ros", type=Path, required=True, help="a checkout of ros2/launch_ros")
    parser.add_argument("--deps", type=Path, required=True, help="a pip --target folder holding osrf_pycommon")
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    folders = {args.launch.absolute() / "launch": "/opt/ros/launch",
               args.launch_ros.absolute() / "launch_ros": "/opt/ros/launch_ros",
               args.launch_ros.absolute() / "ros2launch": "/opt/ros/ros2launch",
               args.deps.absolute(): "/opt/launch-deps"}
    names = [(sys.executable, "/opt/venv/bin/python"), (str(Path(sys.executable).parent.parent), "/opt/venv"),
             *((str(local), fixed) for local, fixed in folders.items()), (sys.base_prefix, "/usr")]
    names.sort(key=lambda pair: -len(pair[0]))
    host = re.compile(r"(\d{4}(?:-\d+){6})-" + re.escape(socket.gethostname()) + r"-(\d+)")
    path = os.pathsep.join(str(folder) for folder in folders)
    notes = {fault.id: NOTES[fault.cause] for fault in FAULTS if fault.cause in NOTES}

    def run_one(fault: Fault, work: Path) -> tuple[str, int]:
        text, code = run(fault, work, path, notes)
        lines = scrub(text, work)
        for local, fixed in names:
            lines = lines.replace(local, fixed)
        return host.sub(r"\1-robot-\2", lines), code

    tags = [re.findall(r"<version>(.+?)</version>", (folder / "package.xml").read_text(encoding="utf-8"))[0]
            for folder in folders if folder.name in ("launch", "launch_ros")]
    stack = f"rclpy {version('ros-kilted-rclpy')}, ros2/launch {tags[0]}, ros2/launch_ros {tags[1]}"
    write_set(args.out, HEADER, "launch_faults.py", stack, FAULTS, run_one, notes=notes)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
