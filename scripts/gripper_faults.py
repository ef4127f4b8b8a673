"""Real console output of ros2_control closing a parallel gripper (controller_manager, joint_state_broadcaster,
parallel_gripper_action_controller on mock_components/GenericSystem), each run with one fault of the gripper's
bring-up or of the program that sends it its goal: fingers that stop on an object with and without
allow_stalling, a joint misspelt, the gripper controller of earlier releases, an effort interface the robot does not
give, a goal with a position per finger, a controller spawned inactive; and a run that went well.

A run is what `ros2 launch` of the gripper's control bring-up prints: a robot_description publisher (as
robot_state_publisher publishes it), ros2_control_node, the spawners of joint_state_broadcaster and gripper_controller
one after the other. From outside the console a client waits for the controller's gripper_cmd action (30 s at most)
and sends one control_msgs/ParallelGripperCommand goal closing the fingers from 4 cm to 1 cm, as a pick's grasp does;
the grasp succeeded when the goal did (a stall the controller allows is a success). Ctrl-C follows two seconds after
the result. The cause of each run is the fault injected, written here before any run was made, by the rule of
`label()`. Output is kept as printed, less ANSI colours, with this machine's folders replaced by fixed names. Writes
real_modules-format excerpts (evals/data/real_modules/README.md).

Run inside a ROS 2 environment with ros2_control and ros2_controllers (e.g. `source /opt/ros/kilted/setup.bash`):

    python3 scripts/gripper_faults.py --out FILE.yaml [--only ID ...]
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from control_faults import CONFIG, LOAD, NOMINAL, TOLERANCE, module_set, write_bringup
from launch_runs import HIT, run_launch

ACTIVATION = "control.controller_activation_failed"
JOINT = "gripper_finger_joint"
OPEN, CLOSE = 0.04, 0.01  # m: the fingers' opening at the start, and the grasp's goal
# the joint's upper limit: the mock adds its following offset to every command, the hold at the start too (0.055 m
# for an object 1.5 cm wide), and ros2_control's joint limiter stops a controller whose joint reads beyond its limit
# (widened from OPEN after the fault-free grasp on an object tried it)
WIDEST = 0.08
WAIT_S = 30.0  # how long the client waits for the gripper's action server
RUN_S = 10.0  # how long it waits for the grasp's result


@dataclass(frozen=True)
class Fault:
    id: str
    cause: str  # the cause when the grasp fails; label() says what a grasp that succeeded is
    quote: str  # what was wrong, as the cause_quote
    controller: dict[str, Any] = field(default_factory=dict)  # merged into gripper_controller's parameters
    controller_type: str = "parallel_gripper_action_controller/GripperActionController"
    hardware: dict[str, str] = field(default_factory=dict)  # the mock hardware's <param>s
    positions: tuple[float, ...] = (CLOSE,)  # the goal's command.position
    inactive: bool = False  # the gripper controller's spawner is given --inactive
    silent: bool = False  # logs_show_cause false: nothing in any process's console could show it


# the fingers stop 1.5 cm short of the goal, as on an object 2.5 cm wide: the mock reports each position that far
# from the command (position_state_following_offset)
ON_OBJECT = {"position_state_following_offset": "0.015"}
FAULTS = (
    Fault("gripper-nominal", NOMINAL, "Nothing was wrong: the gripper closed from 4 cm to 1 cm as asked."),
    Fault("gripper-stall-allowed", NOMINAL, "Nothing was wrong: the fingers stopped on an object 1.5 cm short of the "
          "1 cm goal, and the controller (allow_stalling true) took the stall as the grasp.",
          hardware=ON_OBJECT, controller={"allow_stalling": True}),
    Fault("gripper-stall", TOLERANCE, "The fingers stopped on an object 1.5 cm short of the 1 cm goal, and the "
          "controller (allow_stalling false, its default) aborted the goal as a stall outside its goal tolerance.",
          hardware=ON_OBJECT),
    Fault("gripper-joint-misspelt", CONFIG, "gripper_controller's joint was gripper_finger_jiont (misspelt), a joint "
          "the robot description does not have.", controller={"joint": "gripper_finger_jiont"}),
    Fault("gripper-old-type", LOAD, "gripper_controller's type was gripper_controllers/GripperActionController, the "
          "gripper controller of earlier releases, which this installation does not have (its parallel gripper "
          "controller is parallel_gripper_action_controller/GripperActionController).",
          controller_type="gripper_controllers/GripperActionController"),
    Fault("gripper-effort-interface-missing", CONFIG, "gripper_controller's max_effort_interface named "
          "gripper_finger_joint/max_effort, a command interface the robot description does not give.",
          controller={"max_effort_interface": f"{JOINT}/max_effort"}),
    Fault("gripper-two-positions", CONFIG, "The client sent two finger positions (one per finger), while the parallel "
          "gripper controller takes one position for its one joint.", positions=(CLOSE, CLOSE)),
    Fault("gripper-inactive", ACTIVATION, "The launch file spawned gripper_controller with --inactive, so it was "
          "configured but never activated.", inactive=True),
)


def label(fault: Fault, succeeded: bool) -> tuple[str, str]:
    """The rule written before any run: a grasp whose goal succeeded is 'succeeded' with cause control.nominal,
    whatever the fault; one whose goal did not is 'failed' with the fault's cause."""
    return ("succeeded", NOMINAL) if succeeded else ("failed", fault.cause)


def urdf(fault: Fault) -> str:
    # calculate_dynamics: the mock reports the fingers' velocity, without which the controller never sees them move and
    # so never sees them stall (added after the fault-free grasp on an object never ended)
    hardware = {"calculate_dynamics": "true", **fault.hardware}
    params = "".join(f'<param name="{k}">{v}</param>' for k, v in hardware.items())
    joint = (f'<joint name="{JOINT}"><command_interface name="position"/>'
             f'<state_interface name="position"><param name="initial_value">{OPEN}</param></state_interface>'
             '<state_interface name="velocity"/></joint>')
    links = '<link name="gripper_base"/><link name="gripper_finger"/>'
    chain = (f'<joint name="{JOINT}" type="prismatic"><parent link="gripper_base"/><child link="gripper_finger"/>'
             f'<axis xyz="0 1 0"/><limit lower="0.0" upper="{WIDEST}" effort="20" velocity="0.1"/></joint>')
    return (f'<?xml version="1.0"?><robot name="gripper">{links}{chain}<ros2_control name="GripperSystem" '
            f'type="system"><hardware><plugin>mock_components/GenericSystem</plugin>{params}</hardware>{joint}'
            '</ros2_control></robot>')


def params(fault: Fault) -> dict[str, Any]:
    gripper: dict[str, Any] = {"joint": JOINT, "goal_tolerance": 0.002, "stall_timeout": 1.0, **fault.controller}
    manager = {"update_rate": 100, "joint_state_broadcaster": {"type": "joint_state_broadcaster/JointStateBroadcaster"},
               "gripper_controller": {"type": fault.controller_type}}
    return {"controller_manager": {"ros__parameters": manager}, "gripper_controller": {"ros__parameters": gripper}}


SEND = HIT + """\
import json
import sys
import time
import rclpy
from control_msgs.action import ParallelGripperCommand
from rclpy.action import ActionClient

wait_s, run_s, out = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
positions, joint = [float(p) for p in sys.argv[4].split(',')], sys.argv[5]
rclpy.init()
node = rclpy.create_node('grasp_client')
client = ActionClient(node, ParallelGripperCommand, 'gripper_controller/gripper_cmd')
result = {'server': client.wait_for_server(timeout_sec=wait_s), 'accepted': False, 'status': None, 'seconds': None}
if result['server']:
    time.sleep(1.0)  # as a pick waits for the controller to be active, not only its server to exist
    goal = ParallelGripperCommand.Goal()
    goal.command.name = [joint] * len(positions)
    goal.command.position = positions
    done = send_goal(node, client, goal, [], '', run_s, result)
    if done is not None:
        res = done.result()
        result['status'], result['reached_goal'] = res.status, res.result.reached_goal
        result['stalled'] = res.result.stalled
        result['position'] = [round(p, 4) for p in res.result.state.position]
json.dump(result, open(out, 'w'))
"""

LAUNCH = """\
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch_ros.actions import Node

PARAMS = {params!r}
URDF = {urdf!r}
INACTIVE = {inactive!r}


def generate_launch_description():
    broadcaster = Node(package='controller_manager', executable='spawner', output='screen',
                       arguments=['joint_state_broadcaster'])
    gripper = Node(package='controller_manager', executable='spawner', output='screen',
                   arguments=['gripper_controller'] + (['--inactive'] if INACTIVE else []))
    return LaunchDescription([
        Node(package='gripper_description', executable='describe', name='robot_description_publisher',
             output='screen', arguments=[URDF]),
        Node(package='controller_manager', executable='ros2_control_node', output='screen', parameters=[PARAMS]),
        broadcaster, RegisterEventHandler(OnProcessExit(target_action=broadcaster, on_exit=[gripper]))])
"""


def run(fault: Fault, work: Path, launch_path: list[Path]) -> tuple[str, dict[str, Any]]:
    """Launch the gripper's bring-up, send the grasp from outside it, Ctrl-C two seconds after the result: the
    console and the grasp's result."""
    launch, prefix = write_bringup(work, "gripper", urdf(fault), params(fault), LAUNCH, inactive=fault.inactive)
    result_file = work / "result.json"
    argv = [str(WAIT_S), str(RUN_S), str(result_file), ",".join(map(str, fault.positions)), JOINT]
    return run_launch(launch, prefix, work, launch_path, (SEND, argv), result_file, WAIT_S + 3 * RUN_S)


HEADER = """\
# Held-out set 34 of real console excerpts (issue 23's format): printed by ros2_control {version} (controller_manager,
# joint_state_broadcaster, parallel_gripper_action_controller, mock_components/GenericSystem), built from source on
# ROS 2 Kilted's rclpy, rcl and Fast DDS from PyPI, each run with one fault of a parallel gripper's bring-up or of its
# grasp and started by the real ros2launch: written by scripts/gripper_faults.py, whose faults and labelling rule
# were committed before any of them was run. Output is kept as printed, less ANSI colours, with this machine's folders
# replaced by fixed names. Frozen and measured once before anything was tuned on it.
# Regenerate inside a ROS 2 environment with ros2_control: python3 scripts/gripper_faults.py --out FILE
"""


def main() -> int:
    return module_set(__doc__, FAULTS, run, "gripper_faults.py", HEADER, label,
                      lambda result: result.get("status") == 4,  # action_msgs/GoalStatus SUCCEEDED
                      lambda result: f"Grasp from {OPEN} m to {CLOSE} m: {json.dumps(result)}.")


if __name__ == "__main__":
    raise SystemExit(main())
