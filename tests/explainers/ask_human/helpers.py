"""Recordings of one ask_human_for_help task, written as real rosbag2 bags and read back."""

from __future__ import annotations

import random
from collections.abc import Callable
from pathlib import Path
from typing import Any

from hexar.evals.scenarios.ask_human import AskHumanConditions, simulate_ask_human
from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.log import EventLog
from hexar.events.reader import read_recording
from hexar.explainers.base import Context
from hexar.explainers.registry import Registry
from tests.events.helpers import task_msg

T0 = sec_ns(1_760_000_000)
QUESTION = "Could you please put the coffee on my tray?"


def _task(status: str, error: str = "") -> dict[str, Any]:
    return task_msg("askhumantask0001", "Bring me a coffee from the kitchen",
                    [("ask_human_for_help", {"question": QUESTION}, status, error)])


def record(
    tmp_path: Path,
    cond: AskHumanConditions,
    seed: int = 0,
    navigate: Callable[[BagBuilder, int], SkillResult] | None = None,
    episodic: bool = True,
) -> tuple[EventLog, SkillResult]:
    """waiting -> Running -> succeeded|failed around one simulated execution of the skill."""
    b = BagBuilder()
    b.task_info(T0, _task("waiting"))
    b.task_info(T0 + sec_ns(0.5), _task("Running"))
    nav = None if navigate is None else (lambda t: navigate(b, t))
    scratch = BagBuilder()
    result = simulate_ask_human(
        b if episodic else scratch,
        random.Random(seed),
        T0 + sec_ns(1.0),
        cond,
        question=QUESTION,
        navigate=nav,
    )
    b.task_info(result.end, _task("succeeded" if result.succeeded else "failed", result.error_msg))
    path = b.write(tmp_path / f"bag_{seed}")
    return read_recording(path), result


def context(log: EventLog, registry: Registry | None = None) -> Context:
    return Context.for_task(log, log.task(), registry)
