"""Runtime and launch faults, read from the lines the real ROS 2 Kilted stack and ros2/launch printed here with one
fault each (rclpy 9.1.2, rcl, rcl_lifecycle, Fast DDS, launch 3.4.3; scripts/runtime_faults.py, the spent held-out
set 23), written as recordings with rosbags: no task and no goal, so the robot's start is derived from them."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.events.records import ERROR
from hexar.explainers.base import Explanation
from tests.explainers.helpers import claimed, console_lines, derived_start, printed, write_lines

QOS_ODOM = printed("real-modules-heldout23", "kilted-qos-odom-reliability")
QOS_DEADLINE = printed("real-modules-heldout23", "kilted-qos-cmd-vel-deadline")
TYPES = printed("real-modules-heldout23", "kilted-two-types-one-topic")
TOPIC_NAME = printed("real-modules-heldout23", "kilted-topic-parameter-with-space")
ACTIVATE_FIRST = printed("real-modules-heldout23", "kilted-lifecycle-activate-before-configure")
KEYSTORE = printed("real-modules-heldout23", "kilted-security-keystore-without-enclaves")
LOG_DIR = printed("real-modules-heldout23", "kilted-log-dir-under-a-file")
SERVER_NAME = printed("real-modules-heldout23", "kilted-discovery-server-host-unresolvable")
SERVER_IPV4 = printed("real-modules-heldout23", "kilted-discovery-server-address-invalid")
KILLED = printed("real-modules-heldout23", "kilted-launch-process-killed")
SEGFAULT = printed("real-modules-heldout23", "kilted-launch-process-segfault")
NOT_INSTALLED = printed("real-modules-heldout23", "kilted-launch-executable-missing")


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
