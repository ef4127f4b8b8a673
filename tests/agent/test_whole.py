"""A recording that holds no task: what needs a task is refused with the one-line "no task to explain", what it
recorded is answered over the whole of it (real rosbag2 recordings by other people, and real excerpts written with
rosbags)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.events.errors import NoTaskError
from tests.agent.helpers import converse, real_nav2_run

HEXAR = str(Path(sys.executable).with_name("hexar"))


def test_parameters_nodes_and_topics_of_a_recording_with_no_task(real_bags: Path) -> None:
    run = real_bags / "gps_vehicle_run"
    (sim, nodes, recorded) = converse(run, "is use_sim_time set?", "which nodes were running?",
                                      "what did you record?")
    assert str(sim["answer"]).endswith("use_sim_time = false on all 5 nodes that declared it (/goal_pose_creator, "
                                       "/motion_spec_provider, /motor_carrier_driver, /route_pose_provider, "
                                       "/stanley_controller).")
    assert sim["task_id"] == "recording"
    assert str(nodes["answer"]).startswith("My log holds lines from 4 nodes: rosbag2_recorder (11 lines)")
    assert "5,348 messages on 7 topics" in str(recorded["answer"])


@pytest.mark.parametrize("question", ["what happened?", "why did it fail?", "what did the talker say?"])
def test_what_needs_a_task_is_still_refused(real_bags: Path, question: str) -> None:
    with pytest.raises(NoTaskError, match=r"^no task to explain"):
        Session(RunSettings(recording=real_bags / "rosbag2_talker_mcap", llm="none")).ask(question)


def test_lines_a_question_points_at_are_told_with_no_task(tmp_path: Path) -> None:
    # blind set 1 (tb4memo): an undock that turtlebot4_node logs, with no goal or start line HEXAR reads as a task
    run = real_nav2_run("tb4memo-ignition-undock-succeeded", tmp_path / "run")
    (asked,) = converse(run, "Did the undock succeed, and how long did it take?")
    assert asked["answer"] == (
        "My recording holds no task of mine (no /task_info, no goal, no start of my drivers or controllers in its "
        "logs), so I can't tell what I was doing, but my log says of what you asked: at 13:48:00, motion_control "
        '(INFO) "Undock Goal Succeeded"; at 13:48:00, turtlebot4_node (INFO) "undock goal succeeded".')


def test_the_chat_opens_on_a_recording_with_no_task(real_bags: Path, tmp_path: Path) -> None:
    done = subprocess.run([HEXAR, "chat", str(real_bags / "gps_vehicle_run"), "--llm", "none", "--checkpoints",
                           str(tmp_path / "t.sqlite")], input="is use_sim_time set?\nwhat happened?\nbye\n",
                          capture_output=True, text=True, timeout=120, env={"COLUMNS": "200", "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    out = " ".join(done.stdout.split())
    assert "ask about its log, nodes, topics, parameters or times" in out
    assert "use_sim_time = false on all 5 nodes" in out and "you> what happened? no task to explain" in out


def test_whether_warnings_matter_on_a_recording_with_no_task(tmp_path: Path) -> None:
    """A quote shortened with "..." still finds its lines; with no task to judge them by, the answer says when the
    last of them came and that no error followed."""
    from tests.agent.helpers import converse, real_module_run

    run = real_module_run("dynamixel-hw-if-89-velocity-wheels-skipping-position-sync-harmless", tmp_path / "run")
    (said,) = converse(run, "Are the 'No position interface found... Skipping sync!' warnings for the four wheels "
                            "actually harmful?")
    text = str(said["answer"])
    assert "dynamixel_hardware_interface (WARN) \"No position interface found in command interfaces for joint " \
           "'FL_wheel'. Skipping sync!\"" in text
    assert text.endswith("The last of them came at 19:58:53; my log goes on for less than a second after it without "
                         "another, and holds no error after it.")
