"""Console formats beyond ros2 launch's default: rcutils' other stamps, colour, journald, the logging guide's
function/file/line suffix and spdlog's levels, each read from real lines of the corpora (reformatted only where the
test is about a format the corpus line was not printed in)."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path

from rosbags.highlevel import AnyReader

from hexar.evals.real_nav2 import write_excerpt
from hexar.events import contract as c
from hexar.events.console import NS, parse_console, stamped

# navigation2#3230, as launch printed it (planner_server's WARN)
MSG = ("Cannot create a plan: the robot's start position is off the global costmap. Planning will always fail, are "
       "you sure the robot has been properly localized?")
STAMP_NS = 1664956617010995992
# fanuc_driver#47 (real-modules corpus): RCUTILS_CONSOLE_OUTPUT_FORMAT with the logging guide's suffix
FANUC = (
    "[ros2_control_node-1] [ERROR 1781509379.841754359] [tolerances]: State tolerances failed for joint 4: "
    "(check_state_tolerance_per_joint() at /opt/ros/jazzy/include/joint_trajectory_controller/"
    "joint_trajectory_controller/tolerances.hpp:319)\n"
    "[move_group-8] [INFO 1781509377.922598405] [moveit.simple_controller_manager.follow_joint_trajectory_controller_"
    "handle]: /joint_trajectory_controller started execution (operator()() at ./src/follow_joint_trajectory_"
    "controller_handle.cpp:75)"
)


def test_colour_escapes_are_not_part_of_the_record_however_the_paste_kept_them() -> None:
    # rcutils colours a WARN line yellow and resets after it; launch puts its prefix in front
    for esc in ("\x1b", "^[", ""):  # as printed, as `cat -v` shows it, and pasted without the escape character
        line = f"[planner_server-2] {esc}[33m[WARN] [1664956617.010995992] [planner_server]: {MSG}{esc}[0m"
        [r] = parse_console(line)
        assert (r.level, r.name, r.process, r.msg, r.stamp_ns) == (30, "planner_server", "planner_server-2", MSG,
                                                                   STAMP_NS), esc
        assert not r.synthesised
    [r] = parse_console(f"\x1b[31m[ERROR] [1664956617.010995992] [planner_server]: {MSG}\x1b[0m")
    assert (r.level, r.name) == (40, "planner_server")


def test_date_time_with_ms_and_nanosecond_stamps_of_rcutils_console_formats() -> None:
    when = datetime(2024, 6, 11, 9, 29, 19, 304000, tzinfo=UTC)
    want = int(when.timestamp()) * NS + 304_000_000
    forms = (f"[WARN] [2024-06-11 09:29:19.304] [planner_server]: {MSG}",  # {date_time_with_ms} as the stamp
             f"[2024-06-11 09:29:19.304] [WARN] [planner_server]: {MSG}",  # ... in front of the line
             f"[WARN 2024-06-11 09:29:19.304] [planner_server]: {MSG}")
    for line in forms:
        [r] = parse_console(line)
        assert (r.level, r.name, r.msg, r.stamp_ns) == (30, "planner_server", MSG, want), line
        assert not r.synthesised
    [r] = parse_console(f"[WARN] [{STAMP_NS}] [planner_server]: {MSG}")  # {time_as_nanoseconds}
    assert r.stamp_ns == STAMP_NS


def test_journald_lines_of_a_robot_started_by_systemd() -> None:
    # turtlebot4#20 (blind2): robot_upstart's service, read with journalctl
    text = ("Jun 14 11:09:32 ubuntu systemd[1]: Started \"bringup turtlebot4\".\n"
            "Jun 14 11:09:35 ubuntu turtlebot4-start[2517]: [INFO] [launch]: Default logging verbosity is set to INFO\n"
            "Jun 14 11:09:37 ubuntu turtlebot4-start[2517]: [ERROR] [launch]: Caught exception in launch (see debug "
            "for traceback): executabl>")
    started, verbosity, caught = parse_console(text)
    assert started.msg == 'Started "bringup turtlebot4".'
    assert (verbosity.name, verbosity.level, caught.name, caught.level) == ("launch", 20, "launch", 40)
    assert caught.msg.startswith("Caught exception in launch")
    assert verbosity.stamp_ns is not None and caught.stamp_ns is not None and started.stamp_ns is not None
    assert caught.stamp_ns - verbosity.stamp_ns == 2 * NS and verbosity.stamp_ns - started.stamp_ns == 3 * NS
    assert "stamp" not in caught.synthesised


def test_journald_times_go_onto_the_clock_the_nodes_print() -> None:
    # blind set 20's fault-free console as `journalctl -u` shows it on a robot whose local time is UTC+1: launch's own
    # lines print no stamp, the nodes' lines print seconds since the epoch; launch's line that planner_server died
    # (after Ctrl-C) must stay after the node's last line, not move to the journal's day and hour
    text = ("Nov 30 09:50:57 robot start.sh[918]: [INFO] [launch]: Default logging verbosity is set to INFO\n"
            "Nov 30 09:50:58 robot start.sh[918]: [planner_server-3] [INFO] [1796002258.632251743] "
            "[planner_server]: Creating\n"
            "Nov 30 09:50:59 robot start.sh[918]: [bt_navigator-6] [INFO] [1796002259.402502036] [bt_navigator]: "
            "Goal succeeded\n"
            "Nov 30 09:51:01 robot start.sh[918]: [ERROR] [planner_server-3]: process has died [pid 18285, exit code "
            "-6, cmd '/home/robot/ws/install/nav2_planner/lib/nav2_planner/planner_server']\n")
    verbosity, creating, succeeded, died = parse_console(text)
    assert creating.stamp_ns == 1796002258632251743 and succeeded.stamp_ns == 1796002259402502036
    assert verbosity.stamp_ns is not None and died.stamp_ns is not None
    assert verbosity.stamp_ns <= creating.stamp_ns and died.stamp_ns > succeeded.stamp_ns
    # two seconds after the line before it on the journal's clock, as on the nodes'
    assert abs(died.stamp_ns - succeeded.stamp_ns - 2 * NS) < NS


def test_stacked_outer_prefixes_leave_the_record() -> None:
    # `docker compose logs nav2 | grep -n` (blind set 5's forklift notes keep grep's numbers)
    [r] = parse_console("nav2-1  | 115:[controller_server-2] [INFO] [1785837119.338957612] [controller_server]: "
                        "Received a goal, begin computing control effort.")
    assert (r.process, r.name, r.stamp_ns) == ("controller_server-2", "controller_server", 1785837119338957612)
    assert r.msg == "Received a goal, begin computing control effort."


def test_function_file_and_line_of_the_logging_guides_format_leave_the_message() -> None:
    failed, started = parse_console(FANUC)
    assert failed.msg == "State tolerances failed for joint 4:"
    assert (failed.function, failed.line) == ("check_state_tolerance_per_joint", 319)
    assert failed.file.endswith("joint_trajectory_controller/tolerances.hpp")
    assert started.msg == "/joint_trajectory_controller started execution"
    assert (started.function, started.file, started.line) == (
        "operator()", "./src/follow_joint_trajectory_controller_handle.cpp", 75)


def test_the_recording_carries_function_file_and_line_as_rosout_does(tmp_path: Path) -> None:
    path = write_excerpt(stamped(parse_console(FANUC)), "fanuc-47", True, tmp_path / "rec", None, "")
    with AnyReader([Path(path)]) as reader:
        logs = [reader.deserialize(raw, conn.msgtype)
                for conn, _, raw in reader.messages([x for x in reader.connections if x.topic == c.ROSOUT])]
    by_msg = {m.msg: m for m in logs}
    m = by_msg["State tolerances failed for joint 4:"]
    assert (m.function, m.line, m.level) == ("check_state_tolerance_per_joint", 319, 40)
    assert m.file.endswith("tolerances.hpp")


def test_spdlog_levels_of_a_driver_beside_ros_lines() -> None:
    # moveit_pro_example_ws#930 (real-modules heldout5): the Feetech driver logs through spdlog
    text = ("[INFO] [2026-09-10 21:38:06.236] Initialize hardware 'so101' \n"
            "[2026-09-10 21:38:06.237] [info] Connecting to port: /dev/so101_follower\n"
            "[2026-09-10 21:38:06.237] [error] FeetechHardware::on_init -> Open [/dev/so101_follower]: Bad file "
            "descriptor\n"
            "terminate called after throwing an instance of 'LibSerial::NotOpen'\n"
            "  what():  Serial port not open.")
    init, connecting, error = parse_console(text)
    assert (init.msg, init.level) == ("Initialize hardware 'so101'", 20)
    assert (connecting.msg, connecting.level) == ("Connecting to port: /dev/so101_follower", 20)
    assert error.level == 40 and error.msg.startswith("FeetechHardware::on_init -> Open")
    assert error.msg.endswith("what():  Serial port not open.")  # the crash's lines continue the error
    assert "level" not in error.synthesised and init.stamp_ns == connecting.stamp_ns - NS // 1000


def test_advice_to_change_a_setting_reads_as_a_warning_where_no_level_was_printed() -> None:
    # blind5 mirte: nav2_costmap_2d's inflation layer (an ERROR in its source), pasted bare and wrapped by the console
    text = ("The configured inflation radius (0.150) is smaller than the computed inscribed\n"
            "radius (0.150) of your footprint, it is highly recommended to set inflation\n"
            "radius to be at least as big as the inscribed radius to avoid collisions")
    [r] = parse_console(text)
    assert r.level == 30 and "level" in r.synthesised


def test_line_number_columns_and_a_format_with_a_stamp_but_no_level() -> None:
    # blind13 NavGreen: lines quoted from a log file with its line numbers; blind1 frontier-exploration's
    # "[{time}] [{name}]: {message}"
    text = ("1124  [bt_navigator-16] [1776645869.700] Begin navigating from current location (7.00, 0.00) to "
            "(5.50, 0.00)\n"
            "1125  [planner_server-13] [1776645869.886] GridBased: failed to create plan, no valid path found.\n"
            "[1765479882.488445639] [nav2_costmap_2d]: Robot is out of bounds of the costmap!")
    begin, failed, bounds = parse_console(text)
    assert (begin.process, begin.stamp_ns, begin.level) == ("bt_navigator-16", 1776645869700000000, 20)
    assert begin.msg.startswith("Begin navigating from current location (7.00, 0.00)")
    assert (failed.process, failed.level, failed.msg) == (
        "planner_server-13", 40, "GridBased: failed to create plan, no valid path found.")
    assert (bounds.name, bounds.stamp_ns, bounds.level) == ("nav2_costmap_2d", 1765479882488445639, 30)
    assert bounds.msg == "Robot is out of bounds of the costmap!" and bounds.synthesised == {"level"}


def test_gazebos_own_console_levels_and_source_place() -> None:
    # darshmenon/UR3_ROS2_PICK_AND_PLACE#1 (real-modules heldout17) and gz-common's gzerr/gzwarn/gzmsg prefixes
    text = ("[Err] [Physics.cc:1801] Attempting to create a mimic constraint for joint [left_inner_finger_joint], "
            "but the chosen physics engine does not support mimic constraints, so no constraint will be created.\n"
            "[gazebo-2] [Wrn] [Util.cc:859] Failed to load mesh from [model://robot_description/meshes/a.stl].\n"
            "[Msg] Serving world names on [/gazebo/worlds]")
    err, warn, msg = parse_console(text)
    assert (err.level, err.file, err.line) == (40, "Physics.cc", 1801)
    assert err.msg.startswith("Attempting to create a mimic constraint for joint")
    assert (warn.level, warn.process, warn.msg) == (30, "gazebo-2", "Failed to load mesh from "
                                                                    "[model://robot_description/meshes/a.stl].")
    assert (msg.level, msg.file, msg.msg) == (20, "", "Serving world names on [/gazebo/worlds]")


def test_gazebo_started_by_ros_gz_sim_under_its_command_line_as_process_name() -> None:
    # open-rmf/rmf_simulation#125 as launch printed it; gz-sim#2517's SystemLoader error under the same prefix
    text = ("[spawner-5] [INFO] [1717499382.790573223] [spawner_joint_state_broadcaster]: Waiting for "
            "'/simulation_controller_manager' node to exist\n"
            "[ruby $(which ign) gazebo-1] Stack trace (most recent call last):\n"
            "[ruby $(which gz) sim-1] [Err] [SystemLoader.cc:92] Failed to load system plugin "
            "[libgz-sim8-python-system-loader-system.so] : Could not find shared library.")
    spawner, trace, err = parse_console(text)
    assert (spawner.process, spawner.name) == ("spawner-5", "spawner_joint_state_broadcaster")
    assert (trace.process, trace.msg) == ("ruby $(which ign) gazebo-1", "Stack trace (most recent call last):")
    assert (err.process, err.level, err.file, err.line) == ("ruby $(which gz) sim-1", 40, "SystemLoader.cc", 92)
    assert err.msg == ("Failed to load system plugin [libgz-sim8-python-system-loader-system.so] : Could not find "
                       "shared library.")


# A Python node's uncaught exception as CPython's excepthook prints it, alone (`ros2 run`) and behind launch's prefix
# with launch.log's time in front (real output of rclpy 9.1.2 on ROS 2 Kilted, scripts/stack_faults.py)
TRACEBACK = """\
Traceback (most recent call last):
  File "/home/robot/ws/scan_filter.py", line 6, in <module>
    node = Node('scan_filter')
           ^^^^^^^^^^^^^^^^^^^
rclpy._rclpy_pybind11.RCLError: error creating node: Unable to resolve peer robot-base.local
, at /project/src/participant.cpp:256, at /project/src/rcl/node.c:249"""


def test_a_python_traceback_is_one_error_record_with_the_exception_first() -> None:
    (record,) = parse_console(TRACEBACK)
    first, second, rest = record.msg.split("\n", 2)
    assert first == "rclpy._rclpy_pybind11.RCLError: error creating node: Unable to resolve peer robot-base.local"
    assert second == ", at /project/src/participant.cpp:256, at /project/src/rcl/node.c:249"  # its message goes on
    assert rest.startswith("Traceback (most recent call last):\nFile \"/home/robot/ws/scan_filter.py\", line 6")
    assert record.level == 40 and "level" not in record.synthesised


def test_a_traceback_in_launch_log_keeps_its_process_and_first_stamp() -> None:
    text = "\n".join(f"1795927629.{7235756 + i:07d} [scan_filter-2] {line}" for i, line in
                     enumerate(TRACEBACK.splitlines()))
    text += "\n1795927629.8761501 [ERROR] [scan_filter-2]: process has died [pid 21679, exit code 1, cmd 'x']."
    raised, died = parse_console(text)
    assert raised.process == "scan_filter-2" and raised.msg.startswith("rclpy._rclpy_pybind11.RCLError: ")
    assert raised.stamp_ns == 1795927629723575600 and raised.level == 40
    assert (died.name, died.level) == ("scan_filter-2", 40)


def test_another_process_line_between_does_not_break_a_traceback() -> None:
    text = ("[a-1] Traceback (most recent call last):\n[a-1]   File \"a.py\", line 1, in <module>\n"
            "[b-2] [INFO] [1795927629.1] [b]: still running\n[a-1] ValueError: boom\n"
            "[b-2] [INFO] [1795927629.2] [b]: ok")
    raised, running, ok = parse_console(text)
    assert raised.msg.splitlines()[:2] == ["ValueError: boom", "Traceback (most recent call last):"]
    assert (running.msg, ok.msg) == ("still running", "ok")


def test_python_warnings_and_cyclone_dds_lines_get_their_levels() -> None:
    warned, cyclone = parse_console(
        "/opt/venv/lib/python3/site-packages/rclpy/node.py:221: RuntimeWarning: Failed to fini rosout publisher\n"
        "  self.__node = _rclpy.Node(\n"
        "1795927276.580085 [0]     python: wlan0: does not match an available interface.")
    assert (warned.level, warned.msg.splitlines()[0]) == (30, "RuntimeWarning: Failed to fini rosout publisher")
    assert (warned.file, warned.line) == ("/opt/venv/lib/python3/site-packages/rclpy/node.py", 221)
    assert (cyclone.level, cyclone.msg) == (30, "wlan0: does not match an available interface.")
    assert cyclone.stamp_ns == 1795927276580085000
