"""The fuzz harness's bounded default run: hostile recordings and questions through the CLI, nothing found.

The long run is `scripts/fuzz_long.py`; every seed it ever reported stays here as a regression example.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.fuzz.harness import KINDS, example

DEFAULT = range(24)  # six of each kind, about half a minute on two cores
# seeds the long runs found, each fixed: pizza, navigation, ask-human and planner evidence, ask-human flags,
# a "nan" speed limit, a failed ask-human execution with no recorded step, a step status printed raw (36)
FOUND_BY_LONG_RUNS = [36, 220, 1298, 1616, 1888, 3064, 3154, 5126, 20020, 20232, 20381, 20628, 31456, 35276]


@pytest.mark.parametrize("seed", [*DEFAULT, *FOUND_BY_LONG_RUNS])
def test_fuzz_example_keeps_every_promise(seed: int, tmp_path: Path) -> None:
    outcomes = example(seed, tmp_path)
    assert outcomes, f"seed {seed} ({KINDS[seed % len(KINDS)]}) ran no command"
    problems = [f"{o.args[:1]} exit {o.code}: {p}" for o in outcomes for p in o.problems]
    assert not problems, problems
