"""The manipulation explainer on real rosbag2 recordings of MoveIt's own lines (texts of the mined catalogue,
moveit2 file:line@branch in moveit_catalogue.json): the earliest decisive line is the answer, symptoms never are,
an unknown error is quoted with its node and time, and a controller's line is told by the control explainer."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.events.records import ERROR, INFO, WARN
from hexar.explainers.manipulation.explainer import state_monitor_cause
from tests.explainers.helpers import explain, write_lines

MGI = "move_group_interface"


def _explain(tmp_path: Path, lines: list[tuple[float, str, int, str]], question: str = "Why did it fail?"):  # type: ignore[no-untyped-def]
    return explain(write_lines(tmp_path, lines), "manipulation", question)


def _aborted(at: float) -> list[tuple[float, str, int, str]]:
    return [(at, MGI, INFO, "Plan and Execute request aborted"),
            (at + 0.01, MGI, ERROR, "MoveGroupInterface::move() failed or timeout reached")]


def test_earliest_decisive_line_beats_the_symptoms_after_it(tmp_path: Path) -> None:
    task, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, "moveit.ompl_planning.model_based_planning_context", ERROR, "Unable to solve the planning problem"),
        *_aborted(2)])
    assert task.derived and task.skills[0].skill == "move_arm" and task.outcome == "failed"
    assert found.causes == ["manipulation.planning_failed"]
    assert found.evidence[0].item.endswith("Unable to solve the planning problem")
    assert "motion planner found no solution" in found.text
    assert any("consequence, not the cause" in d and "request aborted" in d for d in found.details)


def test_no_joint_states_and_a_time_mix_are_told_apart_by_the_state_monitor_numbers(tmp_path: Path) -> None:
    line = ("Didn't receive robot state (joint angles) with recent timestamp within 1.000000 seconds. "
            "Requested time {0}, but latest received state has time {1}.")
    assert state_monitor_cause(line.format("63.529000", "0.000000")) == "manipulation.no_joint_states"
    assert state_monitor_cause(line.format("1739369238.330760", "0.000000")) == "manipulation.stale_robot_state"
    _, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, "moveit_ros.current_state_monitor", INFO, line.format("1700000001.000000", "812.400000")),
        (1.1, MGI, ERROR, "Failed to fetch current robot state"), *_aborted(2)])
    assert found.causes == ["manipulation.stale_robot_state"]
    assert "wall-clock time were mixed" in found.text


# lbr-fri-ros2-stack#275 (real-modules corpus): the state monitor's line as that MoveIt printed it, no comma before
# "but", which no mined entry reads whole
LBR_MONITOR = ("Didn't receive robot state (joint angles) with recent timestamp within 1.000000 seconds Requested time "
               "{0} but latest received state has time {1}.")


@pytest.mark.parametrize(("monitor", "cause"), [
    (None, None),  # "Failed to fetch current robot state" pasted alone: either cause, and the answer says so
    (LBR_MONITOR.format("63.529000", "0.000000"), "manipulation.no_joint_states"),
    (LBR_MONITOR.format("1739369238.330760", "0.000000"), "manipulation.stale_robot_state"),
])
def test_failed_to_fetch_the_state_is_told_by_the_monitors_line_or_as_either_cause(
        tmp_path: Path, monitor: str | None, cause: str | None) -> None:
    lines = [(0, MGI, INFO, "Plan and Execute request accepted")]
    if monitor is not None:
        lines.append((1, "moveit_ros.current_state_monitor", INFO, monitor))
    _, found = _explain(tmp_path, [*lines, (1.1, MGI, ERROR, "Failed to fetch current robot state"), *_aborted(2)])
    claims = read_claims(found.text)
    if cause is None:
        assert found.causes == ["manipulation.no_joint_states"]
        assert "My logs do not show what it was" in found.text and "never received" not in found.text
        assert not claims.causes and found.fix is not None and "use_sim_time" in found.fix
    else:
        assert found.causes == [cause] and claims.causes == {cause}


def test_an_error_no_catalogue_knows_is_quoted_with_its_node_and_time_not_guessed(tmp_path: Path) -> None:
    _, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (3.5, "my_gripper_driver", ERROR, "gripper fingers jammed at 12 mm"), *_aborted(4)])
    assert found.causes == ["manipulation.unexplained_failure"]
    assert "do not show a cause I know" in found.text
    assert "“[my_gripper_driver] gripper fingers jammed at 12 mm” at 3.5 s" in found.text
    assert found.confidence < 0.5


def test_a_controller_tolerance_abort_is_told_by_the_control_explainer(tmp_path: Path) -> None:
    _, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, "arm_controller", INFO, "Received new action goal"),
        (2, "arm_controller", WARN, "Aborted due to state tolerance violation"),
        (2.1, "moveit.simple_controller_manager.follow_joint_trajectory_controller_handle", WARN,
         "Controller 'arm_controller' failed with error PATH_TOLERANCE_VIOLATED: "), *_aborted(2.5)])
    assert found.explainer == "manipulation" and found.causes == ["control.tolerance_violated"]
    assert "tolerance" in found.text
    assert found.details[0].startswith("I asked my control explainer")


def test_a_goal_that_completed_is_nominal_despite_warnings(tmp_path: Path) -> None:
    _, found = _explain(tmp_path, [
        (0, "moveit_ros.planning_scene_monitor", WARN,
         "The complete state of the robot is not yet known.  Missing BASE_TF_joint"),
        (1, MGI, INFO, "Plan and Execute request accepted"),
        (4, MGI, INFO, "Plan and Execute request complete!")], "How did it go?")
    assert found.causes == ["manipulation.nominal"]
    assert "without any problem" in found.text


# Real MoveIt 2 lines, each with its source (moveit/moveit2 file:line@branch), and the cause the answer names.
MOVEIT_LINES = [
    # model_based_planning_context.cpp:795@humble logs it at INFO, :779@main at ERROR
    ("moveit.ompl_planning.model_based_planning_context", INFO, "Unable to solve the planning problem",
     "manipulation.planning_failed", "motion planner found no solution"),
    # planning_pipeline.cpp:325@main "Planner '%s' failed with error code %s": the code names the failure
    ("moveit.ros.planning_pipeline", ERROR, "Planner 'ompl' failed with error code NO_IK_SOLUTION",
     "manipulation.ik_failed", "inverse kinematics"),
    # fix_start_state_collision.cpp:100@humble
    ("moveit_ros.fix_start_state_collision", INFO, "Start state appears to be in collision with respect to group arm",
     "manipulation.start_state_in_collision", "already in collision"),
    # model_based_planning_context.cpp:990@humble
    ("moveit.ompl_planning.model_based_planning_context", WARN, "Invalid goal state",
     "manipulation.goal_state_invalid", "goal itself was invalid"),
    # trajectory_execution_manager.cpp:1185@humble
    ("moveit_ros.trajectory_execution_manager", ERROR,
     "Unable to identify any set of controllers that can actuate the specified joints: [ joint_1 joint_2 ]",
     "manipulation.controllers_not_found", "found no controllers"),
    # trajectory_execution_manager.cpp:1173@humble
    ("moveit_ros.trajectory_execution_manager", ERROR, "Controller 'panda_arm_controller' is not known",
     "manipulation.controllers_not_found", "found no controllers"),
    # move_group_capability.cpp:148@humble, move_group's result text as the goal ends
    ("moveit_move_group_default_capabilities.move_action_capability", INFO,
     "Solution found but the environment changed during execution and the path was aborted",
     "manipulation.execution_failed", "executing the planned arm trajectory failed"),
]


@pytest.mark.parametrize(("logger", "level", "line", "cause", "words"), MOVEIT_LINES,
                         ids=[c for _, _, _, c, _ in MOVEIT_LINES])
def test_each_real_moveit_cause_line_names_its_cause(tmp_path: Path, logger: str, level: int, line: str,
                                                     cause: str, words: str) -> None:
    task, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (0.5, logger, level, line),
        (0.6, "moveit_move_group_default_capabilities.move_action_capability", INFO,
         "No motion plan found. No execution attempted."),
        *_aborted(1)])
    assert task.outcome == "failed"
    assert found.causes[0] == cause and words in found.text
    assert found.evidence[0].item.endswith(line)


def _one_line_goal(tmp_path, logger: str, level: int, msg: str):  # type: ignore[no-untyped-def]
    """A plan-and-execute goal accepted, one line of `logger`, then aborted: what the explainer finds."""
    return _explain(tmp_path, [(0, MGI, INFO, "Plan and Execute request accepted"), (0.6, logger, level, msg),
                               *_aborted(1)])[1]


def test_move_groups_result_text_alone_is_a_symptom_not_a_cause(tmp_path: Path) -> None:
    found = _one_line_goal(tmp_path, "moveit_move_group_default_capabilities.move_action_capability", INFO,
                           "No motion plan found. No execution attempted.")
    assert found.causes == ["manipulation.unexplained_failure"]
    assert "do not show a cause I know" in found.text


def test_move_groups_success_text_ends_the_goal_as_done(tmp_path: Path) -> None:
    task, found = _explain(tmp_path, [
        (0, "moveit_move_group_default_capabilities.move_action_capability", INFO,
         "Combined planning and execution request received for MoveGroup action. Forwarding to planning and "
         "execution pipeline."),
        (2, "moveit_move_group_default_capabilities.move_action_capability", INFO, "Solution was found and executed.")],
        question="How did it go?")
    assert task.outcome == "succeeded" and found.causes == ["manipulation.nominal"]


def test_a_warning_healthy_robots_print_too_is_quoted_not_told_as_the_cause_of_an_unfinished_run(
        tmp_path: Path) -> None:
    # planning_scene_monitor.cpp:1392@humble, a weak cause; no goal line and no error: no outcome to explain
    task, found = _explain(tmp_path, [
        (0, "moveit_ros.planning_scene_monitor.planning_scene_monitor", WARN,
         "The complete state of the robot is not yet known.  Missing gripper_joint")], question="How did it go?")
    assert task.outcome == "running" and found.causes == []
    assert "do not show whether anything went wrong" in found.text and "planning_scene_monitor" in found.text



def test_ompls_invalid_start_state_is_the_start_state_not_a_planner_that_found_nothing(tmp_path: Path) -> None:
    # ompl/src/ompl/base/src/Planner.cpp:248@main: within bounds, but MoveIt's validity check rejected the start
    ompl = "ompl"
    _task, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, ompl, WARN, "./src/ompl/base/src/Planner.cpp:248 - right_arm/right_arm: Skipping invalid start state "
                        "(invalid state)"),
        (1.01, ompl, ERROR, "./src/ompl/geometric/planners/rrt/src/RRTConnect.cpp:219 - right_arm/right_arm: Motion "
                            "planning start tree could not be initialized!"),
        (1.1, "moveit.ompl_planning.model_based_planning_context", INFO, "Unable to solve the planning problem"),
        *_aborted(2)])
    assert found.causes == ["manipulation.start_state_in_collision"]
    assert "Skipping invalid start state" in found.evidence[0].item
    assert "start state was rejected by OMPL" in found.text and "a collision, or a path constraint" in found.text


def test_task_constructors_start_state_in_collision_is_the_start_state(tmp_path: Path) -> None:
    # moveit_task_constructor core/src/solvers/joint_interpolation.cpp:79@master: a failing stage's comment
    _task, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, "test_execution-6", ERROR, "move (0/1): Start state is in collision!"),
        *_aborted(2)])
    assert found.causes == ["manipulation.start_state_in_collision"]
    assert "start state was in collision" in found.text


@pytest.mark.parametrize("lines", [
    # tiago_harmonic#14 (jazzy): check_start_state_bounds.cpp:174,189@main, an ERROR and the adapter's abort
    [("move_group.moveit.moveit.ros.check_start_state_bounds", ERROR,
      "Joint 'gripper_left_finger_joint' from the starting state is outside bounds by: [-1.09872e-14 ] should be in "
      "the range [0.001 ], [0.044 ]."),
     ("move_group", ERROR, "PlanningRequestAdapter 'CheckStartStateBounds' failed, because 'Start state out of "
                           "bounds.'. Aborting planning pipeline.")],
    # ARIAC#314 (humble): fix_start_state_bounds.cpp:160@humble, then OMPL's Planner.cpp:248 '(invalid bounds)'
    [("moveit_ros.fix_start_state_bounds", WARN,
      "Joint 'floor_gripper_joint' from the starting state is outside bounds by a significant margin: [-0.246719 ] "
      "should be in the range [-0.001 ], [0.001 ] but the error above the 'start_state_max_bounds_error' parameter "
      "(currently set to 0.050000)"),
     ("ompl", WARN, "./src/ompl/base/src/Planner.cpp:257 - floor_robot/floor_robot: Skipping invalid start state "
                    "(invalid bounds)")],
], ids=["check-bounds-jazzy", "fix-bounds-humble"])
def test_a_start_state_outside_the_joint_limits_is_told_as_that_not_as_a_planner_that_found_nothing(
        tmp_path: Path, lines: list[tuple[str, int, str]]) -> None:
    _task, found = _explain(tmp_path, [(0, MGI, INFO, "Plan and Execute request accepted"),
                                       *[(1 + i / 100, *line) for i, line in enumerate(lines)], *_aborted(2)])
    assert found.causes == ["manipulation.start_state_in_collision"]
    assert "start state was outside its joint limits" in found.text
    assert "in collision" not in found.text and "found no solution" not in found.text


def test_a_group_the_robot_model_lacks_is_a_configuration_error(tmp_path: Path) -> None:
    # catmulti7/dual_ur_ros_2#5 (heldout5, spent): MoveIt Servo named a planning group the SRDF does not define
    # (robot_model.cpp:517@main)
    _task, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (1, "moveit_robot_model.robot_model", ERROR, "Group 'ur_manipulator' not found in model 'ur'"),
        *_aborted(2)])
    assert found.causes == ["manipulation.configuration_error"]
    assert "logs do not show" not in found.text


def test_a_solver_plugin_not_among_the_installed_descriptions_is_a_set_up_error(tmp_path: Path) -> None:
    # pluginlib's LibraryLoadException text (class_loader_imp.hpp:541@rolling) as terminate prints it when a
    # program loading a kinematics solver does not catch it: the base class says MoveIt's plugin is missing
    _, found = _explain(tmp_path, [
        (0, MGI, INFO, "Plan and Execute request accepted"),
        (0.5, "mtc_node-1", INFO, "terminate called after throwing an instance of 'pluginlib::LibraryLoadException'"
                                  "\n  what():  According to the loaded plugin descriptions the class "
                                  "kdl_kinematics_plugin/KDLKinematicsPlugin with base class type "
                                  "kinematics::KinematicsBase does not exist. Declared types are "),
        *_aborted(1)])
    assert found.causes == ["manipulation.configuration_error"]
    assert "kdl_kinematics_plugin/KDLKinematicsPlugin" in " ".join(e.item for e in found.evidence)


def test_a_goal_pose_pilz_refuses_for_its_frame_is_an_invalid_goal_told_by_its_frame(tmp_path: Path) -> None:
    # moveit/moveit2#2857 (held-out 6, spent): pilz trajectory_functions.cpp computePoseIK refuses a goal pose whose
    # frame_id is not the model frame; the answer names the frame, not a collision or IK that never ran
    found = _one_line_goal(tmp_path, "moveit.pilz_industrial_motion_planner.trajectory_functions", ERROR,
                           "Given frame (ur_base_link) is unequal to model frame(world)")
    assert found.causes == ["manipulation.goal_state_invalid"]
    assert "a goal pose given in a frame other than my robot model's frame" in found.text
    assert "collision" not in found.text and "inverse kinematics" not in found.text


# Day 15 of mhered/RoboticsChallenge's devlog (real-modules-heldout12, spent): moveit_controllers.yaml without action_ns
SCM = "move_group.moveit.moveit.plugins.simple_controller_manager"
NO_NS = ("No action namespace specified for controller `arm_controller` through parameter "
         "`moveit_simple_controller_manager.arm_controller.action_ns`")
NONE_FOR_JOINTS = ("Unable to identify any set of controllers that can actuate the specified joints: "
                   "[ ur5_elbow_joint ur5_shoulder_lift_joint ur5_shoulder_pan_joint ]")


def test_a_controller_left_out_for_its_action_ns_is_why_moveit_found_none(tmp_path: Path) -> None:
    task, found = _explain(tmp_path, [
        (0, SCM, ERROR, NO_NS),
        (0.01, SCM, INFO, "Returned 0 controllers in list"),
        (5, "move_group.moveit.moveit.ros.move_group.clear_octomap_service", INFO, "Execution request received"),
        (5.01, "move_group.moveit.moveit.ros.trajectory_execution_manager", ERROR, NONE_FOR_JOINTS),
        (5.02, "moveit_2553292408.moveit.ros.move_group_interface", INFO, "Execute request aborted"),
        (5.03, "moveit_2553292408.moveit.ros.move_group_interface", ERROR,
         "MoveGroupInterface::execute() failed or timeout reached")], "Why didn't that work?")
    assert task.outcome == "failed"
    assert found.causes == ["manipulation.controllers_not_found"]
    assert "MoveIt found no controllers for my arm's joints: its controller manager left out a controller whose " \
           "action_ns" in found.text
    assert any(e.item.endswith("arm_controller.action_ns`") for e in found.evidence)  # the line that says why


def test_a_controller_left_out_with_no_goal_failing_for_it_is_a_set_up_error(tmp_path: Path) -> None:
    # moveit/moveit2#3717 (corpus): the line alone, nothing of MoveIt looking for a controller after it
    _, found = _explain(tmp_path, [(0, SCM, ERROR, NO_NS)], "Why didn't that work?")
    assert found.causes == ["manipulation.configuration_error"]
    assert "found no controllers" not in found.text


@pytest.mark.parametrize(("suite", "ident"), [
    ("real-modules", "moveit2-1480-move-group-without-sim-time"),
    ("real-modules-heldout", "moveit2-tutorials-587-mgi-node-without-sim-time")])
def test_the_state_monitors_hint_without_its_times_is_said_as_the_likely_clock_mix(
        tmp_path: Path, suite: str, ident: str) -> None:
    # "Didn't received robot state (joint angles) with recent timestamp within 1.000000 seconds.\nCheck clock
    # synchronization ...": MoveIt's hint names the clocks; without "Requested time ..." nothing confirms it
    from hexar.evals.real_modules import QUESTIONS, load_excerpts, write_recording
    from hexar.events import read_recording

    excerpt = next(e for e in load_excerpts(suite) if e.id == ident)
    log = read_recording(write_recording(excerpt, tmp_path / "run", task=False))
    _, found = explain(log, "manipulation", QUESTIONS["failed"])
    assert found.causes == ["manipulation.stale_robot_state"]
    assert "most likely, simulated time and wall-clock time were mixed. That line gives no times to confirm it" in \
        found.text
    assert read_claims(found.text).causes == {"manipulation.stale_robot_state"}
