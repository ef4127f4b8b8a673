"""Recordings replayed at x10 into the node, on each transport: each failure is explained unasked, with the cause
`hexar ask` gives on the recording; a later question gets the answer `hexar ask` gives. The rclpy stand-in
publishes as `ros2 bag play` does (the recording's stamps, today's source times), with and without /clock. One
recording per module here; all 60 in the slow test (latencies in scripts/bench_live.py).

With bag-play stamps an unstamped message is dated through the fitted clock, so its publishing jitter counts ten
times at x10: a step that starts 50 ms of robot time before its event (the pizza recording) may be dated after it
on a loaded machine. Failures span seconds and are checked under every clock."""

from __future__ import annotations

import statistics
import time
from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.live.node import FAILURE_QUESTION, INVALID_QUESTION
from tests.live.dds_helpers import HAVE_DDS, NO_DDS, Listener, fresh_domain, live_node, other, replay

ONE_PER_MODULE = ("bagfile_2_1", "bagfile_5_1", "bagfile_11_1", "bagfile_19_1", "bagfile_20_1")
QUESTION = "Why didn't you do what I asked?"


def expected(run: Path) -> tuple[dict[str, list[str]], list[str]]:
    """What `hexar ask` says on the recording: the causes of each failed task, and of QUESTION."""
    session = Session(RunSettings(recording=run, llm="none"))
    failures = {}
    for task in session.context.log.tasks:
        if task.outcome in {"failed", "invalid"}:
            q = INVALID_QUESTION if task.outcome == "invalid" else FAILURE_QUESTION
            failures[task.task_id] = session.ask(q, task=task.task_id)["causes"]
    return failures, session.ask(QUESTION)["causes"]


def _heard_failure(listener: Listener, task_id: str, timeout: float = 15.0) -> str:
    """The key of the failing update this listener heard for a task. Its own reader may take it in after the node's
    answer on a loaded machine (seen on 3.14 in CI, twice, once past 5 s): waited for, and named when it never
    came."""
    deadline = time.monotonic() + timeout
    while True:
        key = next((k for k in list(listener.heard.failures) if k.startswith(task_id + ":")), None)
        if key is not None:
            return key
        assert time.monotonic() < deadline, f"the listener never heard the failing update of task {task_id}"
        time.sleep(0.02)


def check_run(run: Path, transport: str = "dds", robot: str | None = None, *extra: str) -> list[float]:
    """Replay one recording into a fresh node; returns the proactive latencies in seconds."""
    failures, asked = expected(run)
    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain, transport=transport) as node:
            replay(run, domain, 10.0, 120.0, robot or other(transport), *extra)
            got = listener.wait_answers(len(failures), "failure", timeout=5.0)
            assert {a["task_id"]: a["causes"] for a in got} == failures, run.name
            latencies = []
            for received, answer in listener.answers("failure"):
                key = _heard_failure(listener, answer["task_id"])
                latencies.append(received - listener.heard.failures[key])
                assert answer["sentence"] and len(answer["sentence"].split()) <= 25
                assert answer["error"] == ""
            listener.ask(QUESTION)
            answer = listener.wait_answers(1, "question", timeout=10.0)
            assert answer and answer[0]["causes"] == asked, run.name
            assert node.errors == 0
        return latencies
    finally:
        listener.close()


@NO_DDS  # the stand-in is a Cyclone writer at the recording's times
def test_one_recording_per_module(suite: Path, transport: str) -> None:
    # the stand-in writes at the recording's times (live stamps): on Cyclone, so a node on rclpy hears Fast DDS
    # <- Cyclone; the other clocks are in test_every_robot_clock
    latencies = [lat for name in ONE_PER_MODULE for lat in check_run(suite / name, transport, "dds")]
    assert len(latencies) >= 4  # the pizza recording has no failure


@pytest.mark.parametrize("clock", ["live", "bag-play", "bag-play --clock"])
def test_every_robot_clock(suite: Path, transport: str, clock: str) -> None:
    """Live stamps (a DDS stand-in writes each message at its recording time), `ros2 bag play` of an old
    recording (an rclpy stand-in: stamps of the recording day, source times of now), and the same with /clock."""
    if clock != "live":
        pytest.importorskip("rclpy")
    elif not HAVE_DDS:
        pytest.skip("live stamps come from a Cyclone stand-in; cyclonedds has no wheel for this Python")
    robot = "dds" if clock == "live" else "rclpy"
    extra = ("--clock", "40") if clock.endswith("--clock") else ()
    assert len(check_run(suite / "bagfile_11_1", transport, robot, *extra)) == 1
    assert len(check_run(suite / "bagfile_5_1", transport, robot, *extra)) == 1


@pytest.mark.slow
def test_all_sixty_recordings(suite: Path) -> None:
    started = time.monotonic()
    latencies = [lat for run in sorted(suite.iterdir()) for lat in check_run(run)]
    print(f"\n{len(latencies)} proactive answers in {time.monotonic() - started:.0f} s: median "
          f"{statistics.median(latencies) * 1000:.0f} ms, p95 "
          f"{statistics.quantiles(latencies, n=20)[-1] * 1000:.0f} ms, max {max(latencies) * 1000:.0f} ms")
    assert max(latencies) < 1.0
