"""Runtime and launch faults, read from the lines the real ROS 2 Kilted stack and ros2/launch printed here with one
fault each (rclpy 9.1.2, rcl, rcl_lifecycle, Fast DDS, launch 3.4.3; scripts/runtime_faults.py, the spent held-out
set 23), written as recordings with rosbags: no task and no goal, so the robot's start is derived from them."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.events.records import ERROR
from hexar.explainers.base import Explanation
from tests.explainers.helpers import claimed, console_lines, derived_start, write_lines

QOS_ODOM = """\
[WARN] [1795935568.599864660] [ekf_filter]: New publisher discovered on topic 'odom', offering incompatible QoS.\
 No messages will be received from it. Last incompatible policy: RELIABILITY
[WARN] [1795935568.601425416] [base_driver]: New subscription discovered on topic 'odom', requesting incompatible\
 QoS. No messages will be sent to it. Last incompatible policy: RELIABILITY
"""

QOS_DEADLINE = """\
[WARN] [1795935573.023613849] [teleop]: New subscription discovered on topic 'cmd_vel', requesting incompatible\
 QoS. No messages will be sent to it. Last incompatible policy: DEADLINE
[WARN] [1795935573.025127445] [base_controller]: New publisher discovered on topic 'cmd_vel', offering\
 incompatible QoS. No messages will be received from it. Last incompatible policy: DEADLINE
"""

TYPES = """\
Traceback (most recent call last):
  File "/home/robot/ws/types.py", line 9, in <module>
    ekf.create_subscription(Odometry, 'odom', lambda msg: None, 10)
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 1744, in create_subscription
    subscription_object = _rclpy.Subscription(
                          ^^^^^^^^^^^^^^^^^^^^
rclpy._rclpy_pybind11.RCLError: Failed to create subscription: create_subscription() called for existing topic\
 name rt/odom with incompatible type nav_msgs::msg::dds_::Odometry_, at /project/src/subscription.cpp:526, at\
 /project/src/rcl/subscription.c:116
"""

TOPIC_NAME = """\
Traceback (most recent call last):
  File "/home/robot/ws/topic.py", line 8, in <module>
    node.create_subscription(Odometry, node.get_parameter('odom_topic').value, lambda msg: None, 10)
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 1730, in create_subscription
    raise ex from None
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 1728, in create_subscription
    self._validate_topic_or_service_name(topic)
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 1555, in _validate_topic_or_service_name
    validate_topic_name(topic_or_service_name, is_service=is_service)
  File "/opt/venv/lib/python3/site-packages/rclpy/validate_topic_name.py", line 45, in validate_topic_name
    raise InvalidTopicNameException(name, error_msg, invalid_index)
rclpy.exceptions.InvalidTopicNameException: Invalid topic name: topic name must not contain characters other than\
 alphanumerics, '_', '~', '{', or '}':
  'wheel odom'
        ^
"""

ACTIVATE_FIRST = """\
[WARN] [1795935576.415309294] [rcl_lifecycle]: No transition matching 3 found for current state unconfigured
[ERROR] [1795935576.434988699] [lidar_driver]: Unable to start transition 3 from current state (1, 'unconfigured')
"""

KEYSTORE = """\
Traceback (most recent call last):
  File "/home/robot/ws/node.py", line 5, in <module>
    rclpy.init(args=sys.argv)
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 137, in init
    return InitContextManager(args, context, domain_id, signal_handler_options)
           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 95, in __init__
    self.context.init(args, domain_id=domain_id)
  File "/opt/venv/lib/python3/site-packages/rclpy/context.py", line 95, in init
    self.__context = _rclpy.Context(
                     ^^^^^^^^^^^^^^^
rclpy._rclpy_pybind11.RCLError: failed to initialize rcl: SECURITY ERROR: directory\
 '/home/robot/keystore/enclaves' does not exist., at /project/src/rcl/security.c:202
"""

LOG_DIR = """\
Traceback (most recent call last):
  File "/home/robot/ws/node.py", line 5, in <module>
    rclpy.init(args=sys.argv)
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 137, in init
    return InitContextManager(args, context, domain_id, signal_handler_options)
           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 95, in __init__
    self.context.init(args, domain_id=domain_id)
  File "/opt/venv/lib/python3/site-packages/rclpy/context.py", line 102, in init
    _rclpy.rclpy_logging_configure(self.__context)
rclpy._rclpy_pybind11.RCLError: failed to initialize logging: Failed to create log directory 'settings.yaml/log':\
 20, at /project/src/rcl_logging_spdlog.cpp:153
"""

SERVER_NAME = """\
2026-11-29 06:59:38.518 [SERVER_CLIENT_DISCOVERY Error] Wrong domain name passed into the server's list\
 robot-base.local:11811 -> Function load_environment_server_info
[INFO] [1795935578.609752102] [scan_filter]: filtering scans at 10 Hz
"""

SERVER_IPV4 = """\
2026-11-29 06:59:39.372 [SERVER_CLIENT_DISCOVERY Error] Wrong ipv4 address passed into the server's list\
 192.168.1.300 -> Function load_environment_server_info
[INFO] [1795935579.546639707] [scan_filter]: filtering scans at 10 Hz
"""

KILLED = """\
[INFO] [launch]: All log files can be found below /home/robot/ws/.ros/log/2026-11-29-06-59-40-271465-vm-13400
[INFO] [launch]: Default logging verbosity is set to INFO
[INFO] [scan_filter-1]: process started with pid [13401]
[scan_filter-1] [INFO] [1795935580.710916696] [scan_filter]: filtering scans at 10 Hz
[ERROR] [scan_filter-1]: process has died [pid 13401, exit code -9, cmd '/opt/venv/bin/python child.py killed'].
"""

SEGFAULT = """\
[INFO] [launch]: All log files can be found below /home/robot/ws/.ros/log/2026-11-29-06-59-41-432674-vm-13422
[INFO] [launch]: Default logging verbosity is set to INFO
[INFO] [scan_filter-1]: process started with pid [13423]
[scan_filter-1] [INFO] [1795935581.829564150] [scan_filter]: filtering scans at 10 Hz
[ERROR] [scan_filter-1]: process has died [pid 13423, exit code -11, cmd '/opt/venv/bin/python child.py segfault'].
"""

NOT_INSTALLED = """\
[INFO] [launch]: All log files can be found below /home/robot/ws/.ros/log/2026-11-29-06-59-42-608220-vm-13444
[INFO] [launch]: Default logging verbosity is set to INFO
[ERROR] [scan_filter-1]: exception occurred while executing process:
Traceback (most recent call last):
  File "/opt/ros/launch/launch/actions/execute_local.py", line 569, in __execute_process
    transport, self._subprocess_protocol = await async_execute_process(
                                           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/opt/launch-venv/lib/python3.11/site-packages/osrf_pycommon/process_utils/async_execute_process_asyncio/imp\
l.py", line 139, in async_execute_process
    transport, protocol = await _async_execute_process_nopty(
                          ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/opt/launch-venv/lib/python3.11/site-packages/osrf_pycommon/process_utils/async_execute_process_asyncio/imp\
l.py", line 45, in _async_execute_process_nopty
    transport, protocol = await loop.subprocess_exec(
                          ^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/usr/lib/python3.11/asyncio/base_events.py", line 1694, in subprocess_exec
    transport = await self._make_subprocess_transport(
                ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/usr/lib/python3.11/asyncio/unix_events.py", line 207, in _make_subprocess_transport
    transp = _UnixSubprocessTransport(self, protocol, args, shell,
             ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/usr/lib/python3.11/asyncio/base_subprocess.py", line 36, in __init__
    self._start(args=args, shell=shell, stdin=stdin, stdout=stdout,
  File "/usr/lib/python3.11/asyncio/unix_events.py", line 818, in _start
    self._proc = subprocess.Popen(
                 ^^^^^^^^^^^^^^^^^
  File "/usr/lib/python3.11/subprocess.py", line 1026, in __init__
    self._execute_child(args, executable, preexec_fn, close_fds,
  File "/usr/lib/python3.11/subprocess.py", line 1950, in _execute_child
    raise child_exception_type(errno_num, err_msg, err_filename)
FileNotFoundError: [Errno 2] No such file or directory: 'scan_filter_node'
"""


def _derived(tmp_path: Path, console: str) -> Explanation:
    return derived_start(tmp_path, console_lines(console))


@pytest.mark.parametrize(("console", "said", "fix"), [
    (QOS_ODOM, "ekf_filter's subscription to 'odom' gets no message from a publisher whose QoS settings do not match "
               "its own (the reliability policy)", "subscribe best effort"),
    (QOS_DEADLINE, "base_controller's subscription to 'cmd_vel' gets no message from a publisher whose QoS settings "
                   "do not match its own (the deadline policy)", "offer at least that deadline"),
])
def test_a_qos_mismatch_is_told_from_the_end_that_gets_nothing(tmp_path: Path, console: str, said: str,
                                                               fix: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert said in found.text and fix in (found.fix or "")


def test_a_qos_mismatch_never_outranks_another_cause(tmp_path: Path) -> None:
    # a mismatch may be any pair's (a viewer's subscription): the discovery server the node could not use is the cause
    found = _derived(tmp_path, QOS_ODOM + SERVER_IPV4)
    assert found.causes == ["system.network"] and "QoS" not in found.text


@pytest.mark.parametrize(("console", "said"), [
    (SERVER_NAME, "it holds a host name that does not resolve (robot-base.local:11811)"),
    (SERVER_IPV4, "it holds an IPv4 address that is not valid (192.168.1.300)"),
])
def test_a_discovery_server_fast_dds_cannot_read_keeps_the_node_from_the_others(tmp_path: Path, console: str,
                                                                                said: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["system.network"] and claimed(found) == {"system.network"}
    assert "could not use the discovery server ROS_DISCOVERY_SERVER names" in found.text and said in found.text


def test_a_lifecycle_transition_asked_in_the_wrong_state_failed(tmp_path: Path) -> None:
    found = _derived(tmp_path, ACTIVATE_FIRST)
    assert found.causes == ["bringup.lifecycle_transition_failed"]
    assert claimed(found) == {"bringup.lifecycle_transition_failed"}


@pytest.mark.parametrize(("console", "said", "fix"), [
    (KEYSTORE, "security is enabled, and the keystore it names has no such folder (/home/robot/keystore/enclaves)",
     "ros2 security create_keystore"),
    (LOG_DIR, "rcl could not create the folder for its log files (settings.yaml/log)", "ROS_LOG_DIR"),
    (TYPES, "two parts of one process use the topic 'odom' with different message types (one of them "
            "nav_msgs/msg/Odometry)", "one message type per topic"),
    (TOPIC_NAME, "a topic name my node was given is not a valid ROS name", "a valid topic name"),
])
def test_a_setting_ros_refused_as_it_made_the_node_is_a_configuration_error(tmp_path: Path, console: str, said: str,
                                                                            fix: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert said in found.text and fix in (found.fix or "")
    assert "one of my processes died" not in found.text  # the death is the refusal's end, not what went wrong


@pytest.mark.parametrize(("console", "said"), [
    (KILLED, "the process of scan_filter was killed, and nothing in my logs says by whom: the kernel's out-of-memory "
             "killer sends that signal, and so does kill -9 (signal 9, SIGKILL)"),
    (SEGFAULT, "the process of scan_filter ended on a segmentation fault (a crash), and nothing in my logs says where "
               "(signal 11, SIGSEGV)"),
])
def test_a_process_a_signal_ended_with_nothing_before_it_is_told_as_its_death(tmp_path: Path, console: str,
                                                                              said: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.process_died"] and claimed(found) == {"bringup.process_died"}
    assert said in found.text


def test_a_crash_after_an_error_is_quoted_not_told(tmp_path: Path) -> None:
    lines = console_lines(SEGFAULT)
    lines.insert(-1, (lines[-1][0] - 0.1, "scan_filter", ERROR, "Failed to open serial port /dev/ttyUSB0"))
    found = derived_start(tmp_path, lines)
    assert found.causes == ["control.unexplained_failure"]
    assert "one of my processes died" not in found.text and "exit code -11" in found.text  # quoted, not told


def test_a_program_launch_could_not_execute_never_started(tmp_path: Path) -> None:
    found = _derived(tmp_path, NOT_INSTALLED)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert ("a command my launch ran never started: 'scan_filter_node' could not be run: there is no such program "
            "(it is not installed, or not on the PATH)") in found.text


def test_a_launch_that_started_nothing_of_nav2_is_not_a_navigation(tmp_path: Path) -> None:
    assert [t.skills[0].skill for t in write_lines(tmp_path / "a", console_lines(KILLED)).tasks] == [
        "bring_up_controllers"]
    # the same death with no start lines: nothing says whose launch it was, and Nav2's catalogue knows the line
    death = [ln for ln in console_lines(KILLED) if "process has died" in ln[3]]
    assert [t.skills[0].skill for t in write_lines(tmp_path / "b", death).tasks] == ["navigate_to_pose"]


def test_a_crash_of_the_process_that_runs_the_drivers_is_quoted_not_told(tmp_path: Path) -> None:
    manager = "ros2_control_node"
    lines = [(s, name.replace("scan_filter", manager), level, msg.replace("scan_filter", manager))
             for s, name, level, msg in console_lines(SEGFAULT)]
    found = derived_start(tmp_path, lines)
    assert found.causes == ["control.unexplained_failure"] and "one of my processes died" not in found.text
