"""`hexar chat` driven through a pseudo-terminal, as a person types it."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pexpect

HEXAR = str(Path(sys.executable).with_name("hexar"))


def _spawn(suite: Path, db: Path, *extra: str) -> pexpect.spawn:
    env = {**os.environ, "COLUMNS": "160", "TERM": "xterm", "PROMPT_TOOLKIT_NO_CPR": "1", "HOME": str(db.parent)}
    return pexpect.spawn(HEXAR, ["chat", str(suite / "bagfile_7_1"), "--llm", "none", "--checkpoints", str(db),
                                 *extra], env=env, encoding="utf-8", timeout=60, dimensions=(50, 160))


def test_chat_answers_follow_ups_and_resumes(suite: Path, tmp_path: Path) -> None:
    db = tmp_path / "threads.sqlite"
    child = _spawn(suite, db)
    child.expect(r"thread ([0-9a-f]{12})")
    thread = child.match.group(1)
    child.expect("you>")
    child.sendline("Why didn't you bring me the coffee?")
    child.expect("charg")
    child.expect("you>")
    child.sendline("/why")
    child.expect("Here is what I recorded")
    child.expect("you>")
    child.sendline("/evidence")
    child.expect("evidence on")
    child.expect("you>")
    child.sendline("what would have helped")
    child.expect(r"(?i)unplug|charger|dock")
    child.expect("you>")
    child.sendeof()
    child.expect("bye")
    child.expect(pexpect.EOF)

    again = _spawn(suite, db, "--thread", thread)
    again.expect("you: Why didn't you bring me the coffee")
    again.expect(r"\[controller_server\] ERROR")  # a resumed thread keeps bracketed logger names
    again.expect("you>")
    again.sendline("")
    again.sendline("/task")
    again.expect("1. ")
    again.expect("you>")
    again.sendeof()
    again.expect(pexpect.EOF)
