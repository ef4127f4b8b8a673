"""A real recording of one `recommend_pizza` task, written with the scenario simulator."""

from __future__ import annotations

import random
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.evals.scenarios.pizza import simulate_recommend_pizza
from hexar.events.log import EventLog
from hexar.events.reader import read_recording
from tests.events.helpers import task_msg

T0 = 1_700_000_000 * 1_000_000_000


def task(status: str, error: str = "") -> dict[str, Any]:
    return task_msg("pZ4kT9qLmW2xVb7R", "what pizza can I make with what I have?",
                    [("recommend_pizza", {}, status, error)])


def write_pizza_bag(
    path: Path, available: Sequence[str], seed: int = 7, *, recommend: bool = True
) -> EventLog:
    b = BagBuilder()
    rng = random.Random(seed)
    b.task_info(T0, task("waiting"))
    start = T0 + sec_ns(0.3)
    b.task_info(start, task("Running"))
    if recommend:
        result = simulate_recommend_pizza(b, rng, start, available)
        end = result.end
    else:
        end = start + sec_ns(1.0)
    b.task_info(end, task("succeeded"))
    return read_recording(b.write(path / "bag"))


@pytest.fixture
def pizza_bag(tmp_path: Path) -> Callable[..., EventLog]:
    made = iter(range(1_000))

    def make(available: Sequence[str], seed: int = 7, *, recommend: bool = True) -> EventLog:
        # One folder per bag: the rosbag2 writer refuses to overwrite.
        folder = tmp_path / f"run{next(made)}"
        folder.mkdir()
        return write_pizza_bag(folder, available, seed, recommend=recommend)

    return make
