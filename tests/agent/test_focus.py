"""A developer's question that quotes a line, names an identifier or a node, or (on a log read without the robot's
plan) repeats two words of one line: the finding, then the lines it points at; a person's question points at none."""

from __future__ import annotations

from pathlib import Path

from hexar.agent.focus import pointed_lines
from hexar.events import read_recording
from tests.agent.helpers import converse, real_module_run, real_nav2_run

VOXEL = "nav2-2220-voxel-layer-param-uninitialized-type"


def test_an_identifier_points_at_the_line_that_names_it(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run(VOXEL, tmp_path / "run"),
                        "What's wrong with the voxel_layer.plugin parameter in my local_costmap config?")
    text = str(asked["answer"])
    assert text.startswith("I couldn't reach my goal because my navigation stack was misconfigured")
    assert ("What my log says of it: at 07:38:49, controller_server-2 (ERROR) \"Original error: parameter "
            "'voxel_layer.plugin' has invalid type") in text


def test_a_node_named_in_the_question_points_at_its_errors_first(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run(VOXEL, tmp_path / "run"), "Why did controller_server fail to configure?")
    said = str(asked["answer"]).split("What my log says of it: ")[1]
    # launch's process name ("controller_server-2") is the node's; the FATAL line first, then the longer error
    assert said.startswith('at 07:38:49, controller_server (FATAL) "Lifecycle node controller_server does not have '
                           'error state implemented"; at 07:38:49, controller_server-2 (ERROR) "Original error: ')


def test_a_quoted_line_and_the_next_that_repeats_its_words(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("kachaka-106-tf-too-old-clock-offset", tmp_path / "run"),
                        "How far apart were the data time and the transform time in the tf_help error?")
    assert 'tf_help (ERROR) "Data time: 1721806792s 88418722ns, Transform time: 1721806791s 859294000ns"' in \
        str(asked["answer"])


def test_a_repeated_line_is_told_with_the_logs_count(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("warehouse-waypoint-tb3-single-goal-succeeded", tmp_path / "run"),
                        "How many times was a new path passed to the controller?")
    log = read_recording(tmp_path / "run")
    passed = sum(1 for ln in log.logs if ln.msg.startswith("Passing new path to controller"))
    assert passed == 5
    # "how many times?" is counted first (agent/counted.py)
    assert str(asked["answer"]).startswith('5 times: controller_server logged "Passing new path to controller." from ')


def test_words_alone_point_only_on_a_log_read_without_a_plan(suite: Path, tmp_path: Path) -> None:
    run = real_module_run("kilted-lifecycle-configure-serial-port-missing", tmp_path / "run")
    question = "How many times did lifecycle_manager try to configure /base_driver before giving up?"
    lines = pointed_lines(question, read_recording(run))
    assert [ln.msg for ln in lines][-1] == "configure of /base_driver failed twice, state unconfigured; giving up"
    # a person's question on the home robot's recording: no identifier, no quote, and its task is the robot's plan
    for q in ("Why didn't you bring me the book?", "why did it take so long to get to the kitchen?"):
        (home,) = converse(suite / "bagfile_14_2", q)
        assert "What my log says of it" not in str(home["answer"])
    assert pointed_lines("why did the navigation to the kitchen fail?", read_recording(suite / "bagfile_14_2")) == []
    reached = read_recording(real_nav2_run("nav2-1367-reached-goal-but-navigation-failed", tmp_path / "reached"))
    assert [ln.msg for ln in pointed_lines("did you reach the goal or not?", reached, by_words=True)] == \
        ["Reached the goal!"]
    assert pointed_lines("did you reach the goal or not?", reached) == []


def test_a_line_the_answer_already_quotes_is_not_told_again(tmp_path: Path) -> None:
    run = real_module_run("kilted-lifecycle-configure-serial-port-missing", tmp_path / "run")
    (asked,) = converse(run, "Is this a bug in the driver, or is the device on /dev/ttyACM0 just not connected?")
    text = str(asked["answer"])
    assert text.count("cannot open serial port") == 1 and "What my log says of it" not in text


def test_a_topic_the_recording_lacks_is_told_with_the_lines_that_name_it(tmp_path: Path) -> None:
    # blind set 1: nav2_system_tests' tester logs "Received amcl_pose"; the recording holds only /rosout
    (asked,) = converse(real_nav2_run("nav2-4440-system-test-bt-navigator-passed", tmp_path / "run"),
                        "Was amcl_pose being received during the test?")
    assert asked["answer"] == ("My recording holds no /amcl_pose: it has only /rosout, so whether anything was "
                               "published on /amcl_pose it cannot tell. What my log says of it: at 05:54:50, "
                               'nav2_tester (INFO) "Received amcl_pose" (2 times).')


def test_a_position_the_recording_cannot_give_is_told_with_the_lines_on_it(tmp_path: Path) -> None:
    (asked,) = converse(real_nav2_run("orsus-scout-humble-relocalized-in-unmapped-area-off-costmap", tmp_path / "run"),
                        "Where is the robot compared to the costmap bounds?")
    assert str(asked["answer"]).endswith('My position is not recorded: this recording has no /amcl_pose messages. What '
                                         'my log says of it: at 22:13:20, a node (WARN) "Robot is out of bounds of the '
                                         'costmap!".')
