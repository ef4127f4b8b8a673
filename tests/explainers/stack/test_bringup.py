"""bringup_findings on recordings written with rosbags from real console lines of public threads: a params file
rcl could not parse, a configure callback that threw, a process that died, and a healthy bring-up (no finding)."""

from __future__ import annotations

from pathlib import Path

from hexar.evals.real_nav2 import Excerpt, write_recording
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.records import LogLine
from hexar.explainers.stack import bringup_findings

# turtlebot/turtlebot4#341: the params file had a value before ros__parameters.
PARAMS = "\n".join([
    '[smoother_server-2] [ERROR] [1705629351.512110213] [rcl]: Failed to parse global arguments',
    "[smoother_server-2] terminate called after throwing an instance of 'rclcpp::exceptions::RCLInval"
    "idROSArgsError'",
    '[planner_server-3] [ERROR] [1705629351.516292793] [rcl]: Failed to parse global arguments',
    "[planner_server-3] terminate called after throwing an instance of 'rclcpp::exceptions::RCLInvali"
    "dROSArgsError'",
    "[planner_server-3]   what():  failed to initialize rcl: Couldn't parse params file: '--params-fi"
    "le /tmp/launch_params_pl1tbamm'. Error: Cannot have a value before ros__parameters at line 85, a"
    't ./src/parse.c:805, at ./src/rcl/arguments.c:',
]) + "\n"
# turtlebot/turtlebot4#591 (corpus entry tb4-591-jazzy-no-footprint): the configure callback threw.
LIFECYCLE = "\n".join([
    '[controller_server-1] [ERROR] [1746882382.323839447] [controller_server]: Caught exception in ca'
    'llback for transition 10',
    '[controller_server-1] [ERROR] [1746882382.323941469] [controller_server]: Original error: Consid'
    'ering footprint in collision checking but no robot footprint provided in the costmap.',
    '[lifecycle_manager-10] [ERROR] [1746882382.327852169] [lifecycle_manager_navigation]: Failed to '
    'change state for node: controller_server',
    '[lifecycle_manager-10] [ERROR] [1746882382.328004271] [lifecycle_manager_navigation]: Failed to '
    'bring up all requested nodes. Aborting bringup.',
]) + "\n"
# turtlebot/turtlebot4#632 (Jazzy): the controller server's process died at start.
DIED = "\n".join([
    '[INFO] [controller_server-1]: process started with pid [6474]',
    "[ERROR] [controller_server-1]: process has died [pid 6474, exit code -4, cmd '/opt/ros/jazzy/lib"
    '/nav2_controller/controller_server --ros-args --log-level info --ros-args -r __ns:=/ -p use_sim_'
    'time:=False --params-file /tmp/launch_params_di0ju_uk -r /global_costmap/scan:=/scan -r /local_c'
    "ostmap/scan:=/scan -r /tf:=tf -r /tf_static:=tf_static -r cmd_vel:=cmd_vel_nav'].",
]) + "\n"
# ROBOTIS-GIT/turtlebot3#945 (Humble): launch could not parse the params file it substitutes (a multi-line message).
LAUNCH = "\n".join([
    "[INFO] [launch]: Default logging verbosity is set to INFO",
    "[ERROR] [launch]: Caught exception in launch (see debug for traceback): while parsing a block mapping",
    '  in "/opt/ros/humble/share/turtlebot3_navigation2/param/waffle.yaml", line 2, column 3',
    "expected <block end>, but found '<block mapping start>'",
]) + "\n"
# innate-inc/innate-os#518: a robot maker's note that shortens launch's fields ("[pid …, exit code …, cmd '…']").
SHORT_DIED = "[controller_server-6] double free or corruption (!prev)\nprocess has died [exit code -6]\n"
# The lifecycle manager's lines of a healthy start (nav2_lifecycle_manager/src/lifecycle_manager.cpp, INFO).
HEALTHY = "\n".join([
    '[lifecycle_manager-10] [INFO] [1746882380.1] [lifecycle_manager_navigation]: Starting managed no'
    'des bringup...',
    '[lifecycle_manager-10] [INFO] [1746882381.2] [lifecycle_manager_navigation]: Managed nodes are a'
    'ctive',
]) + "\n"


def _logs(tmp: Path, lines: str) -> list[LogLine]:
    ex = Excerpt(id="t", source="test", url="", distro="unknown", outcome="failed",
                 cause="navigation.bringup_failure", cause_quote="", logs_show_cause=True, lines=lines)
    log = read_recording(write_recording(ex, tmp / "bag", task=False))
    return log.view(frozenset({c.ROSOUT})).logs()


def test_a_params_file_rcl_could_not_parse(tmp_path: Path) -> None:
    logs = _logs(tmp_path, PARAMS)
    [f] = bringup_findings(logs)
    assert f.kind == "params_file"
    assert "Couldn't parse params file" in f.line.msg and f.t == f.line.t
    assert f.detail.startswith("Cannot have a value before ros__parameters at line 85")
    assert f.entry is not None and f.entry.source.startswith("rcl/src/rcl/arguments.c:")
    assert "could not parse its parameters file" in f.describe()


def test_a_configure_callback_that_threw_names_node_transition_and_error(tmp_path: Path) -> None:
    logs = _logs(tmp_path, LIFECYCLE)
    first, *rest = bringup_findings(logs)
    assert (first.kind, first.node) == ("lifecycle_transition", "controller_server")
    assert first.detail == ("transition configure: Considering footprint in collision checking but no robot "
                            "footprint provided in the costmap.")
    assert first.t == logs[0].t
    assert all(f.t >= first.t for f in rest)
    assert first.describe().startswith("controller_server stopped in a lifecycle transition and never became active")


def test_a_process_that_died_names_its_node_and_exit_code(tmp_path: Path) -> None:
    [f] = bringup_findings(_logs(tmp_path, DIED))
    assert (f.kind, f.node, f.detail) == ("process_died", "controller_server", "exit code -4")
    assert f.describe() == "the process of controller_server died (exit code -4)"


def test_before_keeps_only_lines_up_to_that_time(tmp_path: Path) -> None:
    logs = _logs(tmp_path, LIFECYCLE)
    assert bringup_findings(logs, before=logs[0].t - 1) == []
    assert len(bringup_findings(logs, before=logs[0].t)) == 1


def test_a_healthy_bringup_has_no_finding(tmp_path: Path) -> None:
    assert bringup_findings(_logs(tmp_path, HEALTHY)) == []


def test_an_exception_in_launch_itself_is_a_bringup_failure_with_its_error(tmp_path: Path) -> None:
    [f] = bringup_findings(_logs(tmp_path, LAUNCH))
    assert f.kind == "launch_failed" and f.node == ""
    assert f.detail.startswith('while parsing a block mapping in "/opt/ros/humble/share/turtlebot3_navigation2/param/'
                               'waffle.yaml", line 2, column 3')
    assert f.describe().startswith("my launch stopped with an error before it had started my navigation nodes (")


def test_a_died_process_with_shortened_fields_is_still_launchs_line(tmp_path: Path) -> None:
    [f] = bringup_findings(_logs(tmp_path, SHORT_DIED))
    assert (f.kind, f.detail) == ("process_died", "exit code -6")
    assert f.entry is not None and f.entry.source.startswith("launch/launch/actions/execute_local.py:")


def test_a_died_process_whose_console_prefix_was_lost_is_named_from_launchs_command(tmp_path: Path) -> None:
    # ros-navigation/navigation2#3508 (Humble): the console line begins with a stamp, so no process prefix is read;
    # launch's own message still names the node in the command it ran (execute_local.py:573@humble)
    died = ("1679533274.4250224 [ERROR] [bt_navigator-28]: process has died [pid 81493, exit code -8, cmd '/opt/ros/"
            "humble/lib/nav2_bt_navigator/bt_navigator --ros-args --log-level info --ros-args -r __node:=bt_navigator "
            "--params-file /tmp/tmp9whtodqw -r /tf:=tf -r /tf_static:=tf_static'].\n")
    [f] = bringup_findings(_logs(tmp_path, died))
    assert (f.kind, f.node, f.detail) == ("process_died", "bt_navigator", "exit code -8")


# turtlebot/turtlebot4_simulator#72 (Humble, blind4, spent): Gazebo crashed, so the controller manager its plugin
# runs never answered; the spawner said so and returned 1 (controller_manager/spawner.py:225-226@8779757f7)
GAVE_UP = "\n".join([
    "[spawner-32] [ERROR] [1712571258.649015310] [spawner_joint_state_broadcaster]: Controller manager not available",
    "[ERROR] [spawner-32]: process has died [pid 3793254, exit code 1, cmd '/opt/ros/humble/lib/controller_manager/"
    "spawner joint_state_broadcaster -c controller_manager --ros-args -r __ns:=/'].",
]) + "\n"


def test_a_spawner_that_found_no_controller_manager_is_no_node_that_failed_to_come_up(tmp_path: Path) -> None:
    assert bringup_findings(_logs(tmp_path, GAVE_UP)) == []


def test_a_spawner_that_died_without_saying_why_is_still_a_death(tmp_path: Path) -> None:
    [f] = bringup_findings(_logs(tmp_path, GAVE_UP.split("\n", 1)[1]))
    assert (f.kind, f.node, f.detail) == ("process_died", "spawner", "exit code 1")


# zzx4king/sentry_nuc15 doc/nav2_jazzy_config_fix.md (blind7 sentry-jazzy-fix-record-humble-style-planner-plugin-name,
# as its author abridged it): planner_server's on_configure could not create the planner and returned FAILURE
# (nav2_planner/src/planner_server.cpp:121-127@jazzy), with no lifecycle manager line pasted after it.
NO_PLANNER = "\n".join([
    "[FATAL] [planner_server]: Failed to create global planner. Exception: ... the class",
    "nav2_navfn_planner/NavfnPlanner ... does not exist.",
    "Declared types are nav2_navfn_planner::NavfnPlanner ...",
]) + "\n"
# waypoint_follower.cpp:123-128@jazzy logs the same kind of FATAL, cleans up and returns SUCCESS: the node came up
# (the line from that format string with pluginlib's ClassLoader wording, class_loader_imp.hpp@humble)
NO_TASK_EXECUTOR = ("[FATAL] [waypoint_follower]: Failed to create waypoint_task_executor. Exception: According to "
                    "the loaded plugin descriptions the class nav2_waypoint_follower::WaitAtWaypoint2 with base "
                    "class type nav2_core::WaypointTaskExecutor does not exist.\n")


def test_a_nav2_server_that_could_not_create_its_plugin_failed_its_configure(tmp_path: Path) -> None:
    [f] = bringup_findings(_logs(tmp_path, NO_PLANNER))
    assert (f.kind, f.node) == ("lifecycle_transition", "planner_server")
    assert f.detail.startswith("transition configure: ... the class nav2_navfn_planner/NavfnPlanner")
    assert f.entry is not None and f.entry.source.startswith("nav2_planner/src/planner_server.cpp:")
    assert f.describe().startswith("planner_server stopped in a lifecycle transition and never became active")


def test_a_waypoint_follower_that_goes_on_after_its_fatal_is_no_node_that_failed(tmp_path: Path) -> None:
    assert bringup_findings(_logs(tmp_path / "wf", NO_TASK_EXECUTOR)) == []
    assert bringup_findings(_logs(tmp_path / "both", NO_TASK_EXECUTOR + NO_PLANNER))[0].node == "planner_server"


def test_rclpys_rclerror_quoting_rcls_params_file_error_is_the_params_file(tmp_path: Path) -> None:
    """A Python node whose rclpy.init raised RCLError "failed to initialize rcl: Couldn't parse params file: …":
    the parameter file could not be parsed, even where rcl's own "Failed to parse global arguments" line before it
    lies outside the window read."""
    from tests.agent.helpers import converse, real_module_run

    run = real_module_run("kilted-params-file-yaml-syntax", tmp_path / "run")
    lines = read_recording(run).logs
    assert [f.kind for f in bringup_findings(lines[1:])] == ["params_file"]
    (wrong,) = converse(run, "what's wrong at line 3 of scan_filter.yaml?")
    assert str(wrong["answer"]).startswith("Starting my drivers and controllers failed because a parameter never "
                                           "reached one of my nodes: its parameter file could not be parsed.")
