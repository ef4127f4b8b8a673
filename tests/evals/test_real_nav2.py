"""The real-Nav2 corpus and its converter: each console format people paste, read from real lines of the corpus,
and written as rosbag2 recordings that HEXAR's reader decodes."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.errors import HexarError
from hexar.evals.real_nav2 import (
    DISTROS,
    NAV_CAUSES,
    SKILL_ERROR,
    corpus,
    parse_corpus,
    task_plan,
    with_task,
    write_recording,
)
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.events.console import (
    BASE_NS,
    NS,
    parse_console,
    stamped,
)

LAUNCH = ("[planner_server-2] [WARN] [1664956617.010995992] [planner_server]: Cannot create a plan: the robot's "
          "start position is off the global costmap. Planning will always fail, are you sure the robot has been "
          "properly localized?")


def test_launch_prefixed_line_keeps_level_stamp_logger_and_message() -> None:
    [r] = parse_console(LAUNCH)
    assert (r.level, r.stamp_ns, r.name, r.process) == (30, 1664956617010995992, "planner_server", "planner_server-2")
    assert r.msg.startswith("Cannot create a plan: the robot's start position is off the global costmap.")
    assert not r.synthesised


def test_node_run_alone_and_namespaced_logger() -> None:
    [r] = parse_console("[FATAL] [1727856652.942189081] [robot.controller_server]: Failed to create controller. "
                        "Exception: According to the loaded plugin descriptions the class dwb_core::DWBLocalPlanner "
                        "with base class type nav2_core::Controller does not exist.")
    assert (r.level, r.name, r.process) == (50, "robot.controller_server", "")
    assert r.stamp_ns == 1727856652942189081


def test_unstamped_old_format_gets_increasing_stamps_marked_synthesised() -> None:
    text = ("[ERROR] [DWBLocalPlanner]: No valid trajectories out of 84! \n"
            "[ERROR] [DWBLocalPlanner]: 1.00: RotateToGoal/Nonrotation command near goal.\n"
            "[ERROR] [dwb_controller]: No valid trajectories out of 84!")
    records = stamped(parse_console(text))
    assert [r.name for r in records] == ["DWBLocalPlanner", "DWBLocalPlanner", "dwb_controller"]
    assert [r.stamp_ns for r in records] == [BASE_NS, BASE_NS + NS // 10, BASE_NS + 2 * NS // 10]
    assert all(r.synthesised == {"stamp"} for r in records)
    assert records[0].msg == "No valid trajectories out of 84!"  # the paste's trailing blank is not the message


def test_empty_stamp_and_logger_of_an_rcl_exception_line() -> None:
    [r] = parse_console("[bt_navigator-12] [ERROR] [] []: Original error: Could not load library: "
                        "libnav2_compute_path_to_pose_action_bt_node.so: cannot open shared object file: No such file "
                        "or directory")
    assert (r.name, r.level, r.process) == ("", 40, "bt_navigator-12")
    assert r.msg.startswith("Original error: Could not load library")
    assert r.synthesised == {"stamp"}  # the console printed an empty logger: that is the record's real name


def test_no_level_lines_get_a_level_from_their_wording() -> None:
    text = ("controller_server: Exception in transformPose: Lookup would require\n"
            "extrapolation into the future.  Requested time 1779014121.719091\n"
            "but the latest data is at time 1779014121.684392\n"
            "controller_server: Unable to transform goal pose into costmap frame\n"
            "[follow_path] [ActionServer] Aborting handle. error_code:102\n"
            "docking_server: Navigation request to staging pose failed.")
    records = parse_console(text)
    assert [(r.name, r.level) for r in records] == [
        ("controller_server", 40), ("controller_server", 30), ("", 40), ("docking_server", 40)]
    assert records[0].msg.splitlines()[-1] == "but the latest data is at time 1779014121.684392"
    assert all("level" in r.synthesised for r in records)


def test_wrapped_message_and_launch_continuation_lines_join_the_message_before() -> None:
    wrapped = ("[controller_server-11] [local_costmap.local_costmap]: Timed out waiting for transform from base_link "
               "to odom to become available, tf error: \n"
               "Could not find a connection between 'odom' and 'base_link' because they are not part of the same "
               "tree. \nTf has two or more unconnected trees.")
    [r] = parse_console(wrapped)
    assert r.name == "local_costmap.local_costmap" and r.msg.endswith("Tf has two or more unconnected trees.")
    multi = ("[planner_server-2] [ERROR] [1691424774.006121032] [transformPoseInTargetFrame]: Extrapolation Error "
             "looking up target frame: Lookup would require extrapolation into the future.\n[planner_server-2] \n"
             "[planner_server-2] [WARN] [1691424774.006158189] [planner_server]: Could not transform the start or "
             "goal pose in the costmap frame")
    assert [r.name for r in parse_console(multi)] == ["transformPoseInTargetFrame", "planner_server"]


def test_an_excerpt_that_begins_inside_a_message_keeps_that_line() -> None:
    # the exception ros2_control_node died of, pasted without the line it continued (UR client library
    # src/comm/tcp_server.cpp:168): still a line of the recording, not dropped for want of a message before it
    text = ("[ros2_control_node-1]   what():  Failed to bind socket for port 50003 to address. Reason: Address "
            "already in use: Address already in use\n[ERROR] [ros2_control_node-1]: process has died ")
    first, died = parse_console(text)
    assert first.msg.startswith("what():  Failed to bind socket") and first.process == "ros2_control_node-1"
    assert died.msg == "process has died"


def test_ctest_and_compose_prefixes_are_removed() -> None:
    text = ('23: [planner_server-7] [WARN] [1727973994.446805085] [planner_server]: GridBased plugin failed to plan '
            'from (-3.77, -4.74) to (94.04, -1674.69): "Goal Coordinates of(94.042922, -1674.689924) was outside '
            'bounds"\n'
            "nav2_1    | [controller_server-6] [WARN] [1660300770.471046016] [controller_server]: "
            "RegulatedPurePursuitController detected collision ahead!")
    assert [(r.name, r.process) for r in parse_console(text)] == [
        ("planner_server", "planner_server-7"), ("controller_server", "controller_server-6")]


def test_bare_lines_before_the_first_stamp_are_stamped_before_it() -> None:
    text = ("Behavior Tree tick rate 100.00 was exceeded!\n"
            "[planner_server-3] [INFO] [1725246766.923489017] [global_costmap.global_costmap]: Received request to "
            "clear entirely the global_costmap\n"
            "Message Filter dropping message: frame 'rplidar_link' at time 1725246931.465 for reason 'the timestamp "
            "on the message is earlier than all the data in the transform cache'")
    first, known, last = stamped(parse_console(text))
    assert first.stamp_ns is not None and known.stamp_ns is not None and last.stamp_ns is not None
    assert first.stamp_ns < known.stamp_ns < last.stamp_ns
    assert (first.name, first.level, last.level) == ("", 30, 30)


def test_wall_clock_summary_lines_keep_their_times_as_stamps() -> None:
    text = ("10:33:02  Made contact with dock, waiting for charge to start\n"
            "10:33:12  Docking failed, will retry: Timed out waiting for charge to start\n"
            "10:34:12  [dock_robot] Aborting handle. error_code:905")
    records = parse_console(text)
    stamps = [r.stamp_ns for r in records]
    assert all(s is not None for s in stamps) and stamps[1] - stamps[0] == 10 * NS and stamps[2] - stamps[1] == 60 * NS
    assert [r.level for r in records] == [20, 40, 40]
    assert records[0].msg == "Made contact with dock, waiting for charge to start"
    assert all("stamp" not in r.synthesised and "level" in r.synthesised for r in records)


def test_launch_timestamped_screen_lines_are_read_as_the_records_behind_the_print_time() -> None:
    # launch's screen format with timestamps prints "{created:.7f} {line}" before each process line
    text = ("1590973658.7966743 [bt_navigator-73] [INFO] [bt_navigator]: Begin navigating from current location to "
            "(0.80, -1.30)\n"
            "1678376108.7435489 [robot_manager_node-2] [ERROR] [1678376108.741479164] [robot_manager]: Could not "
            "configure hardware interface\n"
            "1679533274.4250224 [ERROR] [bt_navigator-28]: process has died [pid 81493, exit code -8, cmd 'x']")
    begin, failed, died = parse_console(text)
    assert (begin.name, begin.level, begin.process) == ("bt_navigator", 20, "bt_navigator-73")
    assert begin.msg.startswith("Begin navigating") and begin.stamp_ns == 1590973658796674300
    assert failed.stamp_ns == 1678376108741479164  # the node's own stamp wins over the print time
    assert (failed.name, failed.level, died.name, died.level) == ("robot_manager", 40, "bt_navigator-28", 40)
    assert not begin.synthesised and not died.synthesised


def test_custom_console_format_with_a_clock_time_and_zone() -> None:
    text = ("[ WARN][6:31:18.730 PM -03][controller_server]: RegulatedPurePursuitController detected collision ahead!\n"
            "[ERROR][6:31:18.730 PM -03][controller_server]: Controller patience exceeded\n"
            "[ WARN][6:31:20.761 PM -03][behavior_server]: Collision Ahead - Exiting Spin")
    first, second, third = parse_console(text)
    assert (first.level, first.name, second.level, third.name) == (30, "controller_server", 40, "behavior_server")
    assert first.stamp_ns is not None and third.stamp_ns is not None
    assert third.stamp_ns - first.stamp_ns == 2_031_000_000 and not first.synthesised


def test_markdown_quoted_lines_and_a_crash_line_without_level() -> None:
    text = ("> [bt_navigator-6] [ERROR] [1691138616.839305494] [bt_navigator]: Exception when loading BT: Error at "
            "line 14: -> Node not recognized: WouldAPlannerRecoveryHelp\n\n"
            'Thread 1 "controller_serv" received signal SIGILL, Illegal instruction.')
    quoted, crash = parse_console(text)
    assert (quoted.process, quoted.name, quoted.level) == ("bt_navigator-6", "bt_navigator", 40)
    assert crash.level == 40 and crash.name == ""


def test_corpus_loads_and_every_entry_is_readable() -> None:
    entries = corpus()
    assert len(entries) >= 20
    assert {e.distro for e in entries} <= set(DISTROS) and {e.cause for e in entries} <= NAV_CAUSES
    for e in entries:
        assert e.url.startswith("https://") and e.cause_quote.strip()
        assert parse_console(e.lines), e.id


@pytest.mark.parametrize("text, message", [
    ("not: [valid", "not valid YAML"),
    ("{}", "non-empty list"),
    ("- id: a\n  source: x\n", "lacks"),
])
def test_bad_corpus_is_a_clear_error(text: str, message: str) -> None:
    with pytest.raises(HexarError, match=message):
        parse_corpus(text)


def test_unknown_cause_or_distro_is_refused() -> None:
    entry = ("- {id: a, source: s, url: 'https://x', distro: humble, outcome: failed, cause: %s, cause_quote: q, "
             "logs_show_cause: true, lines: '[ERROR] [x]: y'}")
    with pytest.raises(HexarError, match="unknown cause"):
        parse_corpus(entry % "navigation.ghosts")
    with pytest.raises(HexarError, match="distro"):
        parse_corpus(entry.replace("humble", "hydro") % "navigation.off_costmap")


def test_recording_with_a_navigation_task(tmp_path: Path) -> None:
    ex = next(e for e in corpus() if e.id == "nav2-4027-cmd-vel-not-set")
    log = read_recording(write_recording(ex, tmp_path / "bag", task=True))
    lines = log.view(frozenset({c.ROSOUT})).logs()
    assert len(lines) == 10 and lines[1].msg.startswith("Begin navigating from current location")
    [task] = log.tasks
    [skill] = task.skills
    assert skill.skill == "navigate_to_pose" and skill.params == {"x": 1.46, "y": 0.05}
    assert skill.state == "failed" and skill.error_msg == SKILL_ERROR
    lo, hi = task.window()
    assert lo < lines[0].t and lines[-1].t < hi


def test_recording_without_task_has_only_rosout(tmp_path: Path) -> None:
    ex = next(e for e in corpus() if e.id == "nav2-3230-tb3-off-costmap")
    log = read_recording(write_recording(ex, tmp_path / "bag", task=False, storage="mcap"))
    assert not log.task_updates and all(t.derived for t in log.tasks)  # only tasks derived from Nav2
    names = [line.name for line in log.view(frozenset({c.ROSOUT})).logs()]
    assert names == ["nav2_costmap_2d", "planner_server", "local_costmap.local_costmap",
                     "global_costmap.global_costmap"]


def test_half_the_excerpts_of_each_outcome_get_a_task() -> None:
    n = len(corpus())
    assert sum(with_task(i) for i in range(n)) == (n + 1) // 2
    plan = task_plan(corpus())
    for outcome in ("failed", "succeeded", "slow"):
        tasks = [t for e, t in zip(corpus(), plan, strict=True) if e.outcome == outcome]
        assert tasks and sum(tasks) == (len(tasks) + 1) // 2


def test_level_and_stamp_in_one_bracket_of_a_custom_console_format() -> None:
    # RCUTILS_CONSOLE_OUTPUT_FORMAT="[{severity} {time}] [{name}]: {message} ({function_name}() at {file_name}:...)"
    text = ("[ros2_control_node-1] [ERROR 1781509379.841754359] [tolerances]: State tolerances failed for joint 4: "
            "(check_state_tolerance_per_joint() at tolerances.hpp:319)\n"
            "[ros2_control_node-1] [WARN 1781509379.841879328] [joint_trajectory_controller]: Aborted due to state "
            "tolerance violation (update() at scaled_joint_trajectory_controller.cpp:306)")
    first, second = parse_console(text)
    assert (first.level, first.name, first.stamp_ns) == (40, "tolerances", 1781509379841754359)
    assert first.msg.startswith("State tolerances failed for joint 4:")
    assert (second.level, second.name) == (30, "joint_trajectory_controller")
