from __future__ import annotations

from pathlib import Path

import pytest

REAL_BAGS = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "real_bags"


@pytest.fixture
def real_bags() -> Path:
    if not REAL_BAGS.is_dir():
        pytest.skip("shared/data/real_bags is not beside this checkout")
    return REAL_BAGS


@pytest.fixture(scope="session")
def suite(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The 60 simulated recordings of the paper's scenarios, written once per test session."""
    from hexar.evals.scenarios.suite import simulate_suite

    out = tmp_path_factory.mktemp("suite")
    simulate_suite(out)
    return out
