"""Whole consoles of the real Nav2 (its kilted branch, built here) that scripts/nav2_faults.py ran with one fault
each (blind sets 20 to 23, spent), written as recordings with rosbags, with and without a /task_info task: Kilted's
goal-end line, which quotes the error, ends the goal derived from the log; what the stack prints as it is stopped
with Ctrl-C (a message filter's drops, launch killing a node that would not end) is never the cause of what
happened before; a message filter's routine drops at start-up, before the goal began, are no transform fault; one
burst of a controller's collision warnings (set 20's box, set 21's wrong initial pose) is one thing in the way, not
people moving about; a console without poses still gives the time a trip took and the straight line to its goal;
the collision monitor's slowdown is why a trip took long, not a failure."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.real_nav2 import Excerpt, blind_set, write_recording
from hexar.events import read_recording


def _excerpt(ident: str) -> Excerpt:
    return next(e for e in blind_set(20) if e.id == f"kilted-nav2-{ident}")


def _ask(tmp_path: Path, ident: str, task: bool) -> dict[str, object]:
    bag = write_recording(_excerpt(ident), tmp_path / f"bag{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("Why did you fail?"))


def test_kilteds_goal_failed_line_quoting_the_planners_error_ends_the_derived_goal(tmp_path: Path) -> None:
    # bt_action_server_impl.hpp@kilted: "Goal failed error_code:%d error_msg:'%s'", whose error_msg holds the
    # planner's "Start Coordinates of(...) was outside bounds" (a cause line of its own)
    log = read_recording(write_recording(_excerpt("start-off-map"), tmp_path / "bag", task=False))
    [task] = log.tasks
    assert task.outcome == "failed" and task.skills[0].params["x"] == 10.0
    assert "the recording ends" not in str(_ask(tmp_path, "start-off-map", False)["answer"]).lower()


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_the_shutdown_after_ctrl_c_is_not_the_cause_of_a_goal_that_ended_before(tmp_path: Path, task: bool) -> None:
    # the base never heard the commands (a remap): the goal ran out of progress and was cancelled; then Ctrl-C, and
    # launch SIGKILLed bt_navigator, which would not end ("process has died [..., exit code -9, ...]")
    lines = _excerpt("cmd-vel-remapped").lines
    assert "user interrupted with ctrl-c (SIGINT)" in lines and "exit code -9" in lines
    answer = _ask(tmp_path, "cmd-vel-remapped", task)
    assert answer["causes"] == ["navigation.no_progress"]
    assert "nothing in my logs says why" in str(answer["answer"])
    assert "process has died" not in str(answer["evidence"])


@pytest.mark.parametrize("ident", ["start-off-map", "start-in-wall"])
def test_drops_at_start_up_and_at_shutdown_are_no_transform_fault(tmp_path: Path, ident: str) -> None:
    # "Message Filter dropping message: ... earlier than all the data in the transform cache" at INFO as the stack
    # went down, and (start-in-wall) as the costmaps came up; the goal between them failed on the robot's own start
    lines = _excerpt(ident).lines
    assert lines.count("earlier than all the data in the transform cache") >= (2 if ident == "start-in-wall" else 1)
    for task in (True, False):
        answer = _ask(tmp_path / str(task), ident, task)
        assert answer["causes"] == ["navigation.unexplained_failure"], answer["answer"]
        assert "transform" not in str(answer["answer"]).split("It can be")[0]


def _reached_late(tmp_path: Path, excerpt: Excerpt, task: bool) -> dict[str, object]:
    bag = write_recording(excerpt, tmp_path / f"late{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask("How did the navigation go?"))


@pytest.mark.parametrize("blind,ident", [(20, "box-ahead"), (21, "amcl-wrong-initial-pose")])
def test_one_burst_of_collision_warnings_is_one_thing_in_the_way_not_people_moving(
        tmp_path: Path, blind: int, ident: str) -> None:
    # a box 0.6 m ahead (set 20) and AMCL started 2.1 m off (set 21): RegulatedPurePursuit warned "detected collision
    # ahead!" on every 20 Hz cycle for under a second, gave up, and the goal was reached after a detour
    excerpt = next(e for e in blind_set(blind) if e.id == f"kilted-nav2-{ident}")
    assert excerpt.lines.count("detected collision ahead!") >= 10
    for task in (True, False):
        answer = _reached_late(tmp_path, excerpt, task)
        text = str(answer["answer"])
        assert answer["causes"] == ["navigation.unexplained_failure"], text
        assert "moving" not in text and "people" not in text
        assert "collision check stopped me" in text and "can't tell what was in the way" in text


def test_collision_warnings_seconds_apart_are_things_moving_into_the_way(tmp_path: Path) -> None:
    # the same real console with its burst of warnings printed again 3 s later (a second thing crossing the path)
    excerpt = _excerpt("box-ahead")
    burst = [ln for ln in excerpt.lines.splitlines() if "detected collision ahead!" in ln][:3]
    again = "\n".join(ln.replace("[1796002709.", "[1796002712.") for ln in burst)
    at = excerpt.lines.index("[controller_server-4] [INFO] [1796002712.333835471]")
    moved = replace(excerpt, lines=excerpt.lines[:at] + again + "\n" + excerpt.lines[at:])
    answer = _reached_late(tmp_path, moved, False)
    assert answer["causes"] == ["navigation.moving_obstacles"], answer["answer"]


def _ask22(tmp_path: Path, ident: str, question: str, task: bool) -> dict[str, object]:
    excerpt = next(e for e in blind_set(22) if e.id == f"kilted-nav2-{ident}")
    bag = write_recording(excerpt, tmp_path / f"b22{int(task)}", task=task)
    return dict(Session(RunSettings(recording=bag, llm="none")).ask(question))


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_a_console_without_poses_still_gives_the_time_and_the_straight_line_to_the_goal(
        tmp_path: Path, task: bool) -> None:
    # set 22's smoother in closed loop on odometry nobody published: 62 s for a goal 8 m away; the recording holds
    # only the console, whose begin line is "Begin navigating from current location (2.00, 4.00) to (10.00, 4.00)"
    answer = _ask22(tmp_path, "smoother-closed-loop-no-odom", "Why did it take so long to get there?", task)
    text = str(answer["answer"])
    assert answer["causes"] == ["navigation.nominal_speed"]
    assert "I took 62 s to get there, 8.0 m in a straight line from where I started" in text
    assert "at least 0.13 m/s on average" in text and "no figures" not in text


def test_the_collision_monitors_slowdown_answers_why_it_took_long_but_is_no_failure(tmp_path: Path) -> None:
    # "Robot to slowdown for 30.000000 percents due to Guard polygon", then "Robot to continue normal operation"
    # 12.9 s later: the reason the trip took longer, and no cause of a failure when asked how it went
    slow = _ask22(tmp_path / "slow", "monitor-slowdown-circle", "Why did it take so long to get there?", False)
    assert "collision monitor slowed me down for 13 s" in str(slow["answer"])
    assert "Robot to slowdown for 30.000000 percents due to Guard polygon" in str(slow["evidence"])
    went = _ask22(tmp_path / "went", "monitor-slowdown-circle", "How did the navigation go?", False)
    assert went["causes"] == ["navigation.nominal"] and "without any problem" in str(went["answer"])


@pytest.mark.parametrize("task", [True, False], ids=["task_info", "derived"])
def test_thetas_goal_in_lethal_cost_is_a_goal_that_cannot_be_reached(tmp_path: Path, task: bool) -> None:
    # set 23: Theta* and a goal inside the wall between the rooms; planner_server printed "GridBasedplugin failed to
    # plan from (2.00, 4.00) to (6.10, 2.00): "Goal Coordinates of(6.100000, 2.000000) was in lethal cost""
    excerpt = next(e for e in blind_set(23) if e.id == "kilted-nav2-theta-goal-in-wall")
    bag = write_recording(excerpt, tmp_path / "bag", task=task)
    answer = Session(RunSettings(recording=bag, llm="none")).ask("Why didn't you get there?")
    assert answer["causes"] == ["navigation.goal_unreachable"]
    assert "goal itself on occupied cells (lethal cost)" in str(answer["answer"])
