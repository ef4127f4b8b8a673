"""Tasks derived from MoveIt's and the arm controllers' goals (no /task_info): from their goal lines, from the
actions' status topics, and from activity; Nav2's own goals are untouched."""

from __future__ import annotations

from pathlib import Path

from hexar.evals.real_modules import load_excerpts, write_recording
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.reader import read_tasks
from hexar.events.records import ERROR, FATAL, INFO

T0 = 1_700_000_000_000_000_000
MGI = "move_group_interface"


def _status_msg(t: int, goal: int, status: int):  # type: ignore[no-untyped-def]
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_HUMBLE)
    m = ts.types
    info = m["action_msgs/msg/GoalInfo"](
        goal_id=m["unique_identifier_msgs/msg/UUID"](uuid=__import__("numpy").array([goal] * 16, dtype="uint8")),
        stamp=m["builtin_interfaces/msg/Time"](sec=t // 1_000_000_000, nanosec=t % 1_000_000_000))
    return m["action_msgs/msg/GoalStatusArray"](status_list=[m["action_msgs/msg/GoalStatus"](goal_info=info,
                                                                                               status=status)])


def test_each_plan_and_execute_goal_becomes_a_move_arm_task(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, MGI, INFO, "Plan and Execute request accepted")
    b.log(T0 + sec_ns(3), MGI, INFO, "Plan and Execute request complete!")
    b.log(T0 + sec_ns(5), MGI, INFO, "Plan and Execute request accepted")
    b.log(T0 + sec_ns(6), "moveit.ompl_planning.model_based_planning_context", ERROR,
          "Unable to solve the planning problem")
    b.log(T0 + sec_ns(7), MGI, INFO, "Plan and Execute request aborted")
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [(t.task_id, t.skills[0].skill, t.outcome) for t in tasks] == [
        ("moveit-goal-1", "move_arm", "succeeded"), ("moveit-goal-2", "move_arm", "failed")]
    assert tasks[1].skills[0].error_msg == "Plan and Execute request aborted"
    assert tasks[0].instruction == "Move the arm (derived from MoveIt)"


def test_a_controllers_goal_status_topic_alone_gives_its_task(tmp_path: Path) -> None:
    b = BagBuilder()
    topic = "/arm_controller/follow_joint_trajectory/_action/status"
    b.raw(T0, topic, c.GOAL_STATUS_TYPE, _status_msg(T0, 7, 2))
    b.raw(T0 + sec_ns(2), topic, c.GOAL_STATUS_TYPE, _status_msg(T0, 7, 6))
    b.log(T0 + sec_ns(1), "some_node", INFO, "hello")
    path = b.write(tmp_path / "run")
    tasks = read_tasks(path).tasks
    assert [(t.skills[0].skill, t.outcome, t.skills[0].params["derived_from"]) for t in tasks] == [
        ("follow_joint_trajectory", "failed", "action status")]
    log = read_recording(path)
    assert {s.topic for s in log.goal_statuses} == {topic}


def test_nav2_goals_stay_nav2_tasks_when_no_arm_goal_is_recorded(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (2.00, 1.00)")
    b.log(T0 + sec_ns(5), "bt_navigator", INFO, "Goal succeeded")
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [t.skills[0].skill for t in tasks] == ["navigate_to_pose"]


def test_a_device_the_os_would_not_open_or_a_drivers_lone_error_gives_a_bring_up_task(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "v4l2_camera", ERROR, "Cannot open '/dev/video0': 13, Permission denied")
    tasks = read_recording(b.write(tmp_path / "a")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("bring_up_controllers", "failed")]
    b = BagBuilder()
    b.log(T0, "ydlidar_ros2_driver_node", ERROR, "Unknown error")  # a device driver's: the robot's start failed
    tasks = read_recording(b.write(tmp_path / "b")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("bring_up_controllers", "failed")]


def test_a_catalogued_controller_manager_error_without_a_cause_still_gives_a_failed_arm_task(tmp_path: Path) -> None:
    # controller_manager.cpp's "After configuring, controller ... expected inactive." names no cause of its own
    b = BagBuilder()
    b.log(T0, "controller_manager", INFO, "Loading controller 'arm_controller'")
    line = "After configuring, controller 'arm_controller' is in state 'unconfigured' , expected inactive."
    b.log(T0 + sec_ns(1), "controller_manager", ERROR, line)
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [(t.skills[0].skill, t.outcome, t.skills[0].error_msg) for t in tasks] == [
        ("follow_joint_trajectory", "failed", line)]


def _died(cmd: str) -> str:
    # launch/launch/actions/execute_local.py: "process has died [pid {}, exit code {}, cmd '{}']."
    return f"process has died [pid 251, exit code 127, cmd '{cmd} --ros-args']."


def test_the_arms_own_process_dying_is_a_bring_up_task_not_a_navigation_one(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "launch", INFO, "All log files can be found below /root/.ros/log")
    b.log(T0 + sec_ns(1), "ros2_control_node-1", ERROR,
          _died("/opt/ros/rolling/lib/controller_manager/ros2_control_node"))
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("bring_up_controllers", "failed")]


def test_a_nav2_process_dying_stays_navigations(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "launch", INFO, "All log files can be found below /root/.ros/log")
    b.log(T0 + sec_ns(1), "controller_server-1", ERROR,
          _died("/opt/ros/humble/lib/nav2_controller/controller_server"))
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [(t.skills[0].skill, t.skills[0].params["source"]) for t in tasks] == [("navigate_to_pose", "nav2")]


def _lifecycle(b: BagBuilder, node: str) -> None:
    # rcl_lifecycle.c, rclcpp_lifecycle and launch_ros/actions/lifecycle_node.py lines of an activate sent early
    b.log(T0, "rcl_lifecycle", 30, "No transition matching 3 found for current state unconfigured")
    b.log(T0 + sec_ns(0.01), node.strip("/").replace("/", "."), ERROR,
          "Unable to start transition 3 from current state unconfigured: Transition is not registered., at "
          "./src/rcl_lifecycle.c:355")
    b.log(T0 + sec_ns(0.02), "launch_ros.actions.lifecycle_node", ERROR,
          f"Failed to make transition 'TRANSITION_ACTIVATE' for LifecycleNode '{node}'")


def test_a_drivers_lifecycle_node_that_failed_its_transition_is_a_bring_up_task_not_navigations(
        tmp_path: Path) -> None:
    b = BagBuilder()
    _lifecycle(b, "/camera/camera_driver")
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("bring_up_controllers", "failed")]


def test_a_nav2_lifecycle_node_that_failed_its_transition_stays_navigations(tmp_path: Path) -> None:
    b = BagBuilder()
    _lifecycle(b, "/controller_server")
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [t.skills[0].params["source"] for t in tasks] == ["nav2"]


# pluginlib's class_loader_imp.hpp: "According to the loaded plugin descriptions the class %s with base class type %s
# does not exist. Declared types are %s" — logged by whichever node loads the plugin.
def _no_plugin(cls: str, base: str) -> str:
    return (f"According to the loaded plugin descriptions the class {cls} with base class type {base} does not exist. "
            "Declared types are  mock_components/GenericSystem")


def test_a_hardware_plugin_the_controller_manager_cannot_load_is_never_a_navigation_task(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "resource_manager", INFO, "Loading hardware 'ethercat_arm'")
    b.log(T0 + sec_ns(0.1), "resource_manager", ERROR,
          _no_plugin("ethercat_driver/EthercatDriver", "hardware_interface::SystemInterface"))
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert all(t.skills[0].params["source"] != "nav2" for t in tasks)


def test_the_same_pluginlib_line_from_a_nav2_node_stays_navigations(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "bt_navigator", ERROR, _no_plugin("nav2_custom/MyCondition", "BT::ConditionNode"))
    tasks = read_recording(b.write(tmp_path / "run")).tasks
    assert [t.skills[0].params["source"] for t in tasks] == ["nav2"]


def test_a_line_of_no_node_in_nav2s_words_is_the_arms_where_only_the_arms_nodes_logged(tmp_path: Path) -> None:
    # a console wrapped line by line (hsr-ros2 docs): the abort names no node, and "Failed to configure" is a text
    # Nav2's lifecycle manager logs too; the one node that logged is the controller manager
    b = BagBuilder()
    b.log(T0, "controller_manager", FATAL,
          "System cannot communicate with servo motors. Error message: Permission denied")
    b.log(T0 + sec_ns(0.1), "", ERROR, "terminate called after throwing an instance of 'std::runtime_error'\n"
                                       "what():  Failed to configure 'hsrb'")
    (task,) = read_recording(b.write(tmp_path / "run")).tasks
    assert task.skills[0].skill != "navigate_to_pose"
    assert task.created == T0  # the window opens at the controller manager's own line, which says why


def test_the_same_line_of_no_node_beside_a_nav2_node_stays_navigations(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "lifecycle_manager_navigation", INFO, "Configuring controller_server")
    b.log(T0 + sec_ns(0.1), "", ERROR, "terminate called after throwing an instance of 'std::runtime_error'\n"
                                       "what():  Failed to configure 'controller_server'")
    (task,) = read_recording(b.write(tmp_path / "run")).tasks
    assert task.skills[0].skill == "navigate_to_pose"


# frankarobotics/franka_ros2#205 (heldout11, spent): launch failed on a move_group description, naming nothing of Nav2
FRANKA_LAUNCH = ("Caught exception in launch (see debug for traceback): launch configuration 'namespace' does not "
                 "exist")
# ROBOTIS-GIT/turtlebot3#945 (Humble): launch failed on the navigation's own parameters file
TB3_LAUNCH = ("Caught exception in launch (see debug for traceback): while parsing a block mapping\n  in \"/opt/ros/"
              "humble/share/turtlebot3_navigation2/param/waffle.yaml\", line 2, column 3")


def test_a_launch_that_failed_naming_nothing_of_nav2_is_the_robots_start_not_a_navigation(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0, "launch", ERROR, FRANKA_LAUNCH)
    tasks = read_recording(b.write(tmp_path / "a")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("bring_up_controllers", "failed")]
    b = BagBuilder()
    b.log(T0, "launch", ERROR, TB3_LAUNCH)  # the same failure, of the navigation's description
    tasks = read_recording(b.write(tmp_path / "b")).tasks
    assert [(t.skills[0].skill, t.outcome) for t in tasks] == [("navigate_to_pose", "failed")]


# ros-controls/ros2_control#1932 (heldout11, spent): the spawner's FATAL (controller_manager_services.py:292@iron),
# whose words MoveIt's looser "Controller … not found" (trajectory_execution_manager.cpp:808@jazzy) also matches
SPAWNER_FATAL = ("Controller : /my_controller parameters not found in parameter file : /home/user/workspace/my_ws/"
                 "install/app_bringup/share/app_bringup/config/my_controller_params.yaml")


def test_a_spawners_line_is_ros2_controls_to_read_not_moveits(tmp_path: Path) -> None:
    from hexar.explainers.control.catalogue import catalogue as control
    from hexar.explainers.logcause import read
    from hexar.explainers.manipulation.catalogue import catalogue as moveit

    b = BagBuilder()
    b.log(T0, "spawner_my_controller", FATAL, SPAWNER_FATAL)
    log = read_recording(b.write(tmp_path / "a"))
    assert [(t.skills[0].skill, t.outcome) for t in log.tasks] == [("follow_joint_trajectory", "failed")]
    [reading] = read(log.logs, [moveit(), control()])
    assert reading.cause is None and reading.catalogue == control().name


def test_move_groups_result_code_said_alone_ends_its_goal(tmp_path: Path) -> None:
    # real_modules heldout2, mogi-simple-arm: move_action logs getActionResultString's default, the code's name
    case = next(e for e in load_excerpts("real-modules-heldout2")
                if e.id == "mogi-simple-arm-move-group-without-sim-time")
    tasks = read_recording(write_recording(case, tmp_path / "run", task=False)).tasks
    assert [(t.skills[0].skill, t.outcome, t.skills[0].error_msg) for t in tasks] == [
        ("move_arm", "failed", "CONTROL_FAILED")]
