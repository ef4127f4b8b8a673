"""Real console output of ROS 2 actions (the goal, feedback and result protocol of Nav2, MoveIt and ros2_control) on
the ROS 2 stack installed here (ROS 2 Kilted's rclpy, rcl_action and Fast DDS from PyPI, with test_msgs' action types),
each run with one fault of an action's goal, feedback or result: a device the execute callback cannot open, a goal
callback that raises or returns a bool, a rejected goal's result asked for, an action name or type the two ends do not
share, two servers of one name, an invalid name, a server dying mid-goal, a cancel refused or never handled, a result
expired before it was asked for, no terminal state, a raising feedback callback; and three runs that succeed with a
warning or an error logged (a goal preempted, a goal canceled on purpose, a late server).

The fifth set beside scripts/stack_faults.py, runtime_faults.py, settings_faults.py and graph_faults.py (held-out
sets 22-25), written the same way: every fault run for real, output kept as printed less ANSI colours and with this
machine's folders replaced by fixed names, each excerpt's cause the fault injected, written before the set was run.
The venv has no action types. The test_msgs wheel puts its libraries in PREFIX/lib and its package in
PREFIX/lib/python3.11/site-packages (pip's --target drops both), so it is installed with --prefix, and the nodes get
PREFIX/lib on LD_LIBRARY_PATH (rosidl loads the type support from there) and the package on PYTHONPATH:

    .venv/bin/python -m pip install --no-deps --prefix /tmp/actdeps ros-test-msgs==2.3.0
    .venv/bin/python scripts/action_faults.py --deps /tmp/actdeps --out FILE.yaml
"""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import replace
from importlib.metadata import distributions, version
from pathlib import Path

from stack_faults import CONFIG, Fault, run_written, scrub, write_set

PROGRAM = """\
import subprocess
import sys
import time
import rclpy
from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from test_msgs.action import Fibonacci, NestedMessage

mode, role = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else 'all'
TRAJ, GRIP = '/arm_controller/follow_joint_trajectory', '/gripper_controller/gripper_cmd'
SPLIT = {'died': 0.0, 'types': 0.0, 'blocking': 0.0, 'late': 2.5}
ORDER = {'gripper': 3, 'rejected': 150, 'cancel': 40, 'refused': 40, 'blocking': 40}
GRASPS = {0: 'open', 1: 'pinch', 2: 'power'}
NAMES = {'gripper': ('gripper_controller', GRIP),
         'name': ('arm_trajectory_controller', '/arm_trajectory_controller/follow_joint_trajectory')}

class Controller(Node):
    def __init__(self, name, action, kind=Fibonacci):
        super().__init__(name)
        self.active, self.last = None, None
        options = {'cancel': {'cancel_callback': self.cancel}, 'blocking': {'cancel_callback': self.cancel},
                   'expired': {'result_timeout': 1}, 'preempt': {'handle_accepted_callback': self.accepted}}
        if mode == 'invalid':
            action = '/' + self.declare_parameter('arm_id', 'ur5e-left').value + '/follow_joint_trajectory'
        ActionServer(self, kind, action, self.execute, goal_callback=self.check, **options.get(mode, {}))
        self.get_logger().info(f'{action} action server ready')

    def check(self, goal):
        if mode == 'gripper':
            self.get_logger().info(f'{GRASPS[goal.order]} grasp requested')
        if mode == 'bool':
            return goal.order <= 100
        if goal.order > 100:
            self.get_logger().error(f'Trajectory has {goal.order} points, this controller takes at most 100')
            return GoalResponse.REJECT
        return GoalResponse.ACCEPT

    def cancel(self, goal):
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    def accepted(self, goal):
        if self.active is not None and self.active.is_active:
            self.get_logger().info('Aborting previous goal')
            self.active.abort()
        self.active = goal
        goal.execute()

    def read_state(self):
        stamp = round(time.monotonic(), 1)
        if self.last is not None:
            self.velocity = 0.1 / (stamp - self.last)
        self.last = stamp

    def execute(self, goal):
        self.get_logger().info(f'Executing trajectory of {goal.request.order} points')
        if mode == 'device':
            self.port = open(self.declare_parameter('port', '/dev/ttyACM0').value, 'r+b', buffering=0)
        if mode == 'died':
            self.create_timer(0.04, self.read_state)
        feedback = Fibonacci.Feedback(sequence=[0, 1])
        for _ in range(1, goal.request.order):
            if not goal.is_active:
                return Fibonacci.Result()
            if goal.is_cancel_requested:
                goal.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result(sequence=feedback.sequence)
            feedback.sequence.append(feedback.sequence[-2] + feedback.sequence[-1])
            goal.publish_feedback(feedback)
            time.sleep(0.1)
        if mode != 'unset':
            goal.succeed()
        return Fibonacci.Result(sequence=feedback.sequence)

server = None
if role == 'all' and mode in SPLIT:
    server, role = subprocess.Popen([sys.executable, sys.argv[0], mode, 'server']), 'client'
if role == 'server':
    time.sleep(SPLIT[mode])
rclpy.init()
executor = SingleThreadedExecutor() if mode == 'blocking' else MultiThreadedExecutor()
if role != 'client':
    name, action = NAMES.get(mode, ('arm_controller', TRAJ))
    executor.add_node(Controller(name, action, NestedMessage if mode == 'types' else Fibonacci))
    if mode == 'twins':
        executor.add_node(Controller('fake_arm_controller', TRAJ))
if role == 'server':
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    sys.exit(0)

commander = Node('arm_commander')
executor.add_node(commander)
log = commander.get_logger()
client = ActionClient(commander, Fibonacci, GRIP if mode == 'gripper' else TRAJ)

def finish(code):
    if server is not None:
        server.terminate()
        server.wait()
    rclpy.shutdown()
    sys.exit(code)

def spin_for(future, seconds):
    executor.spin_until_future_complete(future, timeout_sec=seconds)
    return future.done()

def on_progress(msg):
    log.info(f'{len(msg.sequence)} points done')

def send(order):
    log.info('Sending goal request...')
    future = client.send_goal_async(Fibonacci.Goal(order=order),
                                    feedback_callback=on_progress if mode == 'feedback' else None)
    if not spin_for(future, 3.0):
        log.error('Goal response not received within 3 s')
        finish(1)
    handle = future.result()
    if mode == 'rejected':
        return handle
    if not handle.accepted:
        log.error('Goal was rejected by server')
        finish(1)
    log.info('Goal accepted')
    return handle

log.info('Waiting for action server...')
tries = 5 if mode == 'late' else 1
while not client.wait_for_server(timeout_sec=1.0 if mode == 'late' else 2.0):
    tries -= 1
    if not tries:
        log.error(f'Action server {client._action_name} not available after waiting')
        finish(1)
    log.warning('Action server not available, waiting again...')
handles = [send(ORDER.get(mode, 20))]
if mode == 'preempt':
    spin_for(Future(), 0.5)
    handles.append(send(20))
if mode in ('cancel', 'refused', 'blocking'):
    spin_for(Future(), 0.5)
    log.info('Canceling goal')
    canceling = handles[0].cancel_goal_async()
    if not spin_for(canceling, 2.0):
        log.error('Cancel request not answered within 2 s')
    elif canceling.result().goals_canceling:
        log.info('Goal successfully canceled')
    else:
        log.error('Goal failed to cancel')
if mode == 'expired':
    log.info('Waiting for the motion to finish')
    spin_for(Future(), 4.0)
for handle in handles:
    answer = handle.get_result_async()
    if not spin_for(answer, 6.0):
        log.error('Result not received within 6 s')
        finish(1)
    status, code = answer.result().status, 1
    if status == GoalStatus.STATUS_SUCCEEDED:
        log.info(f'Goal succeeded, {len(answer.result().result.sequence)} points')
        code = 0
    elif status == GoalStatus.STATUS_ABORTED:
        log.error('Goal was aborted')
    elif status == GoalStatus.STATUS_CANCELED:
        log.warning('Goal was canceled')
        code = 0
    else:
        log.error(f'Goal finished with unknown result code {status}')
finish(code)
"""

DIED, FAILED = "bringup.process_died", "manipulation.execution_failed"
FAULTS = (
    Fault("action-execute-serial-port-missing", "control", "control.hardware_failure",
          "The arm controller's execute callback opens the arm's serial port /dev/ttyACM0, which is not there (the "
          "arm's USB cable is unplugged), so every trajectory goal is aborted.", ("device",)),
    Fault("action-goal-callback-raises", "bringup", DIED,
          "The gripper controller's goal callback looks the requested grasp (3) up in its table of grasps, which has "
          "only 0-2, raises KeyError, and the process ends.", ("gripper",)),
    Fault("action-goal-rejected-client-goes-on", "manipulation", FAILED,
          "The arm controller rejects the 150-point trajectory (it takes at most 100), and the commander, which never "
          "checks whether its goal was accepted, asks for the result of the rejected goal.", ("rejected",)),
    Fault("action-goal-callback-returns-bool", "manipulation", FAILED,
          "The arm controller's goal callback returns a bool (True) instead of a GoalResponse, so rclpy rejects every "
          "goal and the commander's trajectory is never executed.", ("bool",)),
    Fault("action-name-mismatch", "manipulation", "manipulation.controllers_not_found",
          "The commander sends its trajectories to /arm_controller/follow_joint_trajectory, but the controller was "
          "renamed arm_trajectory_controller and serves /arm_trajectory_controller/follow_joint_trajectory, so the "
          "commander finds no controller.", ("name",)),
    Fault("action-server-died-mid-goal", "bringup", DIED,
          "The arm controller's state timer, started with the motion, divides by the time between two device "
          "stamps, which is zero (the stamps tick at 10 Hz), raises mid-goal, and the controller's process ends, so "
          "the commander never gets a result.", ("died",)),
    Fault("action-cancel-refused", "control", "control.configuration_error",
          "The arm controller registers no cancel callback, so rclpy's default refuses every cancel, and the "
          "operator's stop is refused while the arm keeps moving to the end of its trajectory.", ("refused",)),
    Fault("action-result-expired", "control", "control.configuration_error",
          "The arm controller keeps a finished goal's result for 1 s only (result_timeout=1), and the commander asks "
          "for the result 4 s after sending the 2 s motion, so the result is gone.", ("expired",)),
    Fault("action-two-types-one-name", "control", CONFIG,
          "The arm controller serves /arm_controller/follow_joint_trajectory with test_msgs' NestedMessage action "
          "while the commander uses Fibonacci on the same name, so the two never match.", ("types",)),
    Fault("action-two-servers-one-name", "control", CONFIG,
          "A fake arm controller left in the launch from the simulation serves the same action name as the real arm "
          "controller, so both answer every goal.", ("twins",)),
    Fault("action-name-invalid", "control", CONFIG,
          "The action name is built from the arm_id parameter 'ur5e-left', whose dash is not allowed in a ROS name, "
          "so the controller dies creating its action server.", ("invalid",)),
    Fault("action-execute-no-terminal-state", "manipulation", FAILED,
          "The arm controller's execute callback returns its result without calling succeed() on the goal, so rclpy "
          "aborts the goal and the commander's trajectory fails.", ("unset",)),
    Fault("action-execute-blocks-cancel", "control", "control.configuration_error",
          "The arm controller spins a single-threaded executor and its execute callback sleeps in a loop until the "
          "motion ends, so the operator's cancel is not handled until the trajectory is over.", ("blocking",)),
    Fault("action-feedback-callback-raises", "bringup", DIED,
          "The commander's feedback callback reads msg.sequence where the feedback message has it under "
          "msg.feedback.sequence, which raises AttributeError on the first feedback, and the process ends.",
          ("feedback",)),
    Fault("action-goal-preempted", "control", "control.nominal",
          "The commander sent a new trajectory half a second into the first; the controller aborts the older goal "
          "for the newer one by design, and the newer one succeeds.", ("preempt",), outcome="succeeded"),
    Fault("action-goal-canceled-on-purpose", "control", "control.nominal",
          "The commander cancels the arm's motion on purpose half a second in (the task no longer needs it); the "
          "controller accepts the cancel and reports the goal canceled.", ("cancel",), outcome="succeeded"),
    Fault("action-server-started-late", "manipulation", "manipulation.nominal",
          "The arm controller comes up 2.5 s after the commander, which waits for it again each second and then sends "
          "its trajectory, which succeeds.", ("late",), outcome="succeeded"),
)
# Read after the run, as a collector reads a thread: what the lines of these faults do not show
SILENT = {"action-two-types-one-name": "The lines show a server of that very name ready and the commander not finding "
                                        "it; nothing printed says that the two ends use different action types.",
          "action-execute-blocks-cancel": "Only the commander's own timeout shows: nothing printed says the "
                                          "controller's executor was held by its execute callback."}
TYPES = "The action is test_msgs' Fibonacci under an arm controller's name, not control_msgs' FollowJointTrajectory."
HEADER = """\
# Held-out set 27 of real console excerpts (issue 23's format): printed by the real ROS 2 stack installed on this
# project's machine (ROS 2 Kilted's rclpy {rclpy}, rcl_action {rcl_action} and Fast DDS {fastdds} from PyPI, with
# test_msgs {test_msgs}'s action types), each run with one fault of an action's goal, feedback or result: written by
# scripts/action_faults.py, which states each excerpt's cause (the fault) before it runs anything. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by /opt/venv/... and /home/robot/ws. Frozen and
# measured once before anything was tuned on it. Regenerate with (DIR: see the script's docstring):
# .venv/bin/python scripts/action_faults.py --deps DIR --out FILE
"""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--deps", type=Path, required=True, help="the --prefix ros-test-msgs was installed in")
    args = parser.parse_args()
    deps = args.deps.resolve()
    site = deps / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"
    paths = {"PYTHONPATH": str(site), "LD_LIBRARY_PATH": str(deps / "lib")}
    env = {k: os.pathsep.join(filter(None, (v, os.environ.get(k)))) for k, v in paths.items()}

    def run_one(fault: Fault, work: Path) -> tuple[str, int]:
        text, code = run_written(replace(fault, env={**fault.env, **env}), work, {"actions": PROGRAM},
                                 {"actions": "arm_actions.py"})
        text = text.replace(str(site), "/opt/venv/lib/python3/site-packages").replace(str(deps), "/opt/venv")
        return scrub(text, work), code

    found = {"rclpy": version("ros-kilted-rclpy"), "rcl_action": version("ros-rcl-action"),
             "fastdds": version("ros-fastdds"),
             "test_msgs": next(iter(distributions(name="ros-test-msgs", path=[str(site)]))).version}
    stack = "rclpy {rclpy}, rcl_action {rcl_action}, Fast DDS {fastdds}, test_msgs {test_msgs}".format(**found)
    faults = [replace(fault, program="actions") for fault in FAULTS]
    write_set(args.out, HEADER.format(**found), "action_faults.py", stack, faults, run_one, SILENT,
              {fault.id: TYPES for fault in faults})
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
