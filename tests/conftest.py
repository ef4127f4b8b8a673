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


@pytest.fixture(autouse=True)
def no_launch_of_this_machine(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    """`hexar serve` and `hexar web --live` follow launch's log under ROS_LOG_DIR (live/launch_log.py): an empty
    folder of the test's own, so no launch this machine ran is read into a test's answers."""
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path_factory.mktemp("ros_log")))
