"""Conversations stay bounded: a thread keeps its latest checkpoint and its last turns only, a conversation file
its recent threads only, and a question longer than the limit is refused without being kept or repeated."""

from __future__ import annotations

import sqlite3
import time
from pathlib import Path

import pytest

from hexar.agent import threads
from hexar.agent.context import RunSettings
from hexar.agent.nodes import KEEP_TURNS
from hexar.agent.questions import MAX_QUESTION
from hexar.agent.session import Session


def rows(db: Path, sql: str) -> list[tuple[object, ...]]:
    with sqlite3.connect(db) as conn:
        return list(conn.execute(sql).fetchall())


def test_a_long_conversation_keeps_one_checkpoint_and_its_last_turns(suite: Path, tmp_path: Path) -> None:
    db = tmp_path / "t.sqlite"
    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"), checkpoints=db)
    first = session.ask("Why didn't you bring me the coffee?")
    for _ in range(KEEP_TURNS + 10):
        session.ask("What happened?", thread=first["thread"])
    deeper = session.ask("why?", thread=first["thread"])  # the conversation still goes deeper
    assert deeper["answer"].startswith("Here is what I recorded")
    assert len(session.history(first["thread"])) == KEEP_TURNS
    assert rows(db, "SELECT COUNT(*) FROM checkpoints") == [(1,)]
    size = db.stat().st_size
    for _ in range(40):
        session.ask("What happened?", thread=first["thread"])
    assert db.stat().st_size <= size * 1.5  # bounded, however long the conversation goes on


def test_memory_threads_keep_one_checkpoint_each(suite: Path) -> None:
    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"))
    thread = session.ask("What happened?")["thread"]
    for _ in range(10):
        session.ask("why?", thread=thread)
    saver = session.graph.checkpointer
    key = f"{session.settings.recording}::{thread}"
    assert [len(cps) for cps in saver.storage[key].values()] == [1]
    assert session.ask("What happened?", thread=thread)["answer"]


def test_old_and_surplus_threads_are_deleted(suite: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(threads, "MAX_THREADS", 5)
    db = tmp_path / "t.sqlite"
    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"), checkpoints=db)
    asked = [session.ask("What happened?")["thread"] for _ in range(8)]
    kept = {str(t).split("::", 1)[1] for (t,) in rows(db, "SELECT DISTINCT thread_id FROM checkpoints")}
    assert kept == set(asked[-5:])
    # a thread nobody continued for longer than MAX_AGE_S goes at the next question
    with sqlite3.connect(db) as conn:
        conn.execute("UPDATE hexar_threads SET used = ? WHERE thread_id LIKE ?",
                     (time.time() - threads.MAX_AGE_S - 1, f"%::{asked[-5]}"))
    session.ask("What happened?", thread=asked[-1])
    kept = {str(t).split("::", 1)[1] for (t,) in rows(db, "SELECT DISTINCT thread_id FROM checkpoints")}
    assert asked[-5] not in kept and asked[-1] in kept


def test_a_question_over_the_limit_is_refused_without_being_kept_or_repeated(suite: Path, tmp_path: Path) -> None:
    db = tmp_path / "t.sqlite"
    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"), checkpoints=db)
    question = "why did you stop there " * (10_000_000 // 23)
    result = session.ask(question)
    assert "too long" in result["error"] and str(MAX_QUESTION) in result["error"] and len(result["error"]) < 300
    assert db.stat().st_size < 1_000_000
    ok = session.ask("a" * 40 + " why did you stop?")
    assert "too long" not in ok["error"]
