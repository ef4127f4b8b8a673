"""Real DDS participants for the live tests: a listener on the node's answers and the robot's /task_info, a
question writer, the node on either transport, the replayer in its own process. Every test uses its own DDS
domain so tests never cross-talk."""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from hexar.events import contract as c
from hexar.events.task_info import parse_task_info
from hexar.live.commands import dds_available
from hexar.live.jobs import failure_key
from hexar.live.limits import Limits
from hexar.live.log import LiveLog
from hexar.live.node import LiveNode, NodeOptions, Transport
from hexar.live.ros import rclpy_available
from hexar.live.topics import ANSWER, ANSWER_QOS, QUESTION, QUESTION_QOS, TopicQos

FIRST_DOMAIN, DOMAINS = 20, 200  # Fast DDS's ports allow domains up to 232
# cyclonedds has no wheel for CPython 3.14: there every participant of these tests, the robot stand-in included, is a
# node of rclpy (Fast DDS), and the tests of the DDS transport itself are skipped
HAVE_DDS = dds_available()
NO_DDS = pytest.mark.skipif(not HAVE_DDS, reason="cyclonedds (the `live` extra) has no wheel for this Python")
DEFAULT = "dds" if HAVE_DDS else "rclpy"  # the transport of a test that does not choose one


def _worker_block() -> tuple[int, int]:
    """The domains this test process may use: all of them, or with pytest-xdist a block of its own per worker
    (PYTEST_XDIST_WORKER gw0, gw1, ...), so tests running at once never share a domain."""
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    worker = int(os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw") or 0)
    size = max(DOMAINS // max(workers, 1), 1)  # more than 200 workers share domains
    return FIRST_DOMAIN + worker * size % DOMAINS, size


_FIRST, _SIZE = _worker_block()
# start from the process id so two test runs on one machine are unlikely to share a domain
_DOMAINS = itertools.count(os.getpid() * 7)


def fresh_domain() -> int:
    return _FIRST + next(_DOMAINS) % _SIZE


@dataclass
class Heard:
    answers: list[tuple[float, dict[str, Any]]] = field(default_factory=list)
    failures: dict[str, float] = field(default_factory=dict)  # failure key -> when the listener got it
    first_update: float | None = None  # when the first /task_info update came


# deeper than the node's writer history, so a burst of answers is not replaced before it is read
LISTEN_ANSWERS = TopicQos(durability=ANSWER_QOS.durability, depth=100)
LISTEN_TASKS = TopicQos(depth=100)


class Listener:
    """Another participant on the domain: reads /hexar/answer and /task_info, writes /hexar/question. A cyclonedds
    participant, or a node of rclpy where cyclonedds is missing."""

    def __init__(self, domain: int) -> None:
        self.heard = Heard()
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self.ros: Any = None
        if HAVE_DDS:
            from hexar.live.dds import DdsEndpoint

            self.endpoint: Any = DdsEndpoint(domain)
            self._answers = self.endpoint.reader(ANSWER, c.STRING_TYPE, LISTEN_ANSWERS)
            self._tasks = self.endpoint.reader(c.TASK_INFO, c.STRING_TYPE, LISTEN_TASKS)
            self._question = self.endpoint.writer(QUESTION, c.STRING_TYPE, QUESTION_QOS)
            self._thread = threading.Thread(target=self._loop, daemon=True)
            self._thread.start()
        else:
            from hexar.live.ros import RosNode, msg_class, qos_profile

            self.ros = RosNode("hexar_test_listener", domain)
            string = msg_class(c.STRING_TYPE)
            node = self.ros.node
            node.create_subscription(string, c.TASK_INFO, lambda m: self._task(str(m.data)), qos_profile(LISTEN_TASKS))
            node.create_subscription(string, ANSWER, lambda m: self._answer(str(m.data)), qos_profile(LISTEN_ANSWERS))
            self._question = node.create_publisher(string, QUESTION, qos_profile(QUESTION_QOS))
            self.ros.spin(lambda line: None)

    def _task(self, text: str) -> None:
        now = time.monotonic()
        update = parse_task_info(0, text)
        key = failure_key(update) if update is not None else None
        with self._lock:
            if update is not None and self.heard.first_update is None:
                self.heard.first_update = now
            if key is not None:
                self.heard.failures.setdefault(key, now)

    def _answer(self, text: str) -> None:
        with self._lock:
            self.heard.answers.append((time.monotonic(), json.loads(text)))

    def _loop(self) -> None:
        while not self._stop.is_set():
            for s in self._tasks.take(64):
                if s.sample_info.valid_data:  # else the replayer's writer went away
                    self._task(str(s.data))
            for s in self._answers.take(16):
                if s.sample_info.valid_data:
                    self._answer(str(s.data))
            time.sleep(0.002)

    def ask(self, question: str, match_s: float = 10.0) -> None:
        # a question written before the node's reader has matched this writer is lost (volatile, as a ROS
        # publisher's): wait for the match first, as discovery takes longer the more topics the node reads
        deadline = time.monotonic() + match_s
        if self.ros is None:
            from hexar.live import msgs

            while not self._question.get_matched_subscriptions() and time.monotonic() < deadline:
                time.sleep(0.02)
            self._question.write(msgs.String(data=question))
            return
        from hexar.live.ros import msg_class

        while not self._question.get_subscription_count() and time.monotonic() < deadline:
            time.sleep(0.02)
        self._question.publish(msg_class(c.STRING_TYPE)(data=question))

    def answers(self, trigger: str | None = None) -> list[tuple[float, dict[str, Any]]]:
        with self._lock:
            return [(t, a) for t, a in self.heard.answers if trigger is None or a.get("trigger") == trigger]

    def wait_task(self, timeout: float = 60.0) -> float | None:
        """When the robot's first /task_info update came (None: none within `timeout`)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and self.heard.first_update is None:
            time.sleep(0.02)
        return self.heard.first_update

    def wait_answers(self, n: int, trigger: str | None = None, timeout: float = 10.0) -> list[dict[str, Any]]:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and len(self.answers(trigger)) < n:
            time.sleep(0.02)
        return [a for _, a in self.answers(trigger)]

    def close(self) -> None:
        self._stop.set()
        if self.ros is not None:
            self.ros.close()
            return
        self._thread.join(2.0)
        self.endpoint.close()


def other(transport: str) -> str:
    """The robot stand-in's transport for a node on `transport`: the other DDS vendor where both exist."""
    if not HAVE_DDS:
        return "rclpy"
    return "dds" if transport == "rclpy" or not rclpy_available() else "rclpy"


def make_transport(kind: str, domain: int, tts_topic: str | None = None, recorder: Any = None) -> Transport:
    if kind == "rclpy":
        from hexar.live.ros import RclpyTransport

        return RclpyTransport(domain, tts_topic=tts_topic, recorder=recorder)
    from hexar.live.dds import DdsTransport

    return DdsTransport(domain, tts_topic=tts_topic, recorder=recorder)


def make_replayer(kind: str, domain: int) -> Any:
    if kind == "rclpy":
        from hexar.live.ros import RclpyReplayer

        return RclpyReplayer(domain)
    from hexar.live.replay import DdsReplayer

    return DdsReplayer(domain)


def wait_matched(writer: Any, topics: set[str], timeout_s: float = 30.0, settle_s: float = 0.5) -> None:
    """Block until each of `topics` has a matched reader, then `settle_s` more: the writer's side matches first,
    and a Fast DDS reader drops samples from a writer it has not yet matched itself. A fixed sleep lost the
    first messages of a volatile topic on a loaded CI machine."""
    from hexar.live.replay import wait_for_readers

    missing = wait_for_readers(writer, topics, timeout_s, settle_s)
    assert not missing, f"no reader matched within {timeout_s} s: {missing}"


def replay_matched(run: Path, robot: Any, rate: float) -> None:
    """Replay `run` in this process once every topic it carries has a matched reader (the node reads them all):
    a goal's first status (keep-last 1) or the goal pose sent before discovery finished is lost for good."""
    from hexar.live.replay import replay as replay_in_process

    stats = replay_in_process(run, robot, rate=rate, warmup_s=30.0)
    assert not stats.unmatched_topics, f"no reader matched within 30 s: {stats.unmatched_topics}"


@contextmanager
def live_node(domain: int, limits: Limits | None = None, transport: str = DEFAULT,
              **options: Any) -> Iterator[LiveNode]:
    node = LiveNode(make_transport(transport, domain, tts_topic=options.pop("tts_topic", None)), LiveLog(limits),
                    NodeOptions(llm="none", **options))
    node.start()
    try:
        yield node
    finally:
        node.stop()


def replay_process(run: Path, domain: int, rate: float = 10.0, *extra: str,
                   transport: str = DEFAULT) -> subprocess.Popen[str]:
    """`hexar replay` in its own process: the traffic crosses process boundaries as a robot's would. Over rclpy
    it is `ros2 bag play`'s kind of traffic: stamps of the recording day, source times of now."""
    cmd = [sys.executable, "-m", "hexar", "replay", str(run), "--rate", str(rate), "--transport", transport,
           "--domain", str(domain), *extra]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def replay(run: Path, domain: int, rate: float = 10.0, timeout: float = 120.0, transport: str = DEFAULT,
           *extra: str) -> str:
    proc = replay_process(run, domain, rate, *extra, transport=transport)
    out, err = proc.communicate(timeout=timeout)
    assert proc.returncode == 0, err
    assert "Traceback" not in err
    return out
