"""The control explainer on real rosbag2 recordings of ros2_control's own lines (controller_manager, spawner,
resource manager, joint_trajectory_controller: texts of ros2_control_catalogue.json)."""

from __future__ import annotations

from pathlib import Path

from hexar.causes import stated_causes
from hexar.claims import read_claims
from hexar.events.records import ERROR, FATAL, INFO, WARN
from hexar.explainers.base import Explanation
from tests.explainers.helpers import explain, write_lines


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]], skill: str = "follow_joint_trajectory"
             ) -> Explanation:
    task, found = explain(write_lines(tmp_path, lines), "control", "Why didn't the arm move?")
    assert task.derived and task.skills[0].skill == skill
    return found


def test_the_controller_managers_line_is_the_cause_and_the_spawners_its_symptom(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'joint_state_broadcaster'"),
        (0.1, "controller_manager", ERROR, "Loader for controller 'joint_state_broadcaster' (type "
                                            "'joint_state_broadcaster/JointStateBroadcaster') not found."),
        (0.2, "spawner_joint_state_broadcaster", FATAL, "Failed loading controller joint_state_broadcaster")])
    assert found.causes == ["control.controller_load_failed"]
    assert found.evidence[0].item.startswith("[controller_manager] ERROR Loader for controller")
    assert "it was not loaded, as the controller's plugin type is not installed" in found.text
    assert "package.xml" in (found.fix or "")


def test_switch_timeout_is_an_activation_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR, "Switch controller timed out after 5.000000 seconds!"),
        (0.1, "spawner_joint_state_broadcaster", ERROR, "Failed to activate controller")])
    assert found.causes == ["control.controller_activation_failed"]
    assert "could not be activated" in found.text


def test_a_hardware_exception_while_configuring_is_a_hardware_failure(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager.resource_manager", ERROR,
         "Exception of type : N9LibSerial10OpenFailedE occurred while configuring hardware 'RobotSystem': "
         "Bad file descriptor")])
    assert found.causes == ["control.hardware_failure"]


def test_foxys_loader_line_without_its_full_stop_is_still_a_load_failure(tmp_path: Path) -> None:
    # ros2_control 0.1.0 controller_manager.cpp:170 printed "Loader for controller '%s' not found" (no full stop)
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'cart_pole_controller'"),
        (0.1, "controller_manager", ERROR, "Loader for controller 'cart_pole_controller' not found")])
    assert found.causes == ["control.controller_load_failed"]


def test_a_message_printed_on_the_line_after_its_header_is_read(tmp_path: Path) -> None:
    # controller_manager.cpp:715@humble "The 'type' param was not defined for '%s'.", its text on the next line
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR, "\nThe 'type' param was not defined for 'arm_controller'.")])
    assert found.causes == ["control.controller_load_failed"]


def test_a_tolerance_abort_without_the_joints_error_lines_names_no_cause(tmp_path: Path) -> None:
    # from humble on, joint_trajectory_controller logs the joint and its error before "Aborted due to state
    # tolerance violation" (tolerances.hpp: "State tolerances failed for joint %zu:"); without them the abort says
    # only that the arm did not follow, not why (a driver not connected, a firewall)
    found = _explain(tmp_path, [
        (0, "scaled_joint_trajectory_controller", INFO, "Received new action goal"),
        (0.01, "scaled_joint_trajectory_controller", INFO, "Accepted new action goal"),
        (1.0, "scaled_joint_trajectory_controller", WARN, "Aborted due to state tolerance violation")])
    assert found.causes == ["control.unexplained_failure"]
    assert "tolerance" not in found.text.lower() and "do not show a cause I know" in found.text
    assert "scaled_joint_trajectory_controller at 1.0 s" in found.text
    assert any("Aborted due to state tolerance violation" in d for d in found.details)


def test_a_tolerance_abort_after_the_joints_error_lines_is_a_tolerance_violation(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "joint_trajectory_controller", INFO, "Accepted new action goal"),
        (1.9, "tolerances", ERROR, "State tolerances failed for joint 4:"),
        (1.9, "tolerances", ERROR, "Position Error: 0.250937, Position Tolerance: 0.250000"),
        (1.91, "joint_trajectory_controller", WARN, "Aborted due to state tolerance violation")])
    assert found.causes == ["control.tolerance_violated"]
    assert found.evidence[0].item.startswith("[tolerances] ERROR State tolerances failed for joint 4")


def _died(code: int) -> str:
    # launch/launch/actions/execute_local.py: "process has died [pid {}, exit code {}, cmd '{}']."
    return (f"process has died [pid 159, exit code {code}, cmd '/opt/ros/humble/lib/controller_manager/"
            "ros2_control_node --ros-args --params-file /tmp/launch_params_6hguf5xf'].")


def test_a_crash_by_a_signal_is_quoted_not_told_as_the_cause(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'joint_state_broadcaster'"),
        (0.5, "ros2_control_node-1", INFO, "Requested 8 bytes, but only got 0."),
        (1.0, "ros2_control_node-1", ERROR, _died(-11))], skill="bring_up_controllers")
    assert found.causes == ["control.unexplained_failure"]
    assert "exit code -11" in found.text and "do not show a cause I know" in found.text
    assert "died" not in found.text.split("The first error")[0]


def test_the_ur_drivers_calibration_error_is_its_set_up_not_a_controllers_interfaces(tmp_path: Path) -> None:
    # Universal_Robots_ROS2_Driver ur_robot_driver/src/hardware_interface.cpp:776@humble, first sentence only (the
    # driver's documentation prints it so; later releases add advice after it)
    found = _explain(tmp_path, [
        (0, "URPositionHardwareInterface", INFO, "Calibration checksum: 'calib_12788084448423163542'"),
        (0.1, "URPositionHardwareInterface", ERROR, "The calibration parameters of the connected robot don't match "
                                                    "the ones from the given kinematics config file.")])
    assert found.causes == ["control.configuration_error"]
    assert "calibration given to the UR driver" in found.text


def test_a_robot_the_ur_driver_cannot_reach_is_a_hardware_failure(tmp_path: Path) -> None:
    # Universal_Robots_Client_Library include/ur_client_library/comm/producer.h:128@master (the exception's text)
    found = _explain(tmp_path, [
        (0, "UR_Client_Library:", ERROR, "Failed to connect to robot. Please check if the robot is booted and "
                                          "connected.")])
    assert found.causes == ["control.hardware_failure"]


def test_a_process_that_could_not_start_is_told_as_a_process_that_died(tmp_path: Path) -> None:
    # exit code 127: the loader gave up (a library's symbol missing), not a crash in the program's own work
    found = _explain(tmp_path, [
        (0, "ros2_control_node-1", INFO, "/opt/ros/rolling/lib/controller_manager/ros2_control_node: symbol lookup "
                                         "error: /opt/ros/rolling/lib/libfoo.so: undefined symbol: _ZN3foo3barEv"),
        (0.1, "ros2_control_node-1", ERROR, _died(127))], skill="bring_up_controllers")
    assert found.causes == ["bringup.process_died"]


def test_a_controller_manager_without_a_clock_is_a_use_sim_time_set_up(tmp_path: Path) -> None:
    # controller_manager.cpp:3402@master
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR, "No clock received, and time argument is zero. Check your controller_manager "
                                         "node's clock configuration (use_sim_time parameter) and if a valid clock "
                                         "source is available")])
    assert found.causes == ["bringup.configuration_error"] and "use_sim_time" in found.text


def test_a_ur_driver_that_cannot_reach_the_robot_says_why_in_its_details(tmp_path: Path) -> None:
    # Universal_Robots_Client_Library src/rtde/rtde_client.cpp:910@master
    found = _explain(tmp_path, [
        (0, "UR_Client_Library:", ERROR, "Failed to initialize RTDE client after 5 attempts, unable to reconnect")])
    assert found.causes == ["control.hardware_failure"]
    assert any("RTDE interface" in d for d in found.details)


def test_a_controller_manager_still_waiting_for_its_robot_description_names_no_cause(tmp_path: Path) -> None:
    # controller_manager.cpp:769@jazzy warns each second until its resource manager is initialised: no description
    # arrived, or one arrived and its hardware failed to load (:789); the spawner's controller_manager_services.py
    # :150@jazzy follows. Which of the two is not in these lines, so none is claimed.
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'joint_state_broadcaster'"),
        (1, "controller_manager", WARN, "Waiting for data on 'robot_description' topic to finish initialization"),
        (11, "spawner_joint_state_broadcaster", ERROR,
         "Could not contact service /controller_manager/list_controllers")], skill="follow_joint_trajectory")
    assert found.causes == ["control.unexplained_failure"] and "do not show a cause I know" in found.text
    assert "never reached" not in found.text
    assert any("no robot description arrived" in d and "failed to load" in d for d in found.details)



def test_a_hardware_read_error_with_older_spacing_is_still_a_hardware_failure(tmp_path: Path) -> None:
    # ros2_control PR 1645 (July 2024) printed "… resulted in an error : [ %s]"; controller_manager.cpp:3293@jazzy
    # prints "… resulted in an error: [ %s]": the same words
    found = _explain(tmp_path, [
        (0, "test_controller_manager", INFO, "Loading controller 'test_controller'"),
        (1.0, "test_controller_manager", ERROR, "Deactivating following hardware components as their read cycle "
                                                "resulted in an error : [ TestActuatorHardware TestSystemHardware ]")])
    assert found.causes == ["control.hardware_failure"]
    assert "a hardware interface failed" in found.text


def test_a_hardware_plugin_not_among_the_installed_descriptions_is_a_set_up_error(tmp_path: Path) -> None:
    # hardware_interface's "Caught exception of type : … while loading hardware: …" around pluginlib's
    # LibraryLoadException text (pluginlib class_loader_imp.hpp): the URDF names a class no package declares
    found = _explain(tmp_path, [
        (0, "controller_manager", ERROR,
         "Caught exception of type : N9pluginlib20LibraryLoadExceptionE while loading hardware: According to the "
         "loaded plugin descriptions the class  joint_state_topic_hardware_interface/JointStateTopicSystem\n"
         " with base class type hardware_interface::SystemInterface does not exist. Declared types are  "
         "mock_components/GenericSystem")])
    assert found.causes == ["control.configuration_error"]
    assert "not among the installed plugin descriptions" in found.text
    assert "hardware interface failed" not in found.text


def test_a_spawner_that_exited_with_an_error_is_a_symptom_not_a_process_that_died(tmp_path: Path) -> None:
    # controller_manager/controller_manager/spawner.py:435@jazzy returns 1 when its controller fails: launch's death
    # line of the spawner tells that failure, not a running process lost
    found = _explain(tmp_path, [
        (0, "spawner-4", ERROR, "process has died [pid 63239, exit code 1, cmd '/opt/ros/jazzy/lib/"
                                "controller_manager/spawner joint_trajectory_controller --ros-args -r "
                                "__node:=spawn_joint_trajectory_controller']."),
        (0.1, "controller_manager", INFO, "Configuring controller: 'gripper_controller'")],
        skill="bring_up_controllers")
    assert "bringup.process_died" not in found.causes
    assert found.causes == ["control.unexplained_failure"]
    assert "processes died" not in found.text


def test_a_hardware_transition_that_failed_without_a_reason_is_quoted_with_its_candidates(tmp_path: Path) -> None:
    # hardware_interface/src/resource_manager.cpp:68@jazzy: logged whenever the component's transition fails, so
    # a device out of reach and a set-up that does not fit the robot end alike
    found = _explain(tmp_path, [
        (0, "resource_manager", INFO, "Loading hardware 'iisy_hardware'"),
        (0.1, "resource_manager", ERROR, "Failed to 'configure' hardware 'iisy_hardware'")])
    assert found.causes == ["control.unexplained_failure"]
    assert "Failed to 'configure' hardware 'iisy_hardware'" in found.text and "either" in found.text
    assert "a hardware interface failed" not in found.text


def test_an_earlier_reason_still_decides_before_a_failed_hardware_transition(tmp_path: Path) -> None:
    # Universal_Robots_Client_Library producer.h:128@master, then resource_manager.cpp:68@jazzy
    found = _explain(tmp_path, [
        (0, "UR_Client_Library:", ERROR, "Failed to connect to robot. Please check if the robot is booted and "
                                          "connected."),
        (0.1, "resource_manager", ERROR, "Failed to 'configure' hardware 'ur'")])
    assert found.causes == ["control.hardware_failure"]


def test_a_required_list_left_empty_is_a_parameter_that_never_reached_the_controller(tmp_path: Path) -> None:
    # generate_parameter_library cpp_conversions.py:123@main wraps RSL's size_gt text; the joint trajectory
    # controller's joints default to [] with size_gt<>: [0] (joint_trajectory_controller_parameters.yaml:2@master)
    found = _explain(tmp_path, [
        (0, "lbr.controller_manager", INFO, "Loading controller 'joint_trajectory_controller'"),
        (0.01, "lbr.controller_manager", ERROR,
         "Exception thrown during init stage with message: Invalid value set during initialization for parameter "
         "'joints': Length of parameter 'joints' is '0' but must be greater than '0'"),
        (0.02, "lbr.controller_manager", ERROR, "Could not initialize the controller named "
                                                "'joint_trajectory_controller'")])
    assert found.causes == ["bringup.configuration_error"]
    assert "never reached" in found.text and "--param-file" in found.text


def test_a_ros2_without_its_control_command_never_loaded_the_controller(tmp_path: Path) -> None:
    # argparse's "invalid choice" from ros2cli: no installed package adds the 'control' command
    # (ros2controlcli/setup.py:49@jazzy registers it), so `ros2 control load_controller` never ran
    found = _explain(tmp_path, [
        (0, "ros2", ERROR, "error: argument Call `ros2 <command> -h` for more detailed usage.: invalid choice: "
                           "'control' (choose from 'action', 'bag', 'component', 'daemon', 'doctor', 'launch')")])
    assert found.causes == ["control.controller_load_failed"]
    assert "`ros2 control` command itself is not installed" in found.text
    assert "type is not installed" not in found.text


def test_ros2_control_4_16s_hardware_exception_wording_is_a_hardware_failure(tmp_path: Path) -> None:
    # ros-controls/ros2_control#1719 (heldout5, spent): resource_manager.cpp:206@ce58faea3 (4.16.1), before #1749
    # put the exception's type into the line
    found = _explain(tmp_path, [
        (0, "controller_manager.resource_manager", ERROR,
         "Exception occurred while initializing hardware 'ros2_control_tiago_system': std::bad_alloc")])
    assert found.causes == ["control.hardware_failure"]


def test_a_second_load_is_no_load_failure_and_activating_an_unconfigured_controller_fails(tmp_path: Path) -> None:
    # controller_manager.cpp@humble: :1420 a second load of a name it holds (the first stays loaded); :1080 a
    # controller asked to activate while not inactive (loaded, never configured) cannot be
    found = _explain(tmp_path, [
        (0, "controller_manager", INFO, "Loading controller 'joint_trajectory_controller'"),
        (0.1, "controller_manager", ERROR, "A controller named 'joint_trajectory_controller' was already loaded "
                                           "inside the controller manager"),
        (0.2, "controller_manager", INFO, "Activating controllers: [ joint_trajectory_controller ]"),
        (0.3, "controller_manager", WARN, "Controller with name 'joint_trajectory_controller' is not inactive so its "
                                          "following controllers do not have to be checked, because it cannot be "
                                          "activated.")])
    assert found.causes == ["control.controller_activation_failed"]
    assert "could not be activated" in found.text and "not loaded" not in found.text


def test_gazebo_that_could_not_load_its_ros2_control_plugin_is_a_set_up_error(tmp_path: Path) -> None:
    # idra-lab/z1_ros2#11 (held-out 6, spent): gz-sim's SystemLoader.cc could not find ign_ros2_control's library
    # (its package not installed), so no controller manager came up and the spawners waited for its services
    found = _explain(tmp_path, [
        (0, "", ERROR, "[Err] [SystemLoader.cc:94] Failed to load system plugin [libign_ros2_control-system.so] : "
                       "couldn't find shared library."),
        (8, "spawner_joint_state_broadcaster", WARN, "Could not contact service /controller_manager/list_controllers"),
        (8.1, "spawner_joint_state_broadcaster", INFO,
         "waiting for service /controller_manager/list_controllers to become available...")])
    assert found.causes == ["control.configuration_error"]
    assert "Gazebo could not load its ros2_control system plugin" in found.text
    assert "GZ_SIM_SYSTEM_PLUGIN_PATH" in found.text


def test_a_controller_that_needs_an_interface_the_hardware_lacks_says_so(tmp_path: Path) -> None:
    # UniversalRobots/Universal_Robots_ROS2_Driver#327 (held-out 2, spent): fake hardware exports no speed scaling
    missing = _explain(tmp_path / "missing", [
        (0, "controller_manager", ERROR, "Can't activate controller 'scaled_joint_trajectory_controller': State "
                                         "interface with key 'speed_scaling/speed_scaling_factor' does not exist")])
    assert missing.causes == ["control.controller_activation_failed"]
    assert "could not be activated: it needs an interface my hardware does not provide" in missing.text
    # moveit/moveit2#2698 (corpus): two controllers claiming one joint's command interface
    claimed = _explain(tmp_path / "claimed", [
        (0, "controller_manager", ERROR, "Resource conflict for controller 'both_arm_controller'. Command interface "
                                         "'robot_joint1_l/position' is already claimed.")])
    assert claimed.causes == ["control.controller_activation_failed"]
    assert "another active controller already claims the command interface" in claimed.text
    # with no reason on the line, the clause keeps its general words
    switch = "Switch controller timed out after 5.000000 seconds!"
    timed_out = _explain(tmp_path / "timed_out", [(0, "controller_manager", ERROR, switch)])
    assert "switching my controllers took too long" in timed_out.text


def test_spawners_that_never_reached_a_controller_manager_name_what_hosts_it(tmp_path: Path) -> None:
    # ZeinBarhoum/chess_manipulator#5 (heldout10.yaml), as its console printed it: both spawners waited for the
    # controller manager, then gave up (spawner.py:120@foxy); gazebo_ros2_control, which hosts it, was not installed
    waiting = "Waiting for '/controller_manager' node to exist"
    found = _explain(tmp_path, [
        (0, "spawner_joint_trajectory_controller", INFO, waiting),
        (0.02, "spawner_joint_state_broadcaster", INFO, waiting),
        (6.0, "spawner_joint_trajectory_controller", INFO, waiting),
        (6.02, "spawner_joint_state_broadcaster", INFO, waiting),
        (8.0, "spawner_joint_trajectory_controller", ERROR, "Controller manager not available"),
        (8.02, "spawner_joint_state_broadcaster", ERROR, "Controller manager not available")])
    assert found.causes == ["control.unexplained_failure"]
    assert "Controller manager not available" in found.text
    assert "never appeared" in found.text and "ros2_control_node" in found.text and "gz_ros2_control" in found.text
    assert "a controller's settings" not in found.text  # no controller was ever asked for
    assert not set(stated_causes(found.text)) - {"control.unexplained_failure", "claim.task_failed"}


# libstdc++'s verbose terminate handler, as ur_robot_driver's console printed it (Universal_Robots_ROS2_Driver#677)
_UNCAUGHT = ("terminate called after throwing an instance of 'std::runtime_error'\n"
             "  what():  Wrong state or command interface configuration.\nmissing state interfaces:")


def test_an_uncaught_exception_is_a_process_that_died_with_its_what(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "resource_manager", INFO, "Successful initialization of hardware 'bmt_1'"),
        (0.1, "resource_manager", INFO, "Successful initialization of hardware 'bmt_1'\n" + _UNCAUGHT)],
        skill="bring_up_controllers")
    assert found.causes == ["bringup.process_died"]
    assert "bringup.process_died" in stated_causes(found.text)
    assert found.text == ("Starting my drivers and controllers failed because one of my processes died of an uncaught "
                          "C++ exception (std::runtime_error), so the software it ran was gone: “[resource_manager] "
                          "Wrong state or command interface configuration.”.")


def test_an_exception_printed_as_a_line_of_no_node_is_the_process_of_the_line_before(tmp_path: Path) -> None:
    # a console wrapped line by line: the abort names no node, after move_group's own lines (moveit2_tutorials#864)
    found = _explain(tmp_path, [
        (0, "move_group.moveit.cartesian_path_service_capability", INFO, "Received request to compute Cartesian "
                                                                          "path"),
        (0.1, "", INFO, "terminate called after throwing an instance of 'std::invalid_argument'\n"
                        "  what():  invalid argument passed")], skill="bring_up_controllers")
    assert found.causes == ["bringup.process_died"]
    assert "(std::invalid_argument), so the software it ran was gone: “[unnamed node] invalid argument passed”" \
        in found.text
    assert read_claims(found.text).affirmed == {"bringup.process_died"}  # "invalid argument" is the log's word


def test_an_unexplained_error_before_the_exception_is_quoted_not_the_death(tmp_path: Path) -> None:
    found = _explain(tmp_path, [
        (0, "resource_manager", INFO, "Loading hardware 'arm'"),
        (0.1, "resource_manager", ERROR, "Something odd happened to 'arm'"),
        (0.2, "resource_manager", INFO, "Loading hardware 'arm'\n" + _UNCAUGHT)], skill="bring_up_controllers")
    assert found.causes == ["control.unexplained_failure"]
    assert "Something odd happened" in found.text and "died" not in found.text


def test_a_drivers_error_on_the_line_of_the_abort_is_quoted_before_the_death(tmp_path: Path) -> None:
    # the feetech driver's console (moveit_pro_example_ws#930): its own error, then the abort, on one record
    found = _explain(tmp_path, [
        (0, "FeetechHardware", INFO, "Connecting to port: /dev/so101_follower"),
        (0.1, "FeetechHardware", ERROR, "FeetechHardware::on_init -> Open [/dev/so101_follower]: Bad file "
                                        "descriptor\nterminate called after throwing an instance of "
                                        "'LibSerial::NotOpen'\n  what():  Serial port not open.")],
        skill="bring_up_controllers")
    assert "bringup.process_died" not in found.causes
    assert "Bad file descriptor" in found.text and "died" not in found.text


def test_rclcpps_exception_for_times_of_two_clocks_is_told_by_its_meaning_not_as_a_death(tmp_path: Path) -> None:
    # ros-controls/ros2_control_demos#755 (held-out 19, spent): Gazebo aborted inside gz_ros2_control's update on
    # rclcpp's time comparison (whether a setting or code mixed the clocks, the lines do not say); the stack trace
    # names the plugin's library at the frame that threw, which shows it loaded, not that it could not be
    frame = ('#9    Object "/ws/install/gz_ros2_control/lib/libgz_ros2_control-system.so", at 0x7d5daa9717c5, in '
             "gz_ros2_control::GazeboSimROS2ControlPlugin::PostUpdate(gz::sim::v8::UpdateInfo const&, "
             "gz::sim::v8::EntityComponentManager const&)")
    lines = [(0, "resource_manager", INFO, "Loading hardware 'RRBot'"),
             (1, "", INFO, "terminate called after throwing an instance of 'std::runtime_error'\n"
                           "  what():  can't compare times with different time sources"),
             (1.1, "", INFO, frame)]
    found = _explain(tmp_path, lines, skill="bring_up_controllers")
    assert found.causes == ["control.unexplained_failure"]
    assert "“[unnamed node] can't compare times with different time sources”" in found.text
    assert "two times from different clocks met" in found.text and "died" not in found.text
    assert "could not load its ros2_control system plugin" not in found.text
    assert not read_claims(found.text).affirmed - {"claim.task_failed"}


# ROBOTIS-GIT/open_manipulator#364 (Jazzy, heldout21, spent): the hardware's on_init indexed an empty list read from
# the ros2_control tag; the reporter fixed it by reverting the xacro that writes that tag
OUT_OF_RANGE = ("Exception of type : St12out_of_range occurred while initializing hardware 'OpenManipulatorXSystem': "
                "vector::_M_range_check: __n (which is 0) >= this->size() (which is 0)")


def test_an_index_out_of_range_while_initializing_hardware_is_its_description_not_its_device(tmp_path: Path) -> None:
    found = _explain(tmp_path, [(0, "controller_manager", ERROR, OUT_OF_RANGE)])
    assert found.causes == ["control.configuration_error"]
    assert "looked up something the ros2_control tag of my robot description does not give it" in found.text
    assert {c for c in read_claims(found.text).affirmed if not c.startswith("claim.")} == {
        "control.configuration_error"}


def test_a_value_the_hardware_could_not_convert_is_its_description_and_other_exceptions_its_device(
        tmp_path: Path) -> None:
    # libstdc++'s std::stod throws invalid_argument("stod") for a text that is no number
    found = _explain(tmp_path / "a", [(0, "controller_manager", ERROR, "Exception of type : St16invalid_argument "
                                       "occurred while initializing hardware 'RobotSystem': stod")])
    assert found.causes == ["control.configuration_error"] and "not a number" in found.text
    found = _explain(tmp_path / "b", [(0, "controller_manager", ERROR, "Exception of type : St13runtime_error "
                                       "occurred while initializing hardware 'RobotSystem': Failed to open port")])
    assert found.causes == ["control.hardware_failure"]


def test_a_completed_slow_motion_quotes_what_the_controller_warned_on_the_way(tmp_path: Path) -> None:
    # scripts/lifecycle_faults.py's control loop that kept 37-38 of its 100 updates a second (held-out set 29),
    # under a task whose trajectory step completed: asked why it took so long, the answer quotes the warning
    from hexar.evals.real_modules import QUESTIONS, load_excerpts, write_recording
    from hexar.events import read_recording

    excerpt = next(e for e in load_excerpts("real-modules-heldout29")
                   if e.id == "kilted-control-loop-slower-than-update-rate")
    log = read_recording(write_recording(excerpt, tmp_path / "run", task=True))
    task, found = explain(log, "control", QUESTIONS["slow"])
    assert task.outcome == "succeeded" and found.causes == ["control.nominal"]
    assert ("My logs show a warning on the way, which did not stop it: “[base_controller] control loop missed its "
            "rate: 38 updates in 1.0 s, update_rate 100 Hz”") in found.text
    assert "(3 like it)" in found.text
    # the warning's words are quoted, not claimed: the answer affirms the motion's success and nothing else
    assert {c for c in read_claims(found.text).affirmed if not c.startswith("claim.")} == {"control.nominal"}


def test_a_completed_motion_without_warnings_says_nothing_more(tmp_path: Path) -> None:
    _, found = explain(write_lines(tmp_path, [
        (0, "joint_trajectory_controller", INFO, "Received new action goal"),
        (0.1, "joint_trajectory_controller", INFO, "Accepted new action goal"),
        (2.0, "joint_trajectory_controller", INFO, "Goal reached, success!")]), "control", "How did it go?")
    assert found.causes == ["control.nominal"] and "on the way" not in found.text
