"""The TTS answer states only settings the recording holds; a default it falls back on is called a default."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events.contract import SAY_EVENTS, SAY_STATUS_NAME
from hexar.events.reader import read_recording
from hexar.explainers.base import Context
from hexar.explainers.tts import TextToSpeechExplainer
from tests.events.helpers import task_msg

T0 = 1_700_000_000 * 1_000_000_000
TEXT = " ".join(["word"] * 96)


def _explain(tmp_path: Path, start_values: list[tuple[str, str]], end: str = "timed_out") -> object:
    b = BagBuilder()
    b.task_info(T0, task_msg("t1", "tell the family", [("say", {"input": "x"}, "Running", "")]))
    b.status(T0 + sec_ns(1), SAY_EVENTS, SAY_STATUS_NAME, "started", [("text", TEXT), *start_values])
    b.status(T0 + sec_ns(21), SAY_EVENTS, SAY_STATUS_NAME, end, [])
    failed = ("failed", "The skill has timed out") if end == "timed_out" else ("succeeded", "")
    b.task_info(T0 + sec_ns(22), task_msg("t1", "tell the family", [("say", {"input": "x"}, *failed)]))
    log = read_recording(b.write(tmp_path / "bag"))
    return TextToSpeechExplainer().explain("Why did you stop talking?", Context.for_task(log, log.task()))


def test_missing_timeout_is_said_to_be_a_default(tmp_path: Path) -> None:
    exp = _explain(tmp_path, [("words_per_minute", "150")])
    text = exp.text  # type: ignore[attr-defined]
    assert "does not say my speech time limit; the default is 20 seconds" in text
    assert "has a 20-second limit" not in text
    assert exp.counterfactual.startswith("If the default limit applied")  # type: ignore[attr-defined]


def test_missing_rate_is_said_to_be_assumed(tmp_path: Path) -> None:
    exp = _explain(tmp_path, [("timeout_s", "20")])
    text = exp.text  # type: ignore[attr-defined]
    assert "has a 20-second limit" in text and "an assumed 150 words per minute" in text
    assert "does not say my speaking rate" in text


@pytest.mark.parametrize("bad", ["nan", "inf", "-3", "0", "1e308"])
def test_unusable_recorded_settings_are_not_stated(tmp_path: Path, bad: str) -> None:
    exp = _explain(tmp_path, [("timeout_s", bad), ("words_per_minute", bad)])
    text = exp.text  # type: ignore[attr-defined]
    assert bad not in text.replace("150", "").replace("20 seconds", "")
    assert "the default is 20 seconds" in text and "an assumed 150" in text


def test_finished_without_a_recorded_limit(tmp_path: Path) -> None:
    exp = _explain(tmp_path, [], end="finished")
    text = exp.text  # type: ignore[attr-defined]
    assert "within my" not in text and "the default is 20 seconds" in text
