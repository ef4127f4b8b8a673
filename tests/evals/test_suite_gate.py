"""The no-LLM suite on all 180 cases: the paper-level thresholds, and exactly the committed baseline."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from hexar.agent.backends import Backend
from hexar.evals import regression as reg
from hexar.evals.report import build
from hexar.evals.run import Selection, run

BASELINE = Path(__file__).resolve().parents[2] / "evals" / "baselines" / "none.json"


@pytest.fixture(scope="module")
def timed_report(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, Any], float]:
    runs = tmp_path_factory.mktemp("suite")
    from hexar.evals.scenarios.suite import simulate_suite

    simulate_suite(runs)
    started = time.perf_counter()
    output = run(runs, Backend("none", None), Selection())
    elapsed = time.perf_counter() - started
    return build(output, runs, Selection().as_dict(), 0), elapsed


def test_thresholds(timed_report: tuple[dict[str, Any], float]) -> None:
    report, elapsed = timed_report
    s = report["summary"]["hexar"]
    assert s["n"] == 180
    assert s["root_cause"]["mean"] >= 0.97
    assert s["incorrect_facts"]["mean"] <= 0.03
    assert s["selection"]["mean"] >= 0.99
    assert s["structured"]["root_cause"] >= 0.97 and s["structured"]["incorrect_facts"] <= 0.03
    assert elapsed < 60, f"--llm none took {elapsed:.1f} s for 180 cases"


def test_matches_committed_baseline_exactly(timed_report: tuple[dict[str, Any], float]) -> None:
    report, _ = timed_report
    baseline = reg.read_baseline(BASELINE)
    assert baseline["backend"] == "none" and len(baseline["methods"]["hexar"]) == 180
    assert reg.differences(report, baseline) == []
    assert not reg.compare(report, baseline, tolerance=0.0).failed
