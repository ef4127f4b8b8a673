"""A robot's start told from lines that name no node of its own, on recordings without /task_info: pluginlib's
class loader failing right after the controller manager began (enactic/openarm_ros2#14, its real lines), launch's
event loop dying on an exception asyncio printed (Universal_Robots_ROS2_Driver#293, Galactic), a section of
MoveIt's sensor settings that lacks parameters (moveit/moveit2#3514), and Gazebo's physics engine without mimic
joints (darshmenon/UR3_ROS2_PICK_AND_PLACE#1)."""

from __future__ import annotations

from pathlib import Path

from hexar.claims import read_claims
from hexar.events.records import ERROR, INFO
from tests.explainers.helpers import explain, write_lines

MANIFEST = ("Could not find a root element for package manifest at /home/otegami/work/cpp/ros2_ws/install/"
            "openarm_hardware/share/openarm_hardware/package.xml.")
OPENARM = [
    (0.0, "launch", INFO, "All log files can be found below /home/otegami/.ros/log/2025-05-23-15-07-52-834283"),
    (0.2, "ros2_control_node-1", INFO, "process started with pid [2239568]"),
    (0.5, "robot_state_publisher", INFO, "Robot initialized"),
    (0.516, "controller_manager", INFO, "Using Steady (Monotonic) clock for triggering controller manager cycles."),
    (0.517, "pluginlib.ClassLoader", ERROR, MANIFEST),
    (0.518, "pluginlib.ClassLoader", ERROR, "Could not find package manifest (neither package.xml or deprecated "
     "manifest.xml) at same directory level as the plugin XML file /home/otegami/work/cpp/ros2_ws/install/"
     "openarm_hardware/share/openarm_hardware/openarm_hardware.xml. Plugins will likely not be exported properly."),
]


def test_an_unreadable_package_manifest_after_the_controller_manager_began_is_its_set_up(tmp_path: Path) -> None:
    log = write_lines(tmp_path, OPENARM)
    task, found = explain(log, "control", "Why didn't that work?")
    # robot_state_publisher runs on every robot: its line makes no Nav2 goal of an arm's start
    assert [s.skill for s in task.skills] == ["bring_up_controllers"] and task.skills[0].state == "failed"
    assert found.causes == ["control.configuration_error"]
    assert read_claims(found.text).affirmed - {"claim.task_failed"} == {"control.configuration_error"}
    assert "could not read the package.xml of openarm_hardware" in found.text


def test_the_class_loaders_error_long_after_any_start_is_no_start(tmp_path: Path) -> None:
    late = [OPENARM[3], (9.0, "pluginlib.ClassLoader", ERROR, MANIFEST)]
    log = write_lines(tmp_path, late)
    assert not [t for t in log.tasks if t.skills and t.skills[0].skill == "bring_up_controllers"
                and t.skills[0].state == "failed"]


ASYNCIO = [
    (0.0, "launch", INFO, "All log files can be found below /home/thomas/.ros/log/2022-02-17-18-49-03-979371"),
    (0.1, "launch", INFO, "Default logging verbosity is set to INFO"),
    (1.2, "", INFO, "Task exception was never retrieved"),
    (1.3, "future", INFO, "<Task finished name='Task-2' coro=<LaunchService._process_one_event() done, defined at "
     "/opt/ros/galactic/lib/python3.8/site-packages/launch/launch_service.py:226> exception=SubstitutionFailure("
     "\"executable 'spawner.py' not found on the libexec directory '/home/thomas/workspace/ros_ur_driver/install/"
     "controller_manager/lib/controller_manager' \")>"),
]


def test_a_launch_that_died_on_an_exception_asyncio_printed_is_a_failed_start(tmp_path: Path) -> None:
    log = write_lines(tmp_path, ASYNCIO)
    _, found = explain(log, "control", "Why didn't that work?")
    assert found.causes == ["bringup.configuration_error"]
    assert "my launch stopped with an error before it had started my nodes" in found.text
    assert "executable 'spawner.py' not found on the libexec directory" in found.text


def test_a_section_of_moveits_settings_without_its_parameters_is_moveits_set_up(tmp_path: Path) -> None:
    log = write_lines(tmp_path, [
        (1.0, "move_group", ERROR, "Missing parameters under 'vision_perception_node': , 'max_update_rate', "
         "'filtered_cloud_topic'"),
        (1.0, "move_group.moveit.moveit.ros.occupancy_map_monitor", ERROR,
         "Failed to configure updater of type PointCloudUpdater")])
    _, found = explain(log, "manipulation", "Why didn't that work?")
    assert found.causes == ["manipulation.configuration_error"]
    assert "the settings under 'vision_perception_node' lack parameters it needs (max_update_rate, " \
           "filtered_cloud_topic)" in found.text


def test_a_physics_engine_without_mimic_joints_is_the_simulations_set_up(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns
    from tests.explainers.helpers import T0
    from tests.explainers.test_stated_causes import _task

    b = BagBuilder()
    b.task_info(T0 - sec_ns(1), _task("Running", "bring_up_controllers"))
    b.task_info(T0 + sec_ns(3), _task("failed", "bring_up_controllers"))
    log = write_lines(tmp_path, [(1.0, "", ERROR, "Attempting to create a mimic constraint for joint "
                                  "[left_inner_finger_joint], but the chosen physics engine does not support mimic "
                                  "constraints, so no constraint will be created.")], b)
    _, found = explain(log, "control", "Why didn't that work?")
    assert found.causes == ["control.configuration_error"]
    assert "does not support the <mimic> joints of my robot description" in found.text
    assert found.fix is not None and "bullet-featherstone" in found.fix
