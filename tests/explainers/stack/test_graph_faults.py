"""Faults of a running graph's parameters, services and node names, read from the lines the real ROS 2 Kilted stack
printed here with one fault each (rclpy 9.1.2, rcl, rcl_yaml_param_parser, Fast DDS; scripts/graph_faults.py, the
spent held-out set 25), written as recordings with rosbags: no task and no goal, so the robot's start is derived from
them."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.explainers.base import Explanation
from tests.explainers.helpers import claimed, console_lines, derived_start, printed


def _derived(tmp_path: Path, ident: str) -> Explanation:
    return derived_start(tmp_path, console_lines(printed("real-modules-heldout25", ident)))


@pytest.mark.parametrize(("ident", "said", "fix"), [
    ("kilted-parameter-out-of-declared-range", "the value given to scan_rate (100) is not one the node's declaration "
     "of it accepts (Parameter scan_rate out of range. Min: 1, Max: 40, value: 100)", "Give scan_rate a value"),
    ("kilted-typed-parameter-never-set", "the node declares the parameter frame_id with a type and no default value, "
     "and no value was given for it", "--ros-args -p frame_id:=..."),
    ("kilted-service-two-types-one-name", "two parts of one process use the service 'map_server/load_map' with "
     "different service types (one of them nav_msgs/srv/LoadMap)", "one service type per service name"),
    ("kilted-service-name-doubled-slash", "a service name my node was given is not a valid ROS name (topic name must "
     "not contain repeated '/')", "Give a valid service name"),
])
def test_a_value_or_name_the_node_does_not_take_is_a_configuration_error(tmp_path: Path, ident: str, said: str,
                                                                         fix: str) -> None:
    found = _derived(tmp_path, ident)
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert said in found.text and fix in (found.fix or "")


@pytest.mark.parametrize("ident", ["kilted-parameter-read-undeclared", "kilted-parameter-declared-twice"])
def test_the_nodes_own_code_misusing_its_parameters_is_the_process_that_died(tmp_path: Path, ident: str) -> None:
    # rclpy raises these for the code's calls (get_parameter of one never declared, declare_parameter twice): no value
    # given from outside was refused
    found = _derived(tmp_path, ident)
    assert found.causes == ["bringup.process_died"] and claimed(found) == {"bringup.process_died"}
    assert "settings" not in found.text


def test_two_nodes_of_one_name_are_a_configuration_error(tmp_path: Path) -> None:
    found = _derived(tmp_path, "kilted-two-nodes-one-name")
    assert found.causes == ["bringup.configuration_error"] and claimed(found) == {"bringup.configuration_error"}
    assert "two of my nodes were started with the same name ('camera_driver')" in found.text
    assert "__node:=" in (found.fix or "")


def test_a_python_programs_death_beside_a_nav2_like_name_is_no_navigation(tmp_path: Path) -> None:
    # the program's own node is called map_server, and it printed one INFO line: that is no Nav2 at work
    found = _derived(tmp_path, "kilted-service-two-types-one-name")
    assert "navigation" not in found.text


def test_a_setting_refused_in_other_words_claims_no_person_refusing() -> None:
    from hexar.explainers.stack.refused import refused_words

    said, _ = refused_words("rclpy._rclpy_pybind11.RCLError: something rcl has no words for, at rcl/node.c:1")
    assert said.startswith("ROS 2 did not accept a setting of my node")
    from hexar.claims import read_claims

    assert "ask_human.refused" not in read_claims(said).affirmed
