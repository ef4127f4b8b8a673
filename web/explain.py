"""The task's answer to the generic question, as `hexar ask --json` gives it: the figure, the annotated
recording and the page all show this one answer."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from hexar.events.log import EventLog

GENERIC_QUESTION = "What happened?"  # the paper's generic question (evals/data/scenarios.yaml)


def explain_tasks(recording: Path, llm: str = "none", tasks: list[str] | None = None) -> tuple[EventLog,
                                                                                          list[dict[str, Any]]]:
    """One fresh conversation per task (so no answer leans on another task's thread)."""
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    session = Session(RunSettings(recording=recording, llm=llm))
    log = session.context.log
    refs = tasks if tasks is not None else [t.task_id for t in log.tasks]
    if refs and not log.tasks:
        log.task()  # raises the one-line "no task to explain" error
    return log, [session.ask(GENERIC_QUESTION, task=ref) for ref in refs]


def plot_task(log: EventLog, result: dict[str, Any], out: Path) -> None:
    """Write the path/timeline figure of the task `result` answered about."""
    from hexar.web.plot import build

    task = log.task(result.get("task_id") or None)
    build(log, task, result).save(out)


def plot_latest(recording: Path, out: Path) -> None:
    """`hexar inspect --plot`: the latest task, explained without a model (inspect never loads one)."""
    log, results = explain_tasks(recording, "none", tasks=["latest"])
    plot_task(log, results[0], out)
