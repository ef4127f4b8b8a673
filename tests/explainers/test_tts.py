from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.evals.scenarios.tts import LONG_MESSAGES, long_message, short_message, simulate_say
from hexar.events.contract import SAY_EVENTS, SAY_STATUS_NAME
from hexar.events.log import EventLog
from hexar.events.reader import read_recording
from hexar.explainers.base import Context
from hexar.explainers.tts import TextToSpeechExplainer
from tests.events.helpers import task_msg

T0 = 1_700_000_000 * 1_000_000_000
TEN_WORDS = "Please take the blue cup from the kitchen table now."


def task(status: str, text: str, error: str = "") -> dict[str, Any]:
    return task_msg("sAy0TtS1x2y3z4w5", "tell the family that Anna is late", [("say", {"input": text}, status, error)])


def say_bag(tmp_path: Path, text: str, seed: int = 0, **kw: float) -> EventLog:
    b = BagBuilder()
    b.task_info(T0, task("waiting", text))
    start = T0 + sec_ns(0.2)
    b.task_info(start, task("Running", text))
    result = simulate_say(b, random.Random(seed), start, text, **kw)
    b.task_info(result.end, task("succeeded" if result.succeeded else "failed", text, result.error_msg))
    return read_recording(b.write(tmp_path / "bag"))


def explain(log: EventLog) -> Any:
    return TextToSpeechExplainer().explain("Why did you stop talking?", Context.for_task(log, log.task()))


def test_long_messages_outlast_the_timeout() -> None:
    for i in (1, 2, 3):
        words = len(long_message(i).split())
        assert 80 <= words <= 150 and words / 150 * 60 > 20
    assert len(short_message().split()) < 10
    with pytest.raises(ValueError):
        long_message(0)


def test_simulated_timeout_fails_the_skill() -> None:
    b = BagBuilder()
    result = simulate_say(b, random.Random(0), T0, long_message(1))
    assert not result.succeeded and result.error_msg == "The skill has timed out"
    assert sec_ns(20) < result.end - T0 < sec_ns(20.5)


def test_timed_out_utterance(tmp_path: Path) -> None:
    text = " ".join(["word"] * 96)  # 96 words at 150 wpm: 38.4 s against a 20 s limit
    log = say_bag(tmp_path, text)
    assert log.task().outcome == "failed"
    started, cut = log.statuses[SAY_EVENTS]
    assert started.name == SAY_STATUS_NAME and cut.message == "timed_out"
    assert cut.get("spoken_s") == "20.00"
    assert cut.t - started.t == sec_ns(20)
    # Seed 0 draws a voice 2.3 % slower than nominal: 39.29 s for the whole text, so 48 words fit in 20 s.
    assert cut.get("text_said") == " ".join(["word"] * 48)

    exp = explain(log)
    assert exp.causes == ["tts.timeout"]
    assert exp.text == (
        "I stopped talking because my speech has a 20-second limit and the message needed about 38 seconds "
        "(96 words at 150 words per minute). I got through the first 48 of 96 words."
    )
    assert exp.counterfactual == (
        "Had the message been shorter than about 50 words, or had my speech time limit been 40 seconds "
        "instead of 20, I would have finished it."
    )
    assert exp.fix is not None and "shorter" in exp.fix
    assert [(e.topic, e.t) for e in exp.evidence] == [(SAY_EVENTS, started.t), (SAY_EVENTS, cut.t)]
    assert exp.evidence[0].item.startswith("started: text = word word")
    assert "timeout_s = 20" in exp.evidence[0].item
    assert exp.evidence[1].item.startswith("timed_out: spoken_s = 20.00, text_said = word")


def test_finished_utterance(tmp_path: Path) -> None:
    log = say_bag(tmp_path, TEN_WORDS, seed=3, timeout_s=20.0, words_per_minute=120.0)
    assert log.task().outcome == "succeeded"
    started, done = log.statuses[SAY_EVENTS]
    assert done.message == "finished"
    # 10 words at 120 wpm = 5 s; seed 3 draws a voice 0.8 % slower than nominal.
    assert done.get("spoken_s") == "5.04"
    assert done.t - started.t == sec_ns(5.040480228853584)
    exp = explain(log)
    assert exp.causes == ["tts.completed"] and exp.enough_information
    assert exp.text == (
        "I said the whole message (10 words); it took 5 seconds, within my 20-second speech limit."
    )
    assert exp.counterfactual is None and exp.fix is None
    assert [e.t for e in exp.evidence] == [started.t, done.t]


def test_long_message_at_a_longer_timeout_finishes(tmp_path: Path) -> None:
    exp = explain(say_bag(tmp_path, LONG_MESSAGES[1], timeout_s=60.0))
    assert exp.causes == ["tts.completed"] and "60-second" in exp.text


def test_nothing_said(tmp_path: Path) -> None:
    b = BagBuilder()
    b.task_info(T0, task("waiting", "hi"))
    b.task_info(T0 + sec_ns(1), task("Running", "hi"))
    log = read_recording(b.write(tmp_path / "bag"))
    exp = explain(log)
    assert not exp.enough_information and exp.causes == [] and exp.evidence == []


def test_unfinished_utterance_is_not_explained(tmp_path: Path) -> None:
    b = BagBuilder()
    b.task_info(T0, task("waiting", "hi"))
    b.status(T0 + sec_ns(0.5), SAY_EVENTS, SAY_STATUS_NAME, "started", [("text", "hi"), ("timeout_s", "20")])
    b.task_info(T0 + sec_ns(1), task("Running", "hi"))
    exp = explain(read_recording(b.write(tmp_path / "bag")))
    assert not exp.enough_information and "does not show how" in exp.text


LASAGNE = ("Here is the recipe for a lasagne. Cook a meat sauce, make a white sauce, then layer lasagne sheets, "
           "sauce and cheese three times and bake for forty minutes.")


def recipe_bag(tmp_path: Path, instruction: str, text: str) -> EventLog:
    b = BagBuilder()
    steps = lambda status, err="": task_msg("rEcIpE0TtS1x2y3z", instruction,  # noqa: E731
                                            [("say", {"input": text}, status, err)])
    b.task_info(T0, steps("waiting"))
    b.task_info(T0 + sec_ns(0.2), steps("Running"))
    result = simulate_say(b, random.Random(0), T0 + sec_ns(0.2), text)
    b.task_info(result.end, steps("succeeded" if result.succeeded else "failed", result.error_msg))
    return read_recording(b.write(tmp_path / "bag"))


def test_asked_for_lasagne_read_a_margherita_recipe(tmp_path: Path) -> None:
    log = recipe_bag(tmp_path, "Read me the recipe for a lasagne", long_message(2))
    out = TextToSpeechExplainer().explain("Did you read me the right recipe?", Context.for_task(log, log.task()))
    assert out.causes == ["tts.utterance_mismatch"]
    assert out.text.startswith("No. What I said did not match your request")
    assert "Margherita" in out.text and '"lasagne"' in out.text
    assert out.fix and "plan" in out.fix and out.counterfactual and "lasagne" in out.counterfactual
    assert out.evidence and out.evidence[0].topic == SAY_EVENTS and "Margherita" in out.evidence[0].item
    # the timeout stays the answer to "why did you stop?": the mismatch is a finding of its own
    assert explain(log).causes == ["tts.timeout"]


def test_asked_for_lasagne_read_a_lasagne_recipe(tmp_path: Path) -> None:
    log = recipe_bag(tmp_path, "Read me the recipe for a lasagne", LASAGNE)
    out = TextToSpeechExplainer().explain("Did you read me the right recipe?", Context.for_task(log, log.task()))
    assert out.causes == ["tts.utterance_matches"]
    assert out.text.startswith('Yes: I said "Here is the recipe for a lasagne."')
    what = TextToSpeechExplainer().explain("What did you say?", Context.for_task(log, log.task()))
    assert what.text.startswith('I said "Here is the recipe for a lasagne."')


def test_a_request_that_asks_for_no_speech_is_not_compared(tmp_path: Path) -> None:
    log = recipe_bag(tmp_path, "Bring me a coffee from the kitchen", "Here is your coffee.")
    out = TextToSpeechExplainer().explain("What did you say?", Context.for_task(log, log.task()))
    assert out.text == 'I said: "Here is your coffee."' and out.causes == ["tts.completed"]
