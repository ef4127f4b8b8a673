"""A robot that fails over and over, or a publisher that floods /task_info with failing tasks: every failure is
explained on /hexar/answer, but only a few are said aloud (two at once, then one every 10 s), and a person's
question goes before the backlog of unasked explanations."""

from __future__ import annotations

import json
import time
from typing import Any

from hexar.events import contract as c
from hexar.events.task_info import parse_task_info
from hexar.live.jobs import SPEAK_BURST
from hexar.live.log import NS
from hexar.live.speech import TopicSpeaker
from hexar.live.topics import TTS_QOS
from hexar.voice.loop import say_answer
from tests.live.dds_helpers import NO_DDS, Listener, fresh_domain, live_node

TTS = "/hexar_test_tts"


def _failing(i: int) -> Any:
    step = {"skill": "navigate_to_zone", "params": {"zone": "kitchen"}, "status": "failed",
            "error_msg": "The skill has been aborted"}
    raw = json.dumps({"instruction": "go to the kitchen", "task_id": f"flood{i}", "task_status": "valid",
                      "task_error_msg": "", "skill_sequence": [step]})
    return parse_task_info(int(time.time_ns()) + i * NS // 100, raw)


def _failures_told(n: int, question: str | None = None, **options: Any
                   ) -> tuple[list[dict[str, Any]], list[str], int, int]:
    """`n` failing tasks (then `question`, if any) into a live node that speaks unasked explanations on TTS with
    `options`: its answers, what it said, and how many unasked ones it did not say and did not tell."""
    domain = fresh_domain()
    listener = Listener(domain)
    said = listener.endpoint.reader(TTS, c.STRING_TYPE, TTS_QOS)
    answers: list[dict[str, Any]] = []
    try:
        with live_node(domain, tts_topic=TTS, proactive="speak", **options) as node:
            node.speakers.append(TopicSpeaker(node.transport, TTS))
            node.on_answer = answers.append
            for i in range(n):
                update = _failing(i)
                if node.log.add(update):
                    node.on_record(update)
            if question is not None:
                node.ask(question)
            deadline = time.monotonic() + 30.0
            while len(answers) + node.untold < n + (question is not None) and time.monotonic() < deadline:
                time.sleep(0.05)
            time.sleep(0.5)
            spoken = [str(s.data) for s in said.take(100) if s.sample_info.valid_data]
            return answers, spoken, node.unspoken, node.untold
    finally:
        listener.close()


@NO_DDS  # the same
def test_failures_in_a_row_are_all_published_and_a_few_said() -> None:
    answers, spoken, unspoken, untold = _failures_told(8, "What happened?")
    triggers = [a["trigger"] for a in answers]
    # a failure whose task the live log no longer keeps (past its last five) by its turn is not told at all
    explained = triggers.count("failure")
    assert explained + untold == 8 and explained > SPEAK_BURST and triggers.count("question") == 1
    assert triggers.index("question") <= 2  # asked after eight failures, answered before most of them
    assert not any(a.get("error") for a in answers)
    # two unasked ones said, and the question's answer; the other unasked ones are published only
    question = next(a for a in answers if a["trigger"] == "question")
    assert len(spoken) == SPEAK_BURST + len(say_answer(question)) and unspoken == explained - SPEAK_BURST


@NO_DDS  # reads the TTS topic through the listener's cyclonedds endpoint
def test_a_household_that_wants_every_failure_said_gets_each() -> None:
    answers, spoken, unspoken, _ = _failures_told(4, speak_every_s=0.0)  # within the live log's five kept tasks
    assert [a["trigger"] for a in answers] == ["failure"] * 4
    assert unspoken == 0 and len(spoken) == 4 > SPEAK_BURST  # one utterance each, none held back
