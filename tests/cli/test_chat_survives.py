"""`hexar chat` and `hexar listen` go on after a bad command or question, and print recorded text visibly."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pexpect
import pytest
from rich.console import Console

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.scenarios.bag import BagBuilder
from hexar.voice.audio import Audio
from hexar.voice.loop import LOG_NAME, Dialogue
from tests.events.helpers import T0, two_skill_task
from tests.fuzz.harness import _bad_char

HEXAR = str(Path(sys.executable).with_name("hexar"))
CLIPBOARD = "\x1b]52;c;ZWNobyBwd25lZA==\x07"


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    b = BagBuilder()
    two_skill_task(b, T0, f"t1{CLIPBOARD}", fail_second=True)
    return b.write(tmp_path_factory.mktemp("rec") / "bag")


def test_chat_unknown_task_and_bad_questions_do_not_end_it(bag: Path, tmp_path: Path) -> None:
    env = {**os.environ, "COLUMNS": "160", "TERM": "xterm", "PROMPT_TOOLKIT_NO_CPR": "1", "HOME": str(tmp_path)}
    child = pexpect.spawn(HEXAR, ["chat", str(bag), "--llm", "none", "--checkpoints", str(tmp_path / "t.sqlite")],
                          env=env, encoding="utf-8", timeout=60, dimensions=(50, 160))
    child.expect("you>")
    child.sendline("/task 9")
    child.expect("no task '9'")
    child.expect("you>")
    child.sendline(f"why {CLIPBOARD}[/]")
    child.expect("you>")
    child.sendline("/task")
    child.expect(r"t1\\x1b\]52;c;")  # the recorded task id, shown not obeyed
    child.expect("you>")
    child.sendline("/thread")
    child.expect(r"#/run/bag\?thread=")  # where the page continues this conversation
    child.expect("you>")
    child.sendline("Why didn't you say hello?")
    child.expect("enough information")  # an answer: the conversation went on
    child.expect("you>")
    child.sendeof()
    child.expect("bye")
    child.expect(pexpect.EOF)
    child.close()
    assert child.exitstatus == 0
    assert "\x1b]52" not in (child.before or "")


class _Heard:
    """Stands where the speech recogniser's output is: the words it returns, one per utterance."""

    name = "recorded-words"

    def __init__(self, words: list[str]) -> None:
        self.words = words

    def transcribe(self, audio: Audio) -> str:
        return self.words.pop(0)


def test_listen_transcripts_and_answers_are_shown_visibly(bag: Path, tmp_path: Path) -> None:
    session = Session(RunSettings(recording=bag, llm="none"))
    console = Console(record=True, width=200)
    heard = _Heard([f"why {CLIPBOARD} [bold]?", "Why didn't you say hello?", "thank you"])
    dialogue = Dialogue(session, heard, [], console=console, log_dir=tmp_path)
    audio = Audio(np.zeros(1600, dtype=np.float32), 16000)
    assert dialogue.run([("wav", audio)] * 3) == 0
    text = console.export_text()
    assert _bad_char(text) is None and "\\x1b]52;c;" in text and "[bold]" in text
    turns: list[dict[str, Any]] = [json.loads(line) for line in (tmp_path / LOG_NAME).read_text().splitlines()]
    assert turns[0]["error"] and turns[0]["transcript"].startswith("why \x1b]52")  # the log keeps exact text
    assert turns[1]["answer"] and not turns[1]["error"]
