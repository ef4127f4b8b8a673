"""The embedded model's evaluated router prompt, saved by one process and loaded by the next, changes nothing
in the reply; a damaged cache file is ignored. Needs llama-cpp-python and the model (opt in with -m slow)."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.backends import EmbeddedModel, embedded_available
from hexar.agent.model_files import model_path
from hexar.prompts import load

pytestmark = pytest.mark.slow
SCHEMA = {"type": "object", "properties": {"explainer": {"enum": ["ask_human_for_help", "navigation", "none",
                                                                  "pizza_recommender", "planner", "text_to_speech"]}},
          "required": ["explainer"]}


def _messages(question: str) -> list[dict[str, str]]:
    return [{"role": "system", "content": load("router")}, {"role": "user", "content": f"Question: {question}"}]


def test_a_saved_prefix_changes_no_reply(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    if not embedded_available():
        pytest.skip("llama-cpp-python or the embedded model is not installed")
    monkeypatch.setenv("HEXAR_MODEL", str(model_path()))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    EmbeddedModel().chat(_messages("Why did you stop talking?"), schema=SCHEMA, max_tokens=16)
    saved = list((tmp_path / "hexar" / "prefix").glob("*.bin"))
    assert len(saved) == 1
    question = _messages("you kept swerving around why")
    restored = EmbeddedModel().chat(question, schema=SCHEMA, max_tokens=16)
    monkeypatch.setenv("HEXAR_PREFIX_CACHE", "0")
    assert EmbeddedModel().chat(question, schema=SCHEMA, max_tokens=16) == restored
    monkeypatch.setenv("HEXAR_PREFIX_CACHE", "1")
    saved[0].write_bytes(b"HXPC1 damaged")
    assert EmbeddedModel().chat(question, schema=SCHEMA, max_tokens=16) == restored
    assert len(list((tmp_path / "hexar" / "prefix").glob("*.bin"))) == 1  # rewritten whole
    assert saved[0].stat().st_size > 1_000_000
