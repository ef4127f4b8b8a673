"""The middleware under every node and a Python node's own exception, read from the lines the real ROS 2 Kilted stack
printed here with one fault each (rclpy 9.1.2, rcl, Fast DDS; the Cyclone DDS core through cyclonedds;
scripts/stack_faults.py, the spent held-out set 22), written as recordings with rosbags: no task and no goal, so the
robot's start is derived from them, and with a failed start on /task_info."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.events.console import parse_console
from hexar.events.records import ERROR, INFO, WARN, LogLine
from hexar.explainers.base import Explanation
from hexar.explainers.stack.middleware import middleware_line
from hexar.explainers.stack.thrown import python_exception
from tests.explainers.helpers import claimed, console_lines, derived_start

PORTS = ("2026-11-29 04:40:42.374 [RTPS Error] Calculated port number is too high. Probably the domainId is over 232 "
         "or portBase is too high. -> Function getMulticastPort")
CYCLONE = "1795927276.580085 [0]     python: wlan0: does not match an available interface."
RANGE = ("[WARN] [1795927242.627193879] [rcl]: Invalid value 'SUBNETT' specified for 'ROS_AUTOMATIC_DISCOVERY_RANGE', "
         "assuming localhost only")
RMW = ("[ERROR] [1795927211.975337174] [rcl]: Expected RMW implementation identifier of 'rmw_cyclonedds_cpp' but "
       "instead found 'rmw_fastrtps_cpp', exiting with 102., at /project/src/rcl/rmw_implementation_identifier_check.c:"
       "154")
PROFILE = ("2026-11-29 04:40:43.128 [XMLPARSER Error] Error opening '/home/robot/ws/fastdds_udp.xml' -> Function "
           "loadXML\n2026-11-29 04:40:43.128 [XMLPARSER Error] Error parsing '/home/robot/ws/fastdds_udp.xml' -> "
           "Function loadXMLFile\n[INFO] [1795927243.204368212] [scan_filter]: filtering scans at 10 Hz")
WRONG_TYPE = """\
Traceback (most recent call last):
  File "/home/robot/ws/scan_filter.py", line 7, in <module>
    node.declare_parameter('scan_rate', 10)
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 688, in _declare_parameter_common
    raise InvalidParameterTypeException(
rclpy.exceptions.InvalidParameterTypeException: Trying to set parameter 'scan_rate' to 'fast' of type 'STRING', \
expecting type 'INTEGER': scan_rate"""
CRASH = """\
[INFO] [1795927630.609408233] [scan_filter]: filtering scans at 10 Hz
Traceback (most recent call last):
  File "/home/robot/ws/scan_filter.py", line 14, in <module>
    rclpy.spin(node)
  File "/opt/venv/lib/python3/site-packages/rclpy/executors.py", line 135, in await_or_execute
    return callback(*args)
           ^^^^^^^^^^^^^^^
  File "/home/robot/ws/scan_filter.py", line 12, in tick
    node.get_logger().info(f'closest obstacle {min(ranges)} m')
                                               ^^^^^^^^^^^
ValueError: min() arg is an empty sequence"""


def _derived(tmp_path: Path, console: str) -> Explanation:
    return derived_start(tmp_path, console_lines(console))


_claims = claimed


@pytest.mark.parametrize(("console", "said"), [
    (PORTS, "could not open its network ports"),
    (CYCLONE, "names a network interface this machine does not have (wlan0)"),
    (RANGE, "DDS discovery stayed on this computer"),
])
def test_a_node_the_dds_middleware_kept_from_the_others_is_a_network_cause(tmp_path: Path, console: str,
                                                                           said: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["system.network"] and _claims(found) == {"system.network"}
    assert said in found.text
    assert found.evidence and found.evidence[0].topic == "/rosout"


@pytest.mark.parametrize(("console", "said"), [
    (RMW, "RMW_IMPLEMENTATION names rmw_cyclonedds_cpp, but the program was built with rmw_fastrtps_cpp"),
    (PROFILE, "Fast DDS could not load its XML profiles file (/home/robot/ws/fastdds_udp.xml)"),
])
def test_a_middleware_setting_that_never_applied_is_a_configuration_error_not_the_network(
        tmp_path: Path, console: str, said: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.configuration_error"]
    assert _claims(found) == {"bringup.configuration_error"}  # "Fast DDS" is named, the network is not claimed
    assert said in found.text


def test_a_python_node_that_died_of_its_exception_is_told_with_the_exception_and_where(tmp_path: Path) -> None:
    found = _derived(tmp_path, CRASH)
    assert found.causes == ["bringup.process_died"]
    assert ("died of an uncaught Python exception (ValueError), so the software it ran was gone: “[unnamed node] "
            "min() arg is an empty sequence”, raised in tick (/home/robot/ws/scan_filter.py, line 12)") in found.text


def test_a_parameter_of_the_wrong_type_rclpy_refused_is_a_configuration_error(tmp_path: Path) -> None:
    found = _derived(tmp_path, WRONG_TYPE)
    assert found.causes == ["bringup.configuration_error"] and _claims(found) == {"bringup.configuration_error"}
    assert "its value was not of the type the node declares, and its process ended there" in found.text
    assert "Trying to set parameter 'scan_rate' to 'fast'" in found.text


def test_python_exceptions_are_parsed_from_the_console_record() -> None:
    record = parse_console(CRASH)[-1]
    line = LogLine(1, record.level, record.name, record.msg)
    exc = python_exception(line)
    assert exc is not None and record.level == ERROR
    assert (exc.type, exc.text) == ("ValueError", "min() arg is an empty sequence")
    assert exc.where == "tick (/home/robot/ws/scan_filter.py, line 12)"  # the node's own frame, not rclpy's
    assert python_exception(LogLine(1, INFO, "scan_filter", "filtering scans at 10 Hz")) is None


def test_a_middleware_line_needs_a_catalogued_middleware_text() -> None:
    ports = LogLine(5, ERROR, "", PORTS.split(" ", 2)[2])
    healthy = LogLine(1, WARN, "controller_manager", "Controller 'arm' is already loaded")
    assert middleware_line([healthy, ports]) == (ports, "system.network")
    assert middleware_line([healthy]) is None
    assert middleware_line([ports], before=4) is None
