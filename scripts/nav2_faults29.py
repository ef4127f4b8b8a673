"""The faults of blind Nav2 set 29, run by scripts/nav2_faults.py (`--set 29`): set 20's bring-up, sent one
NavigateToPose goal as a script sends it, with one mistake each in the goal as sent: a frame nothing publishes, no
frame at all, a stamp 30 s old on a goal in the robot's own frame, a behaviour tree file that is not there, a goal
sent as soon as the action server exists instead of once the stack is active; and three runs with nothing wrong (a
goal in the map frame, one 2 m ahead in the robot's own frame, one replaced by a second goal 3 s after it was sent).
Written, with their causes and the labelling rule of nav2_faults.label() (a goal reached is navigation.nominal, the
last goal where a second replaced the first), before any of them was run.
"""

from __future__ import annotations

from launch_runs import HIT
from nav2_faults import CONFIG, NOMINAL, TRANSFORM, Fault
from nav2_world import WAIT_ACTIVE

# as a script sends a NavigateToPose goal with its own header, behaviour tree and timing (argv: the goal as JSON,
# wait_s, run_s, out): "frame", "stamp_age_s" (None: a zero stamp), "behavior_tree", "wait_active" (false: sent as
# soon as the action server exists), "then" ([x, y, after_s]: a second goal that replaces the first)
GOAL_SENT = HIT + WAIT_ACTIVE + """\
import json
import sys
import time
import rclpy
from nav2_msgs.action import NavigateToPose
from rclpy.action import ActionClient
from rclpy.duration import Duration
from rclpy.node import Node

sent, wait_s, run_s, out = json.loads(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
rclpy.init()
node = Node('goal_sender')
if sent.get('wait_active', True):
    client, result = connect(node, NavigateToPose, 'navigate_to_pose', wait_s)
else:
    client = ActionClient(node, NavigateToPose, 'navigate_to_pose')
    result = {'server': client.wait_for_server(timeout_sec=wait_s), 'active': None, 'accepted': False,
              'status': None, 'seconds': None}


def goal_at(x, y):
    goal = NavigateToPose.Goal()
    goal.pose.header.frame_id = sent.get('frame', 'map')
    if sent.get('stamp_age_s') is not None:
        goal.pose.header.stamp = (node.get_clock().now() - Duration(seconds=sent['stamp_age_s'])).to_msg()
    goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
    goal.pose.pose.orientation.w = 1.0
    goal.behavior_tree = sent.get('behavior_tree', '')
    return goal


if result['server']:
    then = sent.get('then')
    if then:
        first = client.send_goal_async(goal_at(sent['x'], sent['y']))
        rclpy.spin_until_future_complete(node, first, timeout_sec=10.0)
        end = time.monotonic() + then[2]
        while time.monotonic() < end:
            rclpy.spin_once(node, timeout_sec=0.1)
        result['first_accepted'] = bool(first.result() and first.result().accepted)
    x, y = (then[0], then[1]) if then else (sent['x'], sent['y'])
    done = send_goal(node, client, goal_at(x, y), [], '', run_s, result)
    if done is not None:
        res = done.result()
        result['status'], result['error_code'] = res.status, res.result.error_code
        result['error_msg'] = res.result.error_msg
json.dump(result, open(out, 'w'))
"""

FAULTS29 = (
    Fault("goal-map-nominal", NOMINAL, "Nothing was wrong: the goal in the other room was given in the map frame.",
          sent={"x": 10.0, "y": 4.0}),
    Fault("goal-base-link-nominal", NOMINAL, "Nothing was wrong: the goal was given 2 m ahead in the robot's own "
          "frame (base_link), which Nav2 transforms into the map frame.", sent={"x": 2.0, "y": 0.0,
                                                                               "frame": "base_link"}),
    Fault("goal-replaced-nominal", NOMINAL, "Nothing was wrong: a goal in the other room was replaced 3 s after it "
          "was sent by a goal in the robot's own room, which was reached.",
          sent={"x": 10.0, "y": 4.0, "then": [4.5, 2.0, 3.0]}),
    Fault("goal-frame-unknown", TRANSFORM, "The goal was given in the frame odom_combined, which nothing publishes.",
          sent={"x": 10.0, "y": 4.0, "frame": "odom_combined"}),
    Fault("goal-frame-empty", TRANSFORM, "The goal's header had no frame_id at all.",
          sent={"x": 10.0, "y": 4.0, "frame": ""}),
    Fault("goal-stamp-old", TRANSFORM, "The goal was given in the robot's own frame (base_link) with a stamp 30 s "
          "old (a pose saved earlier), older than the transforms bt_navigator keeps.",
          sent={"x": 2.0, "y": 0.0, "frame": "base_link", "stamp_age_s": 30.0}),
    Fault("goal-bt-missing", CONFIG, "The goal asked for a behaviour tree file that is not there "
          "(/opt/nav/navigate_custom.xml).", sent={"x": 10.0, "y": 4.0,
                                                    "behavior_tree": "/opt/nav/navigate_custom.xml"}),
    Fault("goal-before-active", CONFIG, "The goal was sent as soon as bt_navigator's action server existed, before "
          "the lifecycle manager had activated the stack.", sent={"x": 10.0, "y": 4.0, "wait_active": False}),
)

HEADER29 = """\
# Blind Nav2 set 29: console output of the real ROS 2 navigation stack (Nav2 {nav2}, built from source on ROS 2
# Kilted's rclpy, rcl and Fast DDS from PyPI), sent one NavigateToPose goal as a script sends it, each run with one
# mistake in the goal as sent and started by the real ros2launch: written by scripts/nav2_faults.py --set 29, whose
# faults (scripts/nav2_faults29.py) and labelling rule were written before any run was made. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by fixed names. Frozen and measured once before
# anything was tuned on it. Regenerate inside a ROS 2 environment with Nav2: python3 scripts/nav2_faults.py --set 29
# --out FILE
"""
