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
from tests.explainers.helpers import claimed, console_lines, derived_start, printed

DOMAIN_NAME = printed("real-modules-heldout24", "kilted-domain-id-not-a-number")
CYCLONE_MISSPELT = printed("real-modules-heldout24", "kilted-cyclone-config-element-misspelt")
CYCLONE_NO_FILE = printed("real-modules-heldout24", "kilted-cyclone-config-file-missing")
FASTDDS_NO_FILE = printed("real-modules-heldout24", "kilted-fastdds-profiles-file-missing")
NO_SECURITY = printed("real-modules-heldout24", "kilted-keystore-without-this-nodes-enclave")


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
