"""The world of scripts/nav2_faults.py: a small two-room map, a differential base that drives on it and a goal sender.

The base is a ROS 2 program (rclpy) that does what a robot's driver and a laser do for Nav2: it integrates the
velocity commands it receives, publishes odometry and the odom -> base_link transform at 20 Hz, a 360-beam laser
scan at 10 Hz ray-cast on the map (and on boxes that appear once the robot has driven past a given x, seen by the
laser only, as an object put in its way), and, as a localisation that is always right, map -> odom as a static
transform. Where a run has a charging dock, it also does what a dock's detector and a battery's driver do: the dock's
pose as seen from the robot (detected_dock_pose) while the dock is in front of it, and the battery's state, charging
while the robot stands on the dock. It prints one line when it is up, as a driver does. The goal sender is a separate
program, as RViz's "Nav2 Goal" is: its output is not part of the console, only its result (written as JSON) is read.
"""

from __future__ import annotations

from pathlib import Path

from launch_runs import HIT

RESOLUTION = 0.05  # m per cell
WIDTH_M, HEIGHT_M = 12.0, 8.0
WALL_X = 6.0  # the wall between the two rooms, x from WALL_X to WALL_X + WALL_T
WALL_T = 0.2
DOOR = (3.5, 4.5)  # the doorway's y span in that wall: the only way between the rooms


def write_map(folder: Path) -> Path:
    """The map as map_server reads it (a PGM and its YAML): outer walls, and one inner wall with a 1 m doorway."""
    cols, rows = round(WIDTH_M / RESOLUTION), round(HEIGHT_M / RESOLUTION)
    grid = [[254] * cols for _ in range(rows)]  # free
    wall = round(WALL_T / RESOLUTION)
    for r in range(rows):
        for c in range(cols):
            x, y = (c + 0.5) * RESOLUTION, (r + 0.5) * RESOLUTION
            outer = c < wall or c >= cols - wall or r < wall or r >= rows - wall
            inner = WALL_X <= x < WALL_X + WALL_T and not DOOR[0] <= y < DOOR[1]
            if outer or inner:
                grid[r][c] = 0
    folder.mkdir(parents=True, exist_ok=True)
    pgm = folder / "two_rooms.pgm"
    # PGM rows run from the top of the image, which is the map's largest y
    pgm.write_bytes(f"P5\n{cols} {rows}\n255\n".encode() + bytes(v for row in reversed(grid) for v in row))
    yaml = folder / "two_rooms.yaml"
    yaml.write_text(f"image: two_rooms.pgm\nmode: trinary\nresolution: {RESOLUTION}\norigin: [0.0, 0.0, 0.0]\n"
                    "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n", encoding="utf-8")
    return yaml


BASE = """\
import math
import sys
import numpy as np
import rclpy
from geometry_msgs.msg import PoseStamped, TransformStamped, Twist, TwistStamped
from nav_msgs.msg import Odometry
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile
from sensor_msgs.msg import BatteryState, LaserScan
from tf2_msgs.msg import TFMessage

BEAMS, RANGE_MIN, RANGE_MAX, STEP = 360, 0.12, 8.0, 0.025


def load_pgm(path):
    data = open(path, 'rb').read()
    parts = data.split(maxsplit=4)
    cols, rows = int(parts[1]), int(parts[2])
    pixels = np.frombuffer(parts[4][-cols * rows:], dtype=np.uint8).reshape(rows, cols)
    return pixels[::-1] < 128  # occupied, row 0 at y = 0


class Base(Node):
    def __init__(self):
        super().__init__('base_driver')
        value = lambda name, default: self.declare_parameter(name, default).value
        self.x, self.y, self.yaw = value('x', 2.0), value('y', 4.0), value('yaw', 0.0)
        self.scale = value('speed_scale', 1.0)
        self.scan_frame = value('scan_frame', 'base_scan')  # the frame the laser stamps its scans with
        self.tf_until_m = value('tf_stop_after_m', 0.0)  # odom -> base_link stops once it drove this far (0: never)
        self.odom_tf = value('publish_odom_tf', True)  # false where a filter (robot_localization) publishes it
        self.start_xy = (self.x, self.y)
        self.occupied = load_pgm(value('map_image', 'two_rooms.pgm'))
        self.resolution = value('resolution', 0.05)
        self.boxes = [tuple(b) for b in np.reshape(value('boxes', [0.0] * 5), (-1, 5)) if b[1] != b[3]]
        self.put = set()
        self.v = self.w = 0.0
        self.last_cmd = self.get_clock().now()
        topic, stamped = value('cmd_vel_topic', 'cmd_vel'), value('stamped', True)
        self.create_subscription(TwistStamped if stamped else Twist, topic, self.on_cmd, 10)
        self.odom = self.create_publisher(Odometry, 'odom', 10)
        self.scan = self.create_publisher(LaserScan, 'scan', 10)
        self.tf = self.create_publisher(TFMessage, '/tf', 100)
        static = self.create_publisher(TFMessage, '/tf_static',
                                       QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        now = self.get_clock().now().to_msg()
        fixed = [self.transform(now, 'base_link', 'base_scan', 0.0, 0.0, 0.0)]
        if value('publish_map_odom', True):
            fixed.append(self.transform(now, 'map', 'odom', 0.0, 0.0, 0.0))
        static.publish(TFMessage(transforms=fixed))
        self.create_timer(0.05, self.step)
        self.create_timer(0.1, self.publish_scan)
        self.dock = value('dock', [0.0, 0.0, 0.0])  # the charging dock: x, y, and the robot's yaw on it
        self.dock_frame = value('dock_frame', 'base_link')  # the frame the detector stamps its poses with
        if value('detector', False):
            self.detected = self.create_publisher(PoseStamped, 'detected_dock_pose', 10)
            self.create_timer(0.1, self.publish_detection)
        if value('battery', False):
            self.battery = self.create_publisher(BatteryState, 'battery_state', 10)
            self.create_timer(0.5, self.publish_battery)
        self.get_logger().info(f'base up at ({self.x:.2f}, {self.y:.2f}), listening on {topic}')

    def transform(self, stamp, parent, child, x, y, yaw):
        t = TransformStamped()
        t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, parent, child
        t.transform.translation.x, t.transform.translation.y = x, y
        t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        return t

    def on_cmd(self, msg):
        twist = msg.twist if hasattr(msg, 'twist') else msg
        self.v, self.w = twist.linear.x * self.scale, twist.angular.z * self.scale
        self.last_cmd = self.get_clock().now()

    def step(self):
        now = self.get_clock().now()
        if (now - self.last_cmd).nanoseconds > 500_000_000:
            self.v = self.w = 0.0
        self.yaw += self.w * 0.05
        self.x += self.v * math.cos(self.yaw) * 0.05
        self.y += self.v * math.sin(self.yaw) * 0.05
        stamp = now.to_msg()
        odom = Odometry()
        odom.header.stamp, odom.header.frame_id, odom.child_frame_id = stamp, 'odom', 'base_link'
        odom.pose.pose.position.x, odom.pose.pose.position.y = self.x, self.y
        odom.pose.pose.orientation.z, odom.pose.pose.orientation.w = math.sin(self.yaw / 2), math.cos(self.yaw / 2)
        odom.twist.twist.linear.x, odom.twist.twist.angular.z = self.v, self.w
        self.odom.publish(odom)
        far = self.tf_until_m and math.dist(self.start_xy, (self.x, self.y)) >= self.tf_until_m
        if self.odom_tf and not far:
            self.tf.publish(TFMessage(transforms=[self.transform(stamp, 'odom', 'base_link', self.x, self.y,
                                                                 self.yaw)]))

    def publish_scan(self):
        now = self.get_clock().now()
        angles = self.yaw - math.pi + np.arange(BEAMS) * (2 * math.pi / BEAMS)
        dist = np.arange(RANGE_MIN, RANGE_MAX, STEP)
        px = self.x + np.outer(np.cos(angles), dist)
        py = self.y + np.outer(np.sin(angles), dist)
        rows, cols = self.occupied.shape
        c = np.clip((px / self.resolution).astype(int), 0, cols - 1)
        r = np.clip((py / self.resolution).astype(int), 0, rows - 1)
        outside = (px < 0) | (py < 0) | (px >= cols * self.resolution) | (py >= rows * self.resolution)
        hit = self.occupied[r, c] & ~outside
        for box in self.boxes:
            if self.x >= box[0]:  # once the robot got this far the box is there, and stays
                self.put.add(box)
        for _, x0, y0, x1, y1 in self.put:
            hit |= (px >= x0) & (px <= x1) & (py >= y0) & (py <= y1)
        first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
        ranges = np.where(first >= 0, dist[np.maximum(first, 0)], math.inf)
        scan = LaserScan()
        scan.header.stamp, scan.header.frame_id = now.to_msg(), self.scan_frame
        scan.angle_min, scan.angle_max = -math.pi, math.pi - 2 * math.pi / BEAMS
        scan.angle_increment = 2 * math.pi / BEAMS
        scan.scan_time, scan.range_min, scan.range_max = 0.1, RANGE_MIN, RANGE_MAX
        scan.ranges = [float(v) for v in ranges]
        self.scan.publish(scan)

    def publish_detection(self):
        # a camera looking ahead sees the dock within 2.5 m and 60 degrees of its heading, or right at it when docked
        dx, dy = self.dock[0] - self.x, self.dock[1] - self.y
        dist = math.hypot(dx, dy)
        bearing = math.atan2(math.sin(math.atan2(dy, dx) - self.yaw), math.cos(math.atan2(dy, dx) - self.yaw))
        if dist > 0.3 and (dist > 2.5 or abs(bearing) > math.radians(60)):
            return
        pose = PoseStamped()
        pose.header.stamp, pose.header.frame_id = self.get_clock().now().to_msg(), self.dock_frame
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        pose.pose.position.x, pose.pose.position.y = c * dx + s * dy, -s * dx + c * dy
        rel = self.dock[2] - self.yaw
        pose.pose.orientation.z, pose.pose.orientation.w = math.sin(rel / 2), math.cos(rel / 2)
        self.detected.publish(pose)

    def publish_battery(self):
        state = BatteryState()
        state.header.stamp = self.get_clock().now().to_msg()
        docked = math.dist((self.x, self.y), self.dock[:2]) < 0.1
        state.voltage, state.percentage, state.present = 24.0, 0.4, True
        state.current = 1.5 if docked else -0.8  # charging on the dock's contacts, draining off them
        self.battery.publish(state)


rclpy.init(args=sys.argv)
node = Base()
try:
    rclpy.spin(node)
except (KeyboardInterrupt, ExternalShutdownException):
    pass
"""

# the goal senders' connection to their action and their wait, as a person waits for Nav2 to come up before
# clicking a goal in RViz: until the lifecycle manager says its nodes are active, or the deadline
WAIT_ACTIVE = """\
def wait_active(node, deadline, result):
    import time
    import rclpy
    from std_srvs.srv import Trigger
    active = node.create_client(Trigger, 'lifecycle_manager_navigation/is_active')
    while time.monotonic() < deadline and not result['active']:
        if active.wait_for_service(timeout_sec=1.0):
            future = active.call_async(Trigger.Request())
            rclpy.spin_until_future_complete(node, future, timeout_sec=2.0)
            result['active'] = bool(future.result() and future.result().success)
        if not result['active']:
            time.sleep(1.0)


def connect(node, action, name, wait_s):
    # the action's client once its server is there and the stack is active (wait_s at most): the client, and the
    # result the sender fills in
    import time
    from rclpy.action import ActionClient
    result = {'server': False, 'active': False, 'accepted': False, 'status': None, 'seconds': None}
    deadline = time.monotonic() + wait_s
    client = ActionClient(node, action, name)
    result['server'] = client.wait_for_server(timeout_sec=wait_s)
    wait_active(node, deadline, result)
    return client, result


"""

GOAL = HIT + WAIT_ACTIVE + """\
import json
import sys
import rclpy
from nav2_msgs.action import NavigateToPose
from rclpy.node import Node

x, y, wait_s, run_s, out = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
hit = sys.argv[6:9]  # NODE SIGNAL SECONDS: something outside the stack does that to a node's process on the way
rclpy.init()
node = Node('goal_sender')
client, result = connect(node, NavigateToPose, 'navigate_to_pose', wait_s)
if result['server']:
    goal = NavigateToPose.Goal()
    goal.pose.header.frame_id = 'map'
    goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
    goal.pose.pose.orientation.w = 1.0
    done = send_goal(node, client, goal, hit, f'__node:={hit[0]} ' if hit else '', run_s, result)
    if done is not None:
        result['status'] = done.result().status
json.dump(result, open(out, 'w'))
"""

def write_mask(folder: Path, zones: list[tuple[float, float, float, float]], name: str = "keepout_mask",
               percent: int | None = None) -> Path:
    """A costmap filter mask (a PGM and its YAML) as map_server serves it: a keepout mask as nav2_bringup's keepout
    zones are drawn (trinary like the map), each zone (x0, y0, x1, y1) black and the rest free; or, with `percent`,
    a speed mask as Nav2's speed-limit tutorial draws it (scale mode), each zone the value that a speed filter info
    of base 100 and multiplier -1 reads as that percent of the robot's speed."""
    cols, rows = round(WIDTH_M / RESOLUTION), round(HEIGHT_M / RESOLUTION)
    # scale mode: occupancy (255 - pixel) / 255 as 0..100, so 100 - percent is the pixel's occupancy
    pixel = 0 if percent is None else round(255 - (100 - percent) * 255 / 100)
    grid = [[254 if percent is None else 255] * cols for _ in range(rows)]
    for r in range(rows):
        for c in range(cols):
            x, y = (c + 0.5) * RESOLUTION, (r + 0.5) * RESOLUTION
            if any(x0 <= x < x1 and y0 <= y < y1 for x0, y0, x1, y1 in zones):
                grid[r][c] = pixel
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.pgm").write_bytes(f"P5\n{cols} {rows}\n255\n".encode()
                                         + bytes(v for row in reversed(grid) for v in row))
    yaml = folder / f"{name}.yaml"
    mode = ("mode: trinary\n", "occupied_thresh: 0.65\nfree_thresh: 0.25\n") if percent is None else (
        "mode: scale\n", "occupied_thresh: 1.0\nfree_thresh: 0.0\n")
    yaml.write_text(f"image: {name}.pgm\n{mode[0]}resolution: {RESOLUTION}\norigin: [0.0, 0.0, 0.0]\n"
                    f"negate: 0\n{mode[1]}", encoding="utf-8")
    return yaml


# as a script of nav2_simple_commander's followWaypoints (or, with "through" after its arguments, goThroughPoses) sends
# them: the waypoints, each with its orientation toward the next, in one goal of the waypoint follower (or of
# bt_navigator's NavigateThroughPoses)
WAYPOINTS = HIT + WAIT_ACTIVE + """\
import json
import math
import sys
import rclpy
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import FollowWaypoints, NavigateThroughPoses
from rclpy.node import Node

points = [tuple(map(float, p.split(','))) for p in sys.argv[1].split(';')]
frame, wait_s, run_s, out = sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
through = sys.argv[6:7] == ['through']
rclpy.init()
node = Node('waypoint_sender')
Action = NavigateThroughPoses if through else FollowWaypoints
client, result = connect(node, Action, 'navigate_through_poses' if through else 'follow_waypoints', wait_s)
if result['server']:
    goal = Action.Goal()
    for i, (x, y) in enumerate(points):
        pose = PoseStamped()
        pose.header.frame_id = frame
        pose.pose.position.x, pose.pose.position.y = x, y
        nx, ny = points[i + 1] if i + 1 < len(points) else (x + 1.0, y)
        yaw = math.atan2(ny - y, nx - x)
        pose.pose.orientation.z, pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        (goal.poses.goals if through else goal.poses).append(pose)
    done = send_goal(node, client, goal, [], '', run_s, result)
    if done is not None:
        res = done.result()
        result['status'], result['error_code'] = res.status, res.result.error_code
        result['error_msg'] = res.result.error_msg
        statuses = res.result.waypoint_statuses if through else res.result.missed_waypoints
        result['missed'] = [[w.waypoint_index, w.error_code, w.error_msg] for w in statuses
                            if w.waypoint_status == w.FAILED]
json.dump(result, open(out, 'w'))
"""



# as a script of nav2_simple_commander's dockRobotByID sends it: one DockRobot goal for a dock of the database, the
# robot first driven to the dock's staging pose
DOCK = HIT + WAIT_ACTIVE + """\
import json
import sys
import rclpy
from nav2_msgs.action import DockRobot
from rclpy.node import Node

dock_id, wait_s, run_s, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
rclpy.init()
node = Node('dock_sender')
client, result = connect(node, DockRobot, 'dock_robot', wait_s)
if result['server']:
    goal = DockRobot.Goal()
    goal.use_dock_id, goal.dock_id, goal.navigate_to_staging_pose, goal.max_staging_time = True, dock_id, True, 1000.0
    done = send_goal(node, client, goal, [], '', run_s, result)
    if done is not None:
        res = done.result()
        result['status'], result['success'] = res.status, res.result.success
        result['error_code'], result['error_msg'] = res.result.error_code, res.result.error_msg
        result['num_retries'] = res.result.num_retries
json.dump(result, open(out, 'w'))
"""


# as a script of nav2_simple_commander's spin(), backup(), driveOnHeading() or wait() sends it: one goal of the
# behaviour server's action of that name, the distance (or angle, or seconds), speed and time allowance as given
BEHAVIOR = HIT + WAIT_ACTIVE + """\
import json
import sys
import rclpy
from builtin_interfaces.msg import Duration
from nav2_msgs.action import BackUp, DriveOnHeading, Spin, Wait
from rclpy.node import Node

kind, values, out = sys.argv[1], json.loads(sys.argv[2]), sys.argv[5]
wait_s, run_s = float(sys.argv[3]), float(sys.argv[4])
rclpy.init()
node = Node('behavior_sender')
Action = {'spin': Spin, 'backup': BackUp, 'drive_on_heading': DriveOnHeading, 'wait': Wait}[kind]
client, result = connect(node, Action, kind, wait_s)
if result['server']:
    goal = Action.Goal()
    if kind == 'spin':
        goal.target_yaw = values['angle']
    elif kind == 'wait':
        goal.time = Duration(sec=int(values['seconds']))
    else:
        goal.target.x, goal.speed = values['distance'], values['speed']
    if kind != 'wait':
        goal.time_allowance = Duration(sec=int(values['allowance']))
    done = send_goal(node, client, goal, [], '', run_s, result)
    if done is not None:
        res = done.result()
        result['status'], result['error_code'] = res.status, res.result.error_code
        result['error_msg'] = res.result.error_msg
json.dump(result, open(out, 'w'))
"""
