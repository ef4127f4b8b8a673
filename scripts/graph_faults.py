"""Real console output of the ROS 2 stack installed here (ROS 2 Kilted's rclpy, rcl, rcl_yaml_param_parser and Fast
DDS from PyPI), each run with one fault of a running graph's parameters, services, node names or time: a params file
indented with a tab, a params file written for another node name, a parameter outside the range the node declares,
a typed parameter nobody set, a parameter read before it was declared or declared twice, two nodes with one name, a
service client looking in the wrong namespace, a service callback that raises, one service name with two types, a
service name built with a doubled slash, use_sim_time with no /clock, a node's ROS time subtracted from the system
clock, a subscription callback that raises inside a MultiThreadedExecutor.

The fourth set beside scripts/stack_faults.py (held-out set 22), scripts/runtime_faults.py (23) and
scripts/settings_faults.py (24), written the same way: every fault is run for real, the output kept as printed less
ANSI colours and with this machine's folders replaced by fixed names, and each excerpt's cause is the fault injected,
written here before the set was run. The faults were picked after trying which of them this stack can show (the PyPI
wheels have no action types, so no action faults); what they print was not chosen.

    .venv/bin/python scripts/graph_faults.py --out FILE.yaml
"""

from __future__ import annotations

from stack_faults import CONFIG, NODE, Fault, generate

PARAMS = """\
import sys
import rclpy
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from rclpy.node import Node
from rclpy.parameter import Parameter

rclpy.init(args=sys.argv)
node = Node('scan_filter')
mode = sys.argv[1]
if mode == 'range':
    rate = ParameterDescriptor(description='scan rate in Hz',
                               integer_range=[IntegerRange(from_value=1, to_value=40, step=1)])
    node.declare_parameter('scan_rate', 10, rate)
elif mode == 'typed':
    node.declare_parameter('scan_rate', 10)
    node.declare_parameter('frame_id', Parameter.Type.STRING)
    node.get_logger().info(f"scans in frame {node.get_parameter('frame_id').value}")
else:
    node.declare_parameter('scan_rate', 10)
node.get_logger().info(f"filtering scans at {node.get_parameter('scan_rate').value} Hz")
if mode == 'undeclared':
    node.get_logger().info(f"dropping ranges past {node.get_parameter('max_range').value} m")
if mode == 'redeclared':
    node.declare_parameter('scan_rate', 20)
rclpy.spin_once(node, timeout_sec=0.2)
node.destroy_node()
rclpy.shutdown()
"""

CAMERAS = """\
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

rclpy.init()
front = Node('camera_driver')
front.get_logger().info('streaming /dev/video0 at 30 fps')
rear = Node('camera_driver')
rear.get_logger().info('streaming /dev/video2 at 30 fps')
executor = SingleThreadedExecutor()
executor.add_node(front)
executor.add_node(rear)
executor.spin_once(timeout_sec=0.2)
rclpy.shutdown()
"""

SERVICES = """\
import sys
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from nav_msgs.srv import GetMap, LoadMap

rclpy.init()
mode = sys.argv[1]
server = Node('map_server', namespace='/robot1' if mode == 'namespace' else '')
loader = Node('map_loader')
executor = SingleThreadedExecutor()
executor.add_node(server)
executor.add_node(loader)
MAPS = {'warehouse': 'maps/warehouse.yaml'}


def load(request, response):
    server.get_logger().info(f'loading map {request.map_url}')
    server.get_logger().info(f'map file {MAPS[request.map_url]}')
    response.result = LoadMap.Response.RESULT_SUCCESS
    return response


if mode == 'slash':
    prefix = server.declare_parameter('robot_namespace', '/robot1/').value
    server.create_service(LoadMap, f'{prefix}/load_map', load)
elif mode == 'two-types':
    server.create_service(GetMap, 'map_server/load_map', lambda request, response: response)
else:
    server.create_service(LoadMap, '~/load_map', load)
server.get_logger().info('map server ready')
client = loader.create_client(LoadMap, '/map_server/load_map')
for _ in range(3):
    if client.wait_for_service(timeout_sec=1.0):
        break
    loader.get_logger().info('service not available, waiting again...')
else:
    loader.get_logger().error('/map_server/load_map never came up, giving up')
    sys.exit(1)
future = client.call_async(LoadMap.Request(map_url='office'))
executor.spin_until_future_complete(future, timeout_sec=3.0)
loader.get_logger().info(f'map loaded, result {future.result().result}')
rclpy.shutdown()
"""

CLOCKS = """\
import sys
import time
import rclpy
from rclpy.clock import Clock
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from nav_msgs.msg import Odometry

rclpy.init(args=sys.argv)
driver, window = Node('base_driver'), Node('odom_window')
span = window.declare_parameter('window', 2.0).value
pub = driver.create_publisher(Odometry, 'odom', 10)
started = Clock().now()


def publish() -> None:
    msg = Odometry()
    msg.header.stamp = driver.get_clock().now().to_msg()
    msg.header.frame_id = 'odom'
    pub.publish(msg)


def received(msg: Odometry) -> None:
    if sys.argv[1] == 'sim':
        since = window.get_clock().now() - Duration(seconds=span)
        window.get_logger().info(f'averaging odometry since {since.nanoseconds / 1e9:.2f}')
    else:
        elapsed = window.get_clock().now() - started
        window.get_logger().info(f'odometry after {elapsed.nanoseconds / 1e9:.2f} s')


driver.create_timer(0.05, publish)
window.create_subscription(Odometry, 'odom', received, 10)
window.get_logger().info(f'averaging odometry over {span} s')
executor = SingleThreadedExecutor()
executor.add_node(driver)
executor.add_node(window)
end = time.monotonic() + 2.0
while time.monotonic() < end:
    executor.spin_once(timeout_sec=0.1)
rclpy.shutdown()
"""

EKF = """\
import time
import rclpy
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from nav_msgs.msg import Odometry

rclpy.init()
driver, ekf = Node('base_driver'), Node('ekf_filter')
pub = driver.create_publisher(Odometry, 'odom', 10)


def fuse(msg: Odometry) -> None:
    weight = 1.0 / float(msg.pose.covariance[0])
    ekf.get_logger().debug(f'odometry weight {weight:.3f}')


ekf.create_subscription(Odometry, 'odom', fuse, 10)
driver.create_timer(0.05, lambda: pub.publish(Odometry()))
ekf.get_logger().info('fusing odom with a multi-threaded executor')
executor = MultiThreadedExecutor(num_threads=4)
executor.add_node(driver)
executor.add_node(ekf)
end = time.monotonic() + 2.0
while time.monotonic() < end:
    executor.spin_once(timeout_sec=0.1)
rclpy.shutdown()
"""

PROGRAMS = {"node": NODE, "params": PARAMS, "cameras": CAMERAS, "services": SERVICES, "clocks": CLOCKS, "ekf": EKF}
# none of them named after a package (launch, rclpy, time, ...): the script's folder comes first on sys.path
SCRIPTS = {"node": "scan_filter.py", "params": "scan_filter_params.py", "cameras": "camera_container.py",
           "services": "map_services.py", "clocks": "odom_window.py", "ekf": "ekf_filter.py"}
TAB = "scan_filter:\n  ros__parameters:\n    scan_rate: 5\n\tmax_range: 8.0\n"
OTHER_NAME = "scan_filter_node:\n  ros__parameters:\n    scan_rate: 5\n"
OUT_OF_RANGE = "scan_filter:\n  ros__parameters:\n    scan_rate: 100\n"
SIM_TIME = "odom_window:\n  ros__parameters:\n    use_sim_time: true\n    window: 2.0\n"
FILE = ("--ros-args", "--params-file", "scan_filter.yaml")
DIED = "bringup.process_died"
FAULTS = (
    Fault("params-file-tab-indent", "bringup", CONFIG,
          "The params file indents one parameter with a tab, which YAML does not allow, so rcl cannot parse it.",
          FILE, files={"scan_filter.yaml": TAB}),
    Fault("params-file-other-node-name", "bringup", CONFIG,
          "The params file is written for the node's old name (scan_filter_node), so none of its values reach "
          "the node, which runs with its defaults.", FILE, files={"scan_filter.yaml": OTHER_NAME}),
    Fault("parameter-out-of-declared-range", "bringup", CONFIG,
          "The params file sets scan_rate to 100, outside the range 1-40 that the node declares, so the node "
          "refuses it and does not start.", ("range", *FILE), files={"scan_filter.yaml": OUT_OF_RANGE},
          program="params"),
    Fault("typed-parameter-never-set", "bringup", CONFIG,
          "The node declares frame_id with a type and no default, and it was started without the params file "
          "that sets it, so reading it raises.", ("typed",), program="params"),
    Fault("parameter-read-undeclared", "bringup", DIED,
          "The node reads a parameter (max_range) that its code never declared, which raises, and the process "
          "ends.", ("undeclared",), program="params"),
    Fault("parameter-declared-twice", "bringup", DIED,
          "The node's code declares scan_rate a second time, which raises, and the process ends.",
          ("redeclared",), program="params"),
    Fault("two-nodes-one-name", "bringup", CONFIG,
          "Two camera drivers are started in one process with the same node name (camera_driver); the rear one "
          "was meant to be named rear_camera.", program="cameras"),
    Fault("service-client-wrong-namespace", "bringup", CONFIG,
          "The map server runs in the namespace /robot1, but the map loader calls /map_server/load_map without "
          "it, so it never finds the service and gives up.", ("namespace",), program="services"),
    Fault("service-callback-raises", "bringup", DIED,
          "The map server's load_map callback looks up a map name it does not know ('office') in its table, "
          "which raises KeyError, and the process ends.", ("raises",), program="services"),
    Fault("service-two-types-one-name", "bringup", CONFIG,
          "Two nodes in one process use the service map_server/load_map with different types (the server offers "
          "GetMap, the client was built for LoadMap), so the client is not created and the process dies.",
          ("two-types",), program="services"),
    Fault("service-name-doubled-slash", "bringup", CONFIG,
          "The robot_namespace parameter ends with a slash ('/robot1/'), and the service name built from it has "
          "'//' in it, which is not a valid name, so the map server dies creating its service.",
          ("slash",), program="services"),
    Fault("use-sim-time-without-clock", "bringup", CONFIG,
          "The params file (copied from the simulation) sets use_sim_time true on the robot, where nothing "
          "publishes /clock, so the node's time stays 0 and going back its 2 s window raises.",
          ("sim", "--ros-args", "--params-file", "odom_window.yaml"), files={"odom_window.yaml": SIM_TIME},
          program="clocks"),
    Fault("ros-time-minus-system-time", "bringup", DIED,
          "The node subtracts a start time taken from a system clock (rclpy.clock.Clock()) from its own ROS "
          "time, which raises, and the process ends.", ("mixed",), program="clocks"),
    Fault("multithreaded-callback-raises", "bringup", DIED,
          "The EKF's odometry callback, run by a MultiThreadedExecutor, divides by a zero covariance and raises, "
          "and the executor ends the process.", program="ekf"),
)
# Read after the run, as a collector reads a thread: what the lines of these faults do not show
SILENT = {"params-file-other-node-name": "Nothing was printed of the params file: the node started with its default "
                                          "scan_rate, which is all its one line shows.",
          "use-sim-time-without-clock": "The lines show the node's time going negative 2 s back, not use_sim_time or "
                                        "the missing /clock."}
HEADER = """\
# Held-out set 25 of real console excerpts (issue 23's format): printed by the real ROS 2 stack installed on this
# project's machine (ROS 2 Kilted's rclpy, rcl, rcl_yaml_param_parser and Fast DDS from PyPI), each run with one fault
# of a running graph's parameters, services, node names or time: written by scripts/graph_faults.py, which states
# each excerpt's cause (the fault) before it runs anything. Output is kept as printed, less ANSI colours, with this
# machine's folders replaced by /opt/venv/... and /home/robot/ws. Frozen and measured once before anything was tuned
# on it. Regenerate with: .venv/bin/python scripts/graph_faults.py --out FILE
"""


def main() -> int:
    return generate(__doc__, HEADER, "graph_faults.py", FAULTS, PROGRAMS, SCRIPTS, SILENT)


if __name__ == "__main__":
    raise SystemExit(main())
