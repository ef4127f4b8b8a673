"""Recordings that hold Nav2's bring-up and no goal (no /task_info, no navigator line), written with rosbags from
real console lines: a lifecycle manager that never found a node it manages is a node that never came up, and an
error no catalogue reads is quoted with its node and time instead of "lines I do not read" (issue 20)."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.claims import read_claims
from hexar.evals.real_nav2 import Excerpt, write_recording
from hexar.events import contract as c
from hexar.events import read_recording
from hexar.explainers.base import Context, Explanation
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.navigation import diagnose as g
from hexar.explainers.navigation.detectors import NOMINAL, UNEXPLAINED
from hexar.explainers.stack import bringup_findings

# ros-navigation/navigation2#4350 (blind2, spent): robot2's lifecycle manager looked for controller_server/get_state,
# not robot2/controller_server/get_state, while launch shut the servers down
_WAIT = ("[lifecycle_manager-8] [INFO] [1715949712.{}] [robot2.lifecycle_manager_navigation]: Waiting for service "
         "controller_server/get_state...\n")
UNSERVED = (_WAIT.format("764654791") + _WAIT.format("814797211")
            + "[INFO] [controller_server-1]: process has finished cleanly [pid 22610]\n" + _WAIT.format("864954029"))
# the same waits, then the manager goes on (nav2_lifecycle_manager lifecycle_manager.cpp:214@humble, "Configuring "
# + node name, and :288 "Managed nodes are active"): the node came up a little late
SERVED = UNSERVED + """\
[lifecycle_manager-8] [INFO] [1715949714.864954029] [robot2.lifecycle_manager_navigation]: Configuring controller_server
[lifecycle_manager-8] [INFO] [1715949715.864954029] [robot2.lifecycle_manager_navigation]: Managed nodes are active
"""
# ROBOTIS-GIT/turtlebot3#386 (blind9, spent): the map's image path, which no catalogue reads
MAP_IMAGE = ('[ERROR] [map_server]: failed to open image file "/root/ws/install/turtlebot3_navigation2/share/'
             'turtlebot3_navigation2/map/~/map.pgm": Couldn\'t open /root/ws/install/turtlebot3_navigation2/share/'
             'turtlebot3_navigation2/map/~/map.pgm\n')


def _write(tmp: Path, lines: str, task: bool) -> Path:
    ex = Excerpt(id="t", source="test", url="", distro="humble", outcome="failed",
                 cause="navigation.bringup_failure", cause_quote="", logs_show_cause=True, lines=lines)
    return write_recording(ex, tmp / f"bag{int(task)}", task=task)


def _explain(tmp: Path, lines: str, task: bool) -> Explanation:
    log = read_recording(_write(tmp, lines, task))
    return NavigationExplainer().explain("Why didn't you get there?", Context.for_task(log, log.task()))


def test_repeated_waits_that_are_the_managers_last_words_are_a_node_that_never_came_up(tmp_path: Path) -> None:
    logs = read_recording(_write(tmp_path, UNSERVED, False)).view(frozenset({c.ROSOUT})).logs()
    [f] = bringup_findings(logs)
    assert (f.kind, f.node) == ("lifecycle_wait", "controller_server")
    assert f.detail == "'controller_server/get_state', 3 times"
    assert f.line is logs[-1]


def test_waits_the_manager_got_past_are_no_finding(tmp_path: Path) -> None:
    logs = read_recording(_write(tmp_path, SERVED, False)).view(frozenset({c.ROSOUT})).logs()
    assert [f for f in bringup_findings(logs) if f.kind == "lifecycle_wait"] == []


@pytest.mark.parametrize("task", [False, True], ids=["no_task", "task"])
def test_an_unserved_node_is_told_as_a_bringup_failure(tmp_path: Path, task: bool) -> None:
    answer = _explain(tmp_path, UNSERVED, task)
    assert answer.causes == [g.BRINGUP]
    assert "never came up" in answer.text and "controller_server/get_state', 3 times" in answer.text
    assert "do not read" not in answer.text
    assert read_claims(answer.text).affirmed >= {g.BRINGUP}


@pytest.mark.parametrize("task", [False, True], ids=["no_task", "task"])
def test_an_error_no_catalogue_reads_is_quoted_with_its_node(tmp_path: Path, task: bool) -> None:
    answer = _explain(tmp_path, MAP_IMAGE, task)
    assert answer.causes == [UNEXPLAINED]
    assert "came from map_server: 'failed to open image file" in answer.text and " UTC)" in answer.text
    assert "do not read" not in answer.text and "enough information" not in answer.text
    # with no goal recorded, no goal is said to have failed
    assert ("failed" in answer.text.split(". ")[0]) is task


# slam-wheeled-robot's notes (blind5, spent): MPPI's warning, pasted without its level, broken after its first sentence
MPPI = ("[controller_server]: Inconsistent configuration in collision checking.\n"
        "Please verify the robot's shape settings in both the costmap and the cost critic.\n")


def test_a_warning_pasted_without_its_level_is_no_run_that_went_normally(tmp_path: Path) -> None:
    answer = _explain(tmp_path, MPPI, False)
    assert "went normally" not in answer.text and NOMINAL not in answer.causes
    assert "The last warning my logs show came from controller_server: 'Inconsistent configuration" in answer.text


def test_an_initial_pose_asked_for_and_then_set_is_no_finding(tmp_path: Path) -> None:
    # blind set 11 (spent): AMCL asks for an initial pose, a costmap waits for base_link -> map, then AMCL logs
    # "initialPoseReceived" and "Setting pose (79.000000): -2.000 -0.500 -0.000" and the stack comes up
    from hexar.evals.real_nav2 import blind_set

    case = next(e for e in blind_set(11) if e.id == "ros2-nav2-docker-humble-tb3-spawned-initial-pose-stack-active")
    log = read_recording(write_recording(case, tmp_path / "run", task=False))
    answer = NavigationExplainer().explain("what happened?", Context.for_task(log, log.task()))
    assert "initial pose" not in answer.text
    # the warnings of a node with no name stay in the answer: "went normally" is said of Nav2's own nodes
    assert answer.text.startswith("As far as my recording shows, my navigation went normally")
    assert answer.text.endswith("The last warning my logs show came from a node that gave no name (at 22:13:20.700 "
                                "UTC).")


def test_a_configure_asked_of_nodes_already_up_is_a_bring_up_run_twice(tmp_path: Path) -> None:
    # blind set 2 (spent), turtlebot3#1061: lifecycle_manager_localization configures map_server, which is active
    # already, and controller_server, inactive already: rcl_lifecycle has no transition 1 from those states
    from hexar.evals.real_nav2 import blind_set

    case = next(e for e in blind_set(2) if e.id == "tb3-1061-jazzy-lifecycle-bringup-aborted")
    log = read_recording(write_recording(case, tmp_path / "run", task=False))
    answer = NavigationExplainer().explain("what happened?", Context.for_task(log, log.task()))
    assert answer.text.startswith(
        "I couldn't reach my goal because of a bring-up failure: my lifecycle manager asked controller_server to "
        "configure again while it was already inactive, a transition that state does not have: something had brought "
        "it up before (a second lifecycle manager that manages it, or the same launch started twice).")
    assert "never became active" not in answer.text
    assert read_claims(answer.text).causes == {"navigation.bringup_failure"}


def test_a_goal_reached_in_under_a_second_is_not_said_to_take_0_s(tmp_path: Path) -> None:
    # blind set 10: a forklift's MPC goal reached 0.3 s after it began
    from hexar.evals.real_nav2 import blind_set

    case = next(e for e in blind_set(10) if e.id == "forklift-mpc-humble-p45-navigate-to-pose-succeeded")
    log = read_recording(write_recording(case, tmp_path / "run", task=False))
    answer = NavigationExplainer().explain("how did it go?", Context.for_task(log, log.task()))
    assert "I took 0.3 s to get there" in answer.text and "0 s" not in answer.text.replace("0.3 s", "")


@pytest.mark.parametrize(("ident", "then"), [
    # blind set 20: cmd_vel remapped away from the base, progress never made, the client cancels after 90 s
    ("kilted-nav2-cmd-vel-remapped", "; before that, my controller made no progress"),
    # blind set 22: the collision monitor's base frame wrong, the client cancels
    ("kilted-nav2-monitor-base-frame", ", so it does not show whether I got there; on the way my logs show a problem"),
])
def test_a_goal_a_client_canceled_is_not_told_as_given_up_or_unfinished(tmp_path: Path, ident: str, then: str) -> None:
    from hexar.evals.real_nav2 import blind_set

    case = next(e for n in range(1, 30) for e in blind_set(n) if e.id == ident)
    log = read_recording(write_recording(case, tmp_path / "run", task=False))
    answer = NavigationExplainer().explain("what happened?", Context.for_task(log, log.task()))
    assert answer.text.startswith("My navigation to the goal at (10.00, 4.00) was canceled before it finished (a "
                                  "client asked to cancel it)" + then)
    assert "gave up" not in answer.text and "recording ends" not in answer.text
