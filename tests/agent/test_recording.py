""""What did you record?" and "what time is it?": told from the recording itself (its topics and their counts, its
last message's time), never with the task's finding."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from hexar.agent.followups import content_kind
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.reader import read_recording
from hexar.events.records import clock
from tests.agent.helpers import converse, one_step_task


@pytest.mark.parametrize(("question", "kind"), [
    ("what time is it?", "clock"), ("What's the date today?", "clock"), ("what day is it", "clock"),
    ("do you know the time?", "clock"),
    ("what did you record?", "recorded"), ("what's in the recording?", "recorded"),
    ("which topics did you record?", "recorded"), ("what data do you have?", "recorded"),
    ("what time did you get there?", "when"), ("when was this recorded?", "when"),
])
def test_questions_about_the_recording_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_the_time_is_the_last_message_s_with_its_day(suite: Path) -> None:
    run = suite / "bagfile_5_1"
    log = read_recording(run)
    (said,) = converse(run, "what time is it?")
    last = clock(log.end).split(".")[0]
    assert said["answer"] == (f"I tell the time only by my recording: its last message came at {last} UTC on Monday "
                              "10 March 2025. I keep no other clock here.")
    assert said["causes"] == ["planner.plan_ok"]  # not the blocked path nobody asked about


def _say_hello(b: BagBuilder, t0: int) -> None:
    one_step_task(b, t0, 1, "Say hello", "say", {"input": "Hello"})


def test_a_simulator_s_clock_gives_no_time_of_day(tmp_path: Path) -> None:
    b = BagBuilder()
    _say_hello(b, sec_ns(100))
    (said,) = converse(b.write(tmp_path / "sim"), "what time is it?")
    assert said["answer"] == ("I can't tell the time: my recording ran on a simulator's clock, which starts at zero; "
                              "it read 00:01:43 at the last message.")


def test_what_was_recorded_counts_each_topic_and_what_was_set_aside(tmp_path: Path, suite: Path) -> None:
    from hexar.evals.scenarios.bag import TYPESTORE

    t0 = sec_ns(1_741_600_000)
    b = BagBuilder()
    _say_hello(b, t0)
    for k in range(7):
        b.log(t0 + sec_ns(k), "say", 20, f"line {k}")
    ty = TYPESTORE.types
    vector = ty["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0)
    b.raw(t0 + 5, "/odom", "geometry_msgs/msg/Twist", ty["geometry_msgs/msg/Twist"](linear=vector, angular=vector))
    run = b.write(tmp_path / "run")
    (said,) = converse(run, "what did you record?")
    answer: Any = said["answer"]
    assert answer.startswith("My recording is a rosbag2 (sqlite3) of 6 s, from ")
    assert "It holds 11 messages on 3 topics: 7 on /rosout, 3 on /task_info and 1 on /odom. It tells of 1 task." \
        in answer
    assert "While reading it, I set aside: skipped /odom" in answer
    assert {e["topic"] for e in said["evidence"]} == {"/rosout", "/task_info", "/odom"}  # type: ignore[union-attr]
    (many,) = converse(suite / "bagfile_5_1", "what's in your recording?")
    log = read_recording(suite / "bagfile_5_1")
    assert f"It holds {sum(i.count for i in log.topics.values()):,} messages on {len(log.topics)} topics" \
        in str(many["answer"])
    assert "other topics." in str(many["answer"]) and "blocked" not in str(many["answer"])


def test_live_the_counts_are_of_what_was_heard_and_the_time_of_the_last_message(suite: Path) -> None:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session
    from hexar.live.clock import Timeline
    from hexar.live.log import LiveLog
    from hexar.live.replay import bag_messages

    run = suite / "bagfile_5_1"
    timeline, live = Timeline(), LiveLog()
    for topic, _, t, msg in bag_messages(run).messages:
        live.extend(timeline.records(topic, msg, t))
    live.extend(timeline.flush())
    snap = live.snapshot()
    session = Session(RunSettings(recording=Path("live"), llm="none"), log=snap)
    heard = str(session.ask("what did you record?")["answer"])
    assert heard.startswith("What I keep of what I have heard spans ")
    assert f"I have heard {sum(i.count for i in snap.topics.values()):,} messages on {len(snap.topics)} topics" in heard
    now = str(session.ask("what time is it?")["answer"])
    assert now.startswith(f"I tell the time only by what I have heard: its last message came at "
                          f"{clock(snap.end).split('.')[0]} UTC")
