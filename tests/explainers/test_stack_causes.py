"""Bring-up causes told by launch itself (explainers/stack_causes.py): a launch that stopped before starting any node,
a parameter file launch_ros could not find, and a lifecycle transition launch_ros asked for that failed. The lines
are real consoles' (cited per case)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.base import Explanation
from hexar.explainers.stack.loader import cpp_name
from tests.explainers.helpers import T0, claimed, derived_start, explain, write_lines

Line = tuple[float, str, int, str]
HEAD = [(0.0, "launch", INFO, "All log files can be found below /home/user/.ros/log/2026-05-19-17-59-57-715685"),
        (0.01, "launch", INFO, "Default logging verbosity is set to INFO")]


def _task(status: str) -> dict[str, Any]:
    return {"instruction": "start the robot's drivers", "task_id": "0000000000000042", "task_status": "valid",
            "task_error_msg": "", "skill_sequence": [{"skill": "bring_up_controllers", "params": {}, "status": status,
                                                      "error_msg": "The skill has been aborted" if status == "failed"
                                                      else ""}]}


def _on_task(tmp_path: Path, lines: list[Line]) -> Explanation:
    """The lines, and a start of the robot's drivers on /task_info that failed after them."""
    b = BagBuilder()
    b.task_info(T0 - sec_ns(0.5), _task("Running"))
    b.task_info(T0 + sec_ns(2), _task("failed"))
    return explain(write_lines(tmp_path, [*HEAD, *lines], b), "control", "Why didn't that work?")[1]


def _derived(tmp_path: Path, lines: list[Line]) -> Explanation:
    """The lines alone: the robot's start is derived from them (no /task_info, no goal)."""
    return derived_start(tmp_path, [*HEAD, *lines])


_claims = claimed


# ldrobot-lidar-ros2 #5 (Humble): launch could not load the launch file, so it started no node
LAUNCH = ("Caught exception in launch (see debug for traceback): Caught exception when trying to load file of format "
          "[py]: LifecycleNode.__init__() missing 1 required keyword-only argument: 'namespace'")


def test_a_launch_that_stopped_before_any_node_is_told_as_launch_not_as_a_parameter_file(tmp_path: Path) -> None:
    found = _on_task(tmp_path, [(0.5, "launch", ERROR, LAUNCH)])
    assert found.causes == ["bringup.configuration_error"]
    assert "my launch stopped with an error before it had started my nodes" in found.text
    assert "missing 1 required keyword-only argument: 'namespace'" in found.text
    assert "parameter file" not in found.text and _claims(found) == {"bringup.configuration_error"}


# Kinovarobotics/ros2_kortex#216 (heldout8, spent): xacro's words, which read as a planner parameter, with no Nav2 line
INVALID = 'Caught exception in launch (see debug for traceback): Invalid parameter "isaac_joint_commands"'


def test_a_launch_exception_that_reads_as_another_cause_stays_in_the_evidence(tmp_path: Path) -> None:
    found = _derived(tmp_path, [(0.5, "launch", ERROR, INVALID)])
    assert found.causes == ["bringup.configuration_error"]
    assert found.text.startswith("Starting my drivers and controllers failed because my launch stopped with an error")
    assert "Invalid parameter" not in found.text and _claims(found) == {"bringup.configuration_error"}
    assert any("isaac_joint_commands" in e.item for e in found.evidence)


# MOCAP4ROS2-Project/mocap4ros2_vicon#16: the launch file named a parameter file the package did not install
# (launch_ros/actions/node.py:461@humble warns and starts the node without it)
MISSING = ("/home/mocap_ws/install/mocap_vicon_driver/share/mocap_vicon_driver/config/"
           "mocap_vicon_driver_params.yaml")
STARTED = (0.6, "mocap_vicon_driver_main-1", INFO, "process started with pid [33196]")


def test_a_parameter_file_launch_could_not_find_is_a_configuration_error_naming_it(tmp_path: Path) -> None:
    found = _derived(tmp_path, [(0.5, "launch_ros.actions.node", WARN, f"Parameter file path is not a file: {MISSING}"),
                                STARTED])
    assert found.causes == ["bringup.configuration_error"]
    assert MISSING in found.text and "never reached the node" in found.text
    assert _claims(found) == {"bringup.configuration_error"}


def test_a_start_without_that_warning_is_not_told_as_failed(tmp_path: Path) -> None:
    log = write_lines(tmp_path, [*HEAD, STARTED])
    assert all(t.outcome != "failed" for t in log.tasks)


# launch_ros/actions/lifecycle_node.py:123@rolling, as two real consoles print it: with the node's own reason before it
# (ros-industrial socketcan #6: activate asked while unconfigured, rcl_lifecycle's WARN), and without (tof-imager #3)
def _refused(transition: str, node: str) -> Line:
    return (1.4, "launch_ros.actions.lifecycle_node", ERROR,
            f"Failed to make transition 'TRANSITION_{transition}' for LifecycleNode '{node}'")


def test_a_transition_launch_asked_for_names_node_and_transition_when_the_lifecycle_says_why(tmp_path: Path) -> None:
    found = _derived(tmp_path, [(1.3, "rcl_lifecycle", WARN, "No transition matching 3 found for current state "
                                 "unconfigured"), _refused("ACTIVATE", "/socket_can_sender")])
    assert found.causes == ["bringup.lifecycle_transition_failed"]
    assert "launch asked /socket_can_sender to activate" in found.text
    assert _claims(found) == {"bringup.lifecycle_transition_failed"}


def test_a_transition_launch_saw_fail_with_no_reason_claims_no_cause_and_quotes_it(tmp_path: Path) -> None:
    found = _on_task(tmp_path, [(0.5, "tof_imager", INFO, "Initialized"), _refused("CONFIGURE", "/tof_imager")])
    assert _claims(found) <= {"control.unexplained_failure"}
    assert "Failed to make transition 'TRANSITION_CONFIGURE' for LifecycleNode '/tof_imager'" in found.text


# AgibotTech/genie_sim#178: Cyclone DDS was configured to select the loopback interface twice, so no domain
# (rmw_cyclonedds_cpp/src/rmw_node.cpp:1080@humble) and no node could be created
def test_a_dds_domain_cyclone_could_not_create_is_a_network_cause_with_its_fix(tmp_path: Path) -> None:
    found = _on_task(tmp_path, [(0.9, "robot_state_publisher", INFO, "lo: the same interface may not be selected "
                                 "twice"),
                                (1.0, "rmw_cyclonedds_cpp", ERROR, "rmw_create_node: failed to create domain, error "
                                 "Error")])
    assert found.causes == ["system.network"] and _claims(found) == {"system.network"}
    assert "Cyclone DDS failed to create its domain" in found.text and found.fix and "CYCLONEDDS_URI" in found.fix


# ouster-lidar/ouster-ros#345 (Humble, heldout9.yaml): sensor.launch.xml ran `ros2 lifecycle set` behind `sleep 0`
# before the driver node existed; ros2lifecycle's set verb printed "Node not found" and returned 1
# (ros2lifecycle/verb/set.py:52@humble), and launch reported the command's process dead
OUSTER_CMD = "bash -c sleep {s}; $0 $@ /opt/ros/humble/bin/ros2 lifecycle set /ouster/os_driver {t}"
OUSTER: list[Line] = [
    (0.1, "os_driver-1", INFO, "process started with pid [75]"), (0.2, "bash-2", INFO, "process started with pid [77]"),
    (0.5, "", INFO, "Node not found"),
    (0.6, "bash-2", ERROR, f"process has died [pid 77, exit code 1, cmd '{OUSTER_CMD.format(s=0, t='configure')}']."),
    (1.5, "", INFO, "Node not found"),
    (1.6, "bash-3", ERROR, f"process has died [pid 79, exit code 1, cmd '{OUSTER_CMD.format(s=1, t='activate')}'].")]


def test_a_lifecycle_command_of_the_launch_that_failed_is_that_transition_not_a_lost_process(tmp_path: Path) -> None:
    found = _derived(tmp_path, OUSTER)
    assert found.causes == ["bringup.lifecycle_transition_failed"]
    assert "my launch ran 'ros2 lifecycle set' to configure /ouster/os_driver" in found.text
    assert _claims(found) == {"bringup.lifecycle_transition_failed"}


# ICube-Robotics/forcedimension_ros2#10 (heldout8.yaml, spent): the launch's ExecuteProcess lost the space between
# `spawner` and its first argument, so `ros2 run` found no such program (ros2run/command/run.py: "No executable
# found", return 1) and launch reported both commands dead
FD_CMD = "ros2 run controller_manager spawner--controller-manager /fd/controller_manager {c}"
NO_PROGRAM: list[Line] = [
    (0.1, "", INFO, "No executable found"), (0.1, "", INFO, "No executable found"),
    (0.2, "controller_manager joint_state_broadcaster-5", ERROR,
     f"process has died [pid 399582, exit code 1, cmd '{FD_CMD.format(c='joint_state_broadcaster')}']."),
    (0.2, "controller_manager fd_controller-4", ERROR,
     f"process has died [pid 399580, exit code 1, cmd '{FD_CMD.format(c='fd_controller')}'].")]


def test_a_launch_command_ros2_run_could_not_find_is_a_set_up_error_not_a_process_that_died(tmp_path: Path) -> None:
    found = _derived(tmp_path, NO_PROGRAM)
    assert found.causes == ["bringup.configuration_error"]
    assert ("a command my launch ran never started: 'ros2 run controller_manager spawner--controller-manager' found "
            "no program named 'spawner--controller-manager' in the package controller_manager") in found.text
    assert _claims(found) == {"bringup.configuration_error"} and found.fix and "Node(package=" in found.fix


def test_a_ros2_run_command_that_died_after_starting_stays_a_process_that_died(tmp_path: Path) -> None:
    # the same death line without ros2run's words before it: the program ran, then exited
    found = _derived(tmp_path, NO_PROGRAM[2:])
    assert found.causes != ["bringup.configuration_error"]
    assert "never started" not in found.text


# flexivrobotics/flexiv_ros2#15 (Foxy, heldout21, spent): glibc's "symbol lookup error" (elf/dl-lookup.c) on the
# controller manager's stderr, then launch's report of its death; the fix linked the RDK library built for the
# robot computer's processor (flexiv_ros2#16)
FLEXIV: list[Line] = [
    (0.4, "ros2_control_node-1", ERROR, "/opt/ros/foxy/lib/controller_manager/ros2_control_node: symbol lookup error: "
     "/ros-flexiv_ws/install/flexiv_hardware/lib/libflexiv_hardware.so: undefined symbol: "
     "_ZN6flexiv5RobotC1ERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEES8_"),
    (0.5, "ros2_control_node-1", ERROR, "process has died [pid 2567, exit code 127, cmd '/opt/ros/foxy/lib/"
     "controller_manager/ros2_control_node --ros-args --params-file /tmp/launch_params_lwng52a_']."),
]


def test_a_program_the_loader_stopped_names_the_library_and_the_symbol_it_lacked(tmp_path: Path) -> None:
    for found in (_on_task(tmp_path / "task", FLEXIV), _derived(tmp_path / "derived", FLEXIV)):
        assert found.causes == ["bringup.process_died"] and _claims(found) == {"bringup.process_died"}
        assert "the dynamic loader stopped ros2_control_node, because libflexiv_hardware.so needs " \
               "flexiv::Robot::Robot(…)" in found.text
        assert found.fix is not None and "rebuild it against the libraries installed here" in found.fix


def test_a_library_the_loader_could_not_find_is_named_with_where_to_look(tmp_path: Path) -> None:
    # glibc's words when a needed library is not on the loader's path (elf/dl-load.c "cannot open shared object file")
    missing = ("/opt/ros/humble/lib/controller_manager/ros2_control_node: error while loading shared libraries: "
               "libhardware_interface.so: cannot open shared object file: No such file or directory")
    found = _on_task(tmp_path, [(0.4, "ros2_control_node-1", ERROR, missing), FLEXIV[1]])
    assert found.causes == ["bringup.process_died"]
    assert "the dynamic loader could not start ros2_control_node: libhardware_interface.so: cannot open" in found.text
    assert found.fix is not None and "not installed or not on the loader's path" in found.fix


@pytest.mark.parametrize(("symbol", "name"), [
    ("_ZN6flexiv5RobotC1ERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEES8_", "flexiv::Robot::Robot(…)"),
    ("_ZN8eprosima7fastcdr3Cdr9serializeEj", "eprosima::fastcdr::Cdr::serialize(…)"),  # ros2_control heldout
    ("_ZN9nav2_amcl20LikelihoodFieldModelC1EddddmP5map_t",
     "nav2_amcl::LikelihoodFieldModel::LikelihoodFieldModel(…)"),
    ("_ZN3fooD1Ev", "foo::~foo(…)"), ("_Z3fooi", "foo(…)"),
    ("_ZN3foo3barIiE3bazEv", None), ("_ZNSt6vectorIiSaIiEE9push_backERKi", None), ("_ZN3foo", None),
    ("rcl_init", None),
])
def test_a_mangled_symbol_reads_as_its_cpp_name_or_not_at_all(symbol: str, name: str | None) -> None:
    assert cpp_name(symbol) == name
