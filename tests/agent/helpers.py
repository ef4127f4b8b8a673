from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from hexar.agent.context import RunSettings
from hexar.agent.session import Session


def converse(run: Path, *questions: str) -> list[dict[str, Any]]:
    """The questions asked in turn in one new conversation about a recording, without an LLM: their results."""
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    return [session.ask(q, thread=thread) for q in questions]


class CountingModel:
    """A TextModel that records every call. It stands where a real model's API is; it answers 'none' so that
    routing must fall back to the deterministic parts."""

    name = "counting"
    max_prompt_chars = 600

    def __init__(self, reply: str = '{"explainer": "none"}') -> None:
        self.calls: list[Sequence[Mapping[str, str]]] = []
        self.reply = reply

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        self.calls.append(messages)
        if schema is not None:
            json.loads(self.reply)
        return self.reply
