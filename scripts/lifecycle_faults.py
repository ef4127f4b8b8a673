"""Real console output of the ROS 2 stack installed here (ROS 2 Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from
PyPI), each run with one fault of a managed node's lifecycle, an executor, a callback group, a timer or a shutdown,
its transitions driven by a lifecycle manager node through the real /<node>/change_state and /<node>/get_state
services: an on_configure that raises, or cannot open its serial port; a manager naming the wrong node, or a
transition label that does not exist; an on_shutdown that raises; an on_activate waiting on a service its own
single-threaded executor serves; a lifecycle publisher never enabled; a MultiThreadedExecutor of one thread; a client
in its timer's exclusive callback group; a control loop slower than its update_rate; rclpy.shutdown() under a Rate.
Three bring-ups succeed with a warning on the way. Written like scripts/stack_faults.py (set 22) and its successors:
each excerpt's cause is the fault injected, written here before the set was run; output kept as printed.

    .venv/bin/python scripts/lifecycle_faults.py --out /tmp/set29.yaml
"""

from __future__ import annotations

from stack_faults import CONFIG, Fault, generate

BRINGUP = """\
import sys
import threading
import time
import rclpy
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn as Ret
from rclpy.node import Node
MODE = sys.argv[1]
rclpy.init(args=sys.argv)

class BaseDriver(LifecycleNode):
    def __init__(self):
        super().__init__('base_driver')
        self.port = self.declare_parameter('port', '/dev/null').value
        self.wheel_base = self.declare_parameter('wheel_base', '0.42').value
        self.serial, self.activations = None, 0
        self.odom = self.create_lifecycle_publisher(Odometry, 'odom', 10)
        self.get_logger().info('base driver started')
    def on_configure(self, state):
        separation = float(self.wheel_base)
        try:
            self.serial = open(self.port, 'rb')
        except OSError as error:
            self.get_logger().error(f'cannot open serial port: {error}')
            return Ret.ERROR
        self.create_timer(0.1, self.publish)
        self.get_logger().info(f'serial port {self.port} opened, wheel separation {separation} m')
        return Ret.SUCCESS
    def on_activate(self, state):
        self.activations += 1
        if MODE == 'activate-retried' and self.activations == 1:
            self.get_logger().warning('motor board still booting, not ready to drive')
            return Ret.FAILURE
        self.get_logger().info('driving, publishing odometry')
        return Ret.SUCCESS if MODE == 'publisher-never-enabled' else super().on_activate(state)
    def on_deactivate(self, state):
        self.get_logger().info('motors stopped')
        return super().on_deactivate(state)
    def on_cleanup(self, state):
        self.serial.close()
        self.serial = None
        self.get_logger().info('serial port closed')
        return Ret.SUCCESS
    def on_shutdown(self, state):
        self.serial.close()
        self.get_logger().info('base driver shut down')
        return Ret.SUCCESS
    def on_error(self, state):
        self.get_logger().error(f'error while {state.label}, resetting the driver')
        return Ret.SUCCESS
    def publish(self):
        msg = Odometry()
        msg.header.frame_id = 'odom'
        msg.header.stamp = self.get_clock().now().to_msg()
        self.odom.publish(msg)

class BaseController(LifecycleNode):
    def on_activate(self, state):
        client = self.create_client(GetState, '/base_driver/get_state')
        client.wait_for_service(timeout_sec=1.0)
        future = client.call_async(GetState.Request())
        end = time.monotonic() + 3.0
        while not future.done() and time.monotonic() < end:
            time.sleep(0.05)
        if not future.done():
            self.get_logger().error('service call to /base_driver/get_state did not return within 3 s')
            return Ret.FAILURE
        self.get_logger().info(f'base_driver is {future.result().current_state.label}, controller active')
        return super().on_activate(state)

class Monitor(Node):
    def __init__(self):
        super().__init__('odom_monitor')
        self.count, self.seen = 0, None
        self.create_subscription(Odometry, 'odom', self.received, 10)
        self.create_timer(1.0, self.check)
    def received(self, msg):
        self.count += 1
    def check(self):
        if self.count == 0:
            self.get_logger().warning('no odometry on /odom for 1.0 s')
        elif not self.seen:
            self.get_logger().info(f'odometry arriving on /odom ({self.count} messages in 1.0 s)')
        self.seen, self.count = self.count > 0, 0

target = {'wrong-node-name': 'base_controller', 'activate-deadlock': 'base_controller'}.get(MODE, 'base_driver')
steps = [('configure', 1), ('activate', 3)]
if MODE == 'label-misspelt':
    steps = [('configure', 0), ('active', 0)]
if MODE == 'shutdown-raises':
    steps += [('deactivate', 4), ('cleanup', 2), ('shutdown', 5)]
driver_executor = SingleThreadedExecutor()
manager = Node('lifecycle_manager')
manager_executor, log = SingleThreadedExecutor(), manager.get_logger()
manager_executor.add_node(manager)
done, result = threading.Event(), [0]

def call(client, request):
    future = client.call_async(request)
    manager_executor.spin_until_future_complete(future, timeout_sec=5.0)
    if not future.done():
        log.error(f'service call to {client.srv_name} did not return within 5 s')
        return None
    return future.result()

def manage():
    change = manager.create_client(ChangeState, f'/{target}/change_state')
    get = manager.create_client(GetState, f'/{target}/get_state')
    for _ in range(3):
        if change.wait_for_service(timeout_sec=1.0):
            break
        log.info(f'service {change.srv_name} not available, waiting again...')
    else:
        log.error(f'{change.srv_name} never came up, giving up')
        result[0] = 1
        return
    for name, transition_id in steps:
        for attempt in (1, 2):
            label = name if transition_id == 0 else ''
            answer = call(change, ChangeState.Request(transition=Transition(id=transition_id, label=label)))
            state = call(get, GetState.Request())
            state = state.current_state.label if state else 'unknown'
            if answer is not None and answer.success:
                log.info(f'{name} of /{target} succeeded, state {state}')
                break
            if attempt == 1:
                log.warning(f'{name} of /{target} failed (state {state}), retrying in 1 s')
                time.sleep(1.0)
            else:
                log.error(f'{name} of /{target} failed twice, state {state}; giving up')
                result[0] = 1
                return
        if MODE in ('monitor', 'publisher-never-enabled') and name == 'configure':
            time.sleep(2.5)
    time.sleep(1.5)
    log.info(f'bring-up of /{target} done')

def add_nodes():
    if MODE == 'late-driver':
        time.sleep(2.5)
    driver_executor.add_node(BaseDriver())
    if MODE == 'activate-deadlock':
        driver_executor.add_node(BaseController('base_controller'))
    if MODE in ('monitor', 'publisher-never-enabled'):
        driver_executor.add_node(Monitor())

threading.Thread(target=add_nodes, daemon=True).start()
threading.Thread(target=lambda: (manage(), done.set()), daemon=True).start()
while not done.is_set():
    driver_executor.spin_once(timeout_sec=0.1)
rclpy.shutdown()
sys.exit(result[0])
"""

CONTROL = """\
import sys
import threading
import time
import rclpy
from geometry_msgs.msg import Twist
from lifecycle_msgs.srv import GetState
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.lifecycle import LifecycleNode
from rclpy.node import Node
MODE = sys.argv[1]
rclpy.init(args=sys.argv)
driver = LifecycleNode('base_driver')
controller = Node('base_controller')
log = controller.get_logger()
finished, failed = threading.Event(), []

if MODE == 'rate-after-shutdown':
    cmd = controller.create_publisher(Twist, 'cmd_vel', 10)
    threading.Thread(target=rclpy.spin, args=(controller,), daemon=True).start()
    def estop():
        log.warning('e-stop pressed, stopping the base')
        rclpy.shutdown()
    threading.Timer(1.0, estop).start()
    rate = controller.create_rate(20)
    log.info('sending velocity commands at 20 Hz')
    while True:
        cmd.publish(Twist())
        rate.sleep()

if MODE == 'control-loop-overrun':
    update_rate = controller.declare_parameter('update_rate', 100).value
    stamps = []
    def update():
        stamps.append(time.monotonic())
        time.sleep(0.025)  # one round trip to the motor board: read encoders, write wheel speeds
    def report():
        count = sum(1 for s in stamps if s > time.monotonic() - 1.0)
        if count < update_rate * 0.9:
            log.warning(f'control loop missed its rate: {count} updates in 1.0 s, update_rate {update_rate} Hz')
    controller.create_timer(1.0 / update_rate, update)
    controller.create_timer(1.0, report)
    log.info(f'control loop running at {update_rate} Hz')
    end = time.monotonic() + 3.2
    while time.monotonic() < end:
        rclpy.spin_once(controller, timeout_sec=0.1)
    rclpy.shutdown()
    sys.exit(0)

group = ReentrantCallbackGroup() if MODE == 'single-thread' else MutuallyExclusiveCallbackGroup()
client = controller.create_client(GetState, '/base_driver/get_state', callback_group=group)

def check():
    timer.cancel()
    future = client.call_async(GetState.Request())
    end = time.monotonic() + 3.0
    while not future.done() and time.monotonic() < end:
        time.sleep(0.05)
    if future.done():
        log.info(f'base_driver is {future.result().current_state.label}')
    else:
        log.error('service call to /base_driver/get_state did not return within 3 s, holding the base')
        failed.append(True)
    finished.set()

timer = controller.create_timer(0.5, check, callback_group=group)
log.info('checking base_driver before taking velocity commands')
executor = MultiThreadedExecutor(num_threads=1 if MODE == 'single-thread' else 4)
executor.add_node(driver)
executor.add_node(controller)
while not finished.is_set():
    executor.spin_once(timeout_sec=0.1)
executor.shutdown()
rclpy.shutdown()
sys.exit(1 if failed else 0)
"""

PROGRAMS = {"bringup": BRINGUP, "control": CONTROL}
# none of them named after a package (launch, rclpy, time, ...): the script's folder comes first on sys.path
SCRIPTS = {"bringup": "base_bringup.py", "control": "base_control.py"}
LIFECYCLE = "bringup.lifecycle_transition_failed"
DIED = "bringup.process_died"
NOMINAL = "control.nominal"
NO_NOMINAL = ("Labelled control.nominal because the cause ids have no bring-up nominal id; the node driven is a base "
              "driver, whose module is control's.")
FAULTS = (
    Fault("lifecycle-configure-raises", "bringup", LIFECYCLE,
          "The base driver's on_configure converts its wheel_base parameter with float(), and the value was written "
          "with a decimal comma ('0,42'), so on_configure raises and the configure fails, twice.",
          ("configure-raises", "--ros-args", "-p", "wheel_base:='0,42'"), program="bringup"),
    Fault("lifecycle-configure-serial-port-missing", "control", CONFIG,
          "The base driver's port parameter names /dev/ttyACM0, which this computer does not have (the motor board "
          "is elsewhere), so on_configure cannot open it and returns ERROR, and the driver never configures.",
          ("port-missing", "--ros-args", "-p", "port:=/dev/ttyACM0"), program="bringup"),
    Fault("lifecycle-shutdown-raises", "bringup", LIFECYCLE,
          "The base driver's on_shutdown closes the serial port that on_cleanup already closed and set to None, so "
          "on_shutdown raises and the shutdown transition fails; the driver is never finalized.",
          ("shutdown-raises",), program="bringup"),
    Fault("lifecycle-transition-label-misspelt", "bringup", LIFECYCLE,
          "The lifecycle manager asks for transitions by label and its second label is 'active' where the "
          "transition is 'activate', so the base driver is configured but never activated.",
          ("label-misspelt",), program="bringup"),
    Fault("lifecycle-manager-wrong-node-name", "bringup", CONFIG,
          "The lifecycle manager's list names base_controller, but the node is base_driver, so the manager never "
          "finds its change_state service and nothing is configured.", ("wrong-node-name",), program="bringup"),
    Fault("lifecycle-activate-waits-on-own-executor", "control", "control.controller_activation_failed",
          "The base controller's on_activate calls base_driver's get_state service and waits for the answer, but "
          "both nodes are spun by one single-threaded executor, busy in on_activate, so the call never returns and "
          "the controller cannot be activated.", ("activate-deadlock",), program="bringup"),
    Fault("lifecycle-publisher-never-enabled", "bringup", LIFECYCLE,
          "The base driver's on_activate returns SUCCESS without calling the LifecycleNode's on_activate, so its "
          "lifecycle publisher is never activated and no odometry is sent although the driver is active.",
          ("publisher-never-enabled",), program="bringup",
          notes="No cause id names a managed entity the transition left inactive; labelled as the activation that "
                "did not take effect."),
    Fault("multithreaded-executor-one-thread", "control", "control.configuration_error",
          "The base controller is spun by a MultiThreadedExecutor built with num_threads=1, so its timer's "
          "blocking call to base_driver's get_state never gets a thread and times out.",
          ("single-thread",), program="control",
          notes="No cause id names an executor set up wrongly; control.configuration_error is the closest."),
    Fault("client-in-timers-exclusive-group", "control", "control.configuration_error",
          "The base controller's get_state client is in the same MutuallyExclusiveCallbackGroup as the timer that "
          "waits for its answer, so the response is never handled, even on a four-thread executor.",
          ("exclusive-group",), program="control",
          notes="No cause id names a callback group set up wrongly; control.configuration_error is the closest."),
    Fault("control-loop-slower-than-update-rate", "control", "control.configuration_error",
          "The control loop's update_rate is 100 Hz, but each update does a 25 ms round trip to the motor board, "
          "so the loop runs at about 40 Hz.", ("control-loop-overrun",), program="control", outcome="slow",
          notes="An update_rate the hardware cannot keep is set up wrongly; no cause id names an overrun."),
    Fault("rate-sleep-after-shutdown", "bringup", DIED,
          "The e-stop handler calls rclpy.shutdown() from its own thread while the main loop is still sleeping on "
          "a Rate, so Rate.sleep raises ROSInterruptException and the process ends with a traceback.",
          ("rate-after-shutdown",), program="control"),
    Fault("lifecycle-driver-came-up-late", "control", NOMINAL,
          "The base driver started 2.5 s after the lifecycle manager, which waited for its change_state service "
          "and then configured and activated it.", ("late-driver",), program="bringup", outcome="succeeded",
          notes=NO_NOMINAL),
    Fault("lifecycle-activate-retried", "control", NOMINAL,
          "The motor board was still booting at the first activate, which the base driver refused; the manager "
          "retried a second later and the driver became active.", ("activate-retried",), program="bringup",
          outcome="succeeded", notes=NO_NOMINAL),
    Fault("lifecycle-odometry-before-activation", "control", NOMINAL,
          "The odometry monitor warns while the base driver is configured but not yet activated (the manager "
          "brings nodes up in order); once activated, odometry arrives.", ("monitor",), program="bringup",
          outcome="succeeded", notes=NO_NOMINAL),
)
# Read after the run, as a collector reads a thread: what the lines of these faults do not show
SILENT = {"lifecycle-publisher-never-enabled": "The lines show the driver active and the monitor getting no "
                                                "odometry, not the lifecycle publisher left inactive."}
HEADER = """\
# Held-out set 29 of real console excerpts (issue 23's format): printed by the real ROS 2 stack installed on this
# project's machine (ROS 2 Kilted's rclpy, rcl, rcl_lifecycle and Fast DDS from PyPI, with lifecycle_msgs), each run
# with one fault of a managed node's lifecycle, an executor, a callback group, a timer or a shutdown: written by
# scripts/lifecycle_faults.py, which states each excerpt's cause (the fault) before it runs anything. Managed
# transitions are driven through the real /<node>/change_state and /<node>/get_state services. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by /opt/venv/... and /home/robot/ws. Frozen and
# measured once before anything was tuned on it.
# Regenerate with: .venv/bin/python scripts/lifecycle_faults.py --out FILE
"""


def main() -> int:
    return generate(__doc__ or "", HEADER, "lifecycle_faults.py", FAULTS, PROGRAMS, SCRIPTS, SILENT)


if __name__ == "__main__":
    raise SystemExit(main())
