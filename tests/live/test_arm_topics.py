"""The arm's action topics live, on both transports (the robot stand-in on the other DDS vendor where rclpy
exists): an arm without /task_info gets its tasks from MoveIt's move_action status and a joint trajectory
controller's follow_joint_trajectory status, and an aborted goal is explained unasked as `hexar ask` explains the
recording; `hexar replay` republishes the arm's status topics so the live records equal the recording's.

Log lines are MoveIt's and joint_trajectory_controller's own (moveit/moveit2 and ros-controls/ros2_controllers,
file:line@branch beside each)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO
from hexar.live.log import LiveLog
from hexar.live.node import FAILURE_QUESTION
from hexar.live.topics import ARM_STATUS, SUBSCRIBED
from tests.live.dds_helpers import (
    Listener,
    fresh_domain,
    live_node,
    make_replayer,
    make_transport,
    other,
    replay_matched,
)

T0 = 1_700_000_000_000_000_000
TY = TYPESTORE.types
FJT = "/arm_controller/follow_joint_trajectory/_action/status"  # TIAGo's arm controller


def _time(t: int) -> Any:
    return TY["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)


def _status(status: int, goal: int = 3) -> Any:
    return TY["action_msgs/msg/GoalStatusArray"](status_list=[TY["action_msgs/msg/GoalStatus"](
        goal_info=TY["action_msgs/msg/GoalInfo"](
            goal_id=TY["unique_identifier_msgs/msg/UUID"](uuid=np.arange(goal, goal + 16, dtype=np.uint8)),
            stamp=_time(T0)),
        status=status)])


def arm_robot(topic: str, lines: list[tuple[float, str, int, str]]) -> BagBuilder:
    """An arm without /task_info: one goal on `topic` (accepted, executing, aborted) and the lines around it."""
    b = BagBuilder()
    b.raw(T0 + sec_ns(0.1), topic, c.GOAL_STATUS_TYPE, _status(1))
    b.raw(T0 + sec_ns(0.2), topic, c.GOAL_STATUS_TYPE, _status(2))
    for s, name, level, msg in lines:
        b.log(T0 + sec_ns(s), name, level, msg)
    b.raw(T0 + sec_ns(4), topic, c.GOAL_STATUS_TYPE, _status(6))
    return b


# model_based_planning_context.cpp:795@humble (INFO), move_action_capability.cpp:97@humble (the result text)
PLANNING = [(1.0, "moveit.ompl_planning.model_based_planning_context", INFO, "Unable to solve the planning problem"),
            (1.1, "moveit_move_group_default_capabilities.move_action_capability", INFO,
             "No motion plan found. No execution attempted.")]
# joint_trajectory_controller.cpp:360@humble and tolerances.hpp:322/326@humble
TOLERANCE = [(0.3, "arm_controller", INFO, "Accepted new action goal"),
             (2.0, "tolerances", ERROR, "State tolerances failed for joint 2:"),
             (2.0, "tolerances", ERROR, "Position Error: 0.310000, Position Tolerance: 0.200000"),
             (2.01, "arm_controller", 30, "Aborted due to state tolerance violation")]


def recorded_answer(run: Path) -> tuple[str, list[str]]:
    session = Session(RunSettings(recording=run, llm="none"))
    (task,) = [t for t in session.context.log.tasks if t.outcome == "failed"]
    assert task.derived
    return task.task_id, list(session.ask(FAILURE_QUESTION, task=task.task_id)["causes"])


def explained_live(run: Path, transport: str) -> dict[str, Any]:
    domain = fresh_domain()
    listener = Listener(domain)
    robot = make_replayer(other(transport), domain)
    try:
        with live_node(domain, transport=transport) as node:
            # the node reads six more status topics than a Nav2 robot's: a longer warm-up lets discovery match them
            # all before the goal's first status (keep-last 1), so the node sees the goal active, then aborted
            replay_matched(run, robot, rate=4.0)
            answers = listener.wait_answers(1, "failure", timeout=30.0)
            assert node.errors == 0
            return answers[0] if answers else {}
    finally:
        robot.close()
        listener.close()


def test_an_aborted_moveit_goal_is_explained_unasked(tmp_path: Path, transport: str) -> None:
    run = arm_robot(c.MOVE_ACTION_STATUS, PLANNING).write(tmp_path / "moveit")
    task_id, causes = recorded_answer(run)
    assert causes == ["manipulation.planning_failed"]
    answer = explained_live(run, transport)
    assert answer, "no proactive answer for the aborted MoveGroup goal"
    assert answer["task_id"] == task_id and answer["causes"] == causes and answer["error"] == ""


def test_an_aborted_controller_goal_is_explained_unasked(tmp_path: Path, transport: str) -> None:
    run = arm_robot(FJT, TOLERANCE).write(tmp_path / "fjt")
    task_id, causes = recorded_answer(run)
    assert causes == ["control.tolerance_violated"]
    answer = explained_live(run, transport)
    assert answer and answer["task_id"] == task_id and answer["causes"] == causes


def test_the_arms_status_topics_are_subscribed_and_replayed(tmp_path: Path, transport: str) -> None:
    assert {c.MOVE_ACTION_STATUS, c.EXECUTE_TRAJECTORY_STATUS, FJT} <= ARM_STATUS <= {t.topic for t in SUBSCRIBED}
    b = arm_robot(c.EXECUTE_TRAJECTORY_STATUS, [])
    for k, status in enumerate((1, 4)):  # a second goal on a controller, which succeeds
        b.raw(T0 + sec_ns(5 + k), FJT, c.GOAL_STATUS_TYPE, _status(status, goal=40))
    run = b.write(tmp_path / "robot")
    rec = read_recording(run)
    assert len(rec.goal_statuses) == 5

    def last(statuses: list[Any]) -> dict[tuple[str, str], int]:
        # a status topic is keep-last 1 (rcl_action_qos_profile_status_default): a reader may miss a goal's
        # intermediate states, never its last one
        return {(s.topic, s.goal_id): s.status for s in sorted(statuses, key=lambda s: s.t)}

    domain = fresh_domain()
    node_side, log = make_transport(transport, domain), LiveLog()
    node_side.start(log, lambda r: None, lambda q: None)
    robot = make_replayer(other(transport), domain)
    try:
        replay_matched(run, robot, rate=10.0)
        deadline = time.monotonic() + 30.0
        while time.monotonic() < deadline and last(log.snapshot().goal_statuses) != last(rec.goal_statuses):
            time.sleep(0.05)
    finally:
        robot.close()
        node_side.close()
    snap = log.snapshot()
    assert last(snap.goal_statuses) == last(rec.goal_statuses)
    assert [(t.skills[0].skill, t.outcome) for t in snap.tasks] == [(t.skills[0].skill, t.outcome)
                                                                     for t in rec.tasks]
