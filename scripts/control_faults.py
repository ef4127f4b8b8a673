"""Real console output of ros2_control (controller_manager, joint_state_broadcaster, joint_trajectory_controller on
mock_components/GenericSystem hardware), each run with one fault of a robot arm's controller bring-up: a controller
type misspelt or never given, a trajectory controller whose joints or interfaces the robot does not have, joints
left empty, a hardware plugin misspelt, hardware whose state lags its commands or that ignores them, a spawner that
asks the wrong controller manager, no robot description, the controller manager killed mid-trajectory; and a run
that went well.

A run is what `ros2 launch` of an arm's control bring-up prints: a robot_description publisher (as
robot_state_publisher publishes it), ros2_control_node, the spawners of joint_state_broadcaster and arm_controller,
started by ros2launch; one FollowJointTrajectory goal sent from outside the console, as MoveIt or a script sends
it; Ctrl-C two seconds after its result (or after the time a person would wait). The cause of each run is the fault
injected, written here before any run was made, by the rule of `label()`. Output is kept as printed, less ANSI
colours, with this machine's folders replaced by fixed names. Writes real_modules-format excerpts
(evals/data/real_modules/README.md).

Run inside a ROS 2 environment with ros2_control and ros2_controllers (e.g. `source /opt/ros/kilted/setup.bash`):

    python3 scripts/control_faults.py --out FILE.yaml [--only ID ...]

Where ros2launch is not importable, `--launch-path` names folders holding launch, launch_ros, ros2launch and
osrf_pycommon.
"""

from __future__ import annotations

import copy
import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from launch_runs import HIT, Runner, arguments, install, kept, run_launch, runs, write_set

NOMINAL, LOAD, CONFIG = "control.nominal", "control.controller_load_failed", "control.configuration_error"
HARDWARE, TOLERANCE = "control.hardware_failure", "control.tolerance_violated"
LAUNCH_ARG, DIED = "bringup.configuration_error", "bringup.process_died"
JOINTS = ("shoulder_joint", "elbow_joint")
WAIT_S = 30.0  # how long the sender waits for the trajectory controller's action server
RUN_S = 20.0  # how long it waits for the trajectory's result


@dataclass(frozen=True)
class Fault:
    id: str
    cause: str  # the cause when the trajectory fails; label() says what a run that succeeded is
    quote: str  # what was wrong, as the cause_quote
    controller: dict[str, Any] = field(default_factory=dict)  # merged into arm_controller's parameters
    controller_type: str | None = "joint_trajectory_controller/JointTrajectoryController"  # None: no 'type'
    hardware: dict[str, str] = field(default_factory=dict)  # the mock hardware's <param>s
    plugin: str = "mock_components/GenericSystem"
    manager_arg: str | None = None  # the spawners' --controller-manager, when not the default
    description: bool = True  # something publishes /robot_description
    hit: tuple[str, str, float] | None = None  # (process, signal, s): sent to a process that long into the goal
    silent: bool = False  # logs_show_cause false: nothing in any process's console could show it
    limit: float = 3.1  # the joints' position limit in the robot description (rad, both ways)
    initial: bool = True  # the position state interfaces carry an initial_value
    update_rate: int = 100
    # the spawners, in order, each with its arguments; chained: each starts when the one before it ended, as
    # ros2_control's demos start them (set 30's two started together)
    spawns: tuple[tuple[str, tuple[str, ...]], ...] = (("joint_state_broadcaster", ()), ("arm_controller", ()))
    chained: bool = False
    blocker: bool = False  # a forward_command_controller on the same joints' positions, declared beside them
    goal_joints: tuple[str, ...] = ()  # the joints the trajectory names, when not the arm's (set 33)
    describe_delay: float = 0.0  # seconds before the robot description is published (set 33)


FAULTS = (
    Fault("control-nominal", NOMINAL, "Nothing was wrong: the arm's trajectory controller followed the trajectory "
          "on the mock hardware."),
    Fault("controller-type-misspelt", LOAD, "arm_controller's type was joint_trajectory_controller/"
          "JointTrajectoryControler (misspelt), a class no installed plugin provides.",
          controller_type="joint_trajectory_controller/JointTrajectoryControler"),
    Fault("controller-type-missing", LOAD, "arm_controller had no 'type' parameter in the controller manager's "
          "parameters, so the controller manager could not load it.", controller_type=None),
    Fault("jtc-unknown-joint", CONFIG, "arm_controller's joints named wrist_joint, which the robot description does "
          "not have, so its command interface did not exist.",
          controller={"joints": [*JOINTS, "wrist_joint"]}),
    Fault("jtc-velocity-command", CONFIG, "arm_controller asked for velocity command interfaces, while the robot "
          "description gives its joints position commands only.",
          controller={"command_interfaces": ["velocity"]}),
    Fault("jtc-no-joints", CONFIG, "arm_controller's joints parameter was an empty list.",
          controller={"joints": []}),
    Fault("hardware-plugin-misspelt", HARDWARE, "The robot description's hardware plugin was "
          "mock_components/GenericSystm (misspelt), so the controller manager could not load the arm's hardware "
          "interface.", plugin="mock_components/GenericSystm"),
    Fault("hardware-state-offset", TOLERANCE, "The hardware reported each joint 0.3 rad from where it was "
          "commanded (position_state_following_offset), beyond the controller's 0.05 rad goal tolerance.",
          hardware={"position_state_following_offset": "0.3"}),
    Fault("hardware-ignores-commands", HARDWARE, "The hardware ignored every command (disable_commands), as a "
          "driver whose motors are not enabled does, so the joints never moved.",
          hardware={"disable_commands": "true"}, silent=True),
    Fault("spawner-wrong-manager", LAUNCH_ARG, "The spawners were started with --controller-manager "
          "/arm/controller_manager, while the controller manager ran as /controller_manager.",
          manager_arg="/arm/controller_manager"),
    Fault("no-robot-description", LAUNCH_ARG, "Nothing published /robot_description (robot_state_publisher left "
          "out of the launch file), so the controller manager never got the robot's description.",
          description=False),
    Fault("manager-killed", DIED, "ros2_control_node was killed (SIGKILL, as the kernel's out-of-memory killer "
          "does) 0.5 s into the trajectory.", hit=("ros2_control_node", "SIGKILL", 0.5)),
)


def label(fault: Fault, succeeded: bool) -> tuple[str, str]:
    """The rule written before any run: a trajectory that succeeded is 'succeeded' with cause control.nominal,
    whatever the fault; one that did not is 'failed' with the fault's cause."""
    return ("succeeded", NOMINAL) if succeeded else ("failed", fault.cause)


def urdf(fault: Fault) -> str:
    params = "".join(f'<param name="{k}">{v}</param>' for k, v in fault.hardware.items())
    initial = '<param name="initial_value">0.0</param>' if fault.initial else ""
    joints = "".join(
        f'<joint name="{j}"><command_interface name="position"/>'
        f'<state_interface name="position">{initial}</state_interface>'
        f'<state_interface name="velocity"/></joint>' for j in JOINTS)
    links = '<link name="base_link"/><link name="upper_arm"/><link name="forearm"/>'
    chain = "".join(
        f'<joint name="{j}" type="revolute"><parent link="{p}"/><child link="{c}"/><axis xyz="0 0 1"/>'
        f'<limit lower="{-fault.limit}" upper="{fault.limit}" effort="10" velocity="2"/></joint>'
        for j, p, c in ((JOINTS[0], "base_link", "upper_arm"), (JOINTS[1], "upper_arm", "forearm")))
    return (f'<?xml version="1.0"?><robot name="arm">{links}{chain}<ros2_control name="ArmSystem" type="system">'
            f'<hardware><plugin>{fault.plugin}</plugin>{params}</hardware>{joints}</ros2_control></robot>')


def params(fault: Fault) -> dict[str, Any]:
    arm: dict[str, Any] = {
        "joints": list(JOINTS), "command_interfaces": ["position"], "state_interfaces": ["position", "velocity"],
        "constraints": {"goal_time": 1.0, "stopped_velocity_tolerance": 0.05,
                        **{j: {"goal": 0.05, "trajectory": 0.0} for j in JOINTS}}}
    arm.update(copy.deepcopy(fault.controller))
    manager: dict[str, Any] = {"update_rate": fault.update_rate,
                               "joint_state_broadcaster": {"type": "joint_state_broadcaster/JointStateBroadcaster"}}
    if fault.controller_type is not None:
        manager["arm_controller"] = {"type": fault.controller_type}
    out = {"controller_manager": {"ros__parameters": manager}, "arm_controller": {"ros__parameters": arm}}
    if fault.blocker:
        manager["position_forward"] = {"type": "forward_command_controller/ForwardCommandController"}
        out["position_forward"] = {"ros__parameters": {"joints": list(JOINTS), "interface_name": "position"}}
    return out


DESCRIBE = """\
import sys
import time
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.qos import DurabilityPolicy, QoSProfile
from rclpy.utilities import remove_ros_args
from std_msgs.msg import String

rclpy.init()
node = rclpy.create_node('robot_description_publisher')
latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
pub = node.create_publisher(String, 'robot_description', latched)
args = remove_ros_args(sys.argv)  # launch_ros appends --ros-args ... to a Node's arguments
time.sleep(float(args[2]) if len(args) > 2 else 0.0)  # a description that comes late (set 33)
pub.publish(String(data=open(args[1]).read()))
node.get_logger().info('published the robot description')
try:
    rclpy.spin(node)
except (KeyboardInterrupt, ExternalShutdownException):
    pass
"""

# a trajectory sender's start (its arguments begin WAIT_S RUN_S OUT): the action's client once its server is there,
# and the result it fills in; what follows builds `goal` under `if result['server']:` and sends it, and
# TRAJECTORY_RESULT ends it (set 36's sender too)
TRAJECTORY_CLIENT = HIT + """\
import json
import sys
import time
import rclpy
from builtin_interfaces.msg import Duration
from control_msgs.action import FollowJointTrajectory
from rclpy.action import ActionClient
from trajectory_msgs.msg import JointTrajectoryPoint

wait_s, run_s, out = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
rclpy.init()
node = rclpy.create_node('trajectory_sender')
client = ActionClient(node, FollowJointTrajectory, 'arm_controller/follow_joint_trajectory')
result = {'server': client.wait_for_server(timeout_sec=wait_s), 'accepted': False, 'status': None,
          'error_code': None, 'error_string': None, 'seconds': None}
if result['server']:
    time.sleep(1.0)  # as a script waits for the controller to be active, not only its server to exist
    goal = FollowJointTrajectory.Goal()
"""

TRAJECTORY_RESULT = """\
    if done is not None:
        res = done.result()
        result['status'], result['error_code'] = res.status, res.result.error_code
        result['error_string'] = res.result.error_string
json.dump(result, open(out, 'w'))
"""

SEND = TRAJECTORY_CLIENT + """\
    hit = [a for a in sys.argv[4:7] if a]  # PROCESS SIGNAL SECONDS: done to a process on the way (empty: nothing)
    goal.trajectory.joint_names = sys.argv[7].split(',')
    n = len(goal.trajectory.joint_names)  # as many positions as joints named (a partial goal: fewer)
    for t, (a, b) in ((1, (0.5, -0.5)), (2, (1.0, -1.0))):
        goal.trajectory.points.append(JointTrajectoryPoint(positions=[a, b][:n], time_from_start=Duration(sec=t)))
    done = send_goal(node, client, goal, hit, hit[0] if hit else '', run_s, result)
""" + TRAJECTORY_RESULT

LAUNCH = """\
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch_ros.actions import Node

PARAMS = {params!r}
URDF = {urdf!r}
DESCRIBE = {describe!r}
MANAGER = {manager!r}
SPAWNS = {spawns!r}
CHAINED = {chained!r}
DELAY = {delay!r}


def generate_launch_description():
    actions = []
    if DESCRIBE:
        actions.append(Node(package='arm_description', executable='describe', name='robot_description_publisher',
                            output='screen', arguments=[URDF, str(DELAY)]))
    actions.append(Node(package='controller_manager', executable='ros2_control_node', output='screen',
                        parameters=[PARAMS]))
    before = None
    for name, extra in SPAWNS:
        args = [name, *extra] + (['--controller-manager', MANAGER] if MANAGER else [])
        spawner = Node(package='controller_manager', executable='spawner', output='screen', arguments=args)
        if CHAINED and before is not None:
            actions.append(RegisterEventHandler(OnProcessExit(target_action=before, on_exit=[spawner])))
        else:
            actions.append(spawner)
        before = spawner
    return LaunchDescription(actions)
"""


def write_bringup(work: Path, robot: str, description: str, controllers: dict[str, Any], launch: str,
                  **fields: Any) -> tuple[Path, Path]:
    """A control bring-up in `work` (this script's and base_faults.py's, gripper_faults.py's, head_faults.py's): the
    robot's description and controllers' parameters as `<robot>.urdf` and `<robot>_controllers.yaml`, its description
    publisher installed as `<robot>_description`, and the launch file `launch` filled with their paths and `fields`:
    the launch file's path and the install prefix."""
    (work / f"{robot}.urdf").write_text(description, encoding="utf-8")
    (work / f"{robot}_controllers.yaml").write_text(yaml.safe_dump(controllers, sort_keys=False), encoding="utf-8")
    prefix = work / "install"
    install(prefix, f"{robot}_description", "describe", DESCRIBE)
    path = work / f"{robot}_control.launch.py"
    path.write_text(launch.format(params=str(work / f"{robot}_controllers.yaml"), urdf=str(work / f"{robot}.urdf"),
                                  **fields), encoding="utf-8")
    return path, prefix


def setup(fault: Fault, work: Path) -> tuple[Path, Path]:
    """The fault's work folder: the description, the params file, the description publisher as an installed
    program, the launch file."""
    return write_bringup(work, "arm", urdf(fault), params(fault), LAUNCH, describe=fault.description,
                         manager=fault.manager_arg, spawns=[(n, list(a)) for n, a in fault.spawns],
                         chained=fault.chained, delay=fault.describe_delay)


def run(fault: Fault, work: Path, launch_path: list[Path]) -> tuple[str, dict[str, Any]]:
    """Launch the bring-up, send the trajectory from outside it, Ctrl-C two seconds after the result: the console
    and the trajectory's result."""
    launch, prefix = setup(fault, work)
    result_file = work / "result.json"
    hit = [str(v) for v in fault.hit] if fault.hit else ["", "", ""]
    argv = [str(WAIT_S), str(RUN_S), str(result_file), *hit, ",".join(fault.goal_joints or JOINTS)]
    return run_launch(launch, prefix, work, launch_path, (SEND, argv), result_file, WAIT_S + 3 * RUN_S)


HEADER = """\
# Held-out set 30 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, joint_trajectory_controller, mock_components/GenericSystem), built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI, each run with one fault of an arm's control bring-up and started by the
# real ros2launch: written by scripts/control_faults.py, whose faults and labelling rule were committed before any of
# them was run. Output is kept as printed, less ANSI colours, with this machine's folders replaced by fixed names.
# Frozen and measured once before anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/control_faults.py --out FILE
"""


def main() -> int:
    parser = arguments(__doc__)
    parser.add_argument("--set", type=int, choices=(30, 31, 33), default=30,
                        help="30: controller types, interfaces, hardware, spawners, the description, a death; 31: "
                             "limits, tolerances, a claimed interface, an inactive controller, the loop's rate; 33: "
                             "the trajectory's joints, the loop's load, spawners twice or short of time")
    parser.add_argument("--version", default="kilted", help="as the header names it")
    args = parser.parse_args()
    faults, header, faults_file = FAULTS, HEADER, "control_faults.py"
    if args.set == 31:
        from control_faults31 import FAULTS31, HEADER31

        faults, header, faults_file = FAULTS31, HEADER31, "control_faults31.py"
    if args.set == 33:
        from control_faults33 import FAULTS33, HEADER33

        faults, header, faults_file = FAULTS33, HEADER33, "control_faults33.py"
    entries = []
    for fault, lines, result in runs(faults, args, run):
        succeeded = result.get("status") == 4 and result.get("error_code") == 0  # SUCCEEDED, SUCCESSFUL
        outcome, cause = label(fault, succeeded)
        if kept(fault.id, outcome, cause, NOMINAL):
            entries.append(entry(fault, "control_faults.py", faults_file, args.version, (outcome, cause), lines,
                                 f"Trajectory of {len(JOINTS)} joints over 2 s: {json.dumps(result)}."))
    write_set(args.out, header.format(version=args.version), entries)
    return 0


def module_set(doc: str | None, faults: Sequence[Any], run: Runner, script: str, header: str,
               label: Callable[[Any, bool], tuple[str, str]], succeeded: Callable[[dict[str, Any]], bool],
               notes: Callable[[dict[str, Any]], str]) -> int:
    """A stand-alone generator's main (base_faults.py, gripper_faults.py): run each fault, label it by its script's
    rule (`label`, given whether `succeeded(result)`), and write the kept runs as a real_modules data file."""
    parser = arguments(doc)
    parser.add_argument("--version", default="kilted", help="as the header names it")
    args = parser.parse_args()
    entries = []
    for fault, lines, result in runs(faults, args, run):
        outcome, cause = label(fault, succeeded(result))
        if kept(fault.id, outcome, cause, NOMINAL):
            entries.append(entry(fault, script, script, args.version, (outcome, cause), lines, notes(result)))
    write_set(args.out, header.format(version=args.version), entries)
    return 0


def entry(fault: Any, script: str, faults_file: str, version: str, labelled: tuple[str, str], lines: str,
          notes: str) -> dict[str, Any]:
    """One run as a real_modules excerpt (a control fault's: its id, quote and silence)."""
    outcome, cause = labelled
    return {"id": f"kilted-control-{fault.id}", "source": f"scripts/{script} on ros2_control {version}",
            "url": f"scripts/{faults_file}#{fault.id}", "distro": "kilted", "module": "control", "outcome": outcome,
            "cause": cause, "cause_quote": fault.quote, "logs_show_cause": not fault.silent or outcome != "failed",
            "notes": notes, "lines": lines}


if __name__ == "__main__":
    raise SystemExit(main())
