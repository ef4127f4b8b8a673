"""Faults on real DDS traffic, for a node on each transport: the replayer killed and restarted mid-task,
duplicated and reordered messages, a 10 MB log line. The node keeps answering, with the same causes, and never
prints a traceback. The faulty robot is a Cyclone participant: it writes each message at its recording time, so
a copy sent again is the same message (a robot on rclpy would stamp the copy with a new source time)."""

from __future__ import annotations

import signal
import time
import types
from pathlib import Path

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.events import contract as c
from hexar.live import msgs
from hexar.live.replay import DdsReplayer, bag_messages, to_dds
from tests.live.dds_helpers import Listener, fresh_domain, live_node, replay_process, wait_matched
from tests.live.test_replay_explains import QUESTION, expected

RUN = "bagfile_5_1"  # navigation: the path is blocked; ~70 s of traffic


def test_replayer_killed_mid_task_and_restarted(suite: Path, transport: str) -> None:
    failures, asked = expected(suite / RUN)
    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain, transport=transport) as node:
            first = replay_process(suite / RUN, domain, 5.0)  # slow enough to be killed before the failure
            deadline = time.monotonic() + 30
            while node.log.stats()["tasks"] == 0 and time.monotonic() < deadline:
                time.sleep(0.05)
            time.sleep(0.5)  # mid-task: the plan is running
            first.send_signal(signal.SIGKILL)
            first.wait(10)
            assert not listener.answers("failure")
            seen = node.log.stats()["received"]
            again = replay_process(suite / RUN, domain, 20.0)  # the robot's publishers come back from the start
            _, err = again.communicate(timeout=120)
            assert again.returncode == 0 and "Traceback" not in err
            got = listener.wait_answers(len(failures), "failure", timeout=30.0)
            assert {a["task_id"]: a["causes"] for a in got} == failures
            assert len(listener.answers("failure")) == len(failures)  # explained once, not once per publisher
            assert node.log.duplicates >= seen // 2  # what the first publisher sent came again
            listener.ask(QUESTION)
            assert listener.wait_answers(1, "question")[0]["causes"] == asked
            assert node.errors == 0
    finally:
        listener.close()


def test_duplicated_reordered_and_a_10_mb_line(suite: Path, transport: str) -> None:
    failures, asked = expected(suite / RUN)
    domain = fresh_domain()
    listener = Listener(domain)
    writer = DdsReplayer(domain)
    try:
        with live_node(domain, transport=transport) as node:
            writer.prepare()
            messages = list(bag_messages(suite / RUN).messages)
            wait_matched(writer, {topic for topic, *_ in messages} | {c.ROSOUT})
            # swap every pair of neighbouring messages and send each one twice
            for i in range(0, len(messages) - 1, 2):
                messages[i], messages[i + 1] = messages[i + 1], messages[i]
            for topic, msgtype, t, m in messages:
                for _ in range(2):
                    writer.write(topic, msgtype, to_dds(msgtype, m), t)
                time.sleep(0.0005)
            huge = "E" * 10_000_000
            last_t = messages[-1][2]
            writer.write(c.ROSOUT, c.LOG_TYPE, msgs.Log(stamp=msgs.time_of(last_t + 1), level=40, name="flood",
                                                        msg=huge), last_t + 1)
            # generous: the first explanation imports the explainers while the 10 MB line is still arriving
            got = listener.wait_answers(len(failures), "failure", timeout=30.0)
            assert {a["task_id"]: a["causes"] for a in got} == failures, (node.log.stats(), node.errors)
            listener.ask(QUESTION)
            answer = listener.wait_answers(1, "question", timeout=15.0)
            assert answer and answer[0]["causes"] == asked
            deadline = time.monotonic() + 10
            while node.log.truncated == 0 and time.monotonic() < deadline:
                time.sleep(0.05)
            assert node.log.truncated == 1  # the 10 MB line arrived and was kept cut short
            # every second copy is dropped as a duplicate; a depth-1 latched topic (/joy_priority) may keep only
            # its latest sample, so a copy can be replaced before delivery
            assert node.log.duplicates >= len(messages) * 0.95
            assert node.errors == 0 and node.transport.errors == 0  # type: ignore[attr-defined]
    finally:
        writer.close()
        listener.close()


def test_a_message_rclpy_cannot_decode_is_reported_and_the_node_keeps_listening() -> None:
    """A publisher whose DiagnosticArray has another layout (ROS 2 matches by type name only): the rclpy
    transport reports the message it cannot decode, skips it, and still hears the next good one."""
    pytest.importorskip("rclpy")
    from dataclasses import dataclass

    from cyclonedds.idl import IdlStruct
    from cyclonedds.idl.types import uint32

    from hexar.live.log import LiveLog
    from hexar.live.topics import TopicQos
    from tests.live.dds_helpers import make_transport

    # one uint32, read by a DiagnosticArray decoder as a stamp whose nanoseconds and frame id lie past the end;
    # built with real annotations (this module's are strings, which cyclonedds cannot resolve here)
    name = {"typename": "diagnostic_msgs::msg::dds_::DiagnosticArray_"}
    body = {"__annotations__": {"count": uint32}, "count": 0xFFFFFFFF}
    Other = dataclass(types.new_class("Other", (IdlStruct,), name, lambda ns: ns.update(body)))

    domain = fresh_domain()
    transport, log = make_transport("rclpy", domain), LiveLog()
    transport.start(log, lambda r: None, lambda q: None)
    bad = DdsReplayer(domain)
    try:
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic

        from hexar.live.dds import dds_qos
        from hexar.live.topics import dds_name

        participant = bad.endpoint.participant
        writer = DataWriter(participant, Topic(participant, dds_name(c.DIAGNOSTICS), Other), dds_qos(TopicQos()))
        deadline = time.monotonic() + 10
        while not writer.get_matched_subscriptions() and time.monotonic() < deadline:
            time.sleep(0.05)
        writer.write(Other())
        while transport.errors == 0 and time.monotonic() < deadline:  # type: ignore[attr-defined]
            time.sleep(0.05)
        flag = bad.endpoint.writer(c.IS_CHARGING, c.BOOL_TYPE, TopicQos())
        while not flag.get_matched_subscriptions() and time.monotonic() < deadline:
            time.sleep(0.05)
        flag.write(msgs.Bool(data=True), timestamp=123 * 10**9)
        while log.stats()["received"] == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        transport.close()
        bad.close()
    assert transport.errors == 1  # type: ignore[attr-defined]
    assert [s.value for s in log.snapshot().flags[c.IS_CHARGING]] == [True]
