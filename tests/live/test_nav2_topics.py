"""The ordinary Nav2 topics live, over real DDS on loopback: a Nav2 robot with no /task_info gets derived tasks
and its failed goal explained unasked; /cmd_vel commanding while /odom stays still gives
commands_not_reaching_base as `hexar ask` does on the recording; `hexar replay` republishes the four topics so
the live records equal the recording's; and the live log keeps 50 Hz odometry bounded.

Log lines are real Nav2 wording (shared reference nav2_log_messages.md, and the corpus threads cited in
tests/explainers/navigation/test_nav2_causes.py)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.reader import read_recording
from hexar.events.records import ERROR, INFO, WARN, OdomSample
from hexar.explainers.navigation import diagnose as g
from hexar.live.dds import DdsTransport
from hexar.live.limits import Limits
from hexar.live.log import LiveLog
from hexar.live.node import FAILURE_QUESTION
from hexar.live.replay import DdsReplayer
from hexar.live.replay import replay as replay_in_process
from tests.live.dds_helpers import Listener, fresh_domain, live_node, replay, replay_matched

T0 = 1_700_000_000_000_000_000
TY = TYPESTORE.types
GOAL_ID = 7


def _time(t: int) -> Any:
    return TY["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)


def _status(t: int, status: int) -> Any:
    return TY["action_msgs/msg/GoalStatusArray"](status_list=[TY["action_msgs/msg/GoalStatus"](
        goal_info=TY["action_msgs/msg/GoalInfo"](
            goal_id=TY["unique_identifier_msgs/msg/UUID"](uuid=np.arange(GOAL_ID, GOAL_ID + 16, dtype=np.uint8)),
            stamp=_time(T0)),
        status=status)])


def _pose(x: float, y: float) -> Any:
    return TY["geometry_msgs/msg/Pose"](position=TY["geometry_msgs/msg/Point"](x=x, y=y, z=0.0),
                                        orientation=TY["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))


def _twist(vx: float, wz: float = 0.0) -> Any:
    v3 = TY["geometry_msgs/msg/Vector3"]
    return TY["geometry_msgs/msg/Twist"](linear=v3(x=vx, y=0.0, z=0.0), angular=v3(x=0.0, y=0.0, z=wz))


def _odom(t: int, x: float, vx: float) -> Any:
    return TY["nav_msgs/msg/Odometry"](
        header=TY["std_msgs/msg/Header"](stamp=_time(t), frame_id="odom"), child_frame_id="base_link",
        pose=TY["geometry_msgs/msg/PoseWithCovariance"](pose=_pose(x, 0.0), covariance=np.zeros(36)),
        twist=TY["geometry_msgs/msg/TwistWithCovariance"](twist=_twist(vx), covariance=np.zeros(36)))


def nav2_robot(lines: list[tuple[str, int, str]], cmd_vel: bool = False) -> BagBuilder:
    """A Nav2 robot without /task_info: a goal from RViz, the NavigateToPose status, bt_navigator's lines."""
    b = BagBuilder()
    b.raw(T0, c.GOAL_POSE, c.POSE_STAMPED_TYPE, TY["geometry_msgs/msg/PoseStamped"](
        header=TY["std_msgs/msg/Header"](stamp=_time(T0), frame_id="map"), pose=_pose(1.0, 2.0)))
    b.raw(T0 + sec_ns(0.1), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(0.1), 1))
    b.raw(T0 + sec_ns(0.2), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(0.2), 2))
    b.log(T0 + sec_ns(0.2), "bt_navigator", INFO,
          "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    for i, (name, level, msg) in enumerate(lines):
        b.log(T0 + sec_ns(1 + i), name, level, msg)
    if cmd_vel:
        for i in range(40):  # 10 Hz for 4 s: the controller commands 0.26 m/s, the odometry never moves
            t = T0 + sec_ns(1.2 + i * 0.1)
            b.raw(t, c.CMD_VEL, c.TWIST_TYPE, _twist(0.26, 0.1))
            b.raw(t, c.ODOM, c.ODOM_TYPE, _odom(t, 0.0, 0.0))
    done = T0 + sec_ns(6)
    b.log(done, "bt_navigator", ERROR, "Goal failed")
    b.raw(done + sec_ns(0.05), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(done + sec_ns(0.05), 6))
    return b


def recorded_answer(run: Path) -> tuple[str, list[str]]:
    """The failed derived task and the causes `hexar ask` gives for it on the recording."""
    session = Session(RunSettings(recording=run, llm="none"))
    (task,) = [t for t in session.context.log.tasks if t.outcome == "failed"]
    assert task.derived
    return task.task_id, list(session.ask(FAILURE_QUESTION, task=task.task_id)["causes"])


def explained_live(run: Path) -> tuple[dict[str, Any], Any]:
    """Publish the robot's messages over DDS (the replayer's writers, the robot's QoS) into a fresh node; the
    unasked answer and a snapshot of the node's live log."""
    domain = fresh_domain()
    listener = Listener(domain)
    robot = DdsReplayer(domain)
    try:
        with live_node(domain) as node:
            replay_matched(run, robot, rate=10.0)
            answers = listener.wait_answers(1, "failure", timeout=30.0)
            assert node.errors == 0
            return answers[0] if answers else {}, node.log.snapshot()
    finally:
        robot.close()
        listener.close()


# planner_server's wording from opennav_coverage#64 (a goal outside the map)
UNREACHABLE = [("planner_server", WARN, 'GridBased plugin failed to plan from (0.00, -0.01) to (-105.92, 39.25): '
                '"Goal Coordinates of(-105.918845, 39.251424) was outside bounds"')]
# navigation2#4027: the controller kept commanding, the base never moved
NO_MOTION = [("controller_server", INFO, "Received a goal, begin computing control effort."),
             ("controller_server", ERROR, "Failed to make progress")]


def test_a_nav2_robot_without_task_info_gets_its_failed_goal_explained_unasked(tmp_path: Path) -> None:
    run = nav2_robot(UNREACHABLE).write(tmp_path / "nav2")
    task_id, causes = recorded_answer(run)
    assert causes == [g.GOAL_UNREACHABLE]
    answer, snap = explained_live(run)
    assert answer, "no proactive answer for the aborted NavigateToPose goal"
    assert answer["task_id"] == task_id and answer["causes"] == causes
    assert answer["error"] == "" and answer["sentence"]
    (task,) = snap.tasks
    assert task.derived and task.outcome == "failed"
    assert (task.skills[0].params["x"], task.skills[0].params["y"]) == (1.0, 2.0)
    assert not snap.task_updates  # no /task_info: the task came from the goal topics and bt_navigator


def test_cmd_vel_that_odom_never_follows_is_commands_not_reaching_base_live(tmp_path: Path) -> None:
    run = nav2_robot(NO_MOTION, cmd_vel=True).write(tmp_path / "stall")
    task_id, causes = recorded_answer(run)
    assert causes == [g.NOT_REACHING_BASE]
    answer, snap = explained_live(run)
    assert answer and answer["task_id"] == task_id and answer["causes"] == causes
    rec = read_recording(run)
    assert snap.twists == rec.twists and snap.odometry == rec.odometry
    # without /cmd_vel and /odom the same goal is only "no progress": the live cause comes from the new topics
    bare = nav2_robot(NO_MOTION).write(tmp_path / "bare")
    assert recorded_answer(bare)[1] == [g.NO_PROGRESS]


def test_hexar_replay_republishes_the_nav2_topics(tmp_path: Path) -> None:
    b = nav2_robot(NO_MOTION, cmd_vel=True)
    run = b.write(tmp_path / "robot")
    rec = read_recording(run)
    domain = fresh_domain()
    transport, log = DdsTransport(domain), LiveLog()
    transport.start(log, lambda r: None, lambda q: None)
    try:
        replay(run, domain, rate=10.0)
        deadline = time.monotonic() + 3.0  # the reader thread may still be taking the last samples
        sent = len(rec.twists) + len(rec.odometry) + len(rec.goals) + len(rec.goal_statuses) + len(rec.logs)
        while time.monotonic() < deadline and log.stats()["received"] < sent:
            time.sleep(0.02)
    finally:
        transport.close()
    snap = log.snapshot()
    assert transport.errors == 0
    assert len(rec.twists) == len(rec.odometry) == 40 and len(rec.goal_statuses) == 3 and len(rec.goals) == 1
    assert snap.twists == rec.twists
    assert snap.odometry == rec.odometry
    assert snap.goals == rec.goals
    assert snap.goal_statuses == rec.goal_statuses
    assert snap.logs == rec.logs
    assert {t: snap.topics[t].count for t in c.NAV2_TOPICS} == {t: rec.topics[t].count for t in c.NAV2_TOPICS}


def test_odometry_for_hours_stays_bounded(tmp_path: Path) -> None:
    limits = Limits(horizon_s=60.0)
    log = LiveLog(limits)
    hz, hours = 50, 1.0
    n = int(hours * 3600 * hz)
    for i in range(n):
        log.add(OdomSample(T0 + i * (10**9 // hz), 0.001 * i, 0.0, 0.1, 0.0))
    kept = log.stats()["odometry"]
    assert kept <= limits.horizon_s * hz + 600  # the horizon, plus the records added between two prunes
    snap = log.snapshot()
    assert snap.odometry[-1].t == T0 + (n - 1) * (10**9 // hz)  # the newest kept, the oldest dropped
    assert snap.odometry[0].t >= snap.odometry[-1].t - int(limits.horizon_s * 1e9) - 600 * (10**9 // hz)


def test_replay_skips_a_nav2_topic_of_another_type_and_sends_twist_stamped_as_twist(tmp_path: Path) -> None:
    from hexar.live.convert import to_records
    from hexar.live.replay import bag_messages, to_dds

    b = BagBuilder()
    b.log(T0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (1.00, 2.00)")
    # a robot whose /odom is a PoseStamped (not Nav2's Odometry) and whose /cmd_vel is Jazzy's TwistStamped
    b.raw(T0 + sec_ns(1), c.ODOM, c.POSE_STAMPED_TYPE, TY["geometry_msgs/msg/PoseStamped"](
        header=TY["std_msgs/msg/Header"](stamp=_time(T0), frame_id="odom"), pose=_pose(1.0, 0.0)))
    b.raw(T0 + sec_ns(2), c.CMD_VEL, c.TWIST_STAMPED_TYPE, TY["geometry_msgs/msg/TwistStamped"](
        header=TY["std_msgs/msg/Header"](stamp=_time(T0 + sec_ns(2)), frame_id="base_link"), twist=_twist(0.3, 0.2)))
    run = b.write(tmp_path / "jazzy")
    messages, skipped = bag_messages(run)[:2]
    sent = [(topic, to_dds(msgtype, m), t) for topic, msgtype, t, m in messages]
    assert c.ODOM in skipped and [topic for topic, _, _ in sent] == [c.ROSOUT, c.CMD_VEL]
    twist = to_records(c.CMD_VEL, sent[1][1], sent[1][2])
    assert twist == read_recording(run).twists  # same velocities; the header stamp equals the bag time here
    assert read_recording(run).warnings[0].startswith("skipped /odom")  # the reader skips the misfit /odom the same way


def test_a_goal_that_failed_before_the_node_joined_is_answered_when_asked_not_announced(tmp_path: Path) -> None:
    from hexar.live.topics import PUBLISHED_BY_ROBOT

    run = nav2_robot(UNREACHABLE).write(tmp_path / "before")
    task_id, causes = recorded_answer(run)
    domain = fresh_domain()
    robot = DdsReplayer(domain)  # the robot's writers stay: /rosout and the action status are transient-local
    listener = Listener(domain)
    try:
        replay_in_process(run, robot, rate=20.0, warmup_s=0.0)
        assert PUBLISHED_BY_ROBOT[c.NAV_STATUS].durability == "transient_local"
        with live_node(domain) as node:
            recorded = read_recording(run).logs
            deadline = time.monotonic() + 30.0
            while time.monotonic() < deadline and not (node.log.snapshot().goal_statuses
                                                       and len(node.log.snapshot().logs) >= len(recorded)):
                time.sleep(0.05)
            time.sleep(0.5)  # anything more would arrive now, and fail the equalities below
            snap = node.log.snapshot()
            assert [s.status for s in snap.goal_statuses] == [6]  # the late joiner got the last array only
            assert snap.logs == recorded  # and /rosout's history, as rcl's rosout offers it
            assert listener.answers("failure") == []
            listener.ask("Why did the task fail?")
            (answer,) = listener.wait_answers(1, "question", timeout=10.0)
    finally:
        listener.close()
        robot.close()
    assert answer["task_id"] == task_id and answer["causes"] == causes


def test_a_goal_on_a_wall_of_the_latched_map_is_explained_live_from_the_costmap(tmp_path: Path) -> None:
    # nav2_bringup's real tb3_sandbox map, latched on /map and /global_costmap/costmap as map_server and
    # nav2_costmap_2d offer it; the planner only says it found no path, the costmap says why
    from tests.explainers.navigation.maps import costmap, record_grids, sandbox
    from tests.explainers.navigation.test_grids import nearest

    static, res, origin = sandbox()
    wall = nearest(static, 100, 1.3, 1.0)
    b = BagBuilder()
    record_grids(b, T0 - sec_ns(5), static, costmap(static, res), res, origin)
    b.raw(T0 + sec_ns(0.1), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(0.1), 2))
    b.log(T0 + sec_ns(0.2), "bt_navigator", INFO,
          f"Begin navigating from current location (-2.00, -0.50) to ({wall[0]:.2f}, {wall[1]:.2f})")
    b.log(T0 + sec_ns(0.3), "planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50.")
    b.log(T0 + sec_ns(3), "bt_navigator", ERROR, "Goal failed")
    b.raw(T0 + sec_ns(3.05), c.NAV_STATUS, c.GOAL_STATUS_TYPE, _status(T0 + sec_ns(3.05), 6))
    run = b.write(tmp_path / "nav2")
    _, causes = recorded_answer(run)
    assert causes == [g.GOAL_UNREACHABLE]
    answer, snap = explained_live(run)
    assert answer and answer["causes"] == causes and "lies on an obstacle" in answer["sentence"]
    assert {grid.topic for grid in snap.grids} == {c.MAP, c.GLOBAL_COSTMAP}
    assert snap.grids == read_recording(run).grids


def test_a_costmap_republished_for_hours_keeps_only_its_changes(tmp_path: Path) -> None:
    from hexar.events.records import Grid

    log = LiveLog(Limits(max_grids=3))
    for i in range(100):
        packed = bytes([i // 10])  # one change every ten publications
        log.add(Grid(T0 + sec_ns(i), c.GLOBAL_COSTMAP, "map", 0.05, 1, 1, 0.0, 0.0, 0.0, packed))
    kept = log.snapshot().grids
    assert [grid.packed for grid in kept] == [bytes([7]), bytes([8]), bytes([9])]
    assert log.snapshot().topics[c.GLOBAL_COSTMAP].count == 100
