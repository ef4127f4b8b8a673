"""`hexar chat --live`: talk with a running `hexar serve` node over DDS (cyclonedds, or a node of rclpy); its unasked
explanations show up too."""

from __future__ import annotations

import json
import threading
import time
import uuid
from collections.abc import Callable, Iterable
from typing import Any

from hexar.bounded_json import loads
from hexar.errors import BadJsonError
from hexar.events import contract as c
from hexar.live.jobs import BURST, PER_SECOND, Bucket
from hexar.live.topics import ANSWER, ANSWER_QOS, QUESTION, QUESTION_QOS

PROMPT_HELP = "Ask the robot why; answers come from the running `hexar serve`. Ctrl-D quits."


class DdsLine:
    """The chat's two topics over cyclonedds: a participant, no ROS node."""

    def __init__(self, domain: int) -> None:
        from hexar.live import msgs
        from hexar.live.dds import DdsEndpoint

        self._string = msgs.String
        self.endpoint = DdsEndpoint(domain)
        self._answers = self.endpoint.reader(ANSWER, c.STRING_TYPE, ANSWER_QOS)
        self._questions = self.endpoint.writer(QUESTION, c.STRING_TYPE, QUESTION_QOS)

    def take(self) -> list[str]:
        return [str(s.data) for s in self._answers.take(16) if s.sample_info.valid_data]

    def matched(self) -> bool:
        # status counts, not lists (live/replay.py says why)
        return bool(self._questions.get_publication_matched_status().current_count
                    and self._answers.get_subscription_matched_status().current_count)

    def write(self, text: str) -> None:
        self._questions.write(self._string(data=text))

    def close(self) -> None:
        self.endpoint.close()


class RclpyLine:
    """The chat's two topics as a node of rclpy (`hexar_chat`), where cyclonedds is missing or asked not to be."""

    def __init__(self, domain: int) -> None:
        from hexar.live.ros import RosNode, msg_class, qos_profile

        self.ros = RosNode("hexar_chat", domain)
        self._string = msg_class(c.STRING_TYPE)
        self._inbox: list[str] = []
        self._lock = threading.Lock()
        node = self.ros.node
        self._answers = node.create_subscription(self._string, ANSWER, self._heard, qos_profile(ANSWER_QOS))
        self._questions = node.create_publisher(self._string, QUESTION, qos_profile(QUESTION_QOS))
        self.ros.spin(lambda line: None)

    def _heard(self, msg: Any) -> None:
        with self._lock:
            self._inbox.append(str(msg.data))

    def take(self) -> list[str]:
        with self._lock:
            taken, self._inbox = self._inbox, []
        return taken

    def matched(self) -> bool:
        return bool(self._questions.get_subscription_count() and self._answers.get_publisher_count())

    def write(self, text: str) -> None:
        self._questions.publish(self._string(data=text))

    def close(self) -> None:
        self.ros.close()


class LiveChat:
    """A participant that writes questions (tagged with its thread) and reads the node's answers."""

    def __init__(self, domain: int, show: Callable[[dict[str, Any]], None], transport: str = "dds") -> None:
        self.line: DdsLine | RclpyLine = RclpyLine(domain) if transport == "rclpy" else DdsLine(domain)
        self.thread = uuid.uuid4().hex[:12]
        self.show = show
        self._mine = threading.Event()
        # a margin under the node's bucket: a question may reach it sooner after the last than it was sent
        self._pace = Bucket(BURST - 1, PER_SECOND * 0.8, time.monotonic())
        self._asked = self.thread
        self._stop = threading.Event()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        while not self._stop.is_set():
            for text in self.line.take():
                try:  # anyone on the domain can publish here: deep, huge or non-object JSON is skipped
                    result = loads(text)
                except BadJsonError:
                    continue
                if not isinstance(result, dict):
                    continue
                try:
                    self._take(result)
                except (TypeError, ValueError, KeyError, AttributeError):  # an answer of the wrong shape
                    continue
            self._stop.wait(0.02)

    def _take(self, result: dict[str, Any]) -> None:
        if result.get("trigger") in ("failure", "correction"):
            self.thread = str(result.get("thread") or self.thread)[:64]  # "why?" continues that thread
            self.show(result)
        elif result.get("thread") == self._asked:
            # the answer to this chat's question: a "why?" continues it, even if an older unasked
            # explanation came in (as history) while it was on its way
            self.thread = self._asked
            self.show(result)
            self._mine.set()

    def wait_for_node(self, timeout: float) -> None:
        """Wait (at most `timeout`) until a node reads /hexar/question: a question written before discovery
        matched it is lost, and discovery across DDS vendors (a node on rclpy) takes a second or more."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and not self.line.matched():
            time.sleep(0.05)
        # the node's last answers come as transient-local history once matched: an unasked explanation among
        # them sets the thread a "why?" continues, so it must be read before the first question goes out
        time.sleep(0.5)

    def ask(self, question: str, timeout: float = 30.0) -> bool:
        """Send one question and wait for its answer; False when the node did not answer in time. Questions are
        paced under the node's limit per conversation (live/jobs.py), which drops what comes faster unanswered:
        piped questions answered in milliseconds would otherwise lose the fourth."""
        while not self._pace.take(time.monotonic()):
            time.sleep(0.05)
        self._mine.clear()
        self._asked = self.thread
        self.line.write(json.dumps({"question": question, "thread": self.thread}))
        return self._mine.wait(timeout)

    def close(self) -> None:
        self._stop.set()
        self._reader.join(2.0)
        self.line.close()


def chat_live(domain: int, lines: Iterable[str], show: Callable[[dict[str, Any]], None],
              timeout: float = 30.0, transport: str = "dds") -> int:
    """Ask each line in turn, until one ends the talk ("bye"); returns 2 if the node never answered (is `hexar
    serve` running on this domain?)."""
    from hexar.agent.questions import GOODBYE, is_farewell
    from hexar.live.errors import LiveError

    chat = LiveChat(domain, show, transport)
    try:
        chat.wait_for_node(timeout)
        for line in lines:
            if is_farewell(line):  # "bye", "quit": the talk ends here, as `hexar chat` ends, nothing sent
                show({"trigger": "farewell", "answer": GOODBYE, "thread": chat.thread})
                break
            if line.strip() and not chat.ask(line.strip(), timeout):
                raise LiveError(f"no answer from hexar serve on DDS domain {domain} within {timeout:.0f} s")
    finally:
        chat.close()
    return 0
