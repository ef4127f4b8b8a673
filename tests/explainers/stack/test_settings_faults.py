"""Settings of the environment or the code gotten wrong, read from the lines the real ROS 2 Kilted stack printed here
with one fault each (rclpy 9.1.2, rcl, Fast DDS; the Cyclone DDS core through cyclonedds; scripts/settings_faults.py,
the spent held-out set 24), written as recordings with rosbags: no task and no goal, so the robot's start is derived
from them."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.events.console import parse_console
from hexar.explainers.base import Explanation
from hexar.explainers.stack.mining import literals, to_display
from tests.explainers.helpers import claimed, console_lines, derived_start

DOMAIN_NAME = """\
Traceback (most recent call last):
  File "/home/robot/ws/scan_filter.py", line 5, in <module>
    rclpy.init(args=sys.argv)
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 137, in init
    return InitContextManager(args, context, domain_id, signal_handler_options)
           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
  File "/opt/venv/lib/python3/site-packages/rclpy/__init__.py", line 95, in __init__
    self.context.init(args, domain_id=domain_id)
  File "/opt/venv/lib/python3/site-packages/rclpy/context.py", line 95, in init
    self.__context = _rclpy.Context(
                     ^^^^^^^^^^^^^^^
rclpy._rclpy_pybind11.RCLError: failed to initialize rcl: ROS_DOMAIN_ID is not an integral number, at\
 /project/src/rcl/domain_id.c:49
"""

CYCLONE_MISSPELT = """\
1795937989.931316 [0]     python: config: //CycloneDDS/Domain/General: NetworkInterfaceAddres: unknown element\
 (CYCLONEDDS_URI+0 line 1)
Traceback (most recent call last):
  File "/home/robot/ws/participant.py", line 2, in <module>
    DomainParticipant(0)
  File "/opt/venv/lib/python3/site-packages/cyclonedds/domain.py", line 99, in __init__
    super().__init__(self._create_participant(domain_id, cqos, listener._ref if listener else None),
  File "/opt/venv/lib/python3/site-packages/cyclonedds/core.py", line 182, in __init__
    raise DDSException(
cyclonedds.core.DDSException: [DDS_RETCODE_ERROR] Non specific error. Occurred upon initialisation of a\
 cyclonedds.domain.DomainParticipant
"""

CYCLONE_NO_FILE = """\
1795937990.222824 [0]     python: can't open configuration file file:///home/robot/ws/cyclonedds.xml
Traceback (most recent call last):
  File "/home/robot/ws/participant.py", line 2, in <module>
    DomainParticipant(0)
  File "/opt/venv/lib/python3/site-packages/cyclonedds/domain.py", line 99, in __init__
    super().__init__(self._create_participant(domain_id, cqos, listener._ref if listener else None),
  File "/opt/venv/lib/python3/site-packages/cyclonedds/core.py", line 182, in __init__
    raise DDSException(
cyclonedds.core.DDSException: [DDS_RETCODE_ERROR] Non specific error. Occurred upon initialisation of a\
 cyclonedds.domain.DomainParticipant
"""

FASTDDS_NO_FILE = """\
2026-11-29 07:39:50.428 [XMLPARSER Error] realpath failed No such file or directory -> Function loadDefaultXMLFile
[INFO] [1795937990.484465901] [scan_filter]: filtering scans at 10 Hz
"""

NO_SECURITY = """\
[INFO] [1795937991.389829293] [rcl]: Found security directory: keystore/enclaves
/opt/venv/lib/python3/site-packages/rclpy/node.py:221: RuntimeWarning: Failed to fini rosout publisher: rcl node\
 implementation is invalid, at /project/src/rcl/node.c:387
  self.__node = _rclpy.Node(
Traceback (most recent call last):
  File "/home/robot/ws/scan_filter.py", line 6, in <module>
    node = Node('scan_filter')
           ^^^^^^^^^^^^^^^^^^^
  File "/opt/venv/lib/python3/site-packages/rclpy/node.py", line 221, in __init__
    self.__node = _rclpy.Node(
                  ^^^^^^^^^^^^
rclpy._rclpy_pybind11.RCLError: error creating node: This Fast DDS version doesn't have the security libraries
Please compile Fast DDS using the -DSECURITY=ON CMake option, at /project/src/participant.cpp:406, at\
 /project/src/rcl/node.c:249
"""


def _derived(tmp_path: Path, console: str) -> Explanation:
    return derived_start(tmp_path, console_lines(console))


@pytest.mark.parametrize(("console", "said", "fix"), [
    (CYCLONE_MISSPELT, "Cyclone DDS did not take its configuration (//CycloneDDS/Domain/General: "
                       "NetworkInterfaceAddres: unknown element)", "element names are case-sensitive"),
    (CYCLONE_NO_FILE, "Cyclone DDS could not open the configuration file CYCLONEDDS_URI names "
                      "(file:///home/robot/ws/cyclonedds.xml)", "Point CYCLONEDDS_URI at the file"),
    (FASTDDS_NO_FILE, "Fast DDS found no XML profiles file where FASTDDS_DEFAULT_PROFILES_FILE points",
     "Point FASTDDS_DEFAULT_PROFILES_FILE at the XML file"),
])
def test_a_middleware_configuration_that_was_not_taken_is_a_configuration_error(tmp_path: Path, console: str,
                                                                               said: str, fix: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert said in found.text and fix in (found.fix or "")
    assert "died" not in found.text  # the binding's exception after it says nothing more


@pytest.mark.parametrize(("console", "said"), [
    (DOMAIN_NAME, "ROS_DOMAIN_ID is not a whole number, so rcl could not start my node"),
    (NO_SECURITY, "security is enabled, but this Fast DDS was built without its security libraries"),
])
def test_an_environment_setting_rcl_refused_is_a_configuration_error(tmp_path: Path, console: str, said: str) -> None:
    found = _derived(tmp_path, console)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert said in found.text


def test_an_exception_message_goes_on_until_rcls_place_of_the_error() -> None:
    [*_, error] = [r for r in parse_console(NO_SECURITY) if r.msg.startswith("rclpy")]
    first = error.msg.split("\nTraceback")[0]
    assert first.endswith("security libraries\nPlease compile Fast DDS using the -DSECURITY=ON CMake option, at "
                          "/project/src/participant.cpp:406, at /project/src/rcl/node.c:249")
    assert not any(r.msg.startswith("Please compile") for r in parse_console(NO_SECURITY))


def test_a_c_string_constant_is_read_with_its_escapes_and_printf_fields() -> None:
    # Cyclone DDS src/core/ddsi/src/ddsi_config.c:2252@releases/0.10.x
    src = '      DDS_ILOG (DDS_LC_ERROR, domid, "can\'t open configuration file %s\\n", tok);\n'
    regex = r'DDS_ILOG\s*\(\s*DDS_LC_ERROR\s*,\s*[\w>-]+\s*,\s*"([^"]{10,})"'
    [(line, text)] = list(literals(src, regex))
    assert line == 1 and to_display(text) == "can't open configuration file …"
