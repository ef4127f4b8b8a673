"""Spoken answers are short and fit the TTS timeout; transcripts are repaired and stop words end the dialogue."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.voice.transcripts import is_stop, repair
from hexar.voice.utterances import MAX_WORDS, clean, spoken

LONG = ("I stopped talking because my speech has a 20-second limit and the message needed about 45 seconds "
        "(112 words at 150 words per minute). I got through the first 48 of 112 words. "
        "The rest of the message was never said, and nobody heard the end of it.")


def test_short_answer_is_said_as_is() -> None:
    text = "I couldn't reach the kitchen because something blocked my path and I found no other way around it."
    assert spoken(text) == [text]


def test_long_answer_keeps_two_sentences_without_brackets() -> None:
    out = spoken(LONG)
    assert out == ["I stopped talking because my speech has a 20-second limit and the message needed about 45 seconds.",
                   "I got through the first 48 of 112 words."]


def test_every_utterance_fits_the_tts_timeout() -> None:
    sentence = ", ".join(f"then I went to room number {i}" for i in range(12)) + "."
    out = spoken(sentence)
    assert len(out) >= 2
    assert all(len(u.split()) <= MAX_WORDS for u in out)
    assert sum(len(u.split()) for u in out) <= 50
    assert all(u.endswith(".") for u in out)


def test_evidence_answer_is_split_on_its_items() -> None:
    items = ["started: text = Hello everyone. Please wait; she will call.",
             "timed_out: spoken_s = 20.00, text_said = Hi"]
    answer = "Here is what I recorded: " + "; ".join(items) + "."
    out = spoken(answer, items)
    assert out == ["Here is what I recorded: started: text is Hello everyone.",
                   "timed out: spoken s is 20.00, text said is Hi."]


def test_log_lines_are_made_sayable() -> None:
    said = clean("[controller_server] ERROR Failed to make progress; data=True")
    assert said == "Failed to make progress; data is True"
    assert spoken("Here is what I recorded: data=True; data=True; [planner] WARN no path to (1.0, 2.0).") == [
        "Here is what I recorded: data is True.", "no path to."]


@pytest.mark.parametrize("text", ["Stop.", "thank you", "Thank you very much!", "OK, thanks.", "Goodbye.",
                                  "that's all, thank you"])
def test_stop_words(text: str) -> None:
    assert is_stop(text)


@pytest.mark.parametrize("text", ["Why did you stop?", "why did you stop talking", "Stop what?", "What happened?"])
def test_questions_are_not_stop_words(text: str) -> None:
    assert not is_stop(text)


@pytest.mark.parametrize(("heard", "asked"), [
    ("What would've been held?", "what would have helped?"),  # tiny.en on espeak-ng's voice
    ("Tell me mor.", "tell me more?"),
    ("What could of helped", "What could have helped"),
    ("Why?", "Why?"),
    ("Why didn't you bring me the coffee?", "Why didn't you bring me the coffee?"),
    ("why did you stop", "why did you stop"),
])
def test_repair(heard: str, asked: str) -> None:
    assert repair(heard) == asked


def test_a_spoken_why_heard_as_right_is_a_why(suite: Path) -> None:
    assert repair("Right.") == "why?" and repair("right") == "why?"
    assert repair("all right then, what happened at the door") == "all right then, what happened at the door"
    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"))
    thread = session.new_thread()
    session.ask("what happened", thread=thread)
    again = session.ask(repair("Right."), thread=thread)
    assert again["intent"] == "deeper" and "Here is what I recorded" in str(again["answer"])
