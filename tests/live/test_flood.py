"""Anyone on the DDS domain can publish questions and answers: a flood of 10,000 questions leaves the node
bounded and a person's question after it answered; hostile JSON on /hexar/answer does not stop `chat --live`;
control characters and bidi overrides from a recording do not reach the values on /hexar/answer."""

from __future__ import annotations

import json
import threading
import time
from pathlib import Path
from typing import Any

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.live import msgs
from hexar.live.jobs import MAX_QUESTIONS
from hexar.live.topics import ANSWER, ANSWER_QOS
from tests.live.dds_helpers import Listener, fresh_domain, live_node, replay

COFFEE = "Why didn't you bring me the coffee?"


def _drained(node: Any, limit_s: float = 60.0) -> None:
    deadline = time.monotonic() + limit_s
    while len(node._jobs) and time.monotonic() < deadline:
        time.sleep(0.05)


def test_a_question_flood_leaves_the_node_bounded_and_answering(suite: Path) -> None:
    from hexar.agent.nodes import KEEP_TURNS
    from hexar.live.node import KEEP_THREADS

    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain) as node:
            replay(suite / "bagfile_7_1", domain, rate=40.0)
            listener.wait_answers(1, "failure", timeout=30)
            most_waiting = 0
            for i in range(10_000):  # one source without a thread, then 2,000 made-up threads
                listener.ask("What happened?" if i < 8_000 else json.dumps({"question": "What happened?",
                                                                             "thread": f"flood{i}"}))
                if i % 100 == 0:
                    most_waiting = max(most_waiting, len(node._jobs))
            _drained(node)
            listener.ask(json.dumps({"question": COFFEE, "thread": "person"}))
            deadline = time.monotonic() + 30
            mine: list[dict[str, Any]] = []
            while not mine and time.monotonic() < deadline:
                mine = [a for _, a in listener.answers("question") if a.get("thread") == "person"]
                time.sleep(0.02)
            saver = node._session.graph.checkpointer
            threads = {t: ns for t, ns in saver.storage.items() if any(ns.values())}
            histories = [len(node._session.history(t.split("::", 1)[1])) for t in threads]
            answered = len(listener.answers("question"))
    finally:
        listener.close()
    assert mine and mine[0]["causes"] == ["navigation.charging"]  # the person's question, after the flood
    assert most_waiting <= MAX_QUESTIONS + 1  # never more waiting than the queue holds (plus the failure)
    # the flood was refused (one source over its rate) or dropped (made-up sources past the queue), not queued
    assert node.refused > 0 and node._jobs.dropped > 0 and answered < 5_000
    assert len(threads) <= KEEP_THREADS and max(histories) <= KEEP_TURNS
    assert all(len(cps) == 1 for ns in threads.values() for cps in ns.values())  # the latest checkpoint only


def test_questions_without_a_thread_start_a_new_one_once_the_dialogue_is_stale(
        suite: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from hexar.live import node as node_module

    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain) as node:
            replay(suite / "bagfile_7_1", domain, rate=40.0)
            listener.wait_answers(1, "failure", timeout=30)
            listener.ask("why?")  # a follow-up right after the explanation continues its thread
            first = listener.wait_answers(1, "question", timeout=30)[0]
            monkeypatch.setattr(node_module, "FOLLOW_UP_S", 0.0)
            time.sleep(1.1)  # one rate-limit token back for this source
            listener.ask(COFFEE)
            second = listener.wait_answers(2, "question", timeout=30)[1]
            assert node.errors == 0
    finally:
        listener.close()
    failure = listener.answers("failure")[0][1]
    assert first["thread"] == failure["thread"]
    assert second["thread"] != first["thread"] and second["causes"] == ["navigation.charging"]


def test_chat_live_survives_hostile_answers(tmp_path: Path) -> None:
    from hexar.live.chat_live import LiveChat
    from hexar.live.dds import DdsEndpoint

    domain = fresh_domain()
    shown: list[dict[str, Any]] = []
    chat = LiveChat(domain, shown.append)
    robot = DdsEndpoint(domain)
    writer = robot.writer(ANSWER, c.STRING_TYPE, ANSWER_QOS)
    try:
        time.sleep(1.0)
        for hostile in ("[" * 5000 + "]" * 5000, '{"a":' * 5000 + "1" + "}" * 5000, "[1, 2]", '"text"',
                        json.dumps({"trigger": "failure", "thread": {"x": 1}, "answer": ["not", "text"]}),
                        "x" * 2_000_000):
            writer.write(msgs.String(data=hostile))
        time.sleep(0.5)
        real = {"trigger": "question", "thread": chat.thread, "answer": "I was charging.", "causes": []}
        answered = threading.Event()

        def reply() -> None:
            time.sleep(0.3)
            writer.write(msgs.String(data=json.dumps(real)))
            answered.set()

        threading.Thread(target=reply, daemon=True).start()
        assert chat.ask("Why did you stop?", timeout=30.0)
    finally:
        chat.close()
        robot.close()
    assert shown[-1]["answer"] == "I was charging."


def test_control_and_bidi_characters_never_reach_the_answer_values(tmp_path: Path) -> None:
    hostile_error = "Goal failed\x1b]52;c;ZWNobyBwd25lZA==\x07 \u202eevil\u202c"
    b = BagBuilder()
    t0 = sec_ns(1_741_600_000)
    step = {"skill": "navigate_to_zone", "params": {"zone": "kitchen\x1b[31m"}, "status": "failed",
            "error_msg": hostile_error}
    b.task_info(t0 + sec_ns(5), {"instruction": "Bring me \u202ethe coffee\x1b[2J", "task_id": "t\x1b1",
                                 "task_status": "valid", "task_error_msg": "", "skill_sequence": [step]})
    b.log(t0 + sec_ns(4), "bt_navigator", 40, "Goal failed\x1b[31m\u2066")
    run = b.write(tmp_path / "hostile")
    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain):
            replay(run, domain, rate=40.0)
            got = listener.wait_answers(1, "failure", timeout=30)
            listener.ask("What happened?")
            got += listener.wait_answers(1, "question", timeout=30)
    finally:
        listener.close()
    assert len(got) == 2

    def strings(value: Any) -> list[str]:
        if isinstance(value, dict):
            return [*value.keys(), *(s for v in value.values() for s in strings(v))]
        if isinstance(value, list):
            return [s for v in value for s in strings(v)]
        return [value] if isinstance(value, str) else []

    texts = [s for answer in got for s in strings(answer)]
    assert any("\\x1b" in s for s in texts)  # the hostile text is there, made visible
    assert not any(ch in s for s in texts for ch in ("\x1b", "\x07", "\u202e", "\u202c", "\u2066"))
