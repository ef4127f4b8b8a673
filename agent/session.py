"""A conversation with the agent about one recording: `hexar ask`, `hexar chat` and `hexar listen` use it."""

from __future__ import annotations

import sqlite3
import time
import uuid
from pathlib import Path
from typing import Any, cast

from langchain_core.runnables import RunnableConfig
from langgraph.checkpoint.memory import InMemorySaver
from langgraph.checkpoint.sqlite import SqliteSaver

from hexar.agent.backends import Backend, resolve
from hexar.agent.context import RunContext, RunSettings
from hexar.agent.graph import build
from hexar.agent.oneshot import result_of
from hexar.agent.questions import bounded
from hexar.agent.state import AgentState
from hexar.agent.threads import ThreadBook, keep_latest
from hexar.events.log import EventLog


def default_checkpoints() -> Path:
    return Path.home() / ".cache" / "hexar" / "threads.sqlite"


class Session:
    """One recording, one backend, and any number of threads (conversations) over it."""

    def __init__(self, settings: RunSettings, backend: Backend | None = None,
                 checkpoints: Path | None = None, log: EventLog | None = None) -> None:
        self.settings = settings
        self.backend = backend or resolve(settings.llm)
        self.context = RunContext.create(settings, self.backend)
        if log is not None:  # an event log built elsewhere (the live node's snapshot), not read from a file
            self.use_log(log)
        self.context.log  # noqa: B018 -- decode once, so a bad recording fails before the first question
        self._book: ThreadBook | None = None
        if checkpoints is None:
            self._saver: Any = InMemorySaver()
        else:
            checkpoints.parent.mkdir(parents=True, exist_ok=True)
            self._conn = sqlite3.connect(str(checkpoints), check_same_thread=False)
            self._saver = SqliteSaver(self._conn)
            self._book = ThreadBook(self._conn, self._saver)
        self.graph = build(self._saver)

    def use_log(self, log: EventLog) -> None:
        """Answer the next questions from `log` (the live node swaps in a fresh snapshot per question)."""
        self.context._log = log

    def new_thread(self) -> str:
        return uuid.uuid4().hex[:12]

    def ask(self, question: str, thread: str | None = None, task: str | None = None) -> dict[str, Any]:
        thread = thread or self.new_thread()
        started = time.perf_counter()
        self.context.started = time.monotonic()
        update: dict[str, Any] = {"question": bounded(question)}
        if task is not None:
            update["task_ref"] = task
        config: RunnableConfig = {"configurable": {"thread_id": f"{self.settings.recording}::{thread}"},
                                  "recursion_limit": self.settings.recursion_limit}
        state = self.graph.invoke(cast(AgentState, update), config, context=self.context)
        thread_id = config["configurable"]["thread_id"]
        keep_latest(self._saver, thread_id)
        if self._book is not None:
            self._book.used(thread_id)
        return self._result(dict(state), thread, started)

    def switch(self, thread: str, task_id: str) -> None:
        """Talk about another task from the next question on: the thread keeps its history, and the next
        question starts afresh on that task (no follow-up reaches back to the previous task's answer)."""
        config: RunnableConfig = {"configurable": {"thread_id": f"{self.settings.recording}::{thread}"}}
        fresh = {"task_ref": task_id, "explanations": [], "used": [], "told": [], "depth": 0}
        self.graph.update_state(config, cast(AgentState, fresh), as_node="answer")

    def history(self, thread: str) -> list[dict[str, Any]]:
        config: RunnableConfig = {"configurable": {"thread_id": f"{self.settings.recording}::{thread}"}}
        snap = self.graph.get_state(config)
        return list(snap.values.get("history", [])) if snap and snap.values else []

    def _result(self, state: dict[str, Any], thread: str, started: float) -> dict[str, Any]:
        return result_of(state, self.backend.name, str(self.settings.recording), thread, started)
