"""What became of one node ("did controller_manager crash after that or keep running?", "did move_group still start
up?"): its own lines, what launch said of its process, a C++ abort in its output, or that the log holds nothing of
it. Real excerpts written with rosbags."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from tests.agent.helpers import converse, real_module_run, real_nav2_run


@pytest.mark.parametrize(("question", "kind"), [
    ("did controller_manager crash after that or keep running?", "node_status"),
    ("did move_group still start up despite this error?", "node_status"),
    ("did lifecycle_manager bring up the rest of nav2?", "node_status"), ("was amcl running?", "node_status"),
    ("did you start?", None), ("did the robot crash?", None),
])
def test_a_node_by_its_name_is_its_own_question(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_an_abort_in_a_nodes_output_is_said(tmp_path: Path) -> None:
    run = real_module_run("r2c-controllers-1595-libserial-open-failed", tmp_path / "run")
    (crashed,) = converse(run, "did controller_manager crash after that or keep running?")
    text = str(crashed["answer"])
    assert text.startswith("The node controller_manager logged 1 line at 04:42:10; its last (ERROR): ")
    assert text.endswith('its output at 04:42:10 holds "terminate called after throwing": its process aborted there.')


def test_launch_ending_a_process_and_a_node_never_heard(tmp_path: Path) -> None:
    run = real_nav2_run("kilted-nav2-dock-database-missing", tmp_path / "run")
    (manager, never) = converse(run, "did lifecycle_manager bring up the rest of nav2?", "did rviz2 start?")
    assert str(manager["answer"]).startswith("The node lifecycle_manager logged ")
    assert str(manager["answer"]).endswith("launch said its process finished cleanly at 09:33:42.")
    assert never["answer"] == ("My log holds no line from rviz2 and no word from launch about its process: it may not "
                               "have run, or its lines were not recorded; I can't tell.")


def test_a_process_named_after_its_executable_is_the_nodes(tmp_path: Path) -> None:
    # held-out set 26: node base_driver, run by the executable base_driver_node ("base_driver_node-1")
    (asked,) = converse(real_module_run("kilted-respawn-crash-loop", tmp_path / "run"),
                        "Did base_driver start correctly?")
    assert str(asked["answer"]).endswith("launch said its process finished cleanly at 12:58:22.")


def test_whether_a_controller_was_active_is_told_with_what_the_controller_manager_said_of_it(tmp_path: Path) -> None:
    # held-out set 36: arm_controller configured and activated, then a goal with no positions (the stack's shutdown
    # after the goal deactivates it, which says nothing of the goal)
    (asked,) = converse(real_module_run("kilted-control-traj-no-positions", tmp_path / "run"),
                        "Was arm_controller active when the goal arrived?")
    text = str(asked["answer"])
    assert ('other nodes said of it: at 13:53:02, controller_manager (INFO) "Configuring controller: '
            '\'arm_controller\'"; at 13:53:02, controller_manager (INFO) "Activating controllers: [ arm_controller ]"'
            in text)
    assert "Deactivating" not in text


def test_a_hardware_component_is_told_by_what_others_said_of_it(tmp_path: Path) -> None:
    """A ros2_control hardware component has no logger of its own; its name also keeps its 'r' (no chat spelling is
    read inside an identifier: lbr_iisy11_r1300, not lbr_iisy11_are1300)."""
    run = real_module_run("kuka-drivers-344-iiqka-rsi-stale-project-files", tmp_path / "run")
    (active,) = converse(run, "did lbr_iisy11_r1300 actually activate?")
    assert active["answer"] == ("My log holds no line of lbr_iisy11_r1300's own, but other nodes said of it: at "
                                "22:13:20, resource_manager (INFO) \"Successful 'activate' of hardware "
                                "'lbr_iisy11_r1300'\".")


def test_what_a_node_was_doing_when_the_stack_was_stopped(tmp_path: Path) -> None:
    """A real Nav2 console: the lifecycle manager was still activating planner_server when Ctrl-C came, and only
    on the way down said it failed; the answer gives its last line before the shutdown too."""
    run = real_nav2_run("kilted-nav2-ekf-world-map", tmp_path / "run")
    (status,) = converse(run, "Did lifecycle_manager_navigation finish bringing up all the nodes, or did one fail to "
                              "activate?")
    assert 'its last line before my stack began to shut down came at 09:44:24: "Activating planner_server"' \
        in str(status["answer"])
